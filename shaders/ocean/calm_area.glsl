// Calm areas on the GPU (issue 9, point 2; docs/wakes.md): the amplitude scale s of
// planet/calm_area.hpp, computed on the CPU in double over a grid of the nadir frame's (x, y)
// plane (ocean/local_features.hpp, CalmScaleChart) and read here with bilinear filtering. The
// ocean's shaders multiply every wave's amplitude by s: the displacement (w_p s h), the normals
// (w_n s h) and the unresolved variance (eq. 4 with w_r s, and the CPU's tails times s^2:
// ocean::calm_tail_variance_bound).
#ifndef THALASSA_OCEAN_CALM_AREA_GLSL
#define THALASSA_OCEAN_CALM_AREA_GLSL

// Texture unit of the chart (ocean::kCalmScaleUnit).
layout(binding = 12) uniform sampler2D calm_scale_map;  // r: s, dimensionless
// xy: the nadir-frame point (m) of sample (0, 0); z: 1 / the samples' spacing (1/m).
uniform vec3 calm_chart;

// s at the nadir-frame point p (m): 1 outside the chart (whose border samples are 1).
float CalmAmplitudeScale(vec2 p) {
  const vec2 size = vec2(textureSize(calm_scale_map, 0));
  const vec2 uv = ((p - calm_chart.xy) * calm_chart.z + 0.5) / size;
  return textureLod(calm_scale_map, uv, 0.0).r;
}

#endif  // THALASSA_OCEAN_CALM_AREA_GLSL
