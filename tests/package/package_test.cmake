cmake_minimum_required(VERSION 3.25)  # run with -P: policies (IN_LIST) need a version
# Installs thalassa from the build tree into a temporary prefix, then configures, builds and
# runs tests/package/consumer against it with find_package(thalassa). The consumer runs with
# THALASSA_SHADER_PATH unset and THALASSA_SHADER_BUILTIN_PATHS=0, so the only shaders it can
# find are share/thalassa/shaders beside the installed library.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK}/prefix
                RESULT_VARIABLE status OUTPUT_QUIET)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "cmake --install failed")
endif()
foreach(header thalassa/thalassa.hpp thalassa/engine/scene.hpp thalassa/version.hpp)
  if(NOT EXISTS ${WORK}/prefix/include/${header})
    message(FATAL_ERROR "installed tree lacks include/${header}")
  endif()
endforeach()
file(GLOB_RECURSE installed_shaders RELATIVE ${WORK}/prefix/share/thalassa/shaders
     ${WORK}/prefix/share/thalassa/shaders/*)
file(GLOB_RECURSE source_shaders RELATIVE ${SOURCE_DIR}/shaders
     ${SOURCE_DIR}/shaders/*.glsl ${SOURCE_DIR}/shaders/*.vert ${SOURCE_DIR}/shaders/*.frag)
foreach(shader ${source_shaders})
  if(NOT shader IN_LIST installed_shaders)
    message(FATAL_ERROR "share/thalassa/shaders lacks ${shader}")
  endif()
endforeach()
if(EXISTS ${WORK}/prefix/include/thalassa/engine/gl)
  message(FATAL_ERROR "the GL-level headers must not be installed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/consumer -B ${WORK}/build
                        -DCMAKE_PREFIX_PATH=${WORK}/prefix -DCMAKE_BUILD_TYPE=Release
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "configuring the consumer failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/build
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "building the consumer failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=THALASSA_SHADER_PATH
                        THALASSA_SHADER_BUILTIN_PATHS=0
                        LD_LIBRARY_PATH=${WORK}/prefix/lib:${WORK}/prefix/lib/x86_64-linux-gnu
                        ${WORK}/build/consumer
                WORKING_DIRECTORY ${WORK}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the consumer failed (${status}):\n${out}\n${err}")
endif()
message(STATUS "${out}")
# The installed program finds its installed shaders too.
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=THALASSA_SHADER_PATH
                        THALASSA_SHADER_BUILTIN_PATHS=0
                        ${WORK}/prefix/bin/thalassa render --set image.width=8 --set image.height=8
                        -o ${WORK}/installed.exr
                WORKING_DIRECTORY ${WORK} RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the installed thalassa failed (${status}): ${err}")
endif()
