# Retrieval matching on an unordered copy of a real photo set (SET, the
# temple ring of ../shared/data: 47 photos): the photos are copied under
# names that hide their order, tmr_reconstruct matches them by retrieval
# (a vocabulary tree built from their own features, NEIGHBORS similar
# photos each) and registers as many photos as with exhaustive matching of
# the originals; the summary says which matcher ran. When the photos are
# absent the test prints SKIPPED.
set(set_dir ${DATA_DIR}/${SET})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)
skip_without_photos(${set_dir})
file(REMOVE_RECURSE ${WORK_DIR})

file(GLOB photos ${set_dir}/images/*)
file(MAKE_DIRECTORY ${WORK_DIR}/shuffled)
foreach(photo ${photos})
  get_filename_component(name ${photo} NAME)
  get_filename_component(ext ${photo} LAST_EXT)
  string(SHA1 hidden ${name})
  file(COPY_FILE ${photo} ${WORK_DIR}/shuffled/${hidden}${ext})
endforeach()

# One camera per photo in both runs: the original names are numbered
# frames without EXIF (one camera with --folder_cameras), the hidden ones not.
set(common --num_threads 2 --FeatureExtraction.max_image_size 640
    --folder_cameras 0)
run(${TMR_RECONSTRUCT} ${set_dir}/images ${WORK_DIR}/exhaustive ${common})
run(${TMR_RECONSTRUCT} ${WORK_DIR}/shuffled ${WORK_DIR}/retrieval ${common}
    --matcher retrieval --retrieval_neighbors ${NEIGHBORS})
file(READ ${WORK_DIR}/exhaustive/summary.txt exhaustive)
file(READ ${WORK_DIR}/retrieval/summary.txt retrieval)
message(STATUS "exhaustive:\n${exhaustive}\nretrieval:\n${retrieval}")
if(NOT retrieval MATCHES "retrieval matching" OR
   NOT EXISTS ${WORK_DIR}/retrieval/vocab_tree.bin)
  message(FATAL_ERROR "the shuffled copy was not matched by retrieval")
endif()
string(REGEX MATCH "registered: ([0-9]+) of" _ "${exhaustive}")
set(by_exhaustive ${CMAKE_MATCH_1})
string(REGEX MATCH "registered: ([0-9]+) of" _ "${retrieval}")
set(by_retrieval ${CMAKE_MATCH_1})
string(REGEX MATCH "verified pairs: ([0-9]+)" _ "${exhaustive}")
set(pairs_exhaustive ${CMAKE_MATCH_1})
string(REGEX MATCH "verified pairs: ([0-9]+)" _ "${retrieval}")
set(pairs_retrieval ${CMAKE_MATCH_1})
message(STATUS "registered: exhaustive ${by_exhaustive}, retrieval ${by_retrieval}; verified pairs: ${pairs_exhaustive}, ${pairs_retrieval}")
if(NOT by_retrieval EQUAL by_exhaustive)
  message(FATAL_ERROR "retrieval registered ${by_retrieval} photos, exhaustive ${by_exhaustive}")
endif()
