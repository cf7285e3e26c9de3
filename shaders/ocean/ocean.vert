// The projected grid's vertex (Bruneton et al. 2010 sec. 3.2, fig. 3): a rest position on the
// sea computed on the CPU in double (ocean/projected_grid.hpp), displaced by the waves longer
// than the grid cell (eq. 2 with w_p), projected back with reversed-Z (infinite far plane). The
// sea at rest is curved with the planet (sec. 6, "a projection on the sphere"; here the frame's
// exact quadric): the waves displace each point in its own tangent frame (FrameSeaTangentFrame),
// their arguments taken at the point's east and north coordinates in the nadir frame.
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "ocean/trochoids.glsl"
#ifdef CALM_AREAS
#include "ocean/calm_area.glsl"
#endif
#ifdef KELVIN_WAKES
#include "ocean/local_waves.glsl"
#endif

// xyz: rest position on the sea at rest, m, nadir frame (common/frame.glsl); w: the grid cell's
// size there, m, negated on the grid's outer ring (the skirt, ocean/src/ocean_node.cpp).
layout(location = 0) in vec4 rest_and_cell;
out vec3 rest_position;  // m, interpolated for the per-pixel normals of the fragment shader
#ifdef PARALLAX_ITERATIONS
// m: the grid's cell, for the fragment shader's w_p (ocean/parallax.glsl: which waves the mesh
// holds and which the normals alone).
out float grid_cell_size;
#endif
#ifdef METHOD_REFERENCE
// m, nadir frame: the displaced point, whose screen derivatives give the rasterised triangle's
// area for the reference's sample weights (ocean/visible_area_weight.glsl).
out vec3 mesh_position;
#endif

// Two vec4 per wave, longest first (see ocean.frag).
layout(std430, binding = 1) readonly buffer Waves { vec4 waves[]; };
uniform int wave_count;
uniform float n_min;  // N_min, N_max of w_p (sec. 3.2)
uniform float n_max;
// Scales every wavelength in the filter weights: 1, falling to 0 as the camera rises to the view
// from space (ocean/gl/ocean_node.hpp, resolved_wave_scale).
uniform float resolved_wave_scale;
// Distance of the near plane, m: depth = OCEAN_NEAR_PLANE / (distance along the view axis).
const float OCEAN_NEAR_PLANE = 0.01;

void main() {
  const vec3 x = rest_and_cell.xyz;
  const float cell = max(abs(rest_and_cell.w), 1e-6);
  vec3 displacement = vec3(0.0);
  // The skirt stays at rest, outside the image: its triangles cover the border wherever the
  // waves moved the ring inside it (ocean/projected_grid.hpp; the reference's grid has none).
  const bool skirt = rest_and_cell.w < 0.0;
  for (int i = 0; i < (skirt ? 0 : wave_count); ++i) {
    const vec4 a = waves[2 * i];
    const vec4 b = waves[2 * i + 1];
#ifdef METHOD_REFERENCE
    const float w_p = 1.0;  // every wave as geometry (issue 6's reference)
#else
    const float w_p = WaveFilterWeight(n_min, n_max, resolved_wave_scale * b.y / cell);
#endif
    if (w_p <= 0.0) break;  // longest first: every later wave is shorter
    const vec2 direction = vec2(a.x, a.y);
    displacement +=
        w_p * TrochoidDisplacement(direction, a.w, TrochoidArgument(a.z * direction, b.x, x.xy));
  }
#ifdef CALM_AREAS
  displacement *= CalmAmplitudeScale(x.xy);  // every wave's h times s (issue 9)
#endif
#ifdef KELVIN_WAKES
  if (!skirt) displacement += LocalWavesDisplacement(x.xy, cell, n_min, n_max, resolved_wave_scale);
#endif
  const vec3 p = x + FrameSeaTangentFrame(x) * displacement;
  // Camera-relative (the camera is at height FrameCameraHeight() above the nadir).
  const vec3 d = p - FrameCameraPosition();
  gl_Position = FrameClipPosition(d, OCEAN_NEAR_PLANE);
  rest_position = x;
#ifdef PARALLAX_ITERATIONS
  grid_cell_size = cell;
#endif
#ifdef METHOD_REFERENCE
  mesh_position = p;
#endif
}
