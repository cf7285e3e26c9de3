#ifndef THALASSA_COMMON_FRAME_GLSL
#define THALASSA_COMMON_FRAME_GLSL
// The per-frame uniform block, std140, binding 0. Mirrors thalassa::gl::FrameUniforms
// (engine/include/thalassa/engine/gl/scene_graph.hpp). Directions are unit vectors in the
// local east-north-up frame at the camera's nadir (x east, y north, z up).
layout(std140, binding = 0) uniform Frame {
  vec4 frame_camera_right;    // xyz; w = tan(fov_y / 2) * aspect
  vec4 frame_camera_up;       // xyz; w = tan(fov_y / 2)
  vec4 frame_camera_forward;  // xyz; w = camera height above the sea surface, m
  vec4 frame_sun_direction;   // xyz toward the sun; w unused
  vec4 frame_viewport;        // width, height, 1 / width, 1 / height (pixels)
};

// The unit view ray through a window position (gl_FragCoord.xy, pixels, origin bottom-left).
vec3 FrameViewRay(vec2 frag_coord) {
  const vec2 ndc = frag_coord * frame_viewport.zw * 2.0 - 1.0;
  return normalize(frame_camera_forward.xyz + ndc.x * frame_camera_right.w * frame_camera_right.xyz +
                   ndc.y * frame_camera_up.w * frame_camera_up.xyz);
}

float FrameCameraHeight() { return frame_camera_forward.w; }
vec3 FrameSunDirection() { return frame_sun_direction.xyz; }
#endif
