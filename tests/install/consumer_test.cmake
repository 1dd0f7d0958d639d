# ctest `install.consumer`: stages `cmake --install` of this build into STAGE_DIR/prefix, configures
# and builds examples/consumer against it (find_package(aperture) through CMAKE_PREFIX_PATH only)
# and runs it: the gap detector on an image the installed simulator renders, within 1 % of the
# ground truth. Every step's failure fails the test with that step's output.
#   cmake -DAPERTURE_BUILD_DIR=… -DCONSUMER_SOURCE_DIR=… -DSTAGE_DIR=… -DGENERATOR=…
#         [-DCXX_COMPILER=…] [-DCOMPILER_LAUNCHER=…] -P consumer_test.cmake
foreach(var APERTURE_BUILD_DIR CONSUMER_SOURCE_DIR STAGE_DIR GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "consumer_test.cmake: pass -D${var}=…")
  endif()
endforeach()

file(REMOVE_RECURSE ${STAGE_DIR})
set(prefix ${STAGE_DIR}/prefix)
set(build ${STAGE_DIR}/consumer-build)

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed (${result}):\n${out}")
  endif()
  message(STATUS "${what}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

run_step("install" ${CMAKE_COMMAND} --install ${APERTURE_BUILD_DIR} --prefix ${prefix})
foreach(installed lib/cmake/aperture/apertureConfig.cmake include/aperture/perception/gap/gap_detector.h)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "the install has no ${installed}")
  endif()
endforeach()

set(configure_args -S ${CONSUMER_SOURCE_DIR} -B ${build} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
if(CXX_COMPILER)
  list(APPEND configure_args -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
if(COMPILER_LAUNCHER)
  list(APPEND configure_args -DCMAKE_CXX_COMPILER_LAUNCHER=${COMPILER_LAUNCHER})
endif()
run_step("configure the consumer" ${CMAKE_COMMAND} ${configure_args})
# The consumer must have found the staged package, not a source or build tree.
file(STRINGS ${build}/CMakeCache.txt aperture_dir REGEX "^aperture_DIR:")
if(NOT aperture_dir MATCHES "=${prefix}/")
  message(FATAL_ERROR "the consumer found aperture outside the staged install: ${aperture_dir}")
endif()
run_step("build the consumer" ${CMAKE_COMMAND} --build ${build})
run_step("run the consumer" ${build}/gap_on_rendered_image)
message("${step_output}")
