# MPI fault tests of `accelvolume render --mapper shearwarp --mpi` (label "mpi-fault"): a rank
# that fails to load its data, dies or hangs must not leave the others waiting forever. Each
# test runs the CLI under mpiexec and checks the exit code, the time the job took (bounded) and
# the one error line rank 0 prints (naming the failed rank), after dropping mpiexec's banners.
#
# This file has two roles: included from Testing/CLI/CMakeLists.txt (inside BUILD_TESTING) it
# registers the tests; run with `cmake -P` it runs one of them, with these variables:
#   EXE            the accelvolume executable
#   MPIEXEC, NUMPROC_FLAG, PREFLAGS ('|'-separated)  the launcher (empty MPIEXEC: no launcher)
#   RANKS          number of ranks
#   ARGS           accelvolume's arguments, '|'-separated
#   LAST_RANK_ARGS the last rank's arguments instead (an MPMD launch: `-n R-1 ... : -n 1 ...`)
#   FAULT          value of ACCELVOLUME_FAULT, the CLI's test hook (Render.cxx: FaultInjection)
#   EXPECT         the exact exit code expected (never 0 here)
#   ERROR_REGEX    the one line left on stderr must be "accelvolume: error: " + a match of this
#   LAUNCHER_REGEX the whole stderr must match this too (mpiexec's note of a dead rank)
#   OTHER_LINE_REGEX  lines matching this are left out before the one-line check (optional)
#   MIN_SECONDS, MAX_SECONDS  bounds of the job's wall-clock time
#   LINE_MAY_BE_LOST  no line at all is accepted too (a rank killed by the launcher: Open MPI may
#                  tear down its output forwarding before rank 0's last line gets through; about
#                  one run in fifteen here); LAUNCHER_REGEX still has to match
# The tests use --mpi-timeout 5: above the ranks' start-up skew on a loaded 2-core machine, so a
# healthy exchange never runs out, and short enough for CI.
if (CMAKE_SCRIPT_MODE_FILE)
  cmake_minimum_required(VERSION 3.23) # string(TIMESTAMP %f)
  string(REPLACE "|" ";" arguments "${ARGS}")
  set(command "${EXE}" ${arguments})
  if (MPIEXEC)
    string(REPLACE "|" ";" preflags "${PREFLAGS}")
    if (DEFINED LAST_RANK_ARGS)
      string(REPLACE "|" ";" last "${LAST_RANK_ARGS}")
      math(EXPR others "${RANKS} - 1")
      set(command "${MPIEXEC}" ${preflags} ${NUMPROC_FLAG} ${others} "${EXE}" ${arguments}
        : ${NUMPROC_FLAG} 1 "${EXE}" ${last})
    else ()
      set(command "${MPIEXEC}" ${preflags} ${NUMPROC_FLAG} ${RANKS} ${command})
    endif ()
  endif ()
  if (FAULT)
    set(ENV{ACCELVOLUME_FAULT} "${FAULT}")
  else ()
    unset(ENV{ACCELVOLUME_FAULT})
  endif ()
  string(TIMESTAMP start "%s%f")
  execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
    TIMEOUT 90)
  string(TIMESTAMP end "%s%f")
  math(EXPR milliseconds "(${end} - ${start}) / 1000")
  string(REPLACE ";" " " shown "${command}")
  function(fail message)
    message(FATAL_ERROR "${message}\ncommand: ACCELVOLUME_FAULT=${FAULT} ${shown}\n"
      "exit: ${rc}, ${milliseconds} ms\nstdout:\n${out}\nstderr:\n${err}")
  endfunction()
  message(STATUS "exit ${rc} after ${milliseconds} ms")
  if (NOT rc STREQUAL "${EXPECT}")
    fail("expected exit code ${EXPECT}")
  endif ()
  math(EXPR low "${MIN_SECONDS} * 1000")
  math(EXPR high "${MAX_SECONDS} * 1000")
  if (milliseconds GREATER high OR milliseconds LESS low)
    fail("the job took ${milliseconds} ms, expected ${MIN_SECONDS} to ${MAX_SECONDS} s")
  endif ()
  if (LAUNCHER_REGEX AND NOT err MATCHES "${LAUNCHER_REGEX}")
    fail("stderr does not match '${LAUNCHER_REGEX}'")
  endif ()
  # What the ranks printed: without mpiexec's banners (between lines of dashes) and Open MPI's
  # own reports ("[host:pid] ..." stack traces of a rank that aborted, ORTE logs).
  string(REPLACE ";" "\\;" lines "${err}")
  string(REPLACE "\n" ";" lines "${lines}")
  set(printed "")
  set(in_banner OFF)
  foreach (line IN LISTS lines)
    if (line MATCHES "^-----+$")
      if (in_banner)
        set(in_banner OFF)
      else ()
        set(in_banner ON)
      endif ()
    elseif (NOT in_banner AND NOT line STREQUAL "" AND NOT line MATCHES "^\\[[^]]+\\] ")
      if (NOT OTHER_LINE_REGEX OR NOT line MATCHES "${OTHER_LINE_REGEX}")
        string(APPEND printed "${line}\n")
      endif ()
    endif ()
  endforeach ()
  if (LINE_MAY_BE_LOST AND printed STREQUAL "")
    message(STATUS "no line from the ranks: the launcher's teardown dropped it (allowed here)")
    return()
  endif ()
  if (NOT printed MATCHES "^accelvolume: error: [^\n]+\n$")
    fail("expected exactly one line 'accelvolume: error: ...' from the ranks, got:\n${printed}")
  endif ()
  if (NOT printed MATCHES "^accelvolume: error: ${ERROR_REGEX}")
    fail("the error line does not match '${ERROR_REGEX}':\n${printed}")
  endif ()
  message(STATUS "got: ${printed}")
  return()
endif ()

set(_av_mpi_fault_script "${CMAKE_CURRENT_LIST_FILE}")
# accelvolume_mpi_fault_test(NAME RANKS n EXPECT code MAX_SECONDS s ERROR_REGEX re
#   [MIN_SECONDS s] [FAULT spec] [LAUNCHER_REGEX re] [OTHER_LINE_REGEX re] [NO_LAUNCHER]
#   [LINE_MAY_BE_LOST]
#   ARGS ... [LAST_RANK_ARGS ...])
function(accelvolume_mpi_fault_test name)
  cmake_parse_arguments(PARSE_ARGV 1 test "NO_LAUNCHER;LINE_MAY_BE_LOST"
    "RANKS;FAULT;EXPECT;MIN_SECONDS;MAX_SECONDS;ERROR_REGEX;LAUNCHER_REGEX;OTHER_LINE_REGEX"
    "ARGS;LAST_RANK_ARGS")
  if (NOT DEFINED test_MIN_SECONDS)
    set(test_MIN_SECONDS 0)
  endif ()
  list(JOIN test_ARGS "|" joined)
  list(JOIN MPIEXEC_PREFLAGS "|" preflags)
  set(definitions "-DEXE=$<TARGET_FILE:accelvolume>" "-DARGS=${joined}" "-DRANKS=${test_RANKS}"
    "-DFAULT=${test_FAULT}" "-DEXPECT=${test_EXPECT}" "-DMIN_SECONDS=${test_MIN_SECONDS}"
    "-DMAX_SECONDS=${test_MAX_SECONDS}" "-DERROR_REGEX=${test_ERROR_REGEX}"
    "-DLAUNCHER_REGEX=${test_LAUNCHER_REGEX}" "-DOTHER_LINE_REGEX=${test_OTHER_LINE_REGEX}"
    "-DLINE_MAY_BE_LOST=${test_LINE_MAY_BE_LOST}")
  if (NOT test_NO_LAUNCHER)
    list(APPEND definitions "-DMPIEXEC=${MPIEXEC_EXECUTABLE}"
      "-DNUMPROC_FLAG=${MPIEXEC_NUMPROC_FLAG}" "-DPREFLAGS=${preflags}")
  endif ()
  if (DEFINED test_LAST_RANK_ARGS)
    list(JOIN test_LAST_RANK_ARGS "|" last)
    list(APPEND definitions "-DLAST_RANK_ARGS=${last}")
  endif ()
  add_test(NAME accelvolume.cli.mpi_fault_${name}
    COMMAND "${CMAKE_COMMAND}" ${definitions} -P "${_av_mpi_fault_script}")
  set_tests_properties(accelvolume.cli.mpi_fault_${name} PROPERTIES
    LABELS "cli;mpi;mpi-fault" TIMEOUT 120 PROCESSORS ${test_RANKS}
    ENVIRONMENT "ACCELVOLUME_GL=${ACCELVOLUME_TEST_GL}")
endfunction()

set(_av_fault_render render --size 64 64 --phantom-dims 48 48 48 --mapper shearwarp
  --blend composite --tf tf2 --frames 2 --quiet --mpi --mpi-timeout 5)
set(_av_fault_missing "${CMAKE_CURRENT_BINARY_DIR}/cli-tests/mpi_fault_missing/missing.mhd")
# a. One rank (not all) cannot read its input (an MPMD launch gives the last rank a missing
#    file): the ranks agree before rendering, and rank 0 reports that rank's own error.
accelvolume_mpi_fault_test(load_rank1 RANKS 2 EXPECT 1 MAX_SECONDS 30
  ARGS ${_av_fault_render}
  LAST_RANK_ARGS ${_av_fault_render} --input "${_av_fault_missing}"
  ERROR_REGEX "rank 1: cannot open '[^']*missing.mhd'")
accelvolume_mpi_fault_test(load_rank2_of_3 RANKS 3 EXPECT 1 MAX_SECONDS 30
  ARGS ${_av_fault_render}
  LAST_RANK_ARGS ${_av_fault_render} --input "${_av_fault_missing}"
  ERROR_REGEX "rank 2: cannot open '[^']*missing.mhd'")
# b. A rank dies in the second frame (SIGKILL; std::abort): Open MPI's mpiexec ends the job at
#    once with SIGTERM to the others and names the dead rank; rank 0 says what it waited for
#    (when the launcher still forwards it: LINE_MAY_BE_LOST).
accelvolume_mpi_fault_test(die_rank1 RANKS 2 FAULT "die:1:frame=2" EXPECT 137 MAX_SECONDS 30
  LINE_MAY_BE_LOST
  ARGS ${_av_fault_render}
  ERROR_REGEX "rank 0 was ended by SIGTERM"
  LAUNCHER_REGEX "process rank 1 with PID [0-9]+ on node [^ ]+ exited on signal 9")
accelvolume_mpi_fault_test(abort_rank2_of_3 RANKS 3 FAULT "abort:2:frame=2" EXPECT 134
  MAX_SECONDS 30 LINE_MAY_BE_LOST ARGS ${_av_fault_render}
  ERROR_REGEX "rank 0 was ended by SIGTERM"
  LAUNCHER_REGEX "process rank 2 with PID [0-9]+ on node [^ ]+ exited on signal 6")
# c. A rank hangs (sleeps forever): after --mpi-timeout (5 s) rank 0 names it and MPI_Abort
#    ends the job. Before sending its band rows, or before the frame's status exchange; rank 0
#    itself hanging is reported by rank 1 after twice the timeout (the hung rank 0 then says it
#    was ended by SIGTERM, a second line).
accelvolume_mpi_fault_test(hang_rank1 RANKS 2 FAULT "hang:1:frame=2" EXPECT 1
  MIN_SECONDS 5 MAX_SECONDS 35 ARGS ${_av_fault_render}
  ERROR_REGEX "rank 1 sent no band rows to rank 0 within 5 s \\(the MPI communication timeout\\)")
accelvolume_mpi_fault_test(hang_rank2_of_3_at_start RANKS 3 FAULT "hang:2:frame=2:at=start"
  EXPECT 1 MIN_SECONDS 5 MAX_SECONDS 35 ARGS ${_av_fault_render}
  ERROR_REGEX "rank 2 sent no frame status to rank 0 within 5 s")
accelvolume_mpi_fault_test(hang_rank0 RANKS 2 FAULT "hang:0:frame=2" EXPECT 1
  MIN_SECONDS 10 MAX_SECONDS 40 ARGS ${_av_fault_render}
  ERROR_REGEX "rank 0 took no band rows from rank 1 within 10 s"
  OTHER_LINE_REGEX "^accelvolume: error: rank 0 was ended by SIGTERM \\(")
# The test hook itself refuses a malformed value (one process, no launcher).
accelvolume_mpi_fault_test(bad_spec RANKS 1 NO_LAUNCHER FAULT "explode:1" EXPECT 2 MAX_SECONDS 30
  ARGS ${_av_fault_render}
  ERROR_REGEX "invalid ACCELVOLUME_FAULT 'explode:1'")
# --mpi-timeout is checked like every flag.
accelvolume_cli_test(error_mpi_timeout_without_mpi EXPECT 2
  ARGS render --mapper shearwarp --mpi-timeout 5
  VARS "ERROR_REGEX=--mpi-timeout applies only with --mpi")
accelvolume_cli_test(error_mpi_timeout_range EXPECT 2
  ARGS render --mapper shearwarp --mpi --mpi-timeout 90000
  VARS "ERROR_REGEX=--mpi-timeout must be between 0 and 86400 seconds")
