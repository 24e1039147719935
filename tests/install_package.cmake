# The installed package as a user meets it: cmake --install into a fresh
# prefix, then examples/fuse_installed built against it with
# find_package(vkfuse CONFIG) and run (the GPU's image must agree with the
# reference), examples/caller_command_buffer likewise (a plan in the caller's
# own command buffer, the validation layer silent), then fuse_installed
# compiled with `pkg-config --cflags --libs vkfuse` alone.
# With -DBENCH=ON, vkfuse-bench is installed too and runs from the prefix,
# finding its peers there rather than in the source tree.
# With -DPYTHON=<python3>, the Python module is imported from the prefix and
# examples/python/fuse_pair.py runs against it. With -DROS2=ON, examples/ros2_installed
# is built with find_package(vkfuse COMPONENTS ros2) and looks for a capture host.
#   cmake -DBUILD=<build dir> -DSOURCE=<source dir> -DWORK=<scratch dir> -DCXX=<compiler> -DBENCH=ON|OFF
#         -DPYTHON=<python3 or OFF> -DROS2=ON|OFF -P install_package.cmake
foreach(var BUILD SOURCE WORK CXX BENCH PYTHON ROS2)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_package.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
foreach(installed include/vkfuse/vkfuse.hpp include/vkfuse/version.hpp include/vkfuse/core/fusion.hpp
                  include/vkfuse/vk/plan.hpp include/vkfuse/vk/interop.hpp include/vkfuse/sensor/sim_digit.hpp include/vkfuse/rig/rig.hpp
                  lib/cmake/vkfuse/vkfuseConfig.cmake lib/pkgconfig/vkfuse.pc bin/vkfuse)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "cmake --install left out ${installed}")
  endif()
endforeach()
if(BENCH)
  foreach(installed bin/vkfuse-bench share/vkfuse/peers/pipelines.py)
    if(NOT EXISTS ${prefix}/${installed})
      message(FATAL_ERROR "cmake --install left out ${installed}")
    endif()
  endforeach()
  run("the installed vkfuse-bench" ${prefix}/bin/vkfuse-bench --quick --backend cpu --method brovey --sensors 1 --runs 2)
  if(last_output MATCHES "${SOURCE}/bench/peers")
    message(FATAL_ERROR "the installed vkfuse-bench runs the source tree's peers:\n${last_output}")
  endif()
  string(REGEX MATCH "peers: [^\n]*" peers "${last_output}")
  message(STATUS "installed vkfuse-bench: ${peers}")
endif()

file(GLOB_RECURSE internal ${prefix}/include/*/method_table.hpp ${prefix}/include/*/plan_impl.hpp)
if(internal)
  message(FATAL_ERROR "cmake --install published internal headers: ${internal}")
endif()

# find_package(vkfuse CONFIG) in a project of its own.
run("configuring the example" ${CMAKE_COMMAND} -S ${SOURCE}/examples/fuse_installed -B ${WORK}/example
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX})
run("building the example" ${CMAKE_COMMAND} --build ${WORK}/example)
run("running the example" ${WORK}/example/fuse_installed)
message(STATUS "find_package: ${last_output}")
if(NOT last_output MATCHES "agree|CPU reference only")
  message(FATAL_ERROR "the example said: ${last_output}")
endif()

# A plan embedded in a caller's own device and command buffer
# (examples/caller_command_buffer), under the caller's validation layer.
run("configuring the caller example" ${CMAKE_COMMAND} -S ${SOURCE}/examples/caller_command_buffer
    -B ${WORK}/caller_example -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX})
run("building the caller example" ${CMAKE_COMMAND} --build ${WORK}/caller_example)
run("running the caller example" ${WORK}/caller_example/caller_command_buffer)
message(STATUS "caller's command buffer: ${last_output}")
if(last_output MATCHES "DIFFER" OR NOT last_output MATCHES "timeline.*agree" OR
   NOT last_output MATCHES "validation messages: 0|validation: not checked")
  message(FATAL_ERROR "the caller example said: ${last_output}")
endif()

# The optional ROS 2 library, asked for by component.
if(ROS2)
  run("configuring the ROS 2 example" ${CMAKE_COMMAND} -S ${SOURCE}/examples/ros2_installed -B ${WORK}/ros2_example
      -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX})
  run("building the ROS 2 example" ${CMAKE_COMMAND} --build ${WORK}/ros2_example)
  run("running the ROS 2 example" ${WORK}/ros2_example/ros2_installed 231 0.2)
  message(STATUS "vkfuse::ros2: ${last_output}")
  if(NOT last_output MATCHES "no capture host: --source ros2: no capture host .* in ROS domain 231")
    message(FATAL_ERROR "the ROS 2 example said: ${last_output}")
  endif()
endif()

# pkg-config alone.
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
run("pkg-config" pkg-config --cflags --libs vkfuse)
string(STRIP "${last_output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run("compiling with pkg-config's flags" ${CXX} ${SOURCE}/examples/fuse_installed/main.cpp ${flags}
    -o ${WORK}/fuse_pkgconfig)
# pkg-config's flags carry no run path: a shared build is found the way a
# user outside the system's directories finds it.
set(ENV{LD_LIBRARY_PATH} ${prefix}/lib)
run("running the pkg-config build" ${WORK}/fuse_pkgconfig)
message(STATUS "pkg-config: ${last_output}")
if(NOT last_output MATCHES "agree|CPU reference only")
  message(FATAL_ERROR "the pkg-config build said: ${last_output}")
endif()

# The Python module from the prefix alone (the build tree's is not on the path).
if(PYTHON)
  set(ENV{PYTHONPATH} ${prefix}/lib/python3/dist-packages)
  run("the installed Python module" ${PYTHON} ${SOURCE}/examples/python/fuse_pair.py)
  message(STATUS "python: ${last_output}")
  if(NOT last_output MATCHES "agree|CPU reference only")
    message(FATAL_ERROR "examples/python/fuse_pair.py said: ${last_output}")
  endif()
endif()
