# Stock `colmap mapper` and tmr_mapper on the same well-connected tmr_synth
# scene (one city block with its four streets), scored by tmr_eval:
# - stock registers >= 95% of the images in its largest model, median
#   rotation error below 0.5 degrees (the scene is a fair test);
# - tmr_mapper registers >= 98% of what stock registers, and its median
#   rotation error is no worse (up to bundle-adjustment noise: 25% or
#   0.01 degrees, whichever is larger); no model of either is a wrong merge;
# - the same for tmr_mapper with its merged models adjusted by blocks of at
#   most 60 images (--Tmr.ba_max_block_images, default 1,000, which a
#   scene of this size does not reach).
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/stock ${WORK_DIR}/images)
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

run(${TMR_SYNTH} --database_path ${WORK_DIR}/database.db --model_path ${WORK_DIR}/gt
    --family city --city_blocks_x 1 --city_blocks_y 1 --seed 0)
run(${COLMAP} mapper --database_path ${WORK_DIR}/database.db
    --image_path ${WORK_DIR}/images --output_path ${WORK_DIR}/stock
    --Mapper.num_threads 2)
run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
    --output_path ${WORK_DIR}/tmr --Mapper.num_threads 2)
run(${TMR_MAPPER} --database_path ${WORK_DIR}/database.db
    --output_path ${WORK_DIR}/tmr_blocks --Mapper.num_threads 2
    --Tmr.ba_max_block_images 60)
score(stock ${WORK_DIR}/stock)
score(tmr ${WORK_DIR}/tmr)
score(blocks ${WORK_DIR}/tmr_blocks)

expect_fair_stock(95 0.5)
expect_as_good_as_stock(tmr tmr_mapper)
expect_as_good_as_stock(blocks "tmr_mapper by blocks")
if(stock_wrong OR tmr_wrong OR blocks_wrong)
  message(FATAL_ERROR "wrong merge flagged (stock ${stock_wrong}, tmr_mapper ${tmr_wrong}, by blocks ${blocks_wrong})")
endif()
message(STATUS "median rotation error: stock ${stock_rotation}, tmr_mapper ${tmr_rotation}, by blocks ${blocks_rotation}")
