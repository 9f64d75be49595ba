# Runs one accelvolume command for ctest (cmake -P) and checks its outcome.
#   EXE      the accelvolume executable
#   ARGS     its arguments separated by '|'; @WORK@ expands to WORK
#   WORK     a scratch folder for this test (created)
#   EXPECT   expected exit code (default 0); non-zero also requires exactly one stderr line
#            starting with "accelvolume: error: "
#   PNG      file under WORK that must be a PNG afterwards (optional)
#   STATS    file under WORK holding the --stats JSON to check (optional)
#   MAPPER, BLEND, CROP (ARRAY or NULL), WIDTH, INPUT, TF, SHADE (ON or OFF): expected --stats
#            values (optional; @WORK@ in TF expands to WORK)
#   MAKE_RAW name of a 10-byte file to write under WORK first (optional)
#   MAKE_TF  writes WORK/tf.json first, a --tf file of one kind: good, malformed, nocolor,
#            unsorted, nonnumeric (optional)
#   ERROR_REGEX regular expression the error line must match (optional, EXPECT non-zero)
#   STDOUT_REGEX regular expression stdout must match (optional)
cmake_minimum_required(VERSION 3.19)

if (NOT DEFINED EXPECT)
  set(EXPECT 0)
endif ()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
if (MAKE_RAW)
  file(WRITE "${WORK}/${MAKE_RAW}" "0123456789")
endif ()
if (MAKE_TF)
  # Kept here rather than passed on the command line: JSON quotes and brackets do not survive
  # add_test's argument quoting reliably.
  set(tf_good [=[{
  "name": "test ramp",
  "scalarOpacity": [[0, 0], [0.2, 0], [1.0, 0.6]],
  "color": [[0, 0.1, 0.1, 0.3], [0.5, 0.2, 0.8, 0.4], [1.0, 1, 1, 0.9]],
  "gradientOpacity": [[0, 0.2], [2.5e-1, 1]],
  "shade": true,
  "ambient": 0.3, "diffuse": 0.6, "specular": 0.2, "specularPower": 20
}
]=])
  set(tf_malformed [=[{"scalarOpacity": [[0, 0], [1, 1]], "color": [[0, 0, 0, 0] [1, 1, 1, 1]]}]=])
  set(tf_nocolor [=[{"scalarOpacity": [[0, 0], [1, 1]]}]=])
  set(tf_unsorted [=[{"scalarOpacity": [[0, 0], [1, 1], [0.5, 0.5]], "color": [[0, 0, 0, 0]]}]=])
  set(tf_nonnumeric [=[{"scalarOpacity": [[0, "zero"]], "color": [[0, 0, 0, 0]]}]=])
  if (NOT DEFINED tf_${MAKE_TF})
    message(FATAL_ERROR "unknown MAKE_TF kind '${MAKE_TF}'")
  endif ()
  file(WRITE "${WORK}/tf.json" "${tf_${MAKE_TF}}")
endif ()
string(REPLACE "@WORK@" "${WORK}" ARGS "${ARGS}")
string(REPLACE "@WORK@" "${WORK}" TF "${TF}")
string(REPLACE "|" ";" arguments "${ARGS}")

execute_process(COMMAND "${EXE}" ${arguments}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)

function(fail message)
  message(FATAL_ERROR "${message}\ncommand: ${EXE} ${arguments}\nexit: ${rc}\nstdout:\n${out}\nstderr:\n${err}")
endfunction()

if (NOT rc STREQUAL "${EXPECT}")
  fail("expected exit code ${EXPECT}")
endif ()
if (NOT EXPECT EQUAL 0)
  if (NOT err MATCHES "^accelvolume: error: [^\n]+\n$")
    fail("expected exactly one line 'accelvolume: error: ...' on stderr")
  endif ()
  if (ERROR_REGEX AND NOT err MATCHES "${ERROR_REGEX}")
    fail("the error line does not match '${ERROR_REGEX}'")
  endif ()
  message(STATUS "got: ${err}")
  return()
endif ()
if (NOT err STREQUAL "")
  fail("expected no stderr output (VTK messages must not reach the terminal)")
endif ()
if (STDOUT_REGEX AND NOT out MATCHES "${STDOUT_REGEX}")
  fail("stdout does not match '${STDOUT_REGEX}'")
endif ()

if (PNG)
  if (NOT EXISTS "${WORK}/${PNG}")
    fail("${PNG} was not written")
  endif ()
  file(READ "${WORK}/${PNG}" signature LIMIT 8 HEX)
  if (NOT signature STREQUAL "89504e470d0a1a0a")
    fail("${PNG} is not a PNG (starts with ${signature})")
  endif ()
endif ()

if (STATS)
  file(READ "${WORK}/${STATS}" json)
  string(JSON type ERROR_VARIABLE json_error TYPE "${json}")
  if (json_error OR NOT type STREQUAL "OBJECT")
    fail("--stats is not a JSON object: ${json_error}\n${json}")
  endif ()
  foreach (key IN ITEMS mapper blend width height frames first_frame_ms gl_renderer gl_backend
      dims type spacing input sample_distance slices boundary_rerender tf shade gradient_opacity
      lighting crop camera)
    string(JSON value ERROR_VARIABLE json_error GET "${json}" ${key})
    if (json_error)
      fail("--stats lacks '${key}': ${json_error}\n${json}")
    endif ()
  endforeach ()
  foreach (key IN ITEMS median min max mean)
    string(JSON value ERROR_VARIABLE json_error GET "${json}" ms_per_frame ${key})
    if (json_error OR NOT value GREATER 0)
      fail("--stats ms_per_frame.${key} missing or not positive ('${value}')\n${json}")
    endif ()
  endforeach ()
  foreach (key IN ITEMS azimuth elevation roll zoom parallel)
    string(JSON value ERROR_VARIABLE json_error GET "${json}" camera ${key})
    if (json_error)
      fail("--stats lacks camera.${key}\n${json}")
    endif ()
  endforeach ()
  string(JSON dims_length LENGTH "${json}" dims)
  if (NOT dims_length EQUAL 3)
    fail("--stats dims is not a 3-array\n${json}")
  endif ()
  foreach (check IN ITEMS MAPPER BLEND WIDTH INPUT TF SHADE)
    if (NOT "${${check}}" STREQUAL "")
      string(TOLOWER "${check}" key)
      string(JSON value GET "${json}" ${key})
      if (NOT value STREQUAL "${${check}}")
        fail("--stats ${key} is '${value}', expected '${${check}}'\n${json}")
      endif ()
    endif ()
  endforeach ()
  if (DEFINED CROP)
    string(JSON crop_type TYPE "${json}" crop)
    if (NOT crop_type STREQUAL "${CROP}")
      fail("--stats crop is ${crop_type}, expected ${CROP}\n${json}")
    endif ()
  endif ()
endif ()
