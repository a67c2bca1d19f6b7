# Installs the tmr build tree into WORK_DIR/install, then configures, builds
# and runs the consumer project against it.
set(prefix ${WORK_DIR}/install)
file(REMOVE_RECURSE ${WORK_DIR})

include(${CMAKE_CURRENT_LIST_DIR}/../run_command.cmake)

run(${CMAKE_COMMAND} --install ${TMR_BINARY_DIR} --prefix ${prefix})
run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${WORK_DIR}/build
    -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_PREFIX_PATH=${prefix}\;${EXTRA_PREFIX_PATH}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build --parallel 2)
run(${WORK_DIR}/build/partition_summary)
if(EXISTS ${WORK_DIR}/build/synth_and_read)
  run(${WORK_DIR}/build/synth_and_read ${WORK_DIR}/consumer.db)
  run(${WORK_DIR}/build/partition_database ${WORK_DIR}/consumer.db
      ${WORK_DIR}/tree.json)
else()
  message(STATUS "colmap_plugin not installed: only libtmr checked")
endif()
