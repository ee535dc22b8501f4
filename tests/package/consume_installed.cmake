# cmake -P script run by the `package` test (see CMakeLists.txt beside it):
#   1. cmake --install SANDPHYS_BINARY_DIR --prefix WORK_DIR/prefix
#   2. configure CONSUMER_SOURCE_DIR with CMAKE_PREFIX_PATH=WORK_DIR/prefix (and nothing that
#      could find the build tree instead), check that sandphys came from the prefix
#   3. build the consumer and run it; its exit code is the verdict. With BULLET=ON the consumer
#      also asks for the "bullet" component and runs the bridge's consumer.
foreach(var SANDPHYS_BINARY_DIR CONSUMER_SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "consume_installed.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT BULLET)
  set(BULLET OFF)
endif()
if(NOT CONFIG)
  set(CONFIG Release)
endif()

set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/consumer-build")
# Start from nothing, so that a file a previous run installed cannot hide a missing one.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(run_step what)
  message(STATUS "package: ${what}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "package: ${what} failed (${result})")
  endif()
endfunction()

run_step("install the build tree into ${prefix}"
  "${CMAKE_COMMAND}" --install "${SANDPHYS_BINARY_DIR}" --prefix "${prefix}" --config "${CONFIG}")

run_step("configure the consumer"
  "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${consumer_build}" -G "${GENERATOR}"
  "-DCMAKE_BUILD_TYPE=${CONFIG}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
  "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_PREFIX_PATH=${prefix}" "-DCONSUMER_BULLET=${BULLET}"
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)

# The consumer must have found the installed package, not one elsewhere on the machine.
file(STRINGS "${consumer_build}/CMakeCache.txt" found_dir REGEX "^sandphys_DIR:")
string(REGEX REPLACE "^sandphys_DIR:[A-Z]+=" "" found_dir "${found_dir}")
file(REAL_PATH "${found_dir}" found_dir)
file(REAL_PATH "${prefix}" real_prefix)
string(FIND "${found_dir}" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "package: the consumer found sandphys in ${found_dir}, not under ${prefix}")
endif()

run_step("build the consumer" "${CMAKE_COMMAND}" --build "${consumer_build}" --config "${CONFIG}")

set(consumers sandphys_consumer)
if(BULLET)
  list(APPEND consumers sandphys_bullet_consumer)
endif()
foreach(consumer ${consumers})
  # Multi-config generators put the executable in a per-configuration folder.
  set(exe "${consumer_build}/${consumer}")
  if(NOT EXISTS "${exe}")
    set(exe "${consumer_build}/${CONFIG}/${consumer}")
  endif()
  run_step("run ${consumer}" "${exe}")
endforeach()
