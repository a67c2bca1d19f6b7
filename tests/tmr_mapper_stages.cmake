# The staged tmr_mapper (partition, run_task, status, merge), run by hand in
# one process after another as a batch scheduler would, ends with the
# models of the one-command run: same models and images, poses equal up to
# bundle-adjustment noise. Stages out of order get one clear error line.
file(REMOVE_RECURSE ${WORK_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

run(${TMR_SYNTH} --database_path ${WORK_DIR}/database.db --model_path ${WORK_DIR}/gt
    --cameras_per_place 40 --place_distance 100 --seed 1)
run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
    --output_path ${WORK_DIR}/in_process --Mapper.num_threads 2)

# expect_error(PATTERN COMMAND...): the command fails with one error line.
function(expect_error pattern)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "^tmr_mapper: error: ${pattern}[^\n]*\n$")
    message(FATAL_ERROR "expected one error line matching '${pattern}' "
                        "(exit ${rc}):\n${out}\n${err}")
  endif()
endfunction()

set(staged ${WORK_DIR}/staged)
set(plan ${staged}/plan.txt)
expect_error("no '.*project.ini' beside the plan" ${TMR_MAPPER} status --plan ${plan})
expect_error("unknown stage 'mapp'" ${TMR_MAPPER} mapp --plan ${plan})
# A relative database path: the later stages read absolute ones.
run(${TMR_MAPPER} partition --database_path database.db --output_path staged
    WORKING_DIRECTORY ${WORK_DIR})
set(tasks "${last_output}")
if(NOT tasks MATCHES "(^|\n)kernel\\.0 [0-9]+ 0 todo [0-9]+\n"
   OR NOT tasks MATCHES "\nleaf\\.0\\.0 [0-9]+ [0-9]+ todo [0-9]+\n"
   OR NOT tasks MATCHES "\nmerge [0-9]+ 0 waits [0-9]+\n$")
  message(FATAL_ERROR "partition should list the tasks:\n${tasks}")
endif()
# tmr_partition partitions the database as the mapper's plan does.
run(${TMR_PARTITION} --database_path ${WORK_DIR}/database.db
    --output_path ${WORK_DIR}/tmr_partition --picture 0)
file(READ ${staged}/tree.json mapper_tree)
file(READ ${WORK_DIR}/tmr_partition/tree.json partition_tree)
string(JSON mapper_tree REMOVE "${mapper_tree}" timing_s)
string(JSON partition_tree REMOVE "${partition_tree}" timing_s)
if(NOT mapper_tree STREQUAL partition_tree)
  message(FATAL_ERROR "tmr_partition and tmr_mapper partition differ:\n"
                      "${mapper_tree}\n${partition_tree}")
endif()

expect_error("task leaf\\.0\\.0 needs kernel\\.0 finished first"
             ${TMR_MAPPER} run_task --plan ${plan} --task leaf.0.0)
expect_error("the plan has no task 'kernel\\.99'"
             ${TMR_MAPPER} run_task --plan ${plan} --task kernel.99)
expect_error("[0-9]+ tasks have not finished" ${TMR_MAPPER} merge --plan ${plan})
expect_error("the plan in .* was made from another database or with other options"
             ${TMR_MAPPER} run_task --plan ${plan} --task kernel.0 --Tmr.task_ba_global_ratio 1.2)

# Every task in plan order (kernels first), one process each.
string(REGEX MATCHALL "(kernel|leaf)[.0-9]+ " ids "${tasks}")
foreach(id ${ids})
  string(STRIP ${id} id)
  run(${TMR_MAPPER} run_task --plan ${plan} --task ${id} --Mapper.num_threads 1)
endforeach()
run(${TMR_MAPPER} run_task --plan ${plan} --task kernel.0)
if(NOT last_output MATCHES "\\(finished earlier\\)")
  message(FATAL_ERROR "a finished task ran again:\n${last_output}")
endif()
run(${TMR_MAPPER} status --plan ${plan})
if(last_output MATCHES "todo" OR NOT last_output MATCHES "\nmerge [0-9]+ 0 ready [0-9]+\n$")
  message(FATAL_ERROR "tasks left:\n${last_output}")
endif()
run(${TMR_MAPPER} merge --plan ${plan})

file(READ ${WORK_DIR}/in_process/report.json report)
string(JSON in_process_sizes GET "${report}" model_sizes)
file(READ ${staged}/report.json report)
string(JSON staged_sizes GET "${report}" model_sizes)
if(NOT in_process_sizes STREQUAL staged_sizes)
  message(FATAL_ERROR "models differ: ${in_process_sizes} vs ${staged_sizes}")
endif()
string(JSON num_models LENGTH "${report}" model_sizes)
math(EXPR last "${num_models} - 1")
foreach(k RANGE ${last})
  run(${TMR_EVAL} --gt ${WORK_DIR}/in_process/${k} --model ${staged}/${k}
      --output_json ${WORK_DIR}/eval${k}.json)
  file(READ ${WORK_DIR}/eval${k}.json eval)
  string(JSON common GET "${eval}" models 0 common_images)
  string(JSON registered GET "${eval}" models 0 registered_images)
  string(JSON size GET "${report}" model_sizes ${k})
  string(JSON rotation GET "${eval}" models 0 rotation_error_deg max)
  # Below 0.1 degrees (JSON may write small numbers as 1.5e-05).
  if(NOT common EQUAL size OR NOT registered EQUAL size
     OR NOT rotation MATCHES "^(0(\\.0[0-9]*)?|[0-9.]+e-[0-9]+)$")
    message(FATAL_ERROR "model ${k}: ${common} images in common of ${size}, "
                        "rotations differ by up to ${rotation} deg")
  endif()
endforeach()
if(EXISTS ${staged}/.tmr_work)
  message(FATAL_ERROR "merge left the work folder without --Tmr.keep_work")
endif()
