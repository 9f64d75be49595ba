# accelvolume_test_target(TARGET [OPTIMIZED_UNDER_SANITIZERS] [HEADERS h...]
#   [OPTIMIZED_SOURCES s...]): compile options for a
# test executable's own code (the module and the reference renderers it links keep theirs), for
# build time on a 2-core CI machine:
# - optimized builds compile test code at -O1 (Release's -O3 compiled the test files about 1.5x
#   slower and buys nothing: the time tests spend is in the module), sanitizer builds at -O0
#   (about 3x faster than -O1; the module stays at -O1) unless OPTIMIZED_UNDER_SANITIZERS (the
#   image tests: at -O0 their own loops cost more test time than the compile time saved);
# - HEADERS become one precompiled header per target (GoogleTest's and VTK's headers were parsed
#   again by every test file: about 1-3 s each);
# - OPTIMIZED_SOURCES keep -O1 in sanitizer builds (files whose brute-force checks run long
#   enough that -O0 costs more test time than it saves compile time); GCC cannot use a header
#   precompiled at -O0 in an optimized file, so they go without it.
function(accelvolume_test_target target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "OPTIMIZED_UNDER_SANITIZERS" "" "HEADERS;OPTIMIZED_SOURCES")
  if (ACCELVOLUME_SANITIZE AND arg_OPTIMIZED_UNDER_SANITIZERS)
    # The sanitizer builds' own -O1.
  elseif (ACCELVOLUME_SANITIZE)
    target_compile_options(${target} PRIVATE -O0)
    foreach (source IN LISTS arg_OPTIMIZED_SOURCES)
      set_property(SOURCE "${source}" APPEND PROPERTY COMPILE_OPTIONS -O1)
      set_property(SOURCE "${source}" PROPERTY SKIP_PRECOMPILE_HEADERS ON)
    endforeach ()
  elseif (CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo|MinSizeRel)$")
    target_compile_options(${target} PRIVATE -O1)
  endif ()
  if (arg_HEADERS AND NOT ACCELVOLUME_NO_TEST_PCH)
    target_precompile_headers(${target} PRIVATE ${arg_HEADERS})
  endif ()
endfunction()
