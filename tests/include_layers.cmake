# The folders of colmap_plugin in layers, lowest first: a file may include
# its own folder, the folders below it, and the public headers
# (tmr/colmap/*.h) of those folders; each public header belongs to the
# folder that implements it. tools/ and tests/ include public headers only;
# libtmr includes nothing of COLMAP. Fails with
# every include that points the wrong way (docs/design.md).
# Usage: cmake -DSOURCE_DIR=<project> -P include_layers.cmake
cmake_minimum_required(VERSION 3.22)
set(layers io synthetic sfm evaluation merge controllers)
set(owner_match_consistency_options.h sfm)
set(owner_model_evaluation.h evaluation)
set(owner_model_refinement.h merge)
set(owner_reconstruct_images.h controllers)
set(owner_synthetic_scene.h synthetic)
set(owner_synthetic_task_results.h controllers)
set(owner_task_report.h merge)
set(owner_tmr_mapper.h controllers)

set(plugin ${SOURCE_DIR}/colmap_plugin)
list(JOIN layers "|" any_layer)
set(errors "")

# The layer of an include or of a file ("" when it has none): its folder,
# or the owner of the public header it names.
function(layer_of path out)
  set(layer "")
  if(path MATCHES "^(src/)?(${any_layer})/")
    set(layer ${CMAKE_MATCH_2})
  elseif(path MATCHES "^(include/)?tmr/colmap/(.+)$")
    set(layer "${owner_${CMAKE_MATCH_2}}")
  endif()
  set(${out} "${layer}" PARENT_SCOPE)
endfunction()

file(GLOB headers RELATIVE ${plugin}/include/tmr/colmap
     ${plugin}/include/tmr/colmap/*.h)
foreach(header IN LISTS headers)
  if(NOT DEFINED owner_${header})
    string(APPEND errors "include/tmr/colmap/${header}: in no layer "
                         "(set owner_${header} in ${CMAKE_CURRENT_LIST_FILE})\n")
  endif()
endforeach()

file(GLOB_RECURSE files RELATIVE ${plugin}
     ${plugin}/src/*.h ${plugin}/src/*.cc ${plugin}/include/*.h)
foreach(file IN LISTS files)
  if(file MATCHES "^src/([^/]+)/")
    set(folder ${CMAKE_MATCH_1})
    if(NOT folder IN_LIST layers)
      string(APPEND errors "${file}: folder ${folder} is in no layer\n")
      continue()
    endif()
  endif()
  layer_of("${file}" layer)
  if(layer STREQUAL "")
    continue()  # a public header without owner, reported above
  endif()
  list(FIND layers ${layer} rank)
  file(STRINGS ${plugin}/${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]")
  foreach(line IN LISTS lines)
    string(REGEX MATCH "[\"<]([^\">]+)[\">]" quoted "${line}")
    layer_of("${CMAKE_MATCH_1}" included_layer)
    if(included_layer STREQUAL "")
      continue()
    endif()
    list(FIND layers ${included_layer} included_rank)
    if(included_rank GREATER rank)
      string(APPEND errors "${file} includes ${CMAKE_MATCH_1}: "
                           "${included_layer} is above ${layer}\n")
    endif()
  endforeach()
endforeach()

# Programs and integration tests use the public headers only.
file(GLOB_RECURSE outside_files RELATIVE ${SOURCE_DIR}
     ${SOURCE_DIR}/tools/*.h ${SOURCE_DIR}/tools/*.cc
     ${SOURCE_DIR}/tests/*.h ${SOURCE_DIR}/tests/*.cc)
list(FILTER outside_files EXCLUDE REGEX "^tests/include_layers_fixture/")
foreach(file IN LISTS outside_files)
  file(STRINGS ${SOURCE_DIR}/${file} lines
       REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<](${any_layer})/")
  foreach(line IN LISTS lines)
    string(APPEND errors "${file}: ${line} (colmap_plugin's private code)\n")
  endforeach()
endforeach()

file(GLOB_RECURSE libtmr_files RELATIVE ${SOURCE_DIR}
     ${SOURCE_DIR}/libtmr/*.h ${SOURCE_DIR}/libtmr/*.cc)
foreach(file IN LISTS libtmr_files)
  file(STRINGS ${SOURCE_DIR}/${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*<colmap/")
  if(lines)
    string(APPEND errors "${file} includes COLMAP\n")
  endif()
endforeach()

if(errors)
  message(FATAL_ERROR "includes that point the wrong way:\n${errors}")
endif()
message(STATUS "colmap_plugin's layers (${layers}) and libtmr hold")
