# tmr_reconstruct twice on the same photos (SET, the temple ring of
# ../shared/data), each run extracting and matching on two threads: both
# databases number the images alike, by name, although COLMAP's extraction
# writes them in the order its threads finish, and both runs write
# byte-identical models (seeded verification and mapping). When the photos
# are absent the test prints SKIPPED.
set(set_dir ${DATA_DIR}/${SET})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)
skip_without_photos(${set_dir})
file(REMOVE_RECURSE ${WORK_DIR})

foreach(run a b)
  run(${TMR_RECONSTRUCT} ${set_dir}/images ${WORK_DIR}/${run} --num_threads 2)
endforeach()

foreach(run a b)
  execute_process(COMMAND ${SQLITE3} -readonly ${WORK_DIR}/${run}/database.db
                          "SELECT image_id, name FROM images ORDER BY image_id"
                  OUTPUT_VARIABLE images_${run} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR images_${run} STREQUAL "")
    message(FATAL_ERROR "cannot read the images of run ${run}")
  endif()
endforeach()
if(NOT images_a STREQUAL images_b)
  message(FATAL_ERROR "the two databases number the images differently:\n"
                      "${images_a}\n---\n${images_b}")
endif()
# Ids in name order: sorting by name gives the same list.
execute_process(COMMAND ${SQLITE3} -readonly ${WORK_DIR}/a/database.db
                        "SELECT image_id, name FROM images ORDER BY name"
                OUTPUT_VARIABLE by_name)
if(NOT by_name STREQUAL images_a)
  message(FATAL_ERROR "image ids do not follow the names:\n${images_a}")
endif()

# The same partition (tree.json but its stage times), then the same models
# (sparse/0, 1, ...).
foreach(run a b)
  file(READ ${WORK_DIR}/${run}/sparse/tree.json tree_${run})
  string(JSON tree_${run} REMOVE "${tree_${run}}" timing_s)
endforeach()
if(NOT tree_a STREQUAL tree_b)
  message(FATAL_ERROR "the two runs partitioned the photos differently")
endif()
file(GLOB models RELATIVE ${WORK_DIR}/a/sparse ${WORK_DIR}/a/sparse/[0-9]*)
list(LENGTH models num_models)
if(num_models EQUAL 0)
  message(FATAL_ERROR "run a wrote no model")
endif()
foreach(model ${models})
  differing_model_file(${WORK_DIR}/a/sparse/${model} ${WORK_DIR}/b/sparse/${model}
                       file)
  if(file)
    message(FATAL_ERROR "model ${model}: ${file} differs between two runs "
                        "on the same photos")
  endif()
endforeach()
message(STATUS "${num_models} model(s), identical in both runs; image ids by name")
