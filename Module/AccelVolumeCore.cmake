# AccelVolumeCore and AccelVolumeReference: Rendering/Core as two static libraries, each source
# compiled once. Included by AccelVolumeModule.cmake (standalone, Remote/ and plugin builds).
get_filename_component(_av_core_root "${CMAKE_CURRENT_LIST_DIR}/../Rendering/Core" ABSOLUTE)

# Technique folders of Core (docs/techniques.md maps each technique to its files).
set(_av_core_sources
  common/Affine
  common/Camera
  common/Geometry
  common/ParallelFor
  common/Progress
  common/Unorm16
  skipping/CellClassification
  skipping/CellLeapTable
  skipping/DistanceMap
  skipping/DistanceTemplate
  skipping/MinMaxOctree
  skipping/MinMaxOctreeQueries
  skipping/OctantDistanceMap
  skipping/ScreenFootprint
  skipping/OpacityRange
  slicing/Bricking
  slicing/CompositeSlices
  slicing/SlabProxy
  raycast/RayCastAcceleration
  raycast/RayCastEngine
  raycast/RayCastKernel
  raycast/RayCastKernel8Bit
  raycast/RayCastKernel16Bit
  raycast/RayCastKernel32Bit
  raycast/RayCastKernel64Bit
  shearwarp/RunLengthVolume
  shearwarp/RunLengthTranspose
  shearwarp/ShearWarpEncodings
  shearwarp/ShearWarpCompositor
  shearwarp/ShearWarpShading
  shearwarp/ShearWarpEngine
  shearwarp/ShearWarpFactorization
  shearwarp/ShearWarpPartition)
# Test oracles and phantoms: not linked into the module (no public class needs them).
set(_av_reference_sources
  reference/Phantoms
  reference/ReferenceComposite
  reference/ReferenceRenderer)

# ACCELVOLUME_PREBUILT_CORE: the AccelVolumeCore library of another build of these sources with
# the same compiler and build type, used instead of compiling Core again (the top-level build
# passes its own to the ParaView plugin's sub-build). Core uses no VTK, so the plugin's VTK does
# not matter. AccelVolumeReference (tests only) is then not defined.
set(ACCELVOLUME_PREBUILT_CORE "" CACHE FILEPATH
  "A built AccelVolumeCore static library to link instead of compiling Rendering/Core")
if (NOT TARGET AccelVolumeCore AND ACCELVOLUME_PREBUILT_CORE)
  find_package(Threads REQUIRED)
  add_library(AccelVolumeCore STATIC IMPORTED)
  set_target_properties(AccelVolumeCore PROPERTIES
    IMPORTED_LOCATION "${ACCELVOLUME_PREBUILT_CORE}"
    INTERFACE_INCLUDE_DIRECTORIES "${_av_core_root}"
    INTERFACE_LINK_LIBRARIES Threads::Threads)
elseif (NOT TARGET AccelVolumeCore)
  list(TRANSFORM _av_core_sources PREPEND "${_av_core_root}/")
  list(TRANSFORM _av_core_sources APPEND ".cxx")
  list(TRANSFORM _av_reference_sources PREPEND "${_av_core_root}/")
  list(TRANSFORM _av_reference_sources APPEND ".cxx")
  find_package(Threads REQUIRED)
  foreach (_av_core_target IN ITEMS AccelVolumeCore AccelVolumeReference)
    if (_av_core_target STREQUAL "AccelVolumeCore")
      add_library(${_av_core_target} STATIC ${_av_core_sources})
      target_link_libraries(${_av_core_target} PUBLIC Threads::Threads)
    else ()
      add_library(${_av_core_target} STATIC ${_av_reference_sources})
      target_link_libraries(${_av_core_target} PUBLIC AccelVolumeCore)
    endif ()
    target_include_directories(${_av_core_target} PUBLIC "$<BUILD_INTERFACE:${_av_core_root}>")
    # Linked into the shared module: position-independent, symbols hidden there.
    set_target_properties(${_av_core_target} PROPERTIES
      POSITION_INDEPENDENT_CODE ON
      CXX_VISIBILITY_PRESET hidden
      VISIBILITY_INLINES_HIDDEN ON
      CXX_STANDARD 17
      CXX_STANDARD_REQUIRED ON
      CXX_EXTENSIONS OFF)
  endforeach ()
  # The ray caster's lane loops vectorise square roots only without errno, and selects between
  # two computed values (a division or square root in the unused arm) only without trapping
  # maths (results unchanged either way: IEEE operations, only errno and exception traps go);
  # they never contract a * b + c into FMA, so that every SIMD target (RayCastKernelBatch.inl's
  # clones) gives the same bits.
  if (CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    set_source_files_properties("${_av_core_root}/raycast/RayCastKernel8Bit.cxx"
      "${_av_core_root}/raycast/RayCastKernel16Bit.cxx" "${_av_core_root}/raycast/RayCastKernel32Bit.cxx"
      "${_av_core_root}/raycast/RayCastKernel64Bit.cxx" PROPERTIES COMPILE_OPTIONS "-fno-math-errno;-fno-trapping-math;-ffp-contract=off")
    # The packets set rays up in AVX-512 lanes with the operations of Affine::Apply and
    # IntersectRayRegion, the footprint projects box corners in lanes as ProjectBox does and the
    # displayed images convert to 16 bits in lanes: those must not contract either (only an
    # -march build could).
    set_source_files_properties("${_av_core_root}/common/Affine.cxx"
      "${_av_core_root}/common/Geometry.cxx" "${_av_core_root}/common/Unorm16.cxx"
      "${_av_core_root}/skipping/ScreenFootprint.cxx" PROPERTIES COMPILE_OPTIONS "-ffp-contract=off")
  endif ()
endif ()
