# Runs `accelvolume octree` on a small phantom with one builder (cmake -P) and checks its JSON.
#   EXE      the accelvolume executable
#   WORK     a scratch folder for this test (created)
#   BUILDER  reference|cpu|gpu
# For gpu, a context without OpenGL 4.3 is not a failure: the script prints OCTREE_TEST_SKIPPED,
# which the test's SKIP_REGULAR_EXPRESSION turns into a skip.
cmake_minimum_required(VERSION 3.19)

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
# Dims that are not multiples of the leaf, so partial leaves and padding are exercised.
set(arguments octree --phantom vessels --phantom-dims 37 30 21 --leaf 4 --builder ${BUILDER}
  --repeat 3 --stats "${WORK}/stats.json")
execute_process(COMMAND "${EXE}" ${arguments}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)

function(fail message)
  message(FATAL_ERROR "${message}\ncommand: ${EXE} ${arguments}\nexit: ${rc}\nstdout:\n${out}\nstderr:\n${err}")
endfunction()

if (BUILDER STREQUAL "gpu" AND rc EQUAL 1 AND err MATCHES "needs OpenGL 4.3|backend is not available")
  message(STATUS "OCTREE_TEST_SKIPPED: ${err}")
  return()
endif ()
if (NOT rc EQUAL 0)
  fail("expected exit code 0")
endif ()
if (NOT err STREQUAL "")
  fail("expected no stderr output (VTK messages must not reach the terminal)")
endif ()
if (NOT out MATCHES "^octree ${BUILDER} ")
  fail("expected the one-line summary on stdout")
endif ()

file(READ "${WORK}/stats.json" json)
string(JSON type ERROR_VARIABLE json_error TYPE "${json}")
if (json_error OR NOT type STREQUAL "OBJECT")
  fail("--stats is not a JSON object: ${json_error}\n${json}")
endif ()
foreach (key IN ITEMS builder threads leaf dims type input nodes depth bytes bytes_per_s
    read_floor_ms ratio_to_floor transparent_leaf_fraction)
  string(JSON value ERROR_VARIABLE json_error GET "${json}" ${key})
  if (json_error)
    fail("--stats lacks '${key}': ${json_error}\n${json}")
  endif ()
endforeach ()
foreach (key IN ITEMS median min max)
  string(JSON value ERROR_VARIABLE json_error GET "${json}" ms ${key})
  if (json_error OR NOT value GREATER 0)
    fail("--stats ms.${key} missing or not positive ('${value}')\n${json}")
  endif ()
endforeach ()
foreach (key IN ITEMS median min)
  string(JSON value ERROR_VARIABLE json_error GET "${json}" classify_ms ${key})
  if (json_error OR value LESS 0)
    fail("--stats classify_ms.${key} missing or negative ('${value}')\n${json}")
  endif ()
endforeach ()

string(JSON builder GET "${json}" builder)
string(JSON leaf GET "${json}" leaf)
string(JSON bytes GET "${json}" bytes)
string(JSON nodes GET "${json}" nodes)
string(JSON depth GET "${json}" depth)
string(JSON threads GET "${json}" threads)
string(JSON fraction GET "${json}" transparent_leaf_fraction)
# 37x30x21 float32 voxels; leaf grid ceil(36/4) x ceil(29/4) x ceil(20/4) = 9x8x5 -> depth 4.
if (NOT builder STREQUAL "${BUILDER}" OR NOT leaf EQUAL 4 OR NOT bytes EQUAL 93240
    OR NOT depth EQUAL 4 OR NOT nodes GREATER 359)
  fail("unexpected builder/leaf/bytes/depth/nodes\n${json}")
endif ()
if ((BUILDER STREQUAL "reference" AND NOT threads EQUAL 1) OR (BUILDER STREQUAL "gpu" AND NOT threads EQUAL 0)
    OR (BUILDER STREQUAL "cpu" AND threads LESS 1))
  fail("unexpected threads ${threads} for ${BUILDER}\n${json}")
endif ()
if (fraction LESS 0 OR fraction GREATER 1)
  fail("transparent_leaf_fraction outside [0, 1]\n${json}")
endif ()
