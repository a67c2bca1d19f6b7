# Configures tmr with COLMAP out of reach, builds it and runs libtmr's tests.
file(REMOVE_RECURSE ${WORK_DIR})
include(${CMAKE_CURRENT_LIST_DIR}/run_command.cmake)

run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DTMR_DEPS_PREFIX=${WORK_DIR}/no-colmap
    -DCMAKE_DISABLE_FIND_PACKAGE_COLMAP=ON)
if(NOT last_output MATCHES "COLMAP not found, building libtmr only")
  message(FATAL_ERROR "COLMAP was found:\n${last_output}")
endif()
run(${CMAKE_COMMAND} --build ${WORK_DIR} --parallel 2)
if(EXISTS ${WORK_DIR}/tools/tmr_synth OR EXISTS ${WORK_DIR}/colmap_plugin)
  message(FATAL_ERROR "COLMAP targets were built without COLMAP")
endif()
run(${WORK_DIR}/libtmr/libtmr_test)
message(STATUS "libtmr built and tested without COLMAP")
