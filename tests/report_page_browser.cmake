# report.html in a real browser (headless Chromium; SKIPPED without one): the
# weakly linked scene of tmr_mapper_weak_links (two places joined by a
# corridor, a third that nothing links to) reconstructed, scored by
# tmr_eval, and its page written again with the scores (`tmr_mapper
# report`).
# - The page draws with no JavaScript error, from disk, with no network.
# - Its numbers are report.json's: photos, models, steps, links refused,
#   pairs of models that stayed apart; the first such pair's reason is on
#   the page; the largest model's errors against the ground truth are shown.
# - A screenshot of the page is not blank (a white page of this size
#   compresses to a few kB; the drawn one to hundreds).
file(REMOVE_RECURSE ${WORK_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

find_program(CHROMIUM NAMES chromium chromium-browser google-chrome)
if(NOT CHROMIUM)
  message(STATUS "SKIPPED: no chromium (tools/setup_dependencies.sh installs "
                 "Debian's chromium where it can)")
  return()
endif()

set(out ${WORK_DIR}/out)
run(${TMR_SYNTH} --database_path ${WORK_DIR}/database.db --model_path ${WORK_DIR}/gt
    --cameras_per_place 40 --place_distance 100 --seed 1)
run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db --output_path ${out}
    --Mapper.num_threads 2)
if(NOT EXISTS ${out}/report.html)
  message(FATAL_ERROR "tmr_mapper wrote no report.html")
endif()
run(${TMR_EVAL} --gt ${WORK_DIR}/gt --model ${out} --output_json ${out}/eval.json)
run(${TMR_MAPPER} report --plan ${out}/plan.txt)

# Chromium wants a writable home and no sandbox when run as root.
set(browser ${CHROMIUM} --headless --no-sandbox --disable-gpu
    --no-first-run --disable-extensions --user-data-dir=${WORK_DIR}/chromium
    --virtual-time-budget=20000)
execute_process(COMMAND ${browser} --dump-dom file://${out}/report.html
                RESULT_VARIABLE rc OUTPUT_VARIABLE dom ERROR_VARIABLE err
                TIMEOUT 120)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "chromium --dump-dom failed (${rc}): ${err}")
endif()
string(REGEX MATCH "<pre id=\"tmr-status\"[^>]*>([^<]*)</pre>" found "${dom}")
if(NOT found)
  message(FATAL_ERROR "the page wrote no status (its script did not finish):\n${dom}")
endif()
set(status "${CMAKE_MATCH_1}")
string(REPLACE "&quot;" "\"" status "${status}")
string(REPLACE "&lt;" "<" status "${status}")
string(REPLACE "&gt;" ">" status "${status}")
string(REPLACE "&amp;" "&" status "${status}")
message(STATUS "page status: ${status}")
string(JSON num_errors LENGTH "${status}" errors)
if(NOT num_errors EQUAL 0)
  string(JSON errors GET "${status}" errors)
  message(FATAL_ERROR "JavaScript errors on the page: ${errors}")
endif()
string(JSON drawn GET "${status}" drawn)
if(NOT drawn)
  message(FATAL_ERROR "the page did not finish drawing")
endif()

# The page's numbers against report.json's.
file(READ ${out}/report.json report)
string(JSON expected_photos GET "${report}" num_images)
string(JSON expected_models LENGTH "${report}" model_sizes)
string(JSON expected_tasks LENGTH "${report}" tasks)
string(JSON expected_weak LENGTH "${report}" weak_links)
set(expected_refused 0)
math(EXPR last "${expected_tasks} - 1")
foreach(t RANGE ${last})
  string(JSON link ERROR_VARIABLE no_link GET "${report}" tasks ${t} link)
  string(JSON success GET "${report}" tasks ${t} success)
  if(NOT no_link AND NOT success)
    math(EXPR expected_refused "${expected_refused} + 1")
  endif()
endforeach()
foreach(pair photos:${expected_photos} models:${expected_models}
        tasks:${expected_tasks} weak_links:${expected_weak}
        refused_links:${expected_refused})
  string(REPLACE ":" ";" pair "${pair}")
  list(GET pair 0 key)
  list(GET pair 1 expected)
  string(JSON shown GET "${status}" ${key})
  if(NOT shown EQUAL expected)
    message(FATAL_ERROR "the page shows ${key} ${shown}, report.json has ${expected}")
  endif()
endforeach()
if(expected_weak EQUAL 0)
  message(FATAL_ERROR "the scene left no pair of models apart: the test needs one")
endif()
# The first pair's reason, as the DOM writes text (&, <, > escaped).
string(JSON reason GET "${report}" weak_links 0 reason)
string(REPLACE "&" "&amp;" reason "${reason}")
string(REPLACE "<" "&lt;" reason "${reason}")
string(REPLACE ">" "&gt;" reason "${reason}")
string(FIND "${dom}" "${reason}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "the page does not show why models stayed apart: '${reason}'")
endif()
string(FIND "${dom}" "largest model, median rotation error" at)
if(at EQUAL -1)
  message(FATAL_ERROR "the page does not show tmr_eval's scores")
endif()

execute_process(COMMAND ${browser} --window-size=1280,2400
                        --screenshot=${WORK_DIR}/report.png file://${out}/report.html
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK_DIR}/report.png)
  message(FATAL_ERROR "chromium --screenshot failed (${rc}): ${err}")
endif()
file(SIZE ${WORK_DIR}/report.png png_bytes)
message(STATUS "screenshot ${WORK_DIR}/report.png: ${png_bytes} bytes")
if(png_bytes LESS 100000)
  message(FATAL_ERROR "the screenshot is blank or nearly (${png_bytes} bytes)")
endif()
