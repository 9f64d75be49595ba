# ACCELVOLUME_SANITIZE: build every target of this project (module, tests, CLI, benchmarks,
# examples) with GCC/Clang sanitizers. Values: "" (off, the default), "address;undefined"
# (ASan + UBSan; "address" or "undefined" alone work too) or "thread" (TSan). VTK, Mesa and
# Open MPI stay uninstrumented. scripts/sanitize.sh configures such builds and runs the tests;
# docs/sanitizers.md says what runs and why.
#
# Run-time options are compiled into every executable (Testing/Sanitizers/
# AccelVolumeSanitizerOptions.cxx: suppression files, halt on the first UBSan finding, a
# distinctive exit code), so a plain `ctest` or a hand-run binary of that build behaves like the
# script. ASAN_OPTIONS / UBSAN_OPTIONS / LSAN_OPTIONS / TSAN_OPTIONS still override them.
set(ACCELVOLUME_SANITIZE "" CACHE STRING
  "Sanitizers for this project's targets: empty, \"address;undefined\" or \"thread\"")
set_property(CACHE ACCELVOLUME_SANITIZE PROPERTY STRINGS "" "address;undefined" "thread")

string(REPLACE "," ";" ACCELVOLUME_SANITIZERS "${ACCELVOLUME_SANITIZE}")
set(_av_sanitizers "${ACCELVOLUME_SANITIZERS}")
if (NOT _av_sanitizers)
  return()
endif ()
foreach (_av_sanitizer IN LISTS _av_sanitizers)
  if (NOT _av_sanitizer MATCHES "^(address|undefined|thread)$")
    message(FATAL_ERROR "ACCELVOLUME_SANITIZE: unknown sanitizer '${_av_sanitizer}' "
      "(use \"address;undefined\" or \"thread\")")
  endif ()
endforeach ()
if ("thread" IN_LIST _av_sanitizers AND NOT _av_sanitizers STREQUAL "thread")
  message(FATAL_ERROR "ACCELVOLUME_SANITIZE: \"thread\" cannot be combined with other sanitizers")
endif ()
if (CMAKE_VERSION VERSION_LESS "3.19")
  message(FATAL_ERROR "ACCELVOLUME_SANITIZE needs CMake 3.19 (cmake_language(DEFER))")
endif ()
if (NOT CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  message(FATAL_ERROR "ACCELVOLUME_SANITIZE needs GCC or Clang")
endif ()

set(_av_sanitize_flags)
foreach (_av_sanitizer IN LISTS _av_sanitizers)
  list(APPEND _av_sanitize_flags "-fsanitize=${_av_sanitizer}")
endforeach ()
if ("undefined" IN_LIST _av_sanitizers)
  # float-cast-overflow (e.g. a NaN or huge depth cast to int) is UB that -fsanitize=undefined
  # leaves out on GCC; a renderer casts floats to indices everywhere, so check it too. Every
  # finding aborts (no recovery), so a test cannot pass with a finding printed.
  list(APPEND _av_sanitize_flags -fsanitize=float-cast-overflow -fno-sanitize-recover=all)
endif ()
list(APPEND _av_sanitize_flags -fno-omit-frame-pointer)

# Compile and link flags for every target defined from here on (this folder and below);
# C and C++ only.
add_compile_options("$<$<COMPILE_LANGUAGE:C,CXX>:${_av_sanitize_flags}>")
add_link_options(${_av_sanitize_flags})
message(STATUS "AccelVolume: sanitizers ${_av_sanitizers}: ${_av_sanitize_flags}")

# Self-tests (label "sanitizer", Testing/Sanitizers/): each deliberate error must be reported.
get_filename_component(_av_sanitizer_tests "${CMAKE_CURRENT_LIST_DIR}/../Testing/Sanitizers" ABSOLUTE)
if (BUILD_TESTING)
  add_subdirectory("${_av_sanitizer_tests}" "${PROJECT_BINARY_DIR}/Testing/Sanitizers")
endif ()

# The run-time defaults go into every executable; executables are only known once the whole
# project is read, hence the deferred call at the end of the top-level folder.
set(ACCELVOLUME_SANITIZER_OPTIONS_SOURCE "${_av_sanitizer_tests}/AccelVolumeSanitizerOptions.cxx")

function(_accelvolume_sanitizer_options_into_executables directory)
  get_property(targets DIRECTORY "${directory}" PROPERTY BUILDSYSTEM_TARGETS)
  # Source properties are per folder: tell each folder where the suppression files are.
  get_filename_component(sanitizer_dir "${ACCELVOLUME_SANITIZER_OPTIONS_SOURCE}" DIRECTORY)
  set_property(SOURCE "${ACCELVOLUME_SANITIZER_OPTIONS_SOURCE}" DIRECTORY "${directory}"
    PROPERTY COMPILE_DEFINITIONS "ACCELVOLUME_SANITIZER_DIR=\"${sanitizer_dir}\"")
  foreach (target IN LISTS targets)
    get_property(type TARGET "${target}" PROPERTY TYPE)
    if (type STREQUAL "EXECUTABLE")
      target_sources("${target}" PRIVATE "${ACCELVOLUME_SANITIZER_OPTIONS_SOURCE}")
    endif ()
  endforeach ()
  get_property(subdirectories DIRECTORY "${directory}" PROPERTY SUBDIRECTORIES)
  foreach (subdirectory IN LISTS subdirectories)
    _accelvolume_sanitizer_options_into_executables("${subdirectory}")
  endforeach ()
endfunction()
cmake_language(EVAL CODE "cmake_language(DEFER DIRECTORY [[${PROJECT_SOURCE_DIR}]] CALL
  _accelvolume_sanitizer_options_into_executables [[${PROJECT_SOURCE_DIR}]])")
