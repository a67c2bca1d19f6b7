# tmr_reconstruct with its defaults on photos taken walking straight down a
# street (SET, ../shared/data/opensfm_lund: 29 photos, every pair moving
# within a few degrees of the viewing direction), where `colmap mapper`
# registers 2-7 photos: the verified pairs are recognised as
# forward motion, the forward-motion mapper settings are used, and every
# photo is registered in one model. Then with --forward_motion_share 1
# COLMAP's settings come first, with a second mapping only when they
# register fewer than half the photos. The photos are read from
# DATA_DIR/SET, never copied; when they are absent the test prints
# SKIPPED.
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

# --forward_motion_share 1 on a copy of the database (its features and
# matches are reused: only mapping runs): COLMAP's settings come first,
# and a second mapping with the forward-motion settings follows only when
# they register fewer than half the photos (on this street they register
# 21 of 29, so no second mapping).
file(MAKE_DIRECTORY ${WORK_DIR}/general_first)
file(COPY_FILE ${WORK_DIR}/database.db ${WORK_DIR}/general_first/database.db)
run(${TMR_RECONSTRUCT} ${set_dir}/images ${WORK_DIR}/general_first
    --num_threads 2 --forward_motion_share 1)
file(READ ${WORK_DIR}/general_first/summary.txt summary)
message(STATUS "COLMAP's settings first:\n${summary}")
if(summary MATCHES "mapping: COLMAP's settings registered ([0-9]+) of")
  math(EXPR doubled "2 * ${CMAKE_MATCH_1}")
  if(NOT doubled LESS num_photos OR
     NOT summary MATCHES "forward-motion settings did")
    message(FATAL_ERROR "a second mapping after ${CMAKE_MATCH_1} of ${num_photos} photos")
  endif()
elseif(summary MATCHES "mapping: COLMAP's settings\n")
  string(REGEX MATCH "registered: ([0-9]+) of" _ "${summary}")
  math(EXPR doubled "2 * ${CMAKE_MATCH_1}")
  if(doubled LESS num_photos)
    message(FATAL_ERROR "no second mapping after ${CMAKE_MATCH_1} of ${num_photos} photos")
  endif()
else()
  message(FATAL_ERROR "--forward_motion_share 1 did not map with COLMAP's settings first")
endif()
file(GLOB leftovers ${WORK_DIR}/general_first/sparse.*)
if(leftovers)
  message(FATAL_ERROR "mapping left folders behind: ${leftovers}")
endif()
