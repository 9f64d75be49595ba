# Lets find_package(ParaView) succeed without ParaView's Python package installed.
#
# Debian's paraview-dev exports the targets of ParaView's Python modules and of pvpython, but
# those files are in python3-paraview, which conflicts with python3-vtk9 (the main project's
# Python bindings need that one). Without them CMake's export files stop with "The imported
# target ... references the file ... but this file does not exist". Those files return early
# when every target they define exists already, so when a file they check is missing we
# declare their targets first as empty interface targets. The plugin never links them: it
# needs ParaView's C++ libraries only, and the test finds pvbatch with find_program; pvbatch
# loads the Python modules at run time from wherever PYTHONPATH says (scripts/setup.sh).

# accelvolume_paraview_declare_missing_targets(<ParaView config dir>)
function (accelvolume_paraview_declare_missing_targets config_dir)
  foreach (_avpt_file IN ITEMS
      "${config_dir}/vtk/VTKPython-targets.cmake"
      "${config_dir}/ParaViewPython-targets.cmake"
      "${config_dir}/ParaViewTools-targets.cmake")
    if (NOT EXISTS "${_avpt_file}")
      continue ()
    endif ()
    # The prefix the export file computes: its folder, one level up per PATH step.
    get_filename_component(_avpt_prefix "${_avpt_file}" DIRECTORY)
    file(STRINGS "${_avpt_file}" _avpt_steps
      REGEX "^get_filename_component\\(_IMPORT_PREFIX \"\\\${_IMPORT_PREFIX}\" PATH\\)$")
    foreach (_avpt_step IN LISTS _avpt_steps)
      get_filename_component(_avpt_prefix "${_avpt_prefix}" DIRECTORY)
    endforeach ()

    # Any file the per-configuration export files check that is missing?
    get_filename_component(_avpt_base "${_avpt_file}" NAME_WE)
    get_filename_component(_avpt_dir "${_avpt_file}" DIRECTORY)
    file(GLOB _avpt_config_files "${_avpt_dir}/${_avpt_base}-*.cmake")
    set(_avpt_missing "")
    foreach (_avpt_config_file IN LISTS _avpt_config_files)
      file(STRINGS "${_avpt_config_file}" _avpt_checks REGEX "_cmake_import_check_files_for_")
      foreach (_avpt_check IN LISTS _avpt_checks)
        if (_avpt_check MATCHES "\"\\\${_IMPORT_PREFIX}([^\"]*)\"")
          if (NOT EXISTS "${_avpt_prefix}${CMAKE_MATCH_1}")
            set(_avpt_missing "${_avpt_prefix}${CMAKE_MATCH_1}")
            break ()
          endif ()
        endif ()
      endforeach ()
      if (_avpt_missing)
        break ()
      endif ()
    endforeach ()
    if (NOT _avpt_missing)
      continue ()
    endif ()

    file(STRINGS "${_avpt_file}" _avpt_line
      REGEX "^foreach\\(_cmake_expected_target IN ITEMS ")
    string(REGEX REPLACE "^foreach\\(_cmake_expected_target IN ITEMS (.*)\\)$" "\\1"
      _avpt_targets "${_avpt_line}")
    string(REPLACE " " ";" _avpt_targets "${_avpt_targets}")
    list(LENGTH _avpt_targets _avpt_count)
    message(STATUS "AccelVolume plugin: ${_avpt_missing} is missing (python3-paraview not "
      "installed): declaring the ${_avpt_count} targets of ${_avpt_base} as empty")
    foreach (_avpt_target IN LISTS _avpt_targets)
      if (NOT TARGET "${_avpt_target}")
        add_library("${_avpt_target}" INTERFACE IMPORTED)
      endif ()
    endforeach ()
  endforeach ()
endfunction ()

# accelvolume_paraview_fix_hierarchy_files(<python3-paraview root> [ANCESTORS_OF <class>...])
#
# The client-server wrapping of our representation module reads the wrap hierarchy files of the
# modules it depends on, to learn that its class derives from vtkObjectBase (else it wraps
# nothing, and ParaView aborts with "Failed to create 'vtkAccelVolumeRepresentation'"); Debian
# ships ParaView's hierarchy files in python3-paraview as well. Points the imported modules at
# the copies under <root> (python3-paraview unpacked with dpkg -x, see scripts/setup.sh). Where
# those are missing, drops the dangling paths and writes a small hierarchy of the ANCESTORS_OF
# classes, read from ParaView's headers, for the module that holds the first of them: all the
# wrapper needs for classes whose own methods take and return plain values.
function (accelvolume_paraview_fix_hierarchy_files root)
  cmake_parse_arguments(PARSE_ARGV 1 _avph "" "" "ANCESTORS_OF")
  if (CMAKE_VERSION VERSION_LESS "3.21") # IMPORTED_TARGETS
    return ()
  endif ()
  get_property(_avph_targets DIRECTORY "${CMAKE_SOURCE_DIR}" PROPERTY IMPORTED_TARGETS)
  set(_avph_moved 0)
  set(_avph_dropped 0)
  foreach (_avph_target IN LISTS _avph_targets)
    get_property(_avph_file TARGET "${_avph_target}" PROPERTY INTERFACE_vtk_module_hierarchy)
    if (NOT _avph_file OR EXISTS "${_avph_file}")
      continue ()
    endif ()
    if (root AND EXISTS "${root}${_avph_file}")
      set_property(TARGET "${_avph_target}" PROPERTY
        INTERFACE_vtk_module_hierarchy "${root}${_avph_file}")
      math(EXPR _avph_moved "${_avph_moved} + 1")
    else ()
      set_property(TARGET "${_avph_target}" PROPERTY INTERFACE_vtk_module_hierarchy)
      math(EXPR _avph_dropped "${_avph_dropped} + 1")
    endif ()
  endforeach ()
  if (_avph_moved)
    message(STATUS "AccelVolume plugin: ${_avph_moved} wrap hierarchy files of ParaView's "
      "modules taken from ${root}")
  endif ()
  if (NOT _avph_dropped OR NOT _avph_ANCESTORS_OF)
    return ()
  endif ()

  # Which module (target, library) declares each header.
  foreach (_avph_target IN LISTS _avph_targets)
    get_property(_avph_headers TARGET "${_avph_target}" PROPERTY INTERFACE_vtk_module_headers)
    get_property(_avph_library TARGET "${_avph_target}" PROPERTY INTERFACE_vtk_module_library_name)
    foreach (_avph_header IN LISTS _avph_headers)
      get_filename_component(_avph_class "${_avph_header}" NAME_WE)
      set("_avph_path_${_avph_class}" "${_avph_header}")
      set("_avph_library_${_avph_class}" "${_avph_library}")
      set("_avph_target_${_avph_class}" "${_avph_target}")
    endforeach ()
  endforeach ()
  set(_avph_lines "")
  foreach (_avph_class IN LISTS _avph_ANCESTORS_OF)
    while (_avph_class)
      set(_avph_header "${_avph_path_${_avph_class}}")
      if (NOT EXISTS "${_avph_header}")
        message(FATAL_ERROR "AccelVolume plugin: no header of ${_avph_class} among ParaView's "
          "modules, and no wrap hierarchy files: run scripts/setup.sh (python3-paraview)")
      endif ()
      file(READ "${_avph_header}" _avph_text)
      set(_avph_line "${_avph_class}")
      set(_avph_next "")
      set(_avph_space "[ \t\r\n]")
      if (_avph_text MATCHES "class${_avph_space}+[A-Z0-9_]+_EXPORT${_avph_space}+${_avph_class}\
${_avph_space}*:${_avph_space}*public${_avph_space}+([A-Za-z0-9_]+)")
        set(_avph_next "${CMAKE_MATCH_1}")
        string(APPEND _avph_line " : ${_avph_next}")
      endif ()
      string(APPEND _avph_lines
        "${_avph_line} ; ${_avph_class}.h ; ${_avph_library_${_avph_class}}\n")
      set(_avph_class "${_avph_next}")
    endwhile ()
  endforeach ()
  # The typedefs of the methods vtkTypeMacro declares (IsA, GetNumberOfGenerationsFromBase).
  set(_avph_id_type "int")
  if (EXISTS "${_avph_path_vtkType}")
    get_filename_component(_avph_include_dir "${_avph_path_vtkType}" DIRECTORY)
    file(STRINGS "${_avph_include_dir}/vtkOptions.h" _avph_64bit_ids
      REGEX "^#define VTK_USE_64BIT_IDS")
    if (_avph_64bit_ids)
      set(_avph_id_type "long long")
    endif ()
  endif ()
  string(APPEND _avph_lines "vtkTypeBool = int ; vtkABI.h ; vtkCommonCore\n"
    "vtkIdType = ${_avph_id_type} ; vtkType.h ; vtkCommonCore\n")
  list(GET _avph_ANCESTORS_OF 0 _avph_first)
  set(_avph_owner "${_avph_target_${_avph_first}}")
  set(_avph_file "${CMAKE_BINARY_DIR}/CMakeFiles/accelvolume-paraview-ancestors-hierarchy.txt")
  file(WRITE "${_avph_file}" "${_avph_lines}")
  set_property(TARGET "${_avph_owner}" PROPERTY INTERFACE_vtk_module_hierarchy "${_avph_file}")
  message(STATUS "AccelVolume plugin: ${_avph_dropped} wrap hierarchy files of ParaView's modules "
    "are missing (python3-paraview not unpacked in '${root}'); wrote the ancestors of "
    "${_avph_ANCESTORS_OF} for ${_avph_owner} instead")
endfunction ()
