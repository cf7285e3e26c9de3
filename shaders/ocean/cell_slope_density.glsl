// The slope density of one small cell of a resolved sea, and the sun it reflects: the estimator
// of the reference method's sun (ocean/reference_sun.glsl, issue 6, point 1). Shared GLSL / C++
// (DESIGN section 8): CPU reference ocean/src/ross_brdf_reference.hpp, identity tests
// tests/unit/cell_slope_density_test.cpp, GPU against CPU tests/gpu/reference_test.cpp.
//
// FRAME. As ross_brdf.glsl: the tangent frame of the cell's mean surface (x along the wind,
// y across, z its mean normal); slopes zeta = (dz/dx, dz/dy) dimensionless.
//
// THE MODEL. Across a cell much smaller than the shortest wave the slope field is nearly
// linear, so the cell's slopes spread uniformly over a parallelogram of slope space: centre c,
// edges d_u and d_v (the slope differences across the cell along its two sides). The cell's
// slope density is 1 / |d_u x d_v| inside it and 0 outside, and its glint is that density at the
// mirror slope zeta_h. This is the integral over the cell of delta(zeta(x) - zeta_h) - each
// point of the cell whose facet mirrors the sun counted with 1 / |det dzeta/dx| - for the
// linearised slope field. The sun is not a point: its disc maps to a disc of slope space of
// per-axis variance sigma^2 = OCEAN_SUN_MIN_SLOPE_VARIANCE (ross_brdf.glsl), taken as a Gaussian,
// so the density seen is the parallelogram's convolved with that Gaussian.
//
// WHY NOT A GAUSSIAN PER CELL (stop 15's estimator). A Gaussian of the parallelogram's variance
// (|d|^2 / 12 per edge) is normalised too, but the sum of such Gaussians over cells that tile
// slope space is not flat: for a row of cells of width w, Gaussians of standard deviation
// w / sqrt(12) spaced by w sum to 1 +- 2 exp(-2 pi^2 / 12) = 1 +- 0.39 (Poisson summation). The
// image of a glint then depends on where the cells fall, so an image row's sun changed by 10 %
// between two sets of cells. Boxes whose shared edges are smoothed by the same kernel sum to 1
// exactly (a partition of unity): the estimate no longer depends on where the cells fall, only
// on how well a parallelogram follows the slope field (the test checks both).
//
// THE CONVOLUTION, two cases by the parallelogram's smaller width h = |d_u x d_v| / max(|d_u|,
// |d_v|) (its height over its longer edge):
// - h >= 3 sigma ("box"): the product of the box's two profiles, each smoothed by the Gaussian
//   across its own pair of edges: p = S(t_a; w_a) S(t_b; w_b) / |d_u x d_v|, with t_a the
//   distance from c across the edges parallel to d_v, w_a = |d_u x d_v| / |d_v| their distance
//   apart (and b, w_b the same for d_u), and S(t; w) = Phi((w/2 - t) / sigma) - Phi((-w/2 - t) /
//   sigma). Exact away from the corners; normalised exactly (the integral of S over t is w, and
//   dt_a dt_b = |d_u x d_v| / (|d_u| |d_v|) d^2 zeta); a partition of unity over any tiling whose
//   neighbours share edges.
// - h <= 1.5 sigma ("thin": a sliver, a segment or a point, where the box's two pairs of edges
//   become parallel and the product above would stretch the kernel along them by sigma / sin of
//   their angle): the product of the marginals along the longer edge (unit e, length L: the box L
//   convolved with the shorter edge's projection M = |d_short . e|, taken as a box of L
//   smoothed by sigma^2 + M^2 / 12) and across it (a box of h: a Gaussian of sigma^2 + h^2 / 12,
//   smooth since h < 2 sigma). Normalised exactly; the correlation of the two marginals inside a
//   sheared sliver is neglected, which matters only within h < 1.5 sigma across it.
// - between the two, a linear blend in h / sigma of the two (both normalised).
// A flat cell (d_u = d_v = 0) is the sun's Gaussian: the cell's glint is then eq. 15 with the
// paper's minimum variance exactly.

#ifndef THALASSA_OCEAN_CELL_SLOPE_DENSITY_GLSL
#define THALASSA_OCEAN_CELL_SLOPE_DENSITY_GLSL

#include "common/definitions.glsl"
#include "ocean/ross_brdf.glsl"

// The blend from the thin to the box case, in units of sigma of the height h (above).
const Number OCEAN_CELL_THIN_HEIGHT = 1.5;
const Number OCEAN_CELL_BOX_HEIGHT = 3.0;
// A box narrower than this many sigma is its limit, a Gaussian: S(t; w) / w loses digits to the
// erfc's absolute error (1.5e-7) as w -> 0, while the limit's relative error is w^2 / (24
// sigma^2) < 1e-4 here.
const Number OCEAN_CELL_POINT_WIDTH = 0.05;

// A box of width w >= 0 centred on 0 convolved with the unit-area Gaussian of standard deviation
// sigma > 0, at t (all in the same unit): Phi((w/2 - t) / sigma) - Phi((-w/2 - t) / sigma), in
// [0, 1], 1 deep inside. Written with |t| so that the far edge's term is an erfc of a positive
// argument (its tail keeps its digits).
Number OceanSmoothedBox(IN(Number) t, IN(Number) w, IN(Number) sigma) {
  Number scale = 1.0 / (sqrt(2.0) * sigma);
  Number a = abs(t);
  return 0.5 * (OceanErfc((a - 0.5 * w) * scale) - OceanErfc((a + 0.5 * w) * scale));
}

// The unit-area Gaussian of standard deviation sigma > 0 at t (per unit of t).
Number OceanGaussian1D(IN(Number) t, IN(Number) sigma) {
  Number x = t / sigma;
  return exp(-0.5 * x * x) / (sqrt(2.0 * PI) * sigma);
}

// The box of width w smoothed by sigma, normalised to unit area: S(t; w) / w, or its limit the
// Gaussian for w < OCEAN_CELL_POINT_WIDTH sigma.
Number OceanSmoothedBoxDensity(IN(Number) t, IN(Number) w, IN(Number) sigma) {
  return w < OCEAN_CELL_POINT_WIDTH * sigma ? OceanGaussian1D(t, sigma)
                                            : OceanSmoothedBox(t, w, sigma) / w;
}

// The slope density (per unit slope area) at r = zeta - c of the parallelogram of edges d_u,
// d_v centred on c, convolved with the isotropic Gaussian of standard deviation sigma > 0 (see
// the top of the file). Integrates to 1 over the slope plane for every d_u, d_v.
Number OceanCellSlopeDensity(IN(vec2) r, IN(vec2) d_u, IN(vec2) d_v, IN(Number) sigma) {
  Number length_u = length(d_u);
  Number length_v = length(d_v);
  Number area = abs(d_u.x * d_v.y - d_u.y * d_v.x);
  Number length_long = max(length_u, length_v);
  Number height = length_long > 0.0 ? area / length_long : 0.0;
  Number box = clamp((height / sigma - OCEAN_CELL_THIN_HEIGHT) /
                     (OCEAN_CELL_BOX_HEIGHT - OCEAN_CELL_THIN_HEIGHT), 0.0, 1.0);
  Number density = 0.0;
  if (box < 1.0) {
    vec2 e = vec2(1.0, 0.0);
    Number along_short = 0.0;
    if (length_long > 0.0) {
      e = (length_u >= length_v ? d_u : d_v) / length_long;
      along_short = abs(dot(length_u >= length_v ? d_v : d_u, e));
    }
    Number sigma_along = sqrt(sigma * sigma + along_short * along_short / 12.0);
    Number sigma_across = sqrt(sigma * sigma + height * height / 12.0);
    Number thin = OceanSmoothedBoxDensity(dot(r, e), length_long, sigma_along) *
                  OceanGaussian1D(dot(r, vec2(-e.y, e.x)), sigma_across);
    density += (1.0 - box) * thin;
  }
  if (box > 0.0) {
    // box > 0 means height > 1.5 sigma, so area, length_u and length_v are all > 0.
    vec2 n_a = vec2(-d_v.y, d_v.x) / length_v;  // across the edges parallel to d_v
    vec2 n_b = vec2(-d_u.y, d_u.x) / length_u;  // across those parallel to d_u
    Number product = OceanSmoothedBox(dot(r, n_a), area / length_v, sigma) *
                     OceanSmoothedBox(dot(r, n_b), area / length_u, sigma);
    density += box * product / area;
  }
  return density;
}

// The sun reflected by one cell, per unit L_sun Omega_sun (dimensionless), as
// OceanReflectedSun (eq. 15) with the cell's slope density in place of the Gaussian p: for unit
// v and l (toward the sun's centre) in the cell's tangent frame, the cell's slopes a
// parallelogram of centre c and edges d_u, d_v in that frame, and Schlick's R = fresnel_r.
// Smith's masking uses the parallelogram's per-axis variances (d_u^2 + d_v^2) / 12 plus the
// sun's. 0 for v_z < 0, a sun at or below the horizon, or no mirroring facet.
Number OceanCellReflectedSun(IN(vec3) v, IN(vec3) l, IN(vec2) c, IN(vec2) d_u, IN(vec2) d_v,
                             IN(Number) fresnel_r) {
  if (v.z < 0.0 || l.z <= 0.0) {
    return 0.0;
  }
  vec2 zeta_h;
  Number factor = OceanMirrorFacetFactor(v, l, fresnel_r, zeta_h);
  if (factor <= 0.0) {
    return 0.0;
  }
  Number density =
      OceanCellSlopeDensity(zeta_h - c, d_u, d_v, sqrt(OCEAN_SUN_MIN_SLOPE_VARIANCE));
  vec2 s2 = (d_u * d_u + d_v * d_v) / 12.0 + vec2(OCEAN_SUN_MIN_SLOPE_VARIANCE);
  return density * factor / OceanSunMaskedCosView(v, l, s2);
}

#endif  // THALASSA_OCEAN_CELL_SLOPE_DENSITY_GLSL
