# tmr_reconstruct with its defaults on photos taken walking straight down a
# street (SET, ../shared/data/opensfm_lund: 29 photos, every pair moving
# within a few degrees of the viewing direction), where COLMAP's mapper
# settings register 2-7 photos: the verified pairs are recognised as
# forward motion, the forward-motion mapper settings are used, and every
# photo is registered in one model. The photos are read from DATA_DIR/SET,
# never copied; when they are absent the test prints SKIPPED.
set(set_dir ${DATA_DIR}/${SET})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)
skip_without_photos(${set_dir})
file(REMOVE_RECURSE ${WORK_DIR})

run(${TMR_RECONSTRUCT} ${set_dir}/images ${WORK_DIR} --num_threads 2)
file(READ ${WORK_DIR}/summary.txt summary)
message(STATUS "${SET}:\n${summary}")
file(GLOB photos ${set_dir}/images/*)
list(LENGTH photos num_photos)
if(NOT summary MATCHES "mapping: forward-motion settings")
  message(FATAL_ERROR "the forward motion was not recognised")
endif()
if(NOT summary MATCHES "models: 1 " OR
   NOT summary MATCHES "registered: ${num_photos} of ${num_photos} images")
  message(FATAL_ERROR "expected every one of ${num_photos} photos in one model")
endif()
