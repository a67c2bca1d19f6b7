# Stock `colmap mapper` and tmr_mapper on a well-connected tmr_synth scene
# whose parts share few tracks: four plazas whose camera rings
# overlap, no link photos, detection 0.35 and matching that tolerates less
# viewpoint change, so that clusters share points but few tracks. Scored by
# tmr_eval:
# - stock registers >= 90% of the images in its largest model, median
#   rotation error below 1 degree (the scene is a fair test);
# - tmr_mapper gives one model (after Mapper.min_model_size) holding >= 98%
#   of what stock registers, with a median rotation error within 25% of
#   stock's (or 0.01 degrees); no model of either is a wrong merge;
# - report.json lists no weak link for a single model, and the run's
#   scene merges rest on images registered on a scene's points where the
#   clusters share too few tracks;
# - with the track rule alone and no completion (--Tmr.merge_register_images
#   0 --Tmr.complete_models 0) the plazas join in one model: each cluster's
#   halo (images of its neighbours that its tasks also register) gives the
#   neighbouring cluster models shared tracks;
# - with that and no halo (--Tmr.halo_images 0) the plazas stay apart, and
#   report.json and the last progress lines give, for each pair of models
#   that verified pairs link, the pairs and why they stay apart.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/stock ${WORK_DIR}/images)
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

run(${TMR_SYNTH} --database_path ${WORK_DIR}/database.db --model_path ${WORK_DIR}/gt
    --family plazas --num_places 4 --cameras_per_place 60
    --detection_probability 0.35 --match_probability 0.7
    --match_angle_falloff_deg 12 --seed 0)
run(${COLMAP} mapper --database_path ${WORK_DIR}/database.db
    --image_path ${WORK_DIR}/images --output_path ${WORK_DIR}/stock
    --Mapper.num_threads 2)
run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
    --output_path ${WORK_DIR}/tmr --Mapper.num_threads 2)
set(tmr_log "${last_output}")
score(stock ${WORK_DIR}/stock)
score(tmr ${WORK_DIR}/tmr)

expect_fair_stock(90 1.0)
if(NOT tmr_models EQUAL 1)
  message(FATAL_ERROR "tmr_mapper: ${tmr_models} models, not one")
endif()
expect_as_good_as_stock(tmr tmr_mapper)
if(stock_wrong OR tmr_wrong)
  message(FATAL_ERROR "wrong merge flagged (stock ${stock_wrong}, tmr_mapper ${tmr_wrong})")
endif()
file(READ ${WORK_DIR}/tmr/report.json report)
string(JSON num_weak LENGTH "${report}" weak_links)
if(NOT num_weak EQUAL 0)
  message(FATAL_ERROR "one model, yet report.json lists ${num_weak} weak links")
endif()
if(NOT report MATCHES "images registered on the scene's points fit")
  message(FATAL_ERROR "no scene merge rested on registered images:\n${tmr_log}")
endif()

run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
    --output_path ${WORK_DIR}/tracks_with_halo --Mapper.num_threads 2
    --Tmr.merge_register_images 0 --Tmr.complete_models 0)
score(halo ${WORK_DIR}/tracks_with_halo)
if(NOT halo_models EQUAL 1 OR halo_wrong)
  message(FATAL_ERROR "the track rule with halos: ${halo_models} models "
                      "(wrong merge: ${halo_wrong}), not one")
endif()

run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
    --output_path ${WORK_DIR}/tracks_only --Mapper.num_threads 2
    --Tmr.merge_register_images 0 --Tmr.complete_models 0
    --Tmr.halo_images 0)
if(NOT last_output MATCHES "models 0 and 1 stay apart: [0-9]+ verified pairs")
  message(FATAL_ERROR "no weak-link progress line for models 0 and 1")
endif()
file(READ ${WORK_DIR}/tracks_only/report.json report)
string(JSON num_weak LENGTH "${report}" weak_links)
if(num_weak LESS 1)
  message(FATAL_ERROR "the track rule alone: no weak link reported")
endif()
math(EXPR last "${num_weak} - 1")
foreach(k RANGE ${last})
  string(JSON pairs GET "${report}" weak_links ${k} verified_pairs)
  string(JSON reason GET "${report}" weak_links ${k} reason)
  if(pairs LESS 1 OR NOT reason MATCHES "shared tracks|best image shares")
    message(FATAL_ERROR "weak link ${k}: ${pairs} pairs, reason '${reason}'")
  endif()
endforeach()
message(STATUS "median rotation error: stock ${stock_rotation}, tmr_mapper ${tmr_rotation}")
