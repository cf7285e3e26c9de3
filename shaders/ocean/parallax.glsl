// Parallax of the waves drawn in the normals alone (ocean.parallax_iterations;
// docs/ocean_fresnel.md, "The normal-mapped waves' facets: parallax"). Shared GLSL / C++ (DESIGN
// section 8): CPU reference ocean/src/trochoids_reference.hpp, identity tests
// tests/unit/parallax_test.cpp.
//
// WHY. Bruneton et al. 2010 (sec. 3.2) draw the waves longer than the grid's cell as geometry
// (eq. 2, w_p) and those between the pixel and the cell in the normal alone (eq. 3, w_n > w_p).
// Those waves' normals are then read at the rest position x of the rasterised mesh, uniformly
// in the mesh's rest area: a facet tilted away from the eye fills as many pixels as one facing
// it. The true surface shows each facet in proportion to its projected area toward the eye,
// N.v per unit rest area (ocean/visible_area_weight.glsl, the weight the reference gives its
// own samples for the same reason). Facets tilted away reflect at more grazing incidence, where
// Fresnel's factor is larger, so the plain average over-reads: at 1024 x 576, 10 m/s wind seen
// from 100 m, the near rows' reflected sky read 1.11-1.15 of the reference (stop 53,
// docs/validation.md "The methods at a user's resolution").
//
// THE SHIFT. The eye sees, along the pixel's ray, the point of the true surface: the mesh at x'
// displaced by the normal-mapped waves' D(x') (eq. 2's sum over those waves, weights w_n - w_p).
// With the mesh linear about x (tangents m_x, m_y per metre of rest position: its displaced
// area's edges, in the rest tangent frame), the ray r and the shift s = x' - x solve
//   m_x s_x + m_y s_y - t r = -D(x + s)
// for s and the ray's parameter t. The fixed point s = S(D(x + s)) is iterated from s = 0;
// where the waves' slope times the grazing angle's cotangent is below 1 it contracts by that
// factor per step (for slope 0.1 at 20 degrees grazing, 0.27). The map x -> x' then has the
// Jacobian N(x').v / (N_mesh.v), the visible-area weight above, so the pixels sample the
// facets in proportion to their projected area: the identity tests/unit/parallax_test.cpp
// checks. Masking beyond the fixed point's reach (facets hidden behind a crest, where the map
// folds) is not resolved: the iteration stays bounded there (|s| <= |D| / (v.N_mesh) times a
// constant) but lands on any of the folds' branches, so the shift fades out there (below).

#ifndef THALASSA_OCEAN_PARALLAX_GLSL
#define THALASSA_OCEAN_PARALLAX_GLSL

#include "common/definitions.glsl"

// The smallest cosine between the mesh and the eye (v.N_mesh over |N_mesh|) at which a shift is
// computed: a mesh seen more nearly edge-on than 0.6 degrees (its pixels are the silhouette's)
// keeps its rest position rather than divide by almost nothing.
const Number OCEAN_PARALLAX_MIN_MESH_COS = 1e-2;

// One step of the fixed point above: the shift s (m, rest tangent frame: east, north) that puts
// on the ray the point displaced by `displacement` (m, the normal-mapped waves' D at the current
// x + s, rest tangent frame). mesh_dx, mesh_dy: the mesh's tangents (m per m of rest position,
// rest tangent frame; (1, 0, 0) and (0, 1, 0) plus the geometry waves' derivatives, eq. 3 with
// w_p); ray: unit, from the eye (rest tangent frame). Finite for every finite input: 0 where the
// mesh is seen nearly edge-on or from behind.
vec2 OceanParallaxShift(IN(vec3) mesh_dx, IN(vec3) mesh_dy, IN(vec3) ray, IN(vec3) displacement) {
  // Cramer's rule on the columns (mesh_dx, mesh_dy, -ray) with the right side -displacement; the
  // determinant is -ray.(mesh_dx x mesh_dy) = v.N_mesh.
  vec3 area = cross(mesh_dx, mesh_dy);
  Number det = -dot(ray, area);
  if (!(det > OCEAN_PARALLAX_MIN_MESH_COS * length(area))) {
    return vec2(0.0, 0.0);
  }
  vec3 b = -displacement;
  Number s_x = dot(b, cross(mesh_dy, -ray)) / det;
  Number s_y = dot(mesh_dx, cross(b, -ray)) / det;
  return vec2(s_x, s_y);
}

// THE FADE. Where the waves' slope times the cotangent nears 1 the map folds, and the fixed
// point lands on any branch of the fold: a different one from frame to frame as the waves move
// (the default scene from 4 m at 1280 x 720, 0.3-5 degrees below the horizon, changed between
// frames 1/30 s apart 1.56 times as much as without parallax; OceanMethods.
// ParallaxDoesNotFlickerWhereTheWavesFoldTheView). The shift is therefore scaled by a fade of
// q = sigma_v cot theta, sigma_v^2 the normal-mapped waves' slope variance along the view's
// azimuth and theta the grazing angle over the mesh: 1 up to q = 0.4, where 1.2 % of Gaussian
// slopes fold (2 Phi(-1 / q)), falling linearly to 0 at q = 0.8, where 21 % do. The solve is
// linear in D, so a faded shift is the shift of the waves' displacements times the fade.
const Number OCEAN_PARALLAX_FADE_START = 0.4;
const Number OCEAN_PARALLAX_FADE_END = 0.8;

// The fade above (dimensionless, in [0, 1]) for view_slope_variance sigma_v^2 (the normal-mapped
// waves' slope variance along the view's azimuth), the mesh's area vector mesh_area (mesh_dx x
// mesh_dy, any length) and the unit ray from the eye (both in the rest tangent frame). 0 where
// the mesh is seen edge-on or from behind, or for a NaN input.
Number OceanParallaxFade(IN(Number) view_slope_variance, IN(vec3) mesh_area, IN(vec3) ray) {
  Number area = length(mesh_area);
  if (!(area > 0.0)) {
    return 0.0;
  }
  Number sin_grazing = -dot(ray, mesh_area) / area;
  if (!(sin_grazing > OCEAN_PARALLAX_MIN_MESH_COS)) {
    return 0.0;
  }
  Number cot_grazing = sqrt(max(1.0 - sin_grazing * sin_grazing, 0.0)) / sin_grazing;
  Number q = sqrt(max(view_slope_variance, 0.0)) * cot_grazing;
  Number fade =
      (OCEAN_PARALLAX_FADE_END - q) / (OCEAN_PARALLAX_FADE_END - OCEAN_PARALLAX_FADE_START);
  return fade >= 0.0 ? min(fade, 1.0) : 0.0;  // 0 for a NaN q as well
}

#endif  // THALASSA_OCEAN_PARALLAX_GLSL
