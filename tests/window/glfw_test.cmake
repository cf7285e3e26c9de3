cmake_minimum_required(VERSION 3.25)
# A window through GLFW under Xvfb: `thalassa render --backend glfw` opens a window, shows the
# frame, writes the EXR; the frame must equal the headless one (same Mesa rasteriser).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(SMALL --set image.width=48 --set image.height=32)
execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 640x480x24" ${THALASSA} render ${SMALL}
                        --backend glfw -o ${WORK}/window.exr --stats ${WORK}/window.json
                RESULT_VARIABLE window_status ERROR_VARIABLE window_error)
if(NOT window_status EQUAL 0)
  message(FATAL_ERROR "glfw render failed (${window_status}): ${window_error}")
endif()
file(READ ${WORK}/window.json stats)
string(JSON backend GET "${stats}" backend)
if(NOT backend STREQUAL "glfw")
  message(FATAL_ERROR "expected the glfw backend, got ${backend}")
endif()
execute_process(COMMAND ${THALASSA} render ${SMALL} --backend osmesa -o ${WORK}/headless.exr
                RESULT_VARIABLE headless_status)
if(NOT headless_status EQUAL 0)
  message(FATAL_ERROR "headless render failed")
endif()
# The EXR metadata differ (backend, timings), so compare the PNGs, which carry none of them.
file(SHA256 ${WORK}/window.png window_png)
file(SHA256 ${WORK}/headless.png headless_png)
if(NOT window_png STREQUAL headless_png)
  message(FATAL_ERROR "the window's frame differs from the headless one")
endif()
# Without a display, --backend glfw fails at run time with a clear message (status 1).
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=DISPLAY --unset=WAYLAND_DISPLAY
                        ${THALASSA} render ${SMALL} --backend glfw -o ${WORK}/none.exr
                RESULT_VARIABLE none_status ERROR_VARIABLE none_error)
if(NOT none_status EQUAL 1 OR NOT none_error MATCHES "display")
  message(FATAL_ERROR "without a display: status ${none_status}, message: ${none_error}")
endif()
if(EXISTS ${WORK}/none.exr)
  message(FATAL_ERROR "a failed render left ${WORK}/none.exr behind")
endif()
message(STATUS "glfw window render matches the headless render")
