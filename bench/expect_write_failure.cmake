# vkfuse-bench writing its reports where every write fails: --json and --plot
# through a symbolic link to /dev/full (a device is written in place; the link
# must survive), and the table on a stdout that is /dev/full. Each must exit
# non-zero with one line on stderr naming what could not be written, never 0
# with an empty or truncated report.
# Usage: cmake -DBENCH=<vkfuse-bench> -DWORK=<scratch directory> -P expect_write_failure.cmake
set(quick --quick --backend cpu --method brovey --sensors 1 --runs 2 --no-peers)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect_failure what fragment)
  execute_process(COMMAND ${BENCH} ${quick} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX MATCHALL "\n" newlines "${err}")
  list(LENGTH newlines lines)
  if(rc EQUAL 0 OR NOT lines EQUAL 1 OR NOT err MATCHES "^vkfuse-bench: .*${fragment}")
    message(FATAL_ERROR "${what}: expected a non-zero exit and one line matching '${fragment}', "
                        "got exit ${rc} and stderr:\n${err}")
  endif()
endfunction()

foreach(option_name json plot)
  if(option_name STREQUAL "json")
    set(link ${WORK}/full.json)
  else()
    set(link ${WORK}/full.svg)
  endif()
  file(CREATE_LINK /dev/full ${link} SYMBOLIC)
  expect_failure("--${option_name} /dev/full" "full\\.(json|svg): cannot write: No space left on device" --${option_name} ${link})
  if(NOT IS_SYMLINK ${link})
    message(FATAL_ERROR "--${option_name}: ${link} was replaced; a device must be written in place")
  endif()
endforeach()

execute_process(COMMAND ${BENCH} ${quick} RESULT_VARIABLE rc OUTPUT_FILE /dev/full ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "^vkfuse-bench: stdout: cannot write: No space left on device\n$")
  message(FATAL_ERROR "stdout on /dev/full: expected a non-zero exit and one line, got exit ${rc} and:\n${err}")
endif()
