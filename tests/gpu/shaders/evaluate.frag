// Evaluates one shared GLSL function per pixel, for comparison with its double-precision C++
// reference (tests/gpu/reference_test.cpp). Inputs come from a float texture, exactly as the
// CPU sees them: texel (x, y) holds the unit view direction (xyz) for that pixel.
#include "common/definitions.glsl"
#if FUNCTION == 1 || FUNCTION == 2
#include "atmosphere/sky_provider.glsl"
#endif
#include "ocean/ross_brdf.glsl"
#include "ocean/cell_slope_density.glsl"
#include "ocean/visible_area_weight.glsl"
#include "ocean/reference_cell.glsl"
#include "ocean/trochoids.glsl"

layout(binding = 0) uniform sampler2D inputs;
uniform vec3 sun_dir;         // unit, east-north-up
uniform vec2 slope_variance;  // (sigma_x^2, sigma_y^2), tangent frame
// FUNCTION 11 and 13: a cell's slope-space edges d_u (xy) and d_v (zw), tangent frame. FUNCTION 12: a
// rasterised triangle's area vector per pixel (xyz, m^2) and the sea at rest's area per pixel
// (w, m^2, vertical).
uniform vec4 cell_edges;
// FUNCTION 6 and 7: the wave set as the ocean node packs it (two vec4 per wave) and the local
// position (m, relative to the frame's origin) in the input texel's xy.
layout(std430, binding = 1) readonly buffer Waves { vec4 waves[]; };
uniform int wave_count;
// FUNCTION 1 and 2: the camera, planet-centred (m), and for 2 the distance (m) to the point
// along the view direction.
uniform vec3 camera;
uniform float point_distance;
layout(location = 0) out vec4 result;

void main() {
  const vec3 v = texelFetch(inputs, ivec2(gl_FragCoord.xy), 0).xyz;
#if FUNCTION == 1
  // The sky's radiance from the atmosphere's tables (no sun disc), and its transmittance's
  // green channel.
  vec3 transmittance;
  const vec3 sky = SkyBackgroundRadiance(camera, v, sun_dir, transmittance);
  result = vec4(sky, transmittance.y);
#elif FUNCTION == 2
  // Aerial perspective to the point at point_distance along v; transmittance's green channel.
  vec3 transmittance;
  const vec3 in_scattered =
      SkyAerialPerspective(camera, camera + point_distance * v, sun_dir, transmittance);
  result = vec4(in_scattered, transmittance.y);
#elif FUNCTION == 5
  // The Ross BRDF's sun term (eq. 15), the effective Fresnel (eq. 26) and Smith's Lambda.
  result = vec4(OceanReflectedSun(v, sun_dir, slope_variance, 0.02),
                OceanEffectiveFresnel(v.z, OceanSlopeVarianceToward(v, slope_variance), 0.02),
                OceanSmithLambdaToward(v, slope_variance), 1.0);
#elif FUNCTION == 8
  // The slope pdf p (eq. 7), the visible-slope pdfs q_vn (eq. 9) and q_vn^e (eq. 10) at the
  // slopes zeta = v.xy / 2, and the filter weight w (sec. 3.2) at the ratio 4 |v.z|.
  const vec2 zeta = vec2(v.x, v.y) * 0.5;
  const vec3 up_v = normalize(vec3(v.x, v.y, abs(v.z) + 0.05));
  result = vec4(OceanSlopePdf(zeta, slope_variance),
                OceanVisibleSlopePdf(zeta, up_v, sun_dir, slope_variance),
                OceanVisibleSlopePdfE(zeta, up_v, slope_variance),
                WaveFilterWeight(1.0, 2.5, 4.0 * abs(v.z)));
#elif FUNCTION == 11
  // The reference's per-cell sun (ocean/cell_slope_density.glsl): the cell's slope density at
  // zeta = v.xy / 20 from its centre, and the sun it reflects toward up_v with its centre at
  // v.xy / 20.
  const vec2 d_u = cell_edges.xy, d_v = cell_edges.zw;
  const vec3 up_v = normalize(vec3(v.x, v.y, abs(v.z) + 0.05));
  result = vec4(OceanCellSlopeDensity(vec2(v.x, v.y) * 0.05, d_u, d_v,
                                      sqrt(OCEAN_SUN_MIN_SLOPE_VARIANCE)),
                OceanCellReflectedSun(up_v, sun_dir, vec2(v.x, v.y) * 0.05, d_u, d_v, 0.02), 0.0,
                1.0);
#elif FUNCTION == 13
  // Where the reference's cell puts its glint (ocean/reference_cell.glsl): the centroid (u, v) of
  // the cell of slope-space edges cell_edges centred on 0 for the mirror slope v.xy / 20, and the
  // mean of the Gaussian of mean 12 v.x and standard deviation 10^(3 v.y) truncated to
  // [-1/2, 1/2].
  result = vec4(ReferenceGlintCentroid(vec2(0.0), cell_edges.xy, cell_edges.zw,
                                       vec2(v.x, v.y) * 0.05, sqrt(OCEAN_SUN_MIN_SLOPE_VARIANCE)),
                ReferenceTruncatedGaussianMean(12.0 * v.x, pow(10.0, 3.0 * v.y)), 1.0);
#elif FUNCTION == 12
  // The reference's sample weight (ocean/visible_area_weight.glsl) of the facet of slopes
  // v.xy / 2 seen toward up_v, on the triangle of cell_edges.xyz and on the sea at rest itself.
  const vec3 up_v = normalize(vec3(v.x, v.y, abs(v.z) + 0.05));
  const vec3 surface = vec3(-0.5 * v.x, -0.5 * v.y, 1.0);
  const vec3 rest = vec3(0.0, 0.0, cell_edges.w);
  result = vec4(OceanReferenceVisibleWeight(surface, rest, cell_edges.xyz, up_v),
                OceanReferenceVisibleWeight(surface, rest, rest, up_v), 0.0, 1.0);
#elif FUNCTION == 9 || FUNCTION == 10
  // The sky-map mapping U at zeta = 0 and its derivatives (eq. 27) for a view above the
  // surface, in a tangent frame tilted from the vertical; and Appendix A's slope variance.
  const vec3 up_v = normalize(vec3(v.x, v.y, abs(v.z) + 0.05));
  const vec3 n = normalize(vec3(0.1, -0.2, 1.0));
  const vec3 t_x = normalize(vec3(1.0, 0.0, 0.0) - n.x * n);
  const vec3 t_y = cross(n, t_x);
  vec2 u0, du_x, du_y;
  OceanSkyMapGradients(up_v, t_x, t_y, n, u0, du_x, du_y);
#if FUNCTION == 9
  result = vec4(u0.x, u0.y, du_x.x, du_x.y);
#else
  result = vec4(du_y.x, du_y.y, TrochoidSlopeVariance(0.9 * abs(v.x)), 1.0);
#endif
#elif FUNCTION == 6 || FUNCTION == 7
  // Eq. 2's displacement (6) and eq. 3's normal (7) of all waves (w = 1) at local position x.
  const vec2 x = vec2(v.x, v.y);
  vec3 p = vec3(x, 0.0);
  vec3 d_dx = vec3(1.0, 0.0, 0.0);
  vec3 d_dy = vec3(0.0, 1.0, 0.0);
  for (int i = 0; i < wave_count; ++i) {
    const vec4 a = waves[2 * i];
    const vec4 b = waves[2 * i + 1];
    const vec2 direction = vec2(a.x, a.y);
    const float argument = TrochoidArgument(a.z * direction, b.x, x);
    p += TrochoidDisplacement(direction, a.w, argument);
    vec3 wave_dx, wave_dy;
    TrochoidDisplacementDerivatives(direction, a.z, a.w, argument, wave_dx, wave_dy);
    d_dx += wave_dx;
    d_dy += wave_dy;
  }
#if FUNCTION == 6
  result = vec4(p - vec3(x, 0.0), 1.0);
#else
  result = vec4(normalize(cross(d_dx, d_dy)), 1.0);
#endif
#endif
}
