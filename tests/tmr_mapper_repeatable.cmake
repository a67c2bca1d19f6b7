# The same database, options and --Tmr.seed give the same models: two
# tmr_mapper runs write byte-identical model files, model by model, although
# the first runs two tasks at a time and the second one after the other, so
# that tasks finish in another order and no task runs
# beside another (--Tmr.repeatable, the default, runs each COLMAP step on one
# thread). CI saw a cluster merge come out differently when COLMAP's
# alignment drew from the worker thread's unseeded generator
# (docs/mapper.md#repeatable-runs).
file(REMOVE_RECURSE ${WORK_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

# Five linked places of 40 photos: kernels, leaves and merges all run.
run(${TMR_SYNTH} --database_path ${WORK_DIR}/database.db --model_path ${WORK_DIR}/gt
    --cameras_per_place 40 --seed 2)
foreach(threads 2 1)
  run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
      --output_path ${WORK_DIR}/run${threads} --Mapper.num_threads ${threads}
      --Tmr.seed 11)
endforeach()

file(READ ${WORK_DIR}/run1/report.json report1)
file(READ ${WORK_DIR}/run2/report.json report2)
string(JSON sizes1 GET "${report1}" model_sizes)
string(JSON sizes2 GET "${report2}" model_sizes)
if(NOT sizes1 STREQUAL sizes2)
  message(FATAL_ERROR "the two runs' models differ: ${sizes1} vs ${sizes2}")
endif()
string(JSON num_models LENGTH "${report1}" model_sizes)
math(EXPR last "${num_models} - 1")
foreach(k RANGE ${last})
  differing_model_file(${WORK_DIR}/run1/${k} ${WORK_DIR}/run2/${k} file)
  if(file)
    # Say by how much the images moved, for the failure message.
    execute_process(COMMAND ${TMR_EVAL} --gt ${WORK_DIR}/run1/${k}
                    --model ${WORK_DIR}/run2/${k} OUTPUT_VARIABLE eval)
    message(FATAL_ERROR "model ${k}: ${file} differs between two runs "
                        "with the same seed:\n${eval}")
  endif()
endforeach()
message(STATUS "${num_models} models, identical in both runs")
