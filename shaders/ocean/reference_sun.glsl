// The reference method's reflected sun (issue 6, point 1; Bruneton, Neyret & Holzschuch 2010,
// sec. 7.2: "several normal samples per pixel - up to 512 - to correctly sample the Sun, which
// occupies only 1/8000th of the hemisphere"). Included by ocean_geometry.frag with
// METHOD_REFERENCE and REFERENCE_SUN, after its Waves buffer.
//
// Why not point samples. A mirror reflects the sun's 0.27 degree disc toward the eye only where
// the slope lies in a disc of radius ~2.3e-3 around the mirror slope: about 7e-5 of a 10 m/s
// sea's slopes. Averaging point-sampled normals converges as 1 / sqrt(hits): 256 samples per
// pixel still changed an image row's sun by 96 % per doubling (stop 13).
//
// What is done instead. The pixel's footprint on the sea at rest (the parallelogram spanned by
// the rasterised rest positions' screen derivatives) is cut into Kx x Ky cells no wider than
// `reference_spacing` (a fraction of the shortest wave's length, so that every wave is resolved
// and its slope varies nearly linearly across a cell). On each cell the slope field is the
// bilinear patch of its four corners' exact slopes (every wave, w_n = 1), taken in the tangent
// frame of the cell's mean normal; its slopes spread over the parallelogram of slope space that
// the corners span, and the sun the cell reflects is eq. 15 with that parallelogram's density,
// convolved with the sun's disc, in place of the Gaussian p (OceanCellReflectedSun,
// ocean/cell_slope_density.glsl). Summed over cells this is the integral over the footprint of
// delta(slope(x) - mirror slope) - the sum over the footprint's points that mirror the sun of
// 1 / |det d slope / d x| - seen through the sun's disc: no sampling noise from the sun's tiny
// disc, and, because the cells' parallelograms tile slope space as the cells tile the sea (a
// partition of unity), hardly any dependence on where the cells fall (stop 15's Gaussian per
// cell rippled by up to 39 % with it; docs/validation.md). Cells are weighted by their displaced
// area projected toward the eye, N.v with N = d_dx x d_dy (per unit rest area: the visible
// area, as the rasteriser weights the pixel's samples); back-facing cells (N.v < 0) are hidden
// (0). Masking of a cell by a crest inside the same pixel is not modelled: the rasterised grid
// resolves visibility at the pixel's scale only.
//
// Strata. The renderer cuts each pixel into s x s square strata and gives each frame's sample a
// point in one of them (FrameInputs::pixel_stratum, the stratum's side, 1/s pixel): the sample
// integrates the sun over its stratum's footprint only, so that every s^2 samples integrate
// the whole pixel once, with cells s times finer per side than one footprint of the whole pixel
// at the same cost. The cells tile the stratum's footprint exactly, wherever the sample lies in
// it. (Until stop 18 they were shifted by up to half a cell with the sample's place in the
// stratum, so that the Gaussian per cell of stop 15, which rippled with where the cells fell,
// averaged over the shifts; the parallelogram per cell is a partition of unity and needs no
// shift, and without it each round covers the stratum itself rather than a copy blurred by a
// cell: at 8 cells per wavelength the median row's change between 16 and 32 samples fell from
// 2.8 % to 1.3 %; at the default 16 the change is within the noise, docs/validation.md.)

#ifndef THALASSA_OCEAN_REFERENCE_SUN_GLSL
#define THALASSA_OCEAN_REFERENCE_SUN_GLSL

#include "ocean/reference_cell.glsl"

// m: the largest cell side on the sea at rest that counts as resolved (ocean_node.cpp:
// kReferenceSpacingFraction x the shortest wavelength of the set).
uniform float reference_spacing;
// Most cells per stratum side (ReferenceSampling::sun_cells); REFERENCE_MAX_CELLS is the
// compile-time bound of the row buffer below.
uniform int reference_max_cells;
const int REFERENCE_MAX_CELLS = 64;
uniform float fresnel_r;  // R of Schlick's Fresnel (eq. 14), as in ocean_lighting.frag

// Slope (dimensionless, nadir-frame east and north of the local tangent plane: n = (s, 1)
// normalised, as ocean_geometry.frag's `slope`) and visible area weight N.v (per unit rest area)
// of the surface with every wave (calm areas and wakes included), at rest position x (m, nadir
// frame).
vec3 ReferenceSlopeAndWeight(vec3 x, vec3 v) {
  vec3 d_dx = vec3(1.0, 0.0, 0.0);
  vec3 d_dy = vec3(0.0, 1.0, 0.0);
#ifdef CALM_AREAS
  const float calm = CalmAmplitudeScale(x.xy);  // issue 9: every wave's h scaled by s
#else
  const float calm = 1.0;
#endif
  for (int i = 0; i < wave_count; ++i) {
    const vec4 a = waves[2 * i];
    const vec4 b = waves[2 * i + 1];
    const vec2 direction = vec2(a.x, a.y);
    vec3 wave_dx, wave_dy;
    TrochoidDisplacementDerivatives(direction, a.z, a.w,
                                    TrochoidArgument(a.z * direction, b.x, x.xy), wave_dx, wave_dy);
    d_dx += calm * wave_dx;
    d_dy += calm * wave_dy;
  }
#ifdef KELVIN_WAKES
  // The wakes' waves, every one resolved (a vanishing footprint gives w_n = 1, w_r = 0).
  vec2 no_variance = vec2(0.0);
  LocalWavesNormals(x.xy, 1e-6, n_min, n_max, 1.0, vec2(1.0, 0.0), d_dx, d_dy, no_variance);
#endif
  const vec3 n_local = cross(d_dx, d_dy);  // unnormalised: |n_local| is the displaced area ratio
  const float weight = max(dot(FrameSeaTangentFrame(x) * n_local, v), 0.0);
  return vec3(n_local.xy / max(n_local.z, 1e-6), weight);
}

// The sun reflected by the pixel's stratum whose sample point on the sea at rest is x (m, nadir
// frame), with rest-position screen derivatives dx, dy (m per pixel), per unit L_sun Omega_sun
// as OceanReflectedSun; v toward the eye, sun toward the sun (nadir frame), downwind unit (east,
// north). Returns (sun factor, 1 if every cell is at most reference_spacing wide else 0, the
// cells' mean N.v per unit rest area: the stratum's visible area per unit rest area).
vec3 ReferenceReflectedSun(vec3 x, vec3 dx, vec3 dy, vec3 v, vec3 sun, vec2 downwind) {
  const int max_cells = clamp(reference_max_cells, 1, REFERENCE_MAX_CELLS);
  const float spacing = max(reference_spacing, 1e-6);
  const float stratum = clamp(frame_pixel_offset.z, 1e-3, 1.0);  // pixels
  const float want_x = ceil(length(dx) * stratum / spacing);
  const float want_y = ceil(length(dy) * stratum / spacing);
  const int kx = int(clamp(want_x, 1.0, float(max_cells)));
  const int ky = int(clamp(want_y, 1.0, float(max_cells)));
  const float resolved = (want_x <= float(max_cells) && want_y <= float(max_cells)) ? 1.0 : 0.0;
  // The sample point x lies at the pixel's centre + o (FrameViewRay), in the stratum whose lower
  // corner is at centre + lo. Corner (i, j) of the cells, in pixels from x: lo - o + (i, j) *
  // stratum / k. With one stratum (stratum 1, lo -0.5) the cells tile the whole pixel.
  const vec2 o = frame_pixel_offset.xy;
  const vec2 lo = floor((o + 0.5) / stratum) * stratum - 0.5;
  const vec2 k = vec2(float(kx), float(ky));
  const vec2 step = stratum / k;
  const vec2 corner0 = lo - o;

  // The previous row of corners: slope (xy) and weight (z).
  vec3 previous[REFERENCE_MAX_CELLS + 1];
  float sum_weight = 0.0, sum_sun = 0.0;
  for (int j = 0; j <= ky; ++j) {
    vec3 left = vec3(0.0);
    for (int i = 0; i <= kx; ++i) {
      const vec2 c = corner0 + vec2(float(i), float(j)) * step;
      const vec3 here = ReferenceSlopeAndWeight(x + c.x * dx + c.y * dy, v);
      if (i > 0 && j > 0) {
        const vec3 c00 = previous[i - 1], c10 = previous[i], c01 = left, c11 = here;
        const vec2 slope = 0.25 * (c00.xy + c10.xy + c01.xy + c11.xy);
        const float weight = 0.25 * (c00.z + c10.z + c01.z + c11.z);
        if (weight > 0.0) {
          const vec3 cell_point = x + (c.x - 0.5 * step.x) * dx + (c.y - 0.5 * step.y) * dy;
          const mat3 frame = FrameSeaTangentFrame(cell_point);
          vec3 n = frame * normalize(vec3(slope, 1.0));
          if (dot(n, v) < 0.0) n = normalize(n - 2.0 * dot(n, v) * v);
          const vec3 wind = vec3(downwind, 0.0);
          const vec3 t_x = normalize(wind - dot(wind, n) * n);
          const vec3 t_y = cross(n, t_x);
          // The corners' slopes in the cell's tangent frame, and the parallelogram they span
          // (ocean/cell_slope_density.glsl): centre, edges along the cell's two sides.
          const vec2 z00 = ReferenceCellFrameSlope(frame * vec3(c00.xy, 1.0), t_x, t_y, n);
          const vec2 z10 = ReferenceCellFrameSlope(frame * vec3(c10.xy, 1.0), t_x, t_y, n);
          const vec2 z01 = ReferenceCellFrameSlope(frame * vec3(c01.xy, 1.0), t_x, t_y, n);
          const vec2 z11 = ReferenceCellFrameSlope(frame * vec3(c11.xy, 1.0), t_x, t_y, n);
          const vec2 centre = 0.25 * (z00 + z10 + z01 + z11);
          const vec2 d_u = 0.5 * ((z10 - z00) + (z11 - z01));
          const vec2 d_v = 0.5 * ((z01 - z00) + (z11 - z10));
          sum_sun += weight * OceanCellReflectedSun(OceanToTangentFrame(v, t_x, t_y, n),
                                                    OceanToTangentFrame(sun, t_x, t_y, n), centre,
                                                    d_u, d_v, fresnel_r);
          sum_weight += weight;
        }
      }
      if (i > 0) previous[i - 1] = left;
      left = here;
    }
    previous[kx] = left;
  }
  return vec3(sum_weight > 0.0 ? sum_sun / sum_weight : 0.0, resolved,
              sum_weight / float(kx * ky));
}

#endif  // THALASSA_OCEAN_REFERENCE_SUN_GLSL
