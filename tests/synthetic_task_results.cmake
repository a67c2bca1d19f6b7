# The merge stage alone, on task results made from a scene's ground truth
# (tmr_synth_tasks, issue 43): a city block of tmr_synth, `tmr_mapper
# partition`, every task written from the ground truth with noise, `tmr_mapper
# merge`. Scored by tmr_eval:
# - one model holding every image, no wrong merge, median rotation error
#   below 0.05 degrees (the tasks' noise is 0.02 degrees per image);
# - a second tmr_synth_tasks before the merge writes nothing (every task has
#   finished);
# - a missing ground truth is one error line and exit code 1.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

run(${TMR_SYNTH} --database_path ${WORK_DIR}/database.db --model_path ${WORK_DIR}/gt
    --family city --city_blocks_x 1 --city_blocks_y 1 --seed 2)
run(${TMR_MAPPER} partition --database_path ${WORK_DIR}/database.db
    --output_path ${WORK_DIR}/out)
run(${TMR_SYNTH_TASKS} --plan ${WORK_DIR}/out/plan.txt --model_path ${WORK_DIR}/gt)
if(NOT last_output MATCHES "wrote [1-9][0-9]* task models from the ground truth")
  message(FATAL_ERROR "tmr_synth_tasks wrote no task model:\n${last_output}")
endif()
run(${TMR_SYNTH_TASKS} --plan ${WORK_DIR}/out/plan.txt --model_path ${WORK_DIR}/gt)
if(NOT last_output MATCHES "wrote 0 task models")
  message(FATAL_ERROR "finished tasks written again:\n${last_output}")
endif()
execute_process(COMMAND ${TMR_SYNTH_TASKS} --plan ${WORK_DIR}/out/plan.txt
                        --model_path ${WORK_DIR}/missing
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 1 OR NOT err MATCHES "^tmr_synth_tasks: error: no model in '[^']*missing'\n$")
  message(FATAL_ERROR "missing ground truth: exit ${rc}, '${err}'")
endif()
run(${TMR_MAPPER} status --plan ${WORK_DIR}/out/plan.txt)
if(last_output MATCHES "todo")
  message(FATAL_ERROR "tasks left to do:\n${last_output}")
endif()
run(${TMR_MAPPER} merge --plan ${WORK_DIR}/out/plan.txt)
score(merged ${WORK_DIR}/out)
if(NOT merged_models EQUAL 1 OR NOT merged_registered EQUAL merged_images
   OR merged_wrong)
  message(FATAL_ERROR "merge of generated tasks: ${merged_models} models, "
          "largest ${merged_registered} of ${merged_images} (wrong merges: "
          "${merged_wrong})")
endif()
if(NOT merged_rotation LESS 0.05)
  message(FATAL_ERROR "median rotation error ${merged_rotation} deg")
endif()

