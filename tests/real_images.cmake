# tmr_reconstruct and stock `colmap mapper` on a real photo set of
# ../shared/data (SET), on the same database (tmr_reconstruct's):
# - tmr_reconstruct exits 0 and writes database.db, sparse/0, summary.txt
#   and partition.png.
# - Registered images (all models): tmr at least 90% of stock's.
# - Against the set's ground truth (gt/colmap_text): no model is a wrong
#   merge, the largest model's median rotation error is at most
#   max(1.5 x stock's, stock's + 0.2 deg), and its mean reprojection error
#   is below 1.5 px.
# The photos are read from DATA_DIR/SET, never copied; when they are absent
# the test prints SKIPPED and counts as skipped.
set(set_dir ${DATA_DIR}/${SET})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)
skip_without_photos(${set_dir})
file(REMOVE_RECURSE ${WORK_DIR})

run(${TMR_RECONSTRUCT} ${set_dir}/images ${WORK_DIR} --num_threads 2
    --FeatureExtraction.max_image_size ${MAX_IMAGE_SIZE})
foreach(file database.db summary.txt sparse/0/images.bin sparse/partition.png)
  if(NOT EXISTS ${WORK_DIR}/${file})
    message(FATAL_ERROR "missing output ${file}")
  endif()
endforeach()
file(MAKE_DIRECTORY ${WORK_DIR}/stock)
run(${COLMAP} mapper --database_path ${WORK_DIR}/database.db
    --image_path ${set_dir}/images --output_path ${WORK_DIR}/stock
    --Mapper.num_threads 2)

run(${TMR_EVAL} --gt ${set_dir}/gt/colmap_text --model ${WORK_DIR}/sparse
    --output_json ${WORK_DIR}/tmr.json)
largest_model(${WORK_DIR}/tmr.json tmr)
run(${TMR_EVAL} --gt ${set_dir}/gt/colmap_text --model ${WORK_DIR}/stock
    --output_json ${WORK_DIR}/stock.json)
largest_model(${WORK_DIR}/stock.json stock)

math(EXPR needed "(${stock_total} * 90) / 100")
if(tmr_total LESS needed)
  message(FATAL_ERROR "tmr registered ${tmr_total} images, stock ${stock_total}")
endif()
if(tmr_wrong)
  message(FATAL_ERROR "${tmr_wrong} tmr models are wrong merges")
endif()
expect_rotation_no_worse(${tmr_rotation} ${stock_rotation} 150 200000 tmr)
micro(reprojection_u ${tmr_reprojection})
if(reprojection_u GREATER 1500000)
  message(FATAL_ERROR "tmr: mean reprojection error ${tmr_reprojection} px")
endif()
message(STATUS "${SET}: registered tmr ${tmr_total} / stock ${stock_total}; median rotation error tmr ${tmr_rotation} / stock ${stock_rotation} deg; reprojection tmr ${tmr_reprojection} / stock ${stock_reprojection} px")
