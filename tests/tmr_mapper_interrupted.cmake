# tmr_mapper killed (SIGKILL, by execute_process's TIMEOUT) at several points
# of a run never leaves a model that looks complete but is not: every
# numbered folder in the output holds a model that `colmap model_analyzer`
# loads, report.json appears only with all its models, and a plain rerun into
# the same folder finishes with complete models.
file(REMOVE_RECURSE ${WORK_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

run(${TMR_SYNTH} --database_path ${WORK_DIR}/database.db --model_path ${WORK_DIR}/gt
    --cameras_per_place 40 --place_distance 100 --seed 1)
file(SHA256 ${WORK_DIR}/database.db before)

function(check_output out)
  file(GLOB entries RELATIVE ${out} ${out}/*)
  foreach(entry ${entries})
    if(entry MATCHES "^[0-9]+$")
      foreach(file cameras.bin images.bin points3D.bin)
        if(NOT EXISTS ${out}/${entry}/${file})
          message(FATAL_ERROR "model ${entry} lacks ${file}")
        endif()
      endforeach()
      run(${COLMAP} model_analyzer --path ${out}/${entry})
    endif()
  endforeach()
  if(EXISTS ${out}/report.json)
    file(READ ${out}/report.json report)
    string(JSON num_models LENGTH "${report}" model_sizes)
    math(EXPR last "${num_models} - 1")
    foreach(k RANGE ${last})
      if(NOT EXISTS ${out}/${k}/points3D.bin)
        message(FATAL_ERROR "report.json lists model ${k}, which is missing")
      endif()
    endforeach()
  endif()
endfunction()

# Kill points in seconds: during the partition and the first kernels, among
# the leaf tasks, during the merges.
foreach(seconds 0.3 2 6 12 18)
  set(out ${WORK_DIR}/out_${seconds})
  execute_process(
    COMMAND ${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
            --output_path ${out} --Mapper.num_threads 2
    TIMEOUT ${seconds} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  message(STATUS "killed after ${seconds} s: ${rc}")
  check_output(${out})
  if(seconds STREQUAL 6)
    # A plain rerun into the folder of the killed run finishes.
    run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
        --output_path ${out} --Mapper.num_threads 2)
    check_output(${out})
    if(NOT EXISTS ${out}/report.json OR NOT EXISTS ${out}/0/points3D.bin)
      message(FATAL_ERROR "the rerun did not finish")
    endif()
  endif()
endforeach()
file(SHA256 ${WORK_DIR}/database.db after)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "tmr_mapper modified its input database")
endif()
