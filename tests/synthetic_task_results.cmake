# The merge stage alone, on task results made from a scene's ground truth
# (tmr_synth_tasks): a city block of tmr_synth, `tmr_mapper
# partition`, every task written from the ground truth with noise, `tmr_mapper
# merge`. Scored by tmr_eval:
# - one model holding every image, no wrong merge, median rotation error
#   below 0.05 degrees (the tasks' noise is 0.02 degrees per image);
# - a second tmr_synth_tasks before the merge writes nothing (every task has
#   finished);
# - a missing ground truth is one error line and exit code 1;
# - with a memory budget below the merge stage's (0.35 GiB, the tasks'
#   peaks 0.20-0.27), the plan splits the merge into groups of clusters
#   (plan lines merge.G, `status` lists them), `merge --group merge.0`
#   merges one group alone, and `merge` merges the others and joins them
#   into the models of the whole merge: one model of every image, no wrong
#   merge, median rotation error below 0.06 degrees (the join adjusts
#   every pose on the groups' longest tracks: 0.040 measured, 0.075
#   without that adjustment, 0.025 whole); the plan lists the pairs of
#   groups that the join links, the join aligns them a pair of groups at a
#   time, then adjusts the scene.
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


# The merge stage by parts, on the same task results.
set(parts ${WORK_DIR}/parts)
run(${TMR_MAPPER} partition --database_path ${WORK_DIR}/database.db
    --output_path ${parts} --Tmr.memory_budget 0.35)
if(NOT last_output MATCHES "\nmerge\\.0 [0-9]+ 0 waits [0-9]+\nmerge\\.1 "
   OR NOT last_output MATCHES "\nmerge 192 0 waits [0-9]+\n$")
  message(FATAL_ERROR "the plan should merge by parts:\n${last_output}")
endif()
run(${TMR_SYNTH_TASKS} --plan ${parts}/plan.txt --model_path ${WORK_DIR}/gt)
run(${TMR_MAPPER} merge --plan ${parts}/plan.txt --group merge.0)
run(${TMR_MAPPER} status --plan ${parts}/plan.txt)
if(NOT last_output MATCHES "\nmerge\\.0 [0-9]+ 0 done [0-9]+\nmerge\\.1 [0-9]+ 0 ready ")
  message(FATAL_ERROR "group 0 should be merged, group 1 ready:\n${last_output}")
endif()
execute_process(COMMAND ${TMR_MAPPER} merge --plan ${parts}/plan.txt --group merge.9
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 1 OR NOT err MATCHES "^tmr_mapper: error: the plan has no merge group 'merge.9'\n$")
  message(FATAL_ERROR "unknown group: exit ${rc}, '${err}'")
endif()
run(${TMR_MAPPER} merge --plan ${parts}/plan.txt)
if(NOT last_output MATCHES "group 0: merged by an earlier run")
  message(FATAL_ERROR "group 0 merged again:\n${last_output}")
endif()
file(READ ${parts}/plan.txt plan)
if(NOT plan MATCHES "\nmerge\\.0 [^\n]* links=[1-9]")
  message(FATAL_ERROR "group 0 is linked to no group:\n${plan}")
endif()
if(NOT plan MATCHES "\nseam\\.0\\.[1-9][0-9]* [1-9][0-9]* 0 0 [0-9]")
  message(FATAL_ERROR "the plan gives no seam of group 0's links:\n${plan}")
endif()
file(READ ${parts}/report.json report)
if(NOT report MATCHES "join: align groups 0 and [1-9]")
  message(FATAL_ERROR "the join aligned no pair of groups:\n${report}")
endif()
if(NOT report MATCHES "join: adjust model 0 on [1-9][0-9]* longest tracks per image")
  message(FATAL_ERROR "the join did not adjust the scene:\n${report}")
endif()
score(parts ${parts})
if(NOT parts_models EQUAL merged_models OR NOT parts_registered EQUAL merged_registered
   OR parts_wrong)
  message(FATAL_ERROR "merge by parts: ${parts_models} models, largest "
          "${parts_registered} (whole: ${merged_models}, ${merged_registered}; "
          "wrong merges: ${parts_wrong})")
endif()
if(NOT parts_rotation LESS 0.06)
  message(FATAL_ERROR "merge by parts: median rotation error ${parts_rotation} deg")
endif()
