# Writes the AccelVolume CMake package (vtk_module_build exports targets but writes no config),
# usable from the build tree and from an install prefix.
include(CMakePackageConfigHelpers)
set(_av_package_dir "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}/cmake/AccelVolume")
configure_file("${CMAKE_CURRENT_LIST_DIR}/AccelVolumeConfig.cmake.in"
  "${_av_package_dir}/AccelVolumeConfig.cmake" @ONLY)
write_basic_package_version_file("${_av_package_dir}/AccelVolumeConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMajorVersion)
install(FILES
  "${_av_package_dir}/AccelVolumeConfig.cmake"
  "${_av_package_dir}/AccelVolumeConfigVersion.cmake"
  DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/AccelVolume")
