# Which parts of ppm.h the libppm at hand implements. ppm.h declares the scene-file and
# checkpoint functions before libppm implements them; the module compiles their wrappers only
# when they link, so that it builds and loads against either library.
#
# ppm_python_features(<scene files var> <checkpoints var>) sets both variables to ON or OFF.
include(CheckSymbolExists)

function(ppm_python_features scene_files_var checkpoints_var)
  if(TARGET ppm::ppm AND NOT TARGET ppm)
    # An installed libppm: link a test program against it.
    get_target_property(location ppm::ppm LOCATION)
    get_target_property(includes ppm::ppm INTERFACE_INCLUDE_DIRECTORIES)
    set(CMAKE_REQUIRED_LIBRARIES "${location}")
    set(CMAKE_REQUIRED_INCLUDES "${includes}")
    set(CMAKE_REQUIRED_QUIET ON)
    check_symbol_exists(ppm_scene_file_load "ppm/ppm.h" PPM_PY_LINKS_SCENE_FILES)
    check_symbol_exists(ppm_renderer_save_checkpoint "ppm/ppm.h" PPM_PY_LINKS_CHECKPOINTS)
    set(scene_files OFF)
    set(checkpoints OFF)
    if(PPM_PY_LINKS_SCENE_FILES)
      set(scene_files ON)
    endif()
    if(PPM_PY_LINKS_CHECKPOINTS)
      set(checkpoints ON)
    endif()
  else()
    # libppm is built here from source, so nothing links yet: look for the definitions in
    # its API sources instead ("ppm_status ppm_scene_file_load(" starts a definition line).
    file(GLOB api_sources ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../../../lib/api/*.cpp)
    set(scene_files OFF)
    set(checkpoints OFF)
    foreach(source ${api_sources})
      file(STRINGS ${source} lines REGEX "^ppm_status (ppm_scene_file_load|ppm_renderer_save_checkpoint)\\(")
      if(lines MATCHES "ppm_scene_file_load")
        set(scene_files ON)
      endif()
      if(lines MATCHES "ppm_renderer_save_checkpoint")
        set(checkpoints ON)
      endif()
    endforeach()
  endif()
  message(STATUS "libppm scene files: ${scene_files}, checkpoints: ${checkpoints}")
  set(${scene_files_var} ${scene_files} PARENT_SCOPE)
  set(${checkpoints_var} ${checkpoints} PARENT_SCOPE)
endfunction()
