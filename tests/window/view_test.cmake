cmake_minimum_required(VERSION 3.25)
# `thalassa view` under Xvfb: the window's frame is the headless render's, its screenshot's scene
# file draws the same image again, a flight it records replays from the same first frame, a
# flight it plays starts from fly's first frame, its clock runs unless paused, and bad input or
# no display stop it before anything is written.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(SMALL --set image.width=48 --set image.height=32)

function(run_view name)
  execute_process(COMMAND ${XVFB_RUN} -a -s "-screen 0 640x480x24" ${THALASSA} view ${SMALL}
                          ${ARGN} RESULT_VARIABLE status ERROR_VARIABLE error)
  set(${name}_status ${status} PARENT_SCOPE)
  set(${name}_error "${error}" PARENT_SCOPE)
endfunction()

# Three frames, the clock stopped, the last one written.
run_view(paused --frames 3 --paused --screenshot ${WORK}/view.exr)
if(NOT paused_status EQUAL 0)
  message(FATAL_ERROR "view failed (${paused_status}): ${paused_error}")
endif()
foreach(file view.exr view.png view.json)
  if(NOT EXISTS ${WORK}/${file})
    message(FATAL_ERROR "view wrote no ${file}")
  endif()
endforeach()
execute_process(COMMAND ${THALASSA} render ${SMALL} --backend osmesa -o ${WORK}/headless.exr
                RESULT_VARIABLE headless_status)
if(NOT headless_status EQUAL 0)
  message(FATAL_ERROR "headless render failed")
endif()
file(SHA256 ${WORK}/view.png view_png)
file(SHA256 ${WORK}/headless.png headless_png)
if(NOT view_png STREQUAL headless_png)
  message(FATAL_ERROR "the viewer's frame differs from the headless render of its scene")
endif()
# The screenshot's scene file is a scene: `thalassa render` draws the same image from it.
execute_process(COMMAND ${THALASSA} render ${WORK}/view.json --backend osmesa -o ${WORK}/again.exr
                RESULT_VARIABLE again_status ERROR_VARIABLE again_error)
if(NOT again_status EQUAL 0)
  message(FATAL_ERROR "render of the screenshot's scene failed: ${again_error}")
endif()
file(SHA256 ${WORK}/again.png again_png)
if(NOT again_png STREQUAL view_png)
  message(FATAL_ERROR "the screenshot's scene file draws another image")
endif()

# A recorded flight: a flight file whose first frame, rendered by `fly`, is the viewer's first.
run_view(recorded --frames 8 --paused --record ${WORK}/flight.json)
if(NOT recorded_status EQUAL 0 OR NOT EXISTS ${WORK}/flight.json)
  message(FATAL_ERROR "view --record failed (${recorded_status}): ${recorded_error}")
endif()
file(READ ${WORK}/flight.json flight)
string(JSON keys LENGTH "${flight}" keyframes)
string(JSON first_time GET "${flight}" keyframes 0 time)
math(EXPR last_key "${keys} - 1")
string(JSON last_time GET "${flight}" keyframes ${last_key} time)
string(JSON duration GET "${flight}" duration)
if(keys LESS 2 OR NOT first_time EQUAL 0 OR NOT last_time STREQUAL duration)
  message(FATAL_ERROR "the recorded flight's keyframes: ${keys}, from ${first_time} to "
                      "${last_time}, duration ${duration}")
endif()
execute_process(COMMAND ${THALASSA} fly ${WORK}/flight.json --backend osmesa --frames 0
                        -o ${WORK}/replay RESULT_VARIABLE replay_status ERROR_VARIABLE replay_error)
if(NOT replay_status EQUAL 0)
  message(FATAL_ERROR "fly of the recorded flight failed: ${replay_error}")
endif()
file(SHA256 ${WORK}/replay/frame_00000.png replay_png)
if(NOT replay_png STREQUAL headless_png)
  message(FATAL_ERROR "the recorded flight's first frame differs from the viewer's")
endif()
# The clock was stopped: every keyframe keeps the scene's time of the first frame (scene_time),
# the exposure never changed and is left out, and every frame `fly` renders is the viewer's
# (camera, sun and waves still; without scene_time the replay's waves would run).
string(JSON base_time GET "${flight}" scene time)
string(JSON first_clock ERROR_VARIABLE first_clock_error GET "${flight}" keyframes 0 scene_time)
string(JSON last_clock ERROR_VARIABLE last_clock_error GET "${flight}" keyframes ${last_key}
       scene_time)
string(JSON image ERROR_VARIABLE no_image GET "${flight}" keyframes 0 image)
if(first_clock_error OR last_clock_error OR NOT first_clock EQUAL base_time
   OR NOT last_clock EQUAL base_time OR NOT no_image)
  message(FATAL_ERROR "the stopped clock's flight: scene_time ${first_clock} to ${last_clock} "
                      "(the scene's ${base_time}; ${first_clock_error}${last_clock_error}), "
                      "image ${image}")
endif()
# (At 200 frames a second: the eight frames last a few tens of ms, at least 2 ms a step under
# Xvfb, and 1.75 s at most.)
execute_process(COMMAND ${THALASSA} fly ${WORK}/flight.json --backend osmesa --fps 200
                        -o ${WORK}/replay_all --stats ${WORK}/replay_all.json
                RESULT_VARIABLE replay_all_status ERROR_VARIABLE replay_all_error)
file(GLOB replayed ${WORK}/replay_all/frame_*.png)
list(LENGTH replayed replayed_count)
if(NOT replay_all_status EQUAL 0 OR replayed_count LESS 2)
  message(FATAL_ERROR "fly of the whole recorded flight failed or gave ${replayed_count} frames: "
                      "${replay_all_error}")
endif()
file(READ ${WORK}/replay_all.json replay_stats)
math(EXPR last_frame "${replayed_count} - 1")
string(JSON last_scene_time GET "${replay_stats}" frames ${last_frame} scene_time)
if(NOT last_scene_time EQUAL base_time)
  message(FATAL_ERROR "the stopped clock's last frame has the scene time ${last_scene_time}")
endif()
foreach(png ${replayed})
  file(SHA256 ${png} png_hash)
  if(NOT png_hash STREQUAL headless_png)
    message(FATAL_ERROR "${png} of the stopped clock's flight differs from the viewer's frame")
  endif()
endforeach()

# A flight played in the window: at its start, the frame `fly` renders first (the default flight,
# from 400 km: the space mode); with the clock running, the camera moves along it.
run_view(played --flight ${DATA}/flights/orbit_to_surface.json --paused --frames 2
         --screenshot ${WORK}/played.exr)
execute_process(COMMAND ${THALASSA} fly ${SMALL} --backend osmesa --frames 0 -o ${WORK}/default_fly
                RESULT_VARIABLE default_fly_status)
if(NOT played_status EQUAL 0 OR NOT default_fly_status EQUAL 0)
  message(FATAL_ERROR "view --flight (${played_status}) or fly (${default_fly_status}) failed: "
                      "${played_error}")
endif()
file(SHA256 ${WORK}/played.png played_png)
file(SHA256 ${WORK}/default_fly/frame_00000.png default_fly_png)
if(NOT played_png STREQUAL default_fly_png)
  message(FATAL_ERROR "the played flight's first frame differs from fly's")
endif()
# A flight that keys the exposure sets it as it plays: from 2.5 at its start (the viewer's first
# scene) up toward 40 by the third frame.
file(WRITE ${WORK}/exposure_flight.json [=[{"keyframes": [
  {"time": 0, "image": {"exposure": 2.5}}, {"time": 1, "image": {"exposure": 40}}]}]=])
run_view(exposure --flight ${WORK}/exposure_flight.json --frames 3
         --screenshot ${WORK}/exposure.exr)
file(READ ${WORK}/exposure.json exposure_scene)
string(JSON played_exposure GET "${exposure_scene}" image exposure)
if(NOT exposure_status EQUAL 0 OR NOT played_exposure GREATER 2.5
   OR NOT played_exposure LESS_EQUAL 40)
  message(FATAL_ERROR "the played flight's exposure (${exposure_status}): ${played_exposure}, "
                      "${exposure_error}")
endif()
run_view(playing --flight ${DATA}/flights/orbit_to_surface.json --frames 3
         --screenshot ${WORK}/playing.exr)
file(READ ${WORK}/playing.json playing)
string(JSON playing_height GET "${playing}" camera height)
if(NOT playing_status EQUAL 0 OR NOT playing_height LESS 400000)
  message(FATAL_ERROR "the played flight did not move (${playing_status}): height "
                      "${playing_height}, ${playing_error}")
endif()

# The clock runs by default: the scene's time has moved on by the last frame. Recorded, a clock
# at rate 1 needs no scene_time: the flight's waves run with it.
run_view(running --frames 3 --screenshot ${WORK}/running.exr --record ${WORK}/running_flight.json)
if(NOT running_status EQUAL 0)
  message(FATAL_ERROR "view failed (${running_status}): ${running_error}")
endif()
file(READ ${WORK}/running.json running)
string(JSON time GET "${running}" time)
if(NOT time GREATER 0)
  message(FATAL_ERROR "the clock did not run: time ${time}")
endif()
file(READ ${WORK}/running_flight.json running_flight)
string(JSON running_clock ERROR_VARIABLE no_running_clock GET "${running_flight}" keyframes 0
       scene_time)
if(NOT no_running_clock)
  message(FATAL_ERROR "a clock at rate 1 recorded its scene_time ${running_clock}")
endif()

# Bad input: status 2 before any window, nothing written.
# A camera flown below a crest rides it: at 0.3 m with the clock stopped at 8 s, where the default
# sea stands 0.77 m high under it (`thalassa sea`), the frame's camera is kWaveClearance (0.25 m)
# above the water, not inside the wave; without the floor it stays at 0.3 m.
run_view(riding --frames 2 --paused --set camera.height=0.3 --set time=8
         --screenshot ${WORK}/riding.exr)
execute_process(COMMAND ${THALASSA} sea --set time=8 RESULT_VARIABLE sea_status
                OUTPUT_VARIABLE sea_csv ERROR_VARIABLE sea_error)
string(REGEX MATCH "\n[^,]*,[^,]*,[^,]*,([^,]*)," sea_row "${sea_csv}")
set(sea_height "${CMAKE_MATCH_1}")
if(NOT riding_status EQUAL 0 OR NOT sea_status EQUAL 0 OR NOT sea_height GREATER 0.3)
  message(FATAL_ERROR "view (${riding_status}) or sea (${sea_status}) failed, or the sea's "
                      "height ${sea_height} is not above the camera: ${riding_error}${sea_error}")
endif()
file(READ ${WORK}/riding.json riding_scene)
string(JSON riding_height GET "${riding_scene}" camera height)
if(NOT riding_height GREATER sea_height OR NOT riding_height LESS 1.1)
  message(FATAL_ERROR "the camera at 0.3 m over water ${sea_height} m high was drawn at "
                      "${riding_height} m")
endif()
run_view(bad_key --set camera.height=-20000 --frames 1 --screenshot ${WORK}/bad.exr)
if(NOT bad_key_status EQUAL 2 OR NOT bad_key_error MATCHES "camera.height")
  message(FATAL_ERROR "a bad key: status ${bad_key_status}, message: ${bad_key_error}")
endif()
run_view(bad_name --frames 1 --screenshot ${WORK}/bad.png)
if(NOT bad_name_status EQUAL 2 OR NOT bad_name_error MATCHES "--screenshot")
  message(FATAL_ERROR "a screenshot not .exr: status ${bad_name_status}, message: ${bad_name_error}")
endif()
run_view(both --flight ${DATA}/flights/orbit_to_surface.json ${DATA}/scenes/wake_demo/wake_50m.json
         --frames 1 --screenshot ${WORK}/bad.exr)
if(NOT both_status EQUAL 2 OR NOT both_error MATCHES "not both")
  message(FATAL_ERROR "a scene and a flight: status ${both_status}, message: ${both_error}")
endif()
run_view(same_json --frames 1 --record ${WORK}/bad.json --screenshot ${WORK}/bad.exr)
if(NOT same_json_status EQUAL 2 OR NOT same_json_error MATCHES "the same file")
  message(FATAL_ERROR "a flight where the screenshot's scene file goes: status "
                      "${same_json_status}, message: ${same_json_error}")
endif()
run_view(bad_record --frames 1 --record ${WORK}/bad.txt)
if(NOT bad_record_status EQUAL 2 OR NOT bad_record_error MATCHES "--record")
  message(FATAL_ERROR "a flight not .json: status ${bad_record_status}, message: ${bad_record_error}")
endif()
# Without a display: status 1 and a message that says so.
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=DISPLAY --unset=WAYLAND_DISPLAY
                        ${THALASSA} view ${SMALL} --frames 1 --screenshot ${WORK}/none.exr
                RESULT_VARIABLE none_status ERROR_VARIABLE none_error)
if(NOT none_status EQUAL 1 OR NOT none_error MATCHES "display")
  message(FATAL_ERROR "without a display: status ${none_status}, message: ${none_error}")
endif()
foreach(file bad.exr bad.png bad.txt bad.json none.exr)
  if(EXISTS ${WORK}/${file})
    message(FATAL_ERROR "a failed view left ${WORK}/${file} behind")
  endif()
endforeach()
message(STATUS "the viewer's frame matches the headless render, and its scene file draws it again")
