// The geometry of one cell of the reference's sun lattice (issue 6, point 1;
// ocean/reference_sun_scatter.comp), in the shared GLSL / C++ subset so that the CPU tests check
// it in double (tests/unit/reference_cell_test.cpp).
#include "common/definitions.glsl"

#ifndef THALASSA_OCEAN_REFERENCE_CELL_GLSL
#define THALASSA_OCEAN_REFERENCE_CELL_GLSL

// The height z (m) of the sea at rest above the rest point's horizontal position xy (m, nadir
// frame): the root near 0 of the frame's quadric z + 1/2 p^T C p = 0, p = (x, y, z), C the
// symmetric curvature (1/m; common/frame.glsl). As a quadratic in z, a z^2 + b z + c = 0 with
// a = C_zz / 2, b = 1 + C_xz x + C_yz y, c = (C_xx x^2 + 2 C_xy x y + C_yy y^2) / 2; the root
// 2c / (-b - sqrt(b^2 - 4ac)) is free of cancellation (c and z are small near the nadir, where
// the printed -b + sqrt(...) would lose them). Beyond the quadric's silhouette (b^2 < 4ac: past
// the planet's limb, 6,400 km for the Earth) the discriminant is clamped at 0.
Number ReferenceRestHeight(IN(mat3) curvature, IN(vec2) xy) {
  Number a = 0.5 * curvature[2][2];
  Number b = 1.0 + curvature[0][2] * xy.x + curvature[1][2] * xy.y;
  Number c = 0.5 * (curvature[0][0] * xy.x * xy.x + 2.0 * curvature[1][0] * xy.x * xy.y +
                    curvature[1][1] * xy.y * xy.y);
  Number discriminant = max(b * b - 4.0 * a * c, 0.0);
  return -2.0 * c / (b + sqrt(discriminant));
}

// The slopes zeta (dimensionless) in the tangent frame (t_x, t_y, n) of a facet of normal f
// (any length, same frame as the axes): f = (-zeta, 1) up to its length. A corner tilted 90
// degrees or more from the cell's mean normal (not a small cell of a resolved sea) is held at
// 1e6.
vec2 ReferenceCellFrameSlope(IN(vec3) f, IN(vec3) t_x, IN(vec3) t_y, IN(vec3) n) {
  return -vec2(dot(f, t_x), dot(f, t_y)) / max(dot(f, n), 1e-6 * length(f));
}

// Where in its cell the glint lies: the cell's slopes (dimensionless, in its tangent frame) are
// c + u d_u + v d_v for (u, v) in [-1/2, 1/2]^2 (the parallelogram of
// ocean/cell_slope_density.glsl), and the mirror slope m (the slope of the half vector) is
// reached at the (u, v) that solves the 2 x 2 system [d_u d_v] (u, v) = m - c. The solution is
// clamped to the cell: a cell whose slopes miss m reflects only the tail of the sun's disc, from
// its nearest edge. A degenerate parallelogram (|det| below 1e-6 of the product of its edges' lengths,
// or both edges 0: a flat cell) gives the cell's centre (0, 0).
vec2 ReferenceGlintCoordinates(IN(vec2) c, IN(vec2) d_u, IN(vec2) d_v, IN(vec2) m) {
  Number det = d_u.x * d_v.y - d_u.y * d_v.x;
  Number scale = dot(d_u, d_u) * dot(d_v, d_v);
  if (!(abs(det) > 1e-6 * sqrt(scale)) || !(scale > 0.0)) return vec2(0.0, 0.0);
  vec2 r = m - c;
  vec2 uv = vec2(r.x * d_v.y - r.y * d_v.x, d_u.x * r.y - d_u.y * r.x) / det;
  return clamp(uv, vec2(-0.5, -0.5), vec2(0.5, 0.5));
}

// Past this standard deviation (in units of the interval's width) the truncated Gaussian below
// is taken as an exponential tilt of the interval: its log-density's curvature across the
// interval, 1 / (2 s^2) < 0.008, is then left out.
const Number REFERENCE_TILT_SD = 4.0;

// exp(x^2) erfc(x) (dimensionless) for x >= 0, to a relative 1.1e-7 (measured against long
// double from 0 to 26, tests/unit/reference_cell_test.cpp; the formula is also asymptotically
// right): the Chebyshev fit of Press, Teukolsky, Vetterling & Flannery, Numerical Recipes (2nd
// ed., 1992), sec. 6.2, erfc(x) = t exp(-x^2 + P(t)), t = 1 / (1 + x / 2), without its exp(-x^2),
// so that nothing underflows. No loop (llvmpipe's shared loop budget, ocean_node.cpp) and no
// cancellation: A&S 7.1.26's polynomial (OceanScaledErfcPolynomial) is 0.7 % off at x = 5 and
// 38 % as x -> infinity, which the truncated Gaussian's mean below multiplied by the distance in
// standard deviations.
const Number REFERENCE_ERFC_C0 = -1.26551223;
const Number REFERENCE_ERFC_C1 = 1.00002368;
const Number REFERENCE_ERFC_C2 = 0.37409196;
const Number REFERENCE_ERFC_C3 = 0.09678418;
const Number REFERENCE_ERFC_C4 = -0.18628806;
const Number REFERENCE_ERFC_C5 = 0.27886807;
const Number REFERENCE_ERFC_C6 = -1.13520398;
const Number REFERENCE_ERFC_C7 = 1.48851587;
const Number REFERENCE_ERFC_C8 = -0.82215223;
const Number REFERENCE_ERFC_C9 = 0.17087277;
Number ReferenceScaledErfc(IN(Number) x) {
  Number t = 1.0 / (1.0 + 0.5 * x);
  Number p = REFERENCE_ERFC_C8 + t * REFERENCE_ERFC_C9;
  p = REFERENCE_ERFC_C7 + t * p;
  p = REFERENCE_ERFC_C6 + t * p;
  p = REFERENCE_ERFC_C5 + t * p;
  p = REFERENCE_ERFC_C4 + t * p;
  p = REFERENCE_ERFC_C3 + t * p;
  p = REFERENCE_ERFC_C2 + t * p;
  p = REFERENCE_ERFC_C1 + t * p;
  return t * exp(REFERENCE_ERFC_C0 + t * p);
}

// The mean (in the interval's units) of the Gaussian of mean mu and standard deviation s > 0
// truncated to [-1/2, 1/2] (the normal distribution's truncated mean, mu + s (phi(a) - phi(b)) /
// (Phi(b) - Phi(a)), a and b the edges in standard deviations). Written for float: mirrored so
// that the mean lies at or left of the centre; for s > REFERENCE_TILT_SD the density is
// exp(g x) up to a constant, g = mu / s^2, whose mean is coth(g / 2) / 2 - 1 / g (its series
// for |g| < 1); with the interval right of the mean, the ratio from exp(x^2) erfc(x)
// (ReferenceScaledErfc), which does not underflow.
Number ReferenceTruncatedGaussianMean(IN(Number) mu, IN(Number) s) {
  if (!(s > 0.0)) {
    return clamp(mu, -0.5, 0.5);
  }
  Number side = mu > 0.0 ? -1.0 : 1.0;
  Number m = -abs(mu);
  Number mean = 0.0;
  if (s > REFERENCE_TILT_SD) {
    Number g = m / (s * s);  // <= 0
    if (g > -1.0) {
      // The series (coth(x) = 1 / x + x / 3 - x^3 / 45 + 2 x^5 / 945 - ...): the closed form
      // below loses a float's digits to e - 1 and to the difference as g -> 0. The next term,
      // g^7 / 1209600, is below 8.3e-7.
      Number g2 = g * g;
      mean = g * (1.0 / 12.0 - g2 * (1.0 / 720.0 - g2 / 30240.0));
    } else {
      Number e = exp(g);  // coth(g / 2) = (1 + e) / (e - 1) for g < 0
      mean = 0.5 * (1.0 + e) / (e - 1.0) - 1.0 / g;
    }
  } else {
    Number a = (-0.5 - m) / s;
    Number b = (0.5 - m) / s;
    if (a >= 0.0) {
      // phi(a) - phi(b) and Phi(b) - Phi(a), both over exp(-a^2 / 2) / 2.
      Number shrink = exp(-0.5 * (b - a) * (b + a));
      Number numerator = 1.0 - shrink;
      Number denominator = ReferenceScaledErfc(a / sqrt(2.0)) -
                           shrink * ReferenceScaledErfc(b / sqrt(2.0));
      mean = m + s * sqrt(2.0 / PI) * numerator / max(denominator, 1e-30);
    } else {
      Number mass = 1.0 - 0.5 * exp(-0.5 * b * b) * ReferenceScaledErfc(b / sqrt(2.0)) -
                    0.5 * exp(-0.5 * a * a) * ReferenceScaledErfc(-a / sqrt(2.0));
      Number density = (exp(-0.5 * a * a) - exp(-0.5 * b * b)) / sqrt(2.0 * PI);
      mean = m + s * density / max(mass, 1e-30);
    }
  }
  return side * clamp(mean, -0.5, 0.5);
}

// One coordinate of ReferenceGlintCentroid's conditionals: the mean over the cell's [-1/2, 1/2]
// along `edge` of the sun's Gaussian G(r - x edge - t other) (r = m - c), t the other
// coordinate; 0 (the centre) where the edge spans less than 1e-6 sigma of slope.
Number ReferenceConditionalCentroid(IN(vec2) r, IN(vec2) edge, IN(vec2) other, IN(Number) t,
                                    IN(Number) sigma) {
  Number length2 = dot(edge, edge);
  if (!(length2 > 1e-12 * sigma * sigma)) {
    return 0.0;
  }
  return ReferenceTruncatedGaussianMean(dot(r - t * other, edge) / length2,
                                        sigma / sqrt(length2));
}

// Where in its cell the glint's light comes from: the centroid, over the cell's (u, v) in
// [-1/2, 1/2]^2, of the weight with which each point reflects the sun's disc, G(c + u d_u + v d_v
// - m) (G the disc's isotropic Gaussian of standard deviation sigma, per slope axis; the cell's
// slopes and m as in ReferenceGlintCoordinates). Its sun goes to the pixel that sees that point.
// Why not the glint's own point, clamped (ReferenceGlintCoordinates, until stop 32): a glint
// spreads over the sea where the slopes lie within the disc of the mirror slope, sigma / |slope
// gradient| across (1.5e-4 m on the 20 m/s sea's 0.04 m waves), and a cell inside that spread
// put all of its light at its edge nearest the mirror point, so the share of a glint on either
// side of a pixel's edge converged only as the cells' size, slowly (a footprint's half 1.7-3.4 %
// per doubling at 16 cells per wavelength x 8, still 0.1-0.7 % at 128); with the centroid, 0.01-
// 0.07 % from 16 on (docs/validation.md, stop 32). Cells wider than the spread reach the glint's
// point; cells much narrower, their centre.
// The centroid of the Gaussian on the square, from its conditionals: each a truncated Gaussian
// along one edge (mean the point of that edge's line nearest m in slope space once the other
// coordinate is fixed, standard deviation sigma / |edge|), v given u = 0, then u given that v,
// alternately, three times each (written out: no loop). Exact after the first pair where d_u and
// d_v are orthogonal; for sheared cells within 0.01 of the cell's side of the true centroid
// (tests/unit/reference_cell_test.cpp; 0.11 after one and a half pairs). Finite for every
// parallelogram: an edge with no slope change, or below 1e-6 sigma of it, leaves its coordinate
// at the centre, where the weight is uniform along it.
vec2 ReferenceGlintCentroid(IN(vec2) c, IN(vec2) d_u, IN(vec2) d_v, IN(vec2) m, IN(Number) sigma) {
  vec2 r = m - c;
  Number v = ReferenceConditionalCentroid(r, d_v, d_u, 0.0, sigma);
  Number u = ReferenceConditionalCentroid(r, d_u, d_v, v, sigma);
  v = ReferenceConditionalCentroid(r, d_v, d_u, u, sigma);
  u = ReferenceConditionalCentroid(r, d_u, d_v, v, sigma);
  v = ReferenceConditionalCentroid(r, d_v, d_u, u, sigma);
  u = ReferenceConditionalCentroid(r, d_u, d_v, v, sigma);
  return vec2(u, v);
}

// The point (any units, any frame) of the bilinear patch through the cell's corners p00, p10,
// p01, p11 at (u, v) in [-1/2, 1/2]^2 (u from p00 to p10, v from p00 to p01).
vec3 ReferenceBilinear(IN(vec3) p00, IN(vec3) p10, IN(vec3) p01, IN(vec3) p11, IN(vec2) uv) {
  Number s = uv.x + 0.5;
  Number t = uv.y + 0.5;
  return (1.0 - t) * ((1.0 - s) * p00 + s * p10) + t * ((1.0 - s) * p01 + s * p11);
}

// The solid angle (sr) the cell subtends seen from the eye, with its facets' visible projection:
// area the mean of its corners' displaced area vectors per unit rest area (d_dx x d_dy, nadir
// frame; dimensionless), rest_area the cell's area on the sea at rest (m^2), to_eye from the
// cell to the eye (m, nadir frame; not unit). A cell facing away from the eye is hidden: 0.
Number ReferenceCellSolidAngle(IN(vec3) area, Number rest_area, IN(vec3) to_eye) {
  Number distance = length(to_eye);
  if (!(distance > 0.0)) return 0.0;
  return max(dot(area, to_eye), 0.0) * rest_area / (distance * distance * distance);
}

#endif  // THALASSA_OCEAN_REFERENCE_CELL_GLSL
