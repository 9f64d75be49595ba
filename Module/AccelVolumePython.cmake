# Python wrapping of VTK::RenderingAccelVolume with VTK's own wrapping tools (vtkWrapPython),
# as the package `accelvolume`:
#   import accelvolume
#   mapper = accelvolume.vtkAccelVolumeRayCastMapper()
# Standalone build only. Included by the top-level CMakeLists.txt after find_package(VTK)
# (which asked for the optional components WrappingPythonCore and Python) and before
# vtk_module_build, so that Testing/ sees ACCELVOLUME_WRAP_PYTHON; accelvolume_wrap_python()
# is called after vtk_module_build.
#
# Build tree: ${CMAKE_BINARY_DIR}/${ACCELVOLUME_PYTHON_MODULE_DESTINATION}/accelvolume/
#   (run with PYTHONPATH=<that dir>:<VTK's vtkmodules dir>, e.g. /usr/lib/python3/dist-packages).
# Install tree: the same relative path under CMAKE_INSTALL_PREFIX (tested by the packaging
#   tests, label "install": Testing/Install/Downstream/downstream.py).

set(_av_python_found OFF)
# VTK imports every target whatever was found: test the components (Python needs Python3).
if (VTK_WRAP_PYTHON AND VTK_WrappingPythonCore_FOUND AND VTK_Python_FOUND AND
    TARGET VTK::WrapPython AND COMMAND vtk_module_wrap_python)
  set(_av_python_found ON)
endif ()

if (DEFINED ACCELVOLUME_WRAP_PYTHON)
  if (ACCELVOLUME_WRAP_PYTHON AND NOT _av_python_found)
    message(FATAL_ERROR
      "ACCELVOLUME_WRAP_PYTHON is ON but VTK's Python wrapping was not found (VTK components "
      "WrappingPythonCore and Python, Python ${VTK_PYTHON_VERSION} headers: python3-dev). "
      "Set Python3_EXECUTABLE to the Python VTK was built for, or ACCELVOLUME_WRAP_PYTHON=OFF.")
  endif ()
else ()
  if (NOT _av_python_found)
    message(STATUS
      "AccelVolume: Python wrapping OFF (VTK's WrappingPythonCore/Python components or Python "
      "development files not found; install python3-dev and set Python3_EXECUTABLE)")
  endif ()
endif ()
option(ACCELVOLUME_WRAP_PYTHON "Wrap the module for Python (package accelvolume)" ${_av_python_found})

if (NOT ACCELVOLUME_WRAP_PYTHON)
  return()
endif ()

if (DEFINED VTK_PYTHONPATH AND NOT VTK_PYTHONPATH STREQUAL "")
  set(_av_python_destination "${VTK_PYTHONPATH}")
else ()
  set(_av_python_destination "${CMAKE_INSTALL_LIBDIR}/python${VTK_PYTHON_VERSION}/site-packages")
endif ()
set(ACCELVOLUME_PYTHON_MODULE_DESTINATION "${_av_python_destination}" CACHE STRING
  "Where the Python package accelvolume goes, relative to the build tree and the install prefix")
# Where VTK's own package (vtkmodules) lives, for the tests' PYTHONPATH.
if (NOT ACCELVOLUME_VTK_PYTHONPATH) # retried while empty
  execute_process(
    COMMAND "${Python3_EXECUTABLE}" -c
      "import os, vtkmodules; print(os.path.dirname(os.path.dirname(vtkmodules.__file__)))"
    OUTPUT_VARIABLE _av_vtk_pythonpath
    OUTPUT_STRIP_TRAILING_WHITESPACE
    ERROR_QUIET)
  set(ACCELVOLUME_VTK_PYTHONPATH "${_av_vtk_pythonpath}" CACHE PATH
    "Folder holding VTK's vtkmodules package (tests' PYTHONPATH)" FORCE)
endif ()
# The tests' and examples' PYTHONPATH: the build tree's package, then VTK's.
set(ACCELVOLUME_TEST_PYTHONPATH
  "${CMAKE_BINARY_DIR}/${ACCELVOLUME_PYTHON_MODULE_DESTINATION}:${ACCELVOLUME_VTK_PYTHONPATH}")
message(STATUS "AccelVolume: Python wrapping ON (${Python3_EXECUTABLE}, package accelvolume in "
  "${ACCELVOLUME_PYTHON_MODULE_DESTINATION}; vtkmodules from ${ACCELVOLUME_VTK_PYTHONPATH})")

function (accelvolume_wrap_python)
  # Name the extension like VTK's own (vtkFoo.cpython-311-x86_64-linux-gnu.so).
  set(_av_soabi)
  if (Python3_SOABI)
    set(_av_soabi SOABI "${Python3_SOABI}")
  endif ()
  vtk_module_wrap_python(
    MODULES            ${ARGN}
    TARGET             AccelVolume::PythonModules
    WRAPPED_MODULES    _av_wrapped_modules
    PYTHON_PACKAGE     accelvolume
    MODULE_DESTINATION "${ACCELVOLUME_PYTHON_MODULE_DESTINATION}"
    LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    CMAKE_DESTINATION  "${CMAKE_INSTALL_LIBDIR}/cmake/AccelVolume"
    BUILD_STATIC       OFF
    INSTALL_HEADERS    OFF
    COMPONENT          python
    ${_av_soabi})
  if (NOT _av_wrapped_modules)
    message(FATAL_ERROR "AccelVolume: vtk_module_wrap_python wrapped no module")
  endif ()

  # The package's __init__.py, in the build tree and installed beside the extension module.
  set(_av_package_dir "${CMAKE_BINARY_DIR}/${ACCELVOLUME_PYTHON_MODULE_DESTINATION}/accelvolume")
  file(GENERATE OUTPUT "${_av_package_dir}/__init__.py" CONTENT [=[
"""AccelVolume: accelerated volume mappers for VTK (module VTK::RenderingAccelVolume).

Classes: vtkAccelVolumeSliceMapper, vtkAccelVolumeRayCastMapper, vtkAccelVolumeShearWarpMapper,
vtkAccelVolumeSmartMapper, vtkAccelVolumeMinMaxOctree, vtkAccelVolumeHeadlessRenderWindow.

Importing this package loads the module library, whose auto-initialisation registers its
object factory: vtkRenderWindow() then gives a headless window when there is no display (or
when ACCELVOLUME_GL=egl|osmesa).
"""

import os as _os
import sys as _sys

# Load the module library first, into the global symbol scope, as a C++ program linking it has
# it. The OSMesa backend needs the module's glXGetProcAddress shim and libOSMesa's gl* entry
# points to come before glvnd's libGLX / libOpenGL when libGLEW and libvtkRenderingOpenGL2
# resolve them, and libGLEW binds glXGetProcAddressARB when it is loaded: so this must be what
# loads VTK's OpenGL libraries. (Python loads extension modules with RTLD_LOCAL.)
_gl_loaded_before = "vtkmodules.vtkRenderingOpenGL2" in _sys.modules
_flags = _sys.getdlopenflags()
_sys.setdlopenflags(_flags | _os.RTLD_GLOBAL)
try:
    from .vtkRenderingAccelVolume import *  # noqa: F401,F403
finally:
    _sys.setdlopenflags(_flags)
del _flags

# VTK's OpenGL2 classes (the render windows the module's factory stands in for, VTK's mappers).
from vtkmodules import vtkRenderingOpenGL2 as _vtkRenderingOpenGL2  # noqa: F401,E402
from vtkmodules import vtkRenderingVolumeOpenGL2 as _vtkRenderingVolumeOpenGL2  # noqa: F401,E402

if _gl_loaded_before and vtkAccelVolumeHeadlessRenderWindow.IsBackendAvailable(  # noqa: F405
        vtkAccelVolumeHeadlessRenderWindow.BACKEND_OSMESA):  # noqa: F405
    import warnings as _warnings

    _warnings.warn(
        "accelvolume was imported after vtkmodules.vtkRenderingOpenGL2: the OSMesa headless "
        "backend will not work in this process (import accelvolume first, or use "
        "ACCELVOLUME_GL=egl)", RuntimeWarning, stacklevel=2)
]=])
  install(FILES "${_av_package_dir}/__init__.py"
    DESTINATION "${ACCELVOLUME_PYTHON_MODULE_DESTINATION}/accelvolume"
    COMPONENT   python)

  # Installed extension modules find libvtkRenderingAccelVolume in the library folder.
  file(RELATIVE_PATH _av_rel
    "/prefix/${ACCELVOLUME_PYTHON_MODULE_DESTINATION}/accelvolume"
    "/prefix/${CMAKE_INSTALL_LIBDIR}")
  foreach (_av_module IN LISTS _av_wrapped_modules)
    # VTK 9.1 has no public getter for a module's library name; its wrapping uses this one.
    _vtk_module_get_module_property("${_av_module}" PROPERTY library_name VARIABLE _av_library_name)
    if (NOT TARGET "${_av_library_name}Python")
      message(FATAL_ERROR "AccelVolume: no Python target ${_av_library_name}Python")
    endif ()
    set_target_properties("${_av_library_name}Python" PROPERTIES
      INSTALL_RPATH "$ORIGIN;$ORIGIN/${_av_rel}")
  endforeach ()
endfunction ()
