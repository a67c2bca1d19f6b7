# Stock `colmap mapper` on a small well-connected tmr_synth scene (one city
# block with its four streets) registers >= 95% of the
# images with a median rotation error below 0.5 degrees (scored by tmr_eval).
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/sparse ${WORK_DIR}/images)
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

run(${TMR_SYNTH} --database_path ${WORK_DIR}/database.db --model_path ${WORK_DIR}/gt
    --family city --city_blocks_x 1 --city_blocks_y 1 --seed 0)
run(${COLMAP} mapper --database_path ${WORK_DIR}/database.db
    --image_path ${WORK_DIR}/images --output_path ${WORK_DIR}/sparse
    --Mapper.num_threads 2)
run(${TMR_EVAL} --gt ${WORK_DIR}/gt --model ${WORK_DIR}/sparse
    --output_json ${WORK_DIR}/eval.json)

file(READ ${WORK_DIR}/eval.json json)
string(JSON num_images GET "${json}" models 0 reference_images)
# The mapper numbers its models in the order it found them: take the largest.
string(JSON num_models LENGTH "${json}" models)
set(registered 0)
math(EXPR last "${num_models} - 1")
foreach(k RANGE ${last})
  string(JSON images GET "${json}" models ${k} registered_images)
  if(images GREATER registered)
    set(registered ${images})
    string(JSON rotation GET "${json}" models ${k} rotation_error_deg median)
    string(JSON wrong GET "${json}" models ${k} wrong_merge)
  endif()
endforeach()
math(EXPR needed "(${num_images} * 95 + 99) / 100")
message(STATUS "largest model: ${registered} of ${num_images} images, "
               "median rotation error ${rotation} deg, wrong merge ${wrong}")
if(registered LESS needed)
  message(FATAL_ERROR "registered ${registered} < 95% of ${num_images}")
endif()
if(rotation GREATER_EQUAL 0.5)
  message(FATAL_ERROR "median rotation error ${rotation} >= 0.5 deg")
endif()
if(wrong)
  message(FATAL_ERROR "wrong merge flagged")
endif()
