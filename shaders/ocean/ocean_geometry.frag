// The ocean's first pass (Bruneton, Neyret & Holzschuch 2010, sec. 3.2; the paper's sec. 7.3
// times it as "positions + normals + variances"): on the projected grid of ocean.vert, each
// pixel's normal sums the waves longer than the pixel at the pixel's rest position (eq. 3 with
// w_n; not from the filtered positions), and the shorter ones give the unresolved slope
// variance (eq. 4, w_r = 1 - w_n). Both go to a G-buffer that ocean_lighting.frag shades.
//
// METHOD_BASIC, METHOD_NORMALS and METHOD_REFERENCE select the methods the validation compares
// with it (ocean/method.hpp; issue 6, paper sec. 7.2, fig. 10). PARALLAX_ITERATIONS
// (ocean.parallax_iterations) takes the normals of the waves drawn in the normals alone where the
// pixel's ray meets them (ocean/parallax.glsl).
//
// With BACKSTOP the same shader runs as a full-screen pass after the grid, on the pixels the
// grid left uncovered (depth test EQUAL to the cleared far depth): their rest position is where
// the view ray meets the sea at rest. A camera lower than the crests around it (1.5 m over a
// 15 m/s sea) sees triangles displaced past it, folded or seen from below; without the backstop
// those pixels showed the sky pass's dark "ground" (issue 3).
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "ocean/trochoids.glsl"
#include "ocean/parallax.glsl"
#ifdef CALM_AREAS
#include "ocean/calm_area.glsl"
#endif
#ifdef KELVIN_WAKES
#include "ocean/local_waves.glsl"
#endif

#ifdef BACKSTOP
// The depth test must reject the covered pixels before the shader runs (the discard below would
// otherwise let a driver defer the test past the wave sum).
layout(early_fragment_tests) in;
#else
in vec3 rest_position;  // m, on the sea at rest, nadir frame (ocean.vert)
#ifdef PARALLAX_ITERATIONS
in float grid_cell_size;  // m (ocean.vert)
#endif
#ifdef METHOD_REFERENCE
in vec3 mesh_position;  // m, the rasterised (displaced) triangle's point, nadir frame (ocean.vert)
#endif
#endif
layout(location = 0) out vec4 normal_out;    // xyz: unit normal, east-north-up; w: 1 (coverage)
// xy: slope variance along, across the wind. METHOD_REFERENCE (a mirror, no variance): x the
// sample's visible-area weight (ocean/visible_area_weight.glsl), y 1 where the reference's sun
// resolved every wave (or has no sun) else 0, z the sun it reflects (ocean/reference_sun.glsl).
layout(location = 1) out vec4 variance_out;

// Two vec4 per wave, longest first: (direction east, direction north, |k| rad/m, h m) and
// (wrapped phase rad, wavelength m, unused, unused). See ocean/src/ocean_node.cpp.
layout(std430, binding = 1) readonly buffer Waves { vec4 waves[]; };
// tails[i] = slope variance (along, across the wind) of the waves j >= i (Appendix A, eq. 4
// with w_r = 1), wave_count + 1 entries, summed on the CPU in double.
layout(std430, binding = 2) readonly buffer Tails { vec2 tails[]; };

uniform int wave_count;
// Largest slope variance the pixel's own normal variation adds (see main): 0.02, about a
// 10 m/s sea's whole slope variance.
const float ANTIALIAS_MAX_VARIANCE = 0.02;
uniform vec2 downwind;  // unit, east-north-up
uniform float n_min;    // N_min, N_max of w_n (sec. 3.2)
uniform float n_max;
// Scales every wavelength in the filter weights: 1, falling to 0 as the camera rises to the view
// from space (ocean/gl/ocean_node.hpp, resolved_wave_scale).
uniform float resolved_wave_scale;
#ifdef METHOD_BASIC
// Fig. 10's basic method: one slope variance (along, across the wind) for every pixel, the full
// method's in the image's foreground (ocean/method.hpp).
uniform vec2 constant_variance;
#endif
#ifdef METHOD_REFERENCE
#include "ocean/visible_area_weight.glsl"
#endif
#if defined(METHOD_REFERENCE) && defined(REFERENCE_SUN)
#include "ocean/cell_slope_density.glsl"
#include "ocean/reference_sun.glsl"
#endif
// The backstop's surface is the sea at rest, and the reference's mesh holds every wave: neither
// takes the parallax.
#if defined(PARALLAX_ITERATIONS) && !defined(BACKSTOP) && !defined(METHOD_REFERENCE)
#define OCEAN_PARALLAX
#endif

// Eq. 3's w_n of a wave of this wavelength (m) at a pixel of this footprint (m).
float NormalWeight(float wavelength, float footprint) {
  return WaveFilterWeight(n_min, n_max, resolved_wave_scale * wavelength / footprint);
}

// The share w_mesh of a wave's normal taken at the mesh's rest position x: with OCEAN_PARALLAX
// the mesh's own, min(w_p, w_n) (w_p of the grid's cell, as ocean.vert), the rest w_n - w_mesh
// taken where the pixel's ray meets the waves (ocean/parallax.glsl); without it all of w_n.
float MeshShare(float wavelength, float w_n) {
#ifdef OCEAN_PARALLAX
  return min(WaveFilterWeight(n_min, n_max, resolved_wave_scale * wavelength / grid_cell_size),
             w_n);
#else
  return w_n;
#endif
}

void main() {
  const vec3 ray = FrameViewRay(gl_FragCoord.xy);
#ifdef BACKSTOP
  // Where the ray meets the sea at rest; a ray that misses it gets the flat sea's point (clamped
  // at grazing) so that the derivatives stay finite before its pixel is discarded.
  const float distance = FrameSeaDistance(ray);
  const vec3 x = FrameCameraPosition() +
                 (distance >= 0.0 ? distance : FrameCameraHeight() / max(-ray.z, 1e-6)) * ray;
#else
  const vec3 x = rest_position;
#endif
  // The pixel's footprint on the sea (m): its larger side, so that no resolved wave aliases.
  const vec3 x_dx = dFdx(x);
  const vec3 x_dy = dFdy(x);
  const float footprint = max(max(length(x_dx), length(x_dy)), 1e-6);
#ifdef METHOD_REFERENCE
  // The rasterised surface's screen derivatives (m per pixel), for the sample's weight; the
  // backstop's surface is the sea at rest itself.
#ifdef BACKSTOP
  const vec3 mesh_dx = x_dx, mesh_dy = x_dy;
#else
  const vec3 mesh_dx = dFdx(mesh_position), mesh_dy = dFdy(mesh_position);
#endif
#endif
#ifdef BACKSTOP
  if (distance < 0.0) discard;  // the sky's pixel
#endif

  // The normal is summed in the tangent frame of the sea at rest and turned into the nadir frame
  // (below), and the parallax takes the ray in that frame. That frame is the one where the
  // pixel's ray meets the sea at rest, not at x: x is interpolated across the grid's triangles,
  // chords of the curved sea, and a grazing ray meets a chord far from where it meets the sea (a chord of 170 km sags 0.57 km; seen 1 degree above it, the ray's meeting moves
  // by 33 km and the rest normal turns by 5e-3 rad, a third of a 3 m/s sea's slope deviation).
  // Where waves are displaced, x and the ray's meeting with the sea at rest part by the
  // displacement over the grazing angle's tangent, which turns the frame by 1.6e-4 rad a
  // kilometre: 3e-5 rad for a 0.3 m crest seen 0.1 degree above the sea. Measured on a 3 m/s sea
  // seen from 8 km at 64 x 36, whose cells span 10 degrees, against the same view at 8 x 8 finer
  // pixels (tests/gpu/method_test.cpp): in the rows 2.5 and 3.8 degrees below the horizon the sun
  // went from 0.68 and 0.88 of it to 1.11 and 1.05 (the rest is the pixel's own average, whose
  // factors of eq. 15 are the centre's while the grazing angle changes by half of itself across
  // such a pixel), the reflected sky from 1.047 and 1.022 to 1.006 and 1.001. A ray that misses
  // the sea at rest (a crest above the horizon) keeps x.
#ifdef BACKSTOP
  const vec3 x_frame = x;
#else
  const float frame_distance = FrameSeaDistance(ray);
  const vec3 x_frame =
      frame_distance >= 0.0 ? FrameCameraPosition() + frame_distance * ray : x;
#endif
  const mat3 rest_frame = FrameSeaTangentFrame(x_frame);

  // Eq. 3 with w_n, and the unresolved variance of eq. 4 with w_r = 1 - w_n: waves are sorted
  // longest first, so w_n falls with the index and the loops end at the first unresolved wave.
  // Each wave's normal is taken at the mesh's rest position x with the weight w_mesh (MeshShare)
  // and, with OCEAN_PARALLAX, at the rest position x + shift that the pixel's ray sees once the
  // waves drawn in the normals alone are lifted onto the mesh, with w_n - w_mesh. Without
  // parallax every normal is taken at x, and the sums are the paper's eq. 3 term for term.
  const vec2 crosswind = vec2(-downwind.y, downwind.x);
  vec3 d_dx = vec3(1.0, 0.0, 0.0);
  vec3 d_dy = vec3(0.0, 1.0, 0.0);
  vec2 partial_variance = vec2(0.0);
  int first_unresolved = wave_count;
#ifdef CALM_AREAS
  const float calm = CalmAmplitudeScale(x.xy);  // s of every wave's h (issue 9)
#else
  const float calm = 1.0;
#endif
  // The waves the mesh holds whole (w_mesh = 1) come first; from first_partial on, the normal
  // and the variance loop below takes the rest.
  int first_partial = wave_count;
  for (int i = 0; i < wave_count; ++i) {
    const vec4 a = waves[2 * i];
    const vec4 b = waves[2 * i + 1];
#ifdef METHOD_REFERENCE
    const float w_mesh = 1.0;  // every wave's normal, exactly at the sample (issue 6's reference)
#else
    const float w_mesh = MeshShare(b.y, NormalWeight(b.y, footprint));
#endif
    if (w_mesh < 1.0 && first_partial == wave_count) first_partial = i;
    if (w_mesh <= 0.0) break;
    const vec2 direction = vec2(a.x, a.y);
    vec3 wave_dx, wave_dy;
    TrochoidDisplacementDerivatives(direction, a.z, a.w,
                                    TrochoidArgument(a.z * direction, b.x, x.xy), wave_dx, wave_dy);
    d_dx += w_mesh * calm * wave_dx;
    d_dy += w_mesh * calm * wave_dy;
  }
  vec2 shift = vec2(0.0);  // m, rest tangent frame
#ifdef OCEAN_PARALLAX
  {
    // The ray in the rest tangent frame; the mesh's tangents are the geometry's share of eq. 3
    // just summed.
    const vec3 ray_t = transpose(rest_frame) * ray;
    // The view's azimuth, along which the waves' slopes fold the map (OceanParallaxFade).
    const float ray_horizontal = length(ray_t.xy);
    const vec2 azimuth = ray_horizontal > 0.0 ? ray_t.xy / ray_horizontal : vec2(0.0);
    float fade = 0.0;
    for (int iteration = 0; iteration < PARALLAX_ITERATIONS; ++iteration) {
      vec3 displacement = vec3(0.0);  // m: the normal-mapped waves' eq. 2 at x + shift
      float view_variance = 0.0;      // their slope variance along the azimuth (first step)
      for (int i = first_partial; i < wave_count; ++i) {
        const vec4 a = waves[2 * i];
        const vec4 b = waves[2 * i + 1];
        const float w_n = NormalWeight(b.y, footprint);
        if (w_n <= 0.0) break;
        const float w_shifted = w_n - MeshShare(b.y, w_n);
        const vec2 direction = vec2(a.x, a.y);
        displacement +=
            w_shifted * TrochoidDisplacement(direction, a.w,
                                             TrochoidArgument(a.z * direction, b.x, x.xy + shift));
        if (iteration == 0) {
          const float along = dot(direction, azimuth);
          view_variance += TrochoidSlopeVariance(a.z * w_shifted * calm * a.w) * along * along;
        }
      }
      if (iteration == 0) {
        fade = OceanParallaxFade(view_variance, cross(d_dx, d_dy), ray_t);
        if (fade <= 0.0) break;  // the shift stays 0
      }
      shift = fade * OceanParallaxShift(d_dx, d_dy, ray_t, calm * displacement);
    }
  }
#endif
  for (int i = first_partial; i < wave_count; ++i) {
    const vec4 a = waves[2 * i];
    const vec4 b = waves[2 * i + 1];
    const float w_n = NormalWeight(b.y, footprint);
    if (w_n <= 0.0) {
      first_unresolved = i;
      break;
    }
    const vec2 direction = vec2(a.x, a.y);
#ifdef OCEAN_PARALLAX
    const float w_shifted = w_n - MeshShare(b.y, w_n);
    if (w_shifted > 0.0) {
      vec3 wave_dx, wave_dy;
      TrochoidDisplacementDerivatives(direction, a.z, a.w,
                                      TrochoidArgument(a.z * direction, b.x, x.xy + shift),
                                      wave_dx, wave_dy);
      d_dx += w_shifted * calm * wave_dx;
      d_dy += w_shifted * calm * wave_dy;
    }
#endif
    if (w_n < 1.0) {
      const float variance = TrochoidSlopeVariance(a.z * (1.0 - w_n) * calm * a.w);
      const float along = dot(direction, downwind);
      const float across = dot(direction, crosswind);
      partial_variance += variance * vec2(along * along, across * across);
    }
  }
#ifdef KELVIN_WAKES
  LocalWavesNormals(x.xy, footprint, n_min, n_max, resolved_wave_scale, downwind, d_dx, d_dy,
                    partial_variance);
#endif
  const vec3 v = -ray;  // toward the eye
  const vec3 area_local = cross(d_dx, d_dy);  // displaced area per unit rest area
  const vec3 n_local = normalize(area_local);
  vec3 n = rest_frame * n_local;  // the frame where the ray meets the sea at rest (above)
  // Sec. 3.2: a normal facing away from the viewer is reflected back toward it.
  if (dot(n, v) < 0.0) n = normalize(n - 2.0 * dot(n, v) * v);
  normal_out = vec4(n, 1.0);
  // The resolved normal still varies inside the pixel (the waves just above the w_n cut-off are
  // 1 to 2.5 pixels long), and a BRDF no wider than the unresolved variance then samples the
  // sun's tiny reflection at one point of that variation: glitter that aliases and flickers near
  // the camera. The variation is added to the slope variance as the variance of the slopes over
  // the pixel: for slopes that change linearly by d across a pixel, d^2 / 12 (a box filter's),
  // from their screen-space derivatives along and across the wind (specular anti-aliasing in
  // the manner of Kaplanyan et al. 2016, "Filtering distributions of normals for shading
  // antialiasing"). It keeps the energy (the BRDF stays normalised) and removes the sparkle that
  // one sample per pixel cannot resolve; capped at ANTIALIAS_MAX_VARIANCE so that a slope jump
  // across a silhouette does not turn a pixel into a diffuse one.
  const vec2 slope = vec2(n_local.x, n_local.y) / max(n_local.z, 1e-3);
  const vec2 wind_slope = vec2(dot(slope, downwind), dot(slope, crosswind));
  const vec2 slope_dx = dFdx(wind_slope);
  const vec2 slope_dy = dFdy(wind_slope);
  const vec2 pixel_variance =
      min((slope_dx * slope_dx + slope_dy * slope_dy) / 12.0, vec2(ANTIALIAS_MAX_VARIANCE));
#ifdef METHOD_REFERENCE
  // A mirror for the sky and the refracted light, weighted by the visible area of the facet it
  // samples (the renderer's draw_reference averages a pixel's sea samples with it); the sun
  // reflected by the sample's stratum of the pixel, resolved cell by cell.
#ifdef REFERENCE_SUN
  // (sun, resolved, the stratum's mean N.v over its cells).
  const vec3 sun = ReferenceReflectedSun(x, x_dx, x_dy, v, FrameSunDirection(), downwind);
#else
  const vec3 sun = vec3(0.0, 1.0, 0.0);
#endif
#ifdef REFERENCE_SUN_ONLY
  // The sun alone: its cells weigh the stratum's facets by their visible area already, so the
  // stratum weighs by its cells' mean N.v, smooth, rather than by the sample point's, which
  // varies with every short wave (noise between the pixel's strata, nothing else).
  const float weight = OceanReferenceProjectedWeight(sun.z, cross(x_dx, x_dy),
                                                     cross(mesh_dx, mesh_dy), v);
#else
  const float weight = OceanReferenceVisibleWeight(FrameSeaTangentFrame(x) * area_local,
                                                   cross(x_dx, x_dy), cross(mesh_dx, mesh_dy), v);
#endif
  variance_out = vec4(weight, sun.y, sun.x, 0.0);
#elif defined(METHOD_NORMALS)
  // A mirror: no BRDF width (the sun term keeps its disc's, ocean/ross_brdf.glsl).
  variance_out = vec4(0.0);
#elif defined(METHOD_BASIC)
  variance_out = vec4(constant_variance, 0.0, 0.0);
#else
  variance_out =
      vec4(calm * calm * tails[first_unresolved] + partial_variance + pixel_variance, 0.0, 0.0);
#endif
}
