# cmake -DBENCH=<vkfuse-bench> -DARGS=<;-list> -P expect_usage_error.cmake
# A bad command line must exit 2 with exactly one line on stderr and nothing on stdout.
execute_process(COMMAND ${BENCH} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(STRIP "${err}" err)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "vkfuse-bench ${ARGS}: exit ${rc}, expected 2 (stderr: ${err})")
endif()
if(err STREQUAL "" OR err MATCHES "\n")
  message(FATAL_ERROR "vkfuse-bench ${ARGS}: expected one line on stderr, got: '${err}'")
endif()
if(NOT out STREQUAL "")
  message(FATAL_ERROR "vkfuse-bench ${ARGS}: printed to stdout: ${out}")
endif()
message(STATUS "vkfuse-bench ${ARGS}: ${err}")
