# tmr_mapper end to end on a weakly linked tmr_synth scene (paper Fig. 1 /
# Sec. 6.2): two places joined only by a corridor of photos, and a third
# place that nothing links to.
# - It exits 0 and writes complete models that `colmap model_analyzer`
#   loads, tree.json, report.json, project.ini and partition.png, and leaves
#   no temporary folder; the input database is byte-identical and has no
#   -wal/-shm files beside it.
# - The result is separate correct models: no model is flagged as a wrong
#   merge (tmr_eval), no image is in two models, the unlinked place is not
#   joined to the others (at least two models), every model has a median
#   rotation error below 1 degree, and at least 80% of the images are
#   registered.
file(REMOVE_RECURSE ${WORK_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

run(${TMR_SYNTH} --database_path ${WORK_DIR}/database.db --model_path ${WORK_DIR}/gt
    --cameras_per_place 40 --place_distance 100 --seed 1)
file(SHA256 ${WORK_DIR}/database.db before)
run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db --output_path ${WORK_DIR}/out
    --Mapper.num_threads 2)
file(SHA256 ${WORK_DIR}/database.db after)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "tmr_mapper modified its input database")
endif()
if(EXISTS ${WORK_DIR}/database.db-wal OR EXISTS ${WORK_DIR}/database.db-shm)
  message(FATAL_ERROR "tmr_mapper left -wal/-shm files beside its input database")
endif()
foreach(file tree.json report.json project.ini partition.png 0/images.bin)
  if(NOT EXISTS ${WORK_DIR}/out/${file})
    message(FATAL_ERROR "missing output ${file}")
  endif()
endforeach()
file(GLOB leftovers ${WORK_DIR}/out/*.tmp ${WORK_DIR}/out/.tmr_work)
if(leftovers)
  message(FATAL_ERROR "temporary output left behind: ${leftovers}")
endif()
run(${COLMAP} model_analyzer --path ${WORK_DIR}/out/0)
run(${TMR_EVAL} --gt ${WORK_DIR}/gt --model ${WORK_DIR}/out --output_json ${WORK_DIR}/eval.json)
largest_model(${WORK_DIR}/eval.json tmr)
if(tmr_wrong)
  message(FATAL_ERROR "${tmr_wrong} models are wrong merges")
endif()
if(tmr_shared)
  message(FATAL_ERROR "${tmr_shared} images are registered in several models")
endif()
if(tmr_models LESS 2)
  message(FATAL_ERROR "the unlinked place was merged with the others")
endif()
if(tmr_worst_rotation GREATER 1.0)
  message(FATAL_ERROR "a model has a median rotation error of ${tmr_worst_rotation} deg")
endif()
math(EXPR needed "(${tmr_images} * 80 + 99) / 100")
if(tmr_total LESS needed)
  message(FATAL_ERROR "registered ${tmr_total} < 80% of ${tmr_images} images")
endif()
