# The one VTK module's build definition, shared by the standalone build (Module/CMakeLists.txt)
# and the Remote/ build (top-level CMakeLists.txt).
get_filename_component(_av_root "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)

# Core (Rendering/Core, plain C++17: no VTK or GL headers, never in public headers), built once
# as one static library that the module, the tests, the benchmarks and the CLI link. The module
# links it privately and keeps its symbols hidden, so a program that links both gets no clash.
# The CPU oracles and phantoms (reference/) are a library of their own: the module needs none of
# them; the tests, the CLI (its built-in volume) and the benchmarks link it.
include("${CMAKE_CURRENT_LIST_DIR}/AccelVolumeCore.cmake")

# Public VTK-style classes (headers installed, wrappable): Rendering/AccelVolume/.
set(_av_classes
  vtkAccelVolumeMapper
  vtkAccelVolumeHeadlessRenderWindow
  vtkAccelVolumeMinMaxOctree
  vtkAccelVolumeRayCastMapper
  vtkAccelVolumeShearWarpMapper
  vtkAccelVolumeSmartMapper
  vtkAccelVolumeSliceMapper)

# Thin OpenGL / VTK helpers (Rendering/AccelVolume/Private/), excluded from wrapping and
# installation.
set(_av_private_sources
  vtkAccelVolumeBrickCache
  vtkAccelVolumeCPUMask
  vtkAccelVolumeDepthCopy
  vtkAccelVolumeDepthPeeling
  vtkAccelVolumeGPUClassifier
  vtkAccelVolumeImageDisplay
  vtkAccelVolumeInputAdapter
  vtkAccelVolumeMapperSupport
  vtkAccelVolumeMPIExchange
  vtkAccelVolumeObjectFactory
  vtkAccelVolumeOctreeGPUBuilder
  vtkAccelVolumeRenderProgress
  vtkAccelVolumeScalarEncoding
  vtkAccelVolumeSliceCompute
  vtkAccelVolumeSliceDraw
  vtkAccelVolumeSliceGeometry
  vtkAccelVolumeSliceMask
  vtkAccelVolumeSlicePasses
  vtkAccelVolumeSliceResolve
  vtkAccelVolumeSliceResources
  vtkAccelVolumeWorkers)

set(_av_shaders
  AccelVolumeSliceVS
  AccelVolumeSliceFS
  AccelVolumeSliceComponentsFS
  AccelVolumeSliceSampling
  AccelVolumeSliceCS
  AccelVolumeResolveVS
  AccelVolumeResolveFS
  AccelVolumeImageFS
  AccelVolumeWarpVS
  AccelVolumeWarpFS
  AccelVolumeTerminationFS
  AccelVolumeDepthDownsampleFS
  AccelVolumeOctreeLeafCS
  AccelVolumeOctreeReduceCS
  AccelVolumeOctreeClassifyCS)

set(_av_vtk_dir "${_av_root}/Rendering/AccelVolume")
set(_av_class_files)
set(_av_headers)
foreach (_av_class IN LISTS _av_classes)
  list(APPEND _av_class_files "${_av_vtk_dir}/${_av_class}.cxx")
  list(APPEND _av_headers "${_av_vtk_dir}/${_av_class}.h")
endforeach ()
set(_av_sources)
set(_av_private_headers)
foreach (_av_source IN LISTS _av_private_sources)
  list(APPEND _av_sources "${_av_vtk_dir}/Private/${_av_source}.cxx")
  list(APPEND _av_private_headers "${_av_vtk_dir}/Private/${_av_source}.h")
endforeach ()
list(APPEND _av_private_headers "${_av_vtk_dir}/Private/vtkAccelVolumeMinMaxOctreeInternals.h"
  "${_av_vtk_dir}/Private/vtkAccelVolumeSliceMapperInternals.h")
# vtkAccelVolumeSliceMapper's vtkGPUVolumeRayCastMapper API members, apart from its rendering.
list(APPEND _av_sources "${_av_vtk_dir}/vtkAccelVolumeSliceMapperVTKAPI.cxx")
# ... and its frame settings for shading, components and masks (members of its vtkInternals).
list(APPEND _av_sources "${_av_vtk_dir}/Private/vtkAccelVolumeSliceFrameFill.cxx")
# ... and its empty-leaf classification (one octree per contributing component).
list(APPEND _av_sources "${_av_vtk_dir}/Private/vtkAccelVolumeSliceLeaves.cxx")
# The CPU mappers' multi-component tables (vtkAccelVolumeCPUInputs members, MapperSupport.h).
list(APPEND _av_sources "${_av_vtk_dir}/Private/vtkAccelVolumeCPUComponents.cxx")

if (NOT COMMAND vtk_encode_string)
  include("${VTK_DIR}/vtkEncodeString.cmake" OPTIONAL RESULT_VARIABLE _av_encode_found)
  if (NOT _av_encode_found)
    include(vtkEncodeString)
  endif ()
endif ()
foreach (_av_shader IN LISTS _av_shaders)
  vtk_encode_string(
    INPUT         "${_av_vtk_dir}/Shaders/${_av_shader}.glsl"
    HEADER_OUTPUT _av_shader_header
    SOURCE_OUTPUT _av_shader_source)
  list(APPEND _av_sources "${_av_shader_source}")
  list(APPEND _av_private_headers "${_av_shader_header}")
endforeach ()

set(_av_have_osmesa 0)
set(_av_have_egl 0)
if (NOT DEFINED ACCELVOLUME_ENABLE_OSMESA OR ACCELVOLUME_ENABLE_OSMESA)
  find_path(ACCELVOLUME_OSMESA_INCLUDE_DIR GL/osmesa.h)
  find_library(ACCELVOLUME_OSMESA_LIBRARY OSMesa)
  if (ACCELVOLUME_OSMESA_INCLUDE_DIR AND ACCELVOLUME_OSMESA_LIBRARY)
    set(_av_have_osmesa 1)
    list(APPEND _av_sources "${_av_vtk_dir}/Private/vtkAccelVolumeOSMesaLoader.cxx")
  endif ()
endif ()
if (NOT DEFINED ACCELVOLUME_ENABLE_EGL OR ACCELVOLUME_ENABLE_EGL)
  find_path(ACCELVOLUME_EGL_INCLUDE_DIR EGL/egl.h)
  find_library(ACCELVOLUME_EGL_LIBRARY EGL)
  if (ACCELVOLUME_EGL_INCLUDE_DIR AND ACCELVOLUME_EGL_LIBRARY)
    set(_av_have_egl 1)
  endif ()
endif ()
message(STATUS "AccelVolume headless backends: OSMesa=${_av_have_osmesa} EGL=${_av_have_egl}")

vtk_module_add_module(VTK::RenderingAccelVolume
  SOURCES         ${_av_class_files} ${_av_sources}
  HEADERS         ${_av_headers}
  PRIVATE_HEADERS ${_av_private_headers})

# Inline functions (Core's implicit destructors and copies among them) stay inside the module:
# Core's symbols must not be exported (Testing/Symbols/CheckHiddenCore.py).
vtk_module_compile_options(VTK::RenderingAccelVolume PRIVATE -fvisibility-inlines-hidden)

vtk_module_include(VTK::RenderingAccelVolume
  PUBLIC  "$<BUILD_INTERFACE:${_av_vtk_dir}>"
  PRIVATE "${_av_vtk_dir}/Private")
vtk_module_definitions(VTK::RenderingAccelVolume
  PRIVATE
    ACCELVOLUME_HAVE_OSMESA=${_av_have_osmesa}
    ACCELVOLUME_HAVE_EGL=${_av_have_egl})

if (_av_have_osmesa)
  vtk_module_include(VTK::RenderingAccelVolume PRIVATE "${ACCELVOLUME_OSMESA_INCLUDE_DIR}")
  # PUBLIC and not as-needed: executables must list libOSMesa before glvnd's libOpenGL so the
  # GL 1.1 entry points VTK calls directly reach the current OSMesa context (ENVIRONMENT.md).
  vtk_module_link(VTK::RenderingAccelVolume
    PUBLIC "-Wl,--no-as-needed" "${ACCELVOLUME_OSMESA_LIBRARY}")
endif ()
if (_av_have_egl)
  vtk_module_include(VTK::RenderingAccelVolume PRIVATE "${ACCELVOLUME_EGL_INCLUDE_DIR}")
  vtk_module_link(VTK::RenderingAccelVolume PRIVATE "${ACCELVOLUME_EGL_LIBRARY}")
endif ()
find_package(Threads REQUIRED)
vtk_module_link(VTK::RenderingAccelVolume PRIVATE AccelVolumeCore ${CMAKE_DL_LIBS} Threads::Threads)
# A CPU mapper's thread count as a kept TBB task arena (vtkAccelVolumeWorkers: VTK 9.1's
# LocalScope does not hold it); without TBB, std::threads per loop.
find_package(TBB CONFIG QUIET)
if (TARGET TBB::tbb)
  vtk_module_link(VTK::RenderingAccelVolume PRIVATE TBB::tbb)
  vtk_module_definitions(VTK::RenderingAccelVolume PRIVATE ACCELVOLUME_HAVE_TBB=1)
else ()
  vtk_module_definitions(VTK::RenderingAccelVolume PRIVATE ACCELVOLUME_HAVE_TBB=0)
endif ()
