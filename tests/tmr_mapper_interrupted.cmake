# tmr_mapper killed (SIGKILL, by execute_process's TIMEOUT) at several points
# of a run never leaves a model that looks complete but is not: every
# numbered folder in the output holds a model that `colmap model_analyzer`
# loads, report.json appears only with all its models, and a plain rerun into
# the same folder finishes with complete models, reusing the kernel and leaf
# tasks the killed run finished.
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
# Resume: kill points between the first and the last finished task of a
# clean run; a plain rerun reuses what the killed run finished and ends with
# the clean run's models.
run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
    --output_path ${WORK_DIR}/out_clean --Mapper.num_threads 2)
string(REGEX MATCHALL "\\[tmr +[0-9]+\\.[0-9] s\\] (kernel|leaf) " task_lines
       "${last_output}")
list(LENGTH task_lines num_tasks)
if(num_tasks LESS 2)
  message(FATAL_ERROR "expected several tasks:\n${last_output}")
endif()
function(task_ms line var)
  string(REGEX REPLACE ".*\\[tmr +([0-9]+)\\.([0-9]) s.*" "\\1\\200" ms "${line}")
  set(${var} ${ms} PARENT_SCOPE)
endfunction()
list(GET task_lines 0 line)
task_ms("${line}" first_ms)
list(GET task_lines -1 line)
task_ms("${line}" last_ms)
file(READ ${WORK_DIR}/out_clean/report.json report)
string(JSON clean_sizes GET "${report}" model_sizes)
set(resumed 0)
foreach(percent 10 50 90)
  math(EXPR kill_ms "${first_ms} + (${last_ms} - ${first_ms}) * ${percent} / 100 + 200")
  math(EXPR kill_s "${kill_ms} / 1000")
  math(EXPR kill_frac "${kill_ms} % 1000 / 100")
  set(out ${WORK_DIR}/out_resume_${percent})
  execute_process(
    COMMAND ${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
            --output_path ${out} --Mapper.num_threads 2
    TIMEOUT ${kill_s}.${kill_frac} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  file(GLOB finished ${out}/.tmr_work/*.result)
  message(STATUS "killed after ${kill_s}.${kill_frac} s (${rc}); finished tasks: ${finished}")
  if(rc EQUAL 0 OR NOT finished)
    continue()
  endif()
  check_output(${out})
  run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
      --output_path ${out} --Mapper.num_threads 2)
  if(NOT last_output MATCHES "resuming: reusing the tasks"
     OR NOT last_output MATCHES "finished by an earlier run")
    message(FATAL_ERROR "the rerun did not reuse the finished tasks:\n${last_output}")
  endif()
  check_output(${out})
  file(READ ${out}/report.json report)
  string(JSON sizes GET "${report}" model_sizes)
  string(REGEX REPLACE "[ \n]" "" sizes "${sizes}")
  string(REGEX REPLACE "[ \n]" "" clean_sizes "${clean_sizes}")
  if(NOT sizes STREQUAL clean_sizes)
    message(FATAL_ERROR "resumed run: models ${sizes}, clean run: ${clean_sizes}")
  endif()
  math(EXPR resumed "${resumed} + 1")
endforeach()
if(resumed EQUAL 0)
  message(FATAL_ERROR "no kill point left finished tasks to reuse")
endif()

file(SHA256 ${WORK_DIR}/database.db after)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "tmr_mapper modified its input database")
endif()
