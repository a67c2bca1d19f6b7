# Runs COMMAND with ARGS and checks its exit code, standard error and
# output.
#   -DCOMMAND=... -DARGS=a;b -DEXPECT_EXIT=N -DEXPECT_STDERR=regex
#   -DEXPECT_STDOUT=regex
execute_process(COMMAND ${COMMAND} ${ARGS}
                RESULT_VARIABLE exit_code
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT exit_code EQUAL EXPECT_EXIT)
  message(FATAL_ERROR "exit code ${exit_code}, expected ${EXPECT_EXIT}\nstderr: ${err}")
endif()
if(DEFINED EXPECT_STDERR AND NOT err MATCHES "${EXPECT_STDERR}")
  message(FATAL_ERROR "stderr does not match '${EXPECT_STDERR}':\n${err}")
endif()
if(DEFINED EXPECT_STDOUT AND NOT out MATCHES "${EXPECT_STDOUT}")
  message(FATAL_ERROR "stdout does not match '${EXPECT_STDOUT}':\n${out}")
endif()
message(STATUS "exit ${exit_code}, stderr: ${err}")
