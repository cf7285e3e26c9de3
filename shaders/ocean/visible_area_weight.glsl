// The weight of one sample of the reference method's sea: the area of the true surface it stands
// for, seen from the eye, per unit of the area the rasteriser gave it (issue 6, point 1). Shared
// GLSL / C++ (DESIGN section 8): CPU reference ocean/src/ross_brdf_reference.hpp, identity tests
// tests/unit/visible_area_weight_test.cpp, GPU against CPU tests/gpu/reference_test.cpp.
//
// WHY. The reference draws every wave on a grid of one vertex per pixel, so the waves shorter
// than two pixels are aliased in its triangles, and each sample takes its normal from every wave
// exactly at its rest position x (ocean_geometry.frag). A pixel's samples are uniform on the
// screen, that is uniform in the projected area of the rasterised triangles, while the pixel
// sees the true surface's facets in proportion to their own projected area, N.v per unit rest
// area (N = d_dx x d_dy, unnormalised: its length is the displaced area per unit rest area), and
// not at all where they face away. Unweighted, near the horizon the facets tilted away from the
// eye (which the eye sees edge-on or not at all) count as much as those facing it: stop 16
// measured the reference's reflected sky there 1.4 to 2.2 times the full method's, the size a
// toy model gave for this bias (docs/validation.md).
//
// THE WEIGHT of a sample at rest position x:
//   w = max(N.v, 0) |x_dx x x_dy| / |(p_dx x p_dy).v|
// with x_dx, x_dy the rest position's screen derivatives (m per pixel: |x_dx x x_dy| is the rest
// area of one pixel) and p_dx, p_dy the rasterised triangle's (its projected area toward the
// eye, per pixel). The pixel's sea is then sum(w L) / sum(w) over its sea samples: self-
// normalised, so that the weight's overall scale (the pixel's distance, the triangle's size)
// cancels. Identities (the test): a flat sea drawn flat has w = 1 exactly; for a Gaussian sea
// drawn flat the mean of w over the sea at rest is the Smith facing area cos theta_v (1 +
// Lambda(v)) / cos theta_v (smith.glsl), so the weighted average over a pixel's facets is their
// average over the facets' visible projected area: under Smith's uncorrelated masking (which
// eq. 15's 1 + Lambda denominators assume, and which makes the masking of a facet facing the eye
// independent of its slope) that is the distribution of the visible normals. Masking by a
// crest is otherwise not modelled: the rasterised grid resolves visibility at the pixel's scale.

#ifndef THALASSA_OCEAN_VISIBLE_AREA_WEIGHT_GLSL
#define THALASSA_OCEAN_VISIBLE_AREA_WEIGHT_GLSL

#include "common/definitions.glsl"

// The smallest |cos| between a rasterised triangle and the eye that the weight divides by: a
// triangle seen more nearly edge-on than 0.06 degrees covers almost no pixel, and its few
// samples are then weighted as if it were seen at that angle (at most 1e3 times a face-on one's)
// rather than without bound.
const Number OCEAN_REFERENCE_MIN_MESH_COS = 1e-3;

// The weight w above with N.v given (projected, per unit rest area: an average of N.v over some
// cells of the pixel, as the reference's sun takes them). Dimensionless, >= 0, finite for every
// finite input; the arguments as for OceanReferenceVisibleWeight.
Number OceanReferenceProjectedWeight(IN(Number) projected, IN(vec3) rest_area, IN(vec3) mesh_area,
                                     IN(vec3) v) {
  Number mesh_length = length(mesh_area);
  Number mesh_projected = max(abs(dot(mesh_area, v)), OCEAN_REFERENCE_MIN_MESH_COS * mesh_length);
  if (!(mesh_projected > 0.0)) {
    return 0.0;  // a degenerate triangle has no pixel
  }
  return max(projected, 0.0) * length(rest_area) / mesh_projected;
}

// The weight w above (dimensionless, >= 0, finite for every finite input). surface_area: N =
// d_dx x d_dy of the sea with every wave, per unit rest area, in the frame of v; rest_area: x_dx
// x x_dy (m^2 per pixel); mesh_area: p_dx x p_dy (m^2 per pixel), either orientation (a folded
// triangle seen from behind is still what the pixel shows); v: unit, toward the eye.
Number OceanReferenceVisibleWeight(IN(vec3) surface_area, IN(vec3) rest_area, IN(vec3) mesh_area,
                                   IN(vec3) v) {
  return OceanReferenceProjectedWeight(dot(surface_area, v), rest_area, mesh_area, v);
}

#endif  // THALASSA_OCEAN_VISIBLE_AREA_WEIGHT_GLSL
