# Runs COMMAND with ARGS and checks its exit code and standard error.
#   -DCOMMAND=... -DARGS=a;b -DEXPECT_EXIT=N -DEXPECT_STDERR=regex
execute_process(COMMAND ${COMMAND} ${ARGS}
                RESULT_VARIABLE exit_code
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT exit_code EQUAL EXPECT_EXIT)
  message(FATAL_ERROR "exit code ${exit_code}, expected ${EXPECT_EXIT}\nstderr: ${err}")
endif()
if(DEFINED EXPECT_STDERR AND NOT err MATCHES "${EXPECT_STDERR}")
  message(FATAL_ERROR "stderr does not match '${EXPECT_STDERR}':\n${err}")
endif()
message(STATUS "exit ${exit_code}, stderr: ${err}")
