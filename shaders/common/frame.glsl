#ifndef THALASSA_COMMON_FRAME_GLSL
#define THALASSA_COMMON_FRAME_GLSL
// The per-frame uniform block, std140, binding 0. Mirrors thalassa::gl::FrameUniforms
// (engine/include/thalassa/engine/gl/scene_graph.hpp). Directions are unit vectors and positions
// metres in the local east-north-up frame tangent at the camera's nadir (x east, y north, z up;
// origin the nadir point on the sea, the camera at (0, 0, FrameCameraHeight())).
layout(std140, binding = 0) uniform Frame {
  vec4 frame_camera_right;    // xyz; w = tan(fov_y / 2) * aspect
  vec4 frame_camera_up;       // xyz; w = tan(fov_y / 2)
  vec4 frame_camera_forward;  // xyz; w = camera height above the sea surface, m
  vec4 frame_sun_direction;   // xyz toward the sun; w unused
  vec4 frame_viewport;        // width, height, 1 / width, 1 / height (pixels)
  // C of the sea at rest z + 1/2 x^T C x = 0 (1/m; symmetric; 0 for the flat sea): the WGS84
  // ellipsoid or the sphere through the nadir, exactly (ocean/sea_surface.hpp).
  mat3 frame_sea_curvature;
  // xy: where each pixel is sampled, relative to its centre (pixels; 0 but in supersampled
  // renders); z: the side of the pixel's square stratum that the sample stands for (pixels, 1:
  // the whole pixel; the reference's sun integrates over it); w unused.
  vec4 frame_pixel_offset;
};

// The unit view ray through a window position (gl_FragCoord.xy, pixels, origin bottom-left),
// moved by the frame's pixel offset.
vec3 FrameViewRay(vec2 frag_coord) {
  const vec2 ndc = (frag_coord + frame_pixel_offset.xy) * frame_viewport.zw * 2.0 - 1.0;
  return normalize(frame_camera_forward.xyz + ndc.x * frame_camera_right.w * frame_camera_right.xyz +
                   ndc.y * frame_camera_up.w * frame_camera_up.xyz);
}

float FrameCameraHeight() { return frame_camera_forward.w; }
// The camera's position (m, this frame): above the nadir, the frame's origin.
vec3 FrameCameraPosition() { return vec3(0.0, 0.0, FrameCameraHeight()); }

// Clip-space position of a camera-relative point d (m, nadir frame), reversed-Z with an infinite
// far plane (depth = near / distance along the view axis), the image shifted so that each pixel
// centre sees what FrameViewRay(centre) sees.
vec4 FrameClipPosition(vec3 d, float near) {
  const float along = dot(d, frame_camera_forward.xyz);
  return vec4(dot(d, frame_camera_right.xyz) / frame_camera_right.w -
                  2.0 * frame_pixel_offset.x * frame_viewport.z * along,
              dot(d, frame_camera_up.xyz) / frame_camera_up.w -
                  2.0 * frame_pixel_offset.y * frame_viewport.w * along,
              near, along);
}
vec3 FrameSunDirection() { return frame_sun_direction.xyz; }

// The quadratic a t^2 + b t + c of the sea at rest along the unit ray from the camera
// (ocean/sea_surface.hpp, sea_surface_ray_coefficients): every term is small near the camera, so
// float keeps its relative precision from 1 mm to 36,000 km up.
vec3 FrameSeaRayCoefficients(vec3 ray) {
  const float h = FrameCameraHeight();
  const vec3 c_z = frame_sea_curvature[2];
  return vec3(0.5 * dot(ray, frame_sea_curvature * ray), ray.z + h * dot(c_z, ray),
              h * (1.0 + 0.5 * h * c_z.z));
}

// Distance (m) along the unit ray from the camera to the sea at rest, or -1 where it misses
// (the near root 2c / (-b + sqrt(b^2 - 4ac)), free of cancellation).
float FrameSeaDistance(vec3 ray) {
  const vec3 q = FrameSeaRayCoefficients(ray);
  const float discriminant = q.y * q.y - 4.0 * q.x * q.z;
  if (!(q.y < 0.0) || !(discriminant >= 0.0) || !(q.z > 0.0)) return -1.0;
  return 2.0 * q.z / (-q.y + sqrt(discriminant));
}

// The outward unit normal of the sea at rest at the point x (m, this frame).
vec3 FrameSeaNormal(vec3 x) { return normalize(vec3(0.0, 0.0, 1.0) + frame_sea_curvature * x); }

// The tangent frame of the sea at rest at x: east and north of the nadir frame projected on the
// tangent plane and made orthonormal (columns: east, north, up), so that waves defined in the
// nadir's (east, north) keep their directions wherever the planet curves under them.
mat3 FrameSeaTangentFrame(vec3 x) {
  const vec3 up = FrameSeaNormal(x);
  const vec3 east = normalize(vec3(1.0, 0.0, 0.0) - up.x * up);
  return mat3(east, cross(up, east), up);
}
#endif
