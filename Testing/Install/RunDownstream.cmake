# Packaging test driver (one ctest test per MODE):
#   cmake -DMODE=install|build -DBUILD_DIR=<AccelVolume build> -DWORK_DIR=<scratch folder>
#         [-DSOURCE_DIR=<Downstream project>] [-DGENERATOR=...] [-DCXX_COMPILER=...] [-DC_COMPILER=...]
#         [-DBUILD_TYPE=Release] [-DGL=osmesa] [-DLIBDIR=lib]
#         [-DPYTHON=/usr/bin/python3 -DPYTHON_DEST=<package folder, relative>
#          -DVTK_PYTHONPATH=<folder of vtkmodules>] -P RunDownstream.cmake
# MODE=install: `cmake --install BUILD_DIR --prefix WORK_DIR/prefix`, checks the installed
#   layout and the library's run path, then builds the downstream project against the prefix.
# MODE=build: builds the downstream project against BUILD_DIR/LIBDIR/cmake/AccelVolume.
# Either way it then runs the downstream program with ACCELVOLUME_GL=GL and, when PYTHON is
# given (the module was wrapped), the downstream Python script Downstream/downstream.py with
# PYTHONPATH = the prefix's (or build tree's) package folder + VTK's.
cmake_minimum_required(VERSION 3.12)

foreach (_var IN ITEMS MODE BUILD_DIR WORK_DIR)
  if (NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
    message(FATAL_ERROR "RunDownstream.cmake: -D${_var}=... is required")
  endif ()
endforeach ()
if (NOT DEFINED SOURCE_DIR)
  set(SOURCE_DIR "${CMAKE_CURRENT_LIST_DIR}/Downstream")
endif ()
if (NOT DEFINED BUILD_TYPE OR BUILD_TYPE STREQUAL "")
  set(BUILD_TYPE Release)
endif ()
if (NOT DEFINED GL OR GL STREQUAL "")
  set(GL osmesa)
endif ()
if (NOT DEFINED LIBDIR OR LIBDIR STREQUAL "")
  set(LIBDIR lib)
endif ()

function (av_step name)
  string(TIMESTAMP _t0 "%s")
  execute_process(COMMAND ${ARGN}
    RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  string(TIMESTAMP _t1 "%s")
  math(EXPR _dt "${_t1} - ${_t0}")
  if (NOT _rc EQUAL 0)
    message("${_out}")
    message(FATAL_ERROR "[${MODE}] ${name} failed (${_rc}): ${ARGN}")
  endif ()
  message(STATUS "[${MODE}] ${name}: ok (${_dt} s)")
  set(av_step_output "${_out}" PARENT_SCOPE)
endfunction ()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(_downstream_build "${WORK_DIR}/downstream-build")

if (MODE STREQUAL "install")
  set(_prefix "${WORK_DIR}/prefix")
  av_step("cmake --install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${_prefix}"
    --config "${BUILD_TYPE}")

  # The installed layout the package promises.
  set(_missing)
  foreach (_file IN ITEMS
      include/AccelVolume/vtkAccelVolumeSliceMapper.h
      include/AccelVolume/vtkAccelVolumeHeadlessRenderWindow.h
      include/AccelVolume/vtkRenderingAccelVolumeModule.h
      ${LIBDIR}/libvtkRenderingAccelVolume.so
      ${LIBDIR}/cmake/AccelVolume/AccelVolumeConfig.cmake
      ${LIBDIR}/cmake/AccelVolume/AccelVolumeConfigVersion.cmake
      ${LIBDIR}/cmake/AccelVolume/AccelVolume-targets.cmake
      ${LIBDIR}/cmake/AccelVolume/AccelVolume-vtk-module-properties.cmake)
    if (NOT EXISTS "${_prefix}/${_file}")
      list(APPEND _missing "${_file}")
    endif ()
  endforeach ()
  if (_missing)
    message(FATAL_ERROR "[install] missing from ${_prefix}: ${_missing}")
  endif ()
  # No private headers, and no reference to the build or source tree in the package files.
  file(GLOB _headers RELATIVE "${_prefix}/include/AccelVolume" "${_prefix}/include/AccelVolume/*")
  message(STATUS "[install] headers: ${_headers}")
  file(GLOB _pkg_files "${_prefix}/${LIBDIR}/cmake/AccelVolume/*.cmake")
  foreach (_pkg_file IN LISTS _pkg_files)
    file(READ "${_pkg_file}" _text)
    string(FIND "${_text}" "${BUILD_DIR}" _at)
    if (NOT _at EQUAL -1)
      message(FATAL_ERROR "[install] ${_pkg_file} refers to the build tree ${BUILD_DIR}")
    endif ()
  endforeach ()

  # Run path of the installed library: it may only point inside the prefix ($ORIGIN...) or be
  # absent; every dependency must resolve (to system libraries) without the build tree.
  file(REAL_PATH "${_prefix}/${LIBDIR}/libvtkRenderingAccelVolume.so" _lib)
  find_program(_readelf NAMES readelf)
  if (_readelf)
    execute_process(COMMAND "${_readelf}" -d "${_lib}" OUTPUT_VARIABLE _dyn RESULT_VARIABLE _rc)
    string(REGEX MATCHALL "\\((RPATH|RUNPATH)\\)[^\n]*" _paths "${_dyn}")
    message(STATUS "[install] run path: ${_paths}")
    foreach (_p IN LISTS _paths)
      if (NOT _p MATCHES "\\[(\\$ORIGIN[^]]*)?\\]$")
        message(FATAL_ERROR "[install] the installed library's run path is not relocatable: ${_p}")
      endif ()
    endforeach ()
  endif ()
  find_program(_ldd NAMES ldd)
  if (_ldd)
    execute_process(COMMAND "${_ldd}" "${_lib}" OUTPUT_VARIABLE _deps RESULT_VARIABLE _rc)
    if (_deps MATCHES "not found" OR _deps MATCHES "${BUILD_DIR}/")
      message(FATAL_ERROR "[install] unresolved or build-tree dependencies:\n${_deps}")
    endif ()
  endif ()

  set(_find_args "-DCMAKE_PREFIX_PATH=${_prefix}")
  set(_expected_lib_dir "${_prefix}/${LIBDIR}")
elseif (MODE STREQUAL "build")
  set(_find_args "-DAccelVolume_DIR=${BUILD_DIR}/${LIBDIR}/cmake/AccelVolume")
  set(_expected_lib_dir "${BUILD_DIR}/${LIBDIR}")
else ()
  message(FATAL_ERROR "RunDownstream.cmake: MODE must be install or build, not '${MODE}'")
endif ()

set(_configure "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${_downstream_build}"
  "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}" ${_find_args})
if (GENERATOR)
  list(APPEND _configure -G "${GENERATOR}")
endif ()
if (CXX_COMPILER)
  list(APPEND _configure "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif ()
if (C_COMPILER)
  list(APPEND _configure "-DCMAKE_C_COMPILER=${C_COMPILER}")
endif ()
av_step("configure downstream" ${_configure})
string(REGEX MATCH "AccelVolume [^\n]* from [^\n]*" _found "${av_step_output}")
message(STATUS "[${MODE}] ${_found}")
if (MODE STREQUAL "install" AND NOT _found MATCHES " from ${_prefix}/")
  message(FATAL_ERROR "[install] the downstream project did not find the installed package")
endif ()

av_step("build downstream" "${CMAKE_COMMAND}" --build "${_downstream_build}" --config "${BUILD_TYPE}")

set(_exe "${_downstream_build}/accelvolume_downstream")
if (NOT EXISTS "${_exe}")
  file(GLOB_RECURSE _exe "${_downstream_build}/accelvolume_downstream" "${_downstream_build}/accelvolume_downstream.exe")
  list(GET _exe 0 _exe)
endif ()

# The program must load the library from the tree it was built against.
find_program(_ldd NAMES ldd)
if (_ldd)
  execute_process(COMMAND "${_ldd}" "${_exe}" OUTPUT_VARIABLE _deps)
  string(REGEX MATCH "libvtkRenderingAccelVolume[^\n]*=> *[^ \n]+" _resolved "${_deps}")
  message(STATUS "[${MODE}] ${_resolved}")
  if (NOT _resolved MATCHES "=> *${_expected_lib_dir}/")
    message(FATAL_ERROR "[${MODE}] the downstream program does not load AccelVolume from ${_expected_lib_dir}:\n${_deps}")
  endif ()
endif ()

av_step("run downstream (ACCELVOLUME_GL=${GL})" "${CMAKE_COMMAND}" -E env "ACCELVOLUME_GL=${GL}" "${_exe}")
message("${av_step_output}")

if (PYTHON AND PYTHON_DEST)
  if (MODE STREQUAL "install")
    set(_python_root "${_prefix}")
    foreach (_file IN ITEMS "${PYTHON_DEST}/accelvolume/__init__.py")
      if (NOT EXISTS "${_prefix}/${_file}")
        message(FATAL_ERROR "[install] missing from ${_prefix}: ${_file}")
      endif ()
    endforeach ()
    file(GLOB _extensions "${_prefix}/${PYTHON_DEST}/accelvolume/vtkRenderingAccelVolume*.so")
    if (NOT _extensions)
      message(FATAL_ERROR "[install] no extension module in ${_prefix}/${PYTHON_DEST}/accelvolume")
    endif ()
  else ()
    set(_python_root "${BUILD_DIR}")
  endif ()
  set(_pythonpath "${_python_root}/${PYTHON_DEST}")
  if (VTK_PYTHONPATH)
    string(APPEND _pythonpath ":${VTK_PYTHONPATH}")
  endif ()
  # Run from the work folder so nothing in the source tree shadows the package.
  av_step("run downstream Python (ACCELVOLUME_GL=${GL})" "${CMAKE_COMMAND}" -E chdir "${WORK_DIR}"
    "${CMAKE_COMMAND}" -E env "PYTHONPATH=${_pythonpath}" PYTHONNOUSERSITE=1
    "ACCELVOLUME_GL=${GL}" "ACCELVOLUME_EXPECT_DIR=${_python_root}"
    "${PYTHON}" "${SOURCE_DIR}/downstream.py")
  message("${av_step_output}")
else ()
  message(STATUS "[${MODE}] no Python wrapping: downstream Python script not run")
endif ()
