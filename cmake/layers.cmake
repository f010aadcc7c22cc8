# Per-library include directories. hitl's include strings are root-relative ("engine/hil/session.h")
# so that a header names its layer, but no library exports the repository root: each exports a
# directory of its own in the build tree holding links to only its own source folders. A library
# thus sees the headers of itself and of what it links, nothing else, and an include that runs up
# or across the layers (docs/architecture.md, "The layer table") fails to compile, as Bazel's layering
# check does. tests/layers_test.cpp states the table and checks includes and link dependencies.
#
#   hitl_library_folders(<library> <folder>...)   folders relative to HITL_SOURCE_ROOT
#
# HITL_SOURCE_ROOT is the repository root (set by the top-level project and by target/ configured
# on its own). The names of the libraries it was called for are kept in the global property
# HITL_LAYER_LIBRARIES (for the layer test's link check).
function(hitl_library_folders library)
  if(NOT HITL_SOURCE_ROOT)
    message(FATAL_ERROR "hitl_library_folders: HITL_SOURCE_ROOT is not set")
  endif()
  set(stage ${CMAKE_BINARY_DIR}/layer-include/${library})
  foreach(folder IN LISTS ARGN)
    if(NOT IS_DIRECTORY ${HITL_SOURCE_ROOT}/${folder})
      message(FATAL_ERROR "hitl_library_folders(${library}): no folder ${folder}")
    endif()
    get_filename_component(parent ${stage}/${folder} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    # A link left by a build of a tree that has moved points elsewhere: made again.
    if(IS_SYMLINK ${stage}/${folder})
      file(READ_SYMLINK ${stage}/${folder} linked)
      if(NOT linked STREQUAL "${HITL_SOURCE_ROOT}/${folder}")
        file(REMOVE ${stage}/${folder})
      endif()
    endif()
    if(NOT IS_SYMLINK ${stage}/${folder})
      file(CREATE_LINK ${HITL_SOURCE_ROOT}/${folder} ${stage}/${folder} SYMBOLIC)
    endif()
  endforeach()
  get_target_property(type ${library} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${library} INTERFACE ${stage})
  else()
    target_include_directories(${library} PUBLIC ${stage})
  endif()
  set_property(GLOBAL APPEND PROPERTY HITL_LAYER_LIBRARIES ${library})
  set_property(TARGET ${library} PROPERTY HITL_FOLDERS ${ARGN})
endfunction()

# Writes <file>: one line per library, "library|folder folder|linked linked ...", its folders and
# the targets it links directly (read by tests/layers_test.cpp). Call once at the end of configure.
function(hitl_write_layer_links file)
  get_property(libraries GLOBAL PROPERTY HITL_LAYER_LIBRARIES)
  set(text "")
  foreach(library IN LISTS libraries)
    get_target_property(folders ${library} HITL_FOLDERS)
    get_target_property(type ${library} TYPE)
    if(type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(links ${library} INTERFACE_LINK_LIBRARIES)
    else()
      get_target_property(links ${library} LINK_LIBRARIES)
    endif()
    if(NOT links)
      set(links "")
    endif()
    string(REPLACE ";" " " folders "${folders}")
    string(REPLACE ";" " " links "${links}")
    string(APPEND text "${library}|${folders}|${links}\n")
  endforeach()
  file(WRITE ${file} "${text}")
endfunction()
