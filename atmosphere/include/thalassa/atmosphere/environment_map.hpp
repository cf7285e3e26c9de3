// thalassa — a sky provider built from an HDR photograph: an equirectangular (latitude-longitude)
// environment map, with the sun taken out of it, the sky irradiance, the ocean paper's radiance
// below the horizon, and the stereographic sky map and panorama the renderer uploads (issue 4,
// point 4). CPU only, double-precision arithmetic, no GL. Documented in docs/sky.md.
//
// Conventions (used by every function here)
// -----------------------------------------
// * Frame: the local east-north-up (ENU) frame, x east, y north, z up. Directions are unit
//   vectors in it; the queries normalise what they are given and throw std::invalid_argument on
//   a zero or non-finite vector.
// * Angles: radians. Azimuth alpha is measured clockwise from north (north 0, east pi / 2), so
//   d = (sin alpha sin theta, cos alpha sin theta, cos theta) for the zenith angle theta.
// * The photograph (width W, height H, W = 2H exactly): rows top first; row y covers zenith
//   angles theta in [pi y / H, pi (y + 1) / H], so the top edge is the zenith and the bottom edge
//   the nadir; column x covers azimuths alpha in [north_offset + 2 pi x / W,
//   north_offset + 2 pi (x + 1) / W]. With north_offset = 0 the left edge looks north and east
//   is a quarter of the way right. A texel's value is its radiance at the texel centre and its
//   average over the texel (the map is read bilinearly between centres, and integrated as
//   constant over each texel).
// * Radiance: spectral radiance in W m^-2 sr^-1 nm^-1 at 680, 550, 440 nm for R, G, B
//   (shaders/common/definitions.glsl) = the photo's pixel value times `scale`. Irradiance: the
//   same times sr, W m^-2 nm^-1. Colours are std::array<double, 3> (R, G, B).
// * Errors: a file or image that cannot serve as a sky throws EnvironmentMapError naming the
//   source and what is wrong; a bad argument to a query (a zero direction, a map size below 1)
//   throws std::invalid_argument. No query returns NaN.
//
// Source of the below-horizon radiance: Bruneton, Neyret & Holzschuch 2010, "Real-time realistic
// ocean lighting using seamless transitions from geometry to BRDF" (../shared/papers/000_*),
// sec. 6 "Multiple reflections".
#pragma once

#include <array>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "thalassa/engine/image.hpp"

namespace thalassa::atmosphere {

using Vec3 = std::array<double, 3>;  // a direction, ENU
using Vec2 = std::array<double, 2>;  // stereographic sky-map coordinates u (dimensionless)
using Rgb = std::array<double, 3>;   // R, G, B at 680, 550, 440 nm

// A photograph or image that cannot serve as a sky: unreadable, not 2:1, too small, with
// negative or non-finite pixels, or a bad option. The message names the source and the problem.
class EnvironmentMapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// ---- Stereographic sky-map coordinates (the ocean's eq. 27 map) ---------------------------

// The default half-width of the stereographic map's square, in u units: the map covers
// u in [-kSkyMapExtent, kSkyMapExtent]^2. The horizon is the unit circle, so the corners and
// edges (|u| > 1: 12.7 deg below the horizon at the edge midpoints, 31 deg at the corners) hold
// directions below the horizon, filled with below_horizon_radiance(): the ocean's filtered
// (mipmapped, anisotropic) fetch near the horizon then averages the multiple-reflection radiance
// that the paper puts there, rather than a clamped edge texel of a map that ends at the horizon.
inline constexpr double kSkyMapExtent = 1.25;
// The largest |u| stereographic_coordinates() returns (near the nadir, which maps to infinity):
// the same value and rule as OCEAN_SKY_MAP_MAX_RADIUS / OceanStereographic in
// shaders/ocean/ross_brdf.glsl (the tests check that they agree).
inline constexpr double kSkyMapMaxRadius = 1000.0;

// u = (r_x, r_y) / (1 + r_z) for the unit direction r (ENU; normalised here): the zenith maps to
// (0, 0), the horizon to |u| = 1, the lower hemisphere outside it. Within
// 2 / kSkyMapMaxRadius rad of the nadir (1 + r_z < 2 / kSkyMapMaxRadius^2) |u| is held at
// kSkyMapMaxRadius along (r_x, r_y); the nadir itself maps to (kSkyMapMaxRadius, 0).
Vec2 stereographic_coordinates(const Vec3& direction);
// The inverse: r = (2 u_x, 2 u_y, 1 - |u|^2) / (1 + |u|^2), a unit ENU vector, evaluated
// without overflow for any finite u (|u| -> infinity tends to the nadir). Throws
// std::invalid_argument on a non-finite u.
Vec3 stereographic_direction(const Vec2& u);

// ---- Equirectangular texels ------------------------------------------------------------

// The exact solid angle (sr) of any texel of row y of a width x height equirectangular map:
// (2 pi / width) (cos theta_top - cos theta_bottom), theta_top = pi y / height, evaluated as
// (2 pi / width) 2 sin((theta_top + theta_bottom) / 2) sin(pi / (2 height)) so that rows at
// the poles keep full relative precision. The texels of a map sum to 4 pi.
double equirect_texel_solid_angle(int width, int height, int y);

// ---- Fresnel reflectance of water ------------------------------------------------------

// Refractive index of water relative to air, dimensionless: the usual 1.333 (fresh water, 589 nm).
// One index serves all three channels: fresh water goes from about 1.331 at 680 nm to 1.340 at
// 440 nm, which moves mean_fresnel_reflectance() from 0.0661 to 0.0676 (sea water is ~0.006
// higher, a further +1%).
inline constexpr double kWaterRefractiveIndex = 1.333;

// The Fresnel reflectance of unpolarised light, (R_s + R_p) / 2, for light in air (index 1)
// meeting a medium of relative index n > 1 at incidence cosine mu in [0, 1] (the exact Fresnel
// equations; mu is clamped to [0, 1]). 1 at grazing incidence, ((n - 1) / (n + 1))^2 at normal.
double fresnel_reflectance(double mu, double n);
// The hemispherical, cosine-weighted average of fresnel_reflectance over the incidence
// directions, 2 ∫_0^1 F(mu) mu dmu (the reflectance of a flat surface under a uniform sky: the
// "diffuse" or albedo average), computed by 64-point Gauss-Legendre quadrature in mu (F is
// analytic on [0, 1] for n > 1, so the rule converges to rounding). Throws std::invalid_argument
// unless n > 1 and finite.
double mean_fresnel_reflectance(double n);
// mean_fresnel_reflectance(kWaterRefractiveIndex), computed once (about 0.066).
double mean_water_fresnel();

// ---- The environment map ---------------------------------------------------------------

struct EnvironmentMapOptions {
  // Azimuth of the photograph's left edge, radians clockwise from north (finite).
  double north_offset = 0.0;
  // Radiance = pixel value times scale (finite, > 0).
  double scale = 1.0;
  // Find the sun and take it out of the map (see EnvironmentMap, "Sun extraction").
  bool extract_sun = true;
};

// The sun found in a photograph and removed from it.
struct ExtractedSun {
  Vec3 direction{};         // unit, ENU: the centroid of the removed radiance (see below)
  Rgb irradiance{};         // W m^-2 nm^-1 on a surface facing the sun: sum (L - L_fill) Ω
  double solid_angle{};     // sr: sum over the region of Ω times the texel's share of the peak
  double angular_radius{};  // rad: the radius of a disc of that solid angle
  int texel_count{};        // texels removed
};

// Sun extraction
// --------------
// A photograph holds the sun as a tiny, saturated or extremely bright region. The ocean draws the
// sun analytically (its glint), so a sun left in the map would be counted twice, and its
// brightness would make the ocean's filtered sky fetch ring. The rule (constants in the .cpp,
// each with its reason):
//  1. Luminance of a texel: 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709 weights; it only ranks
//     texels, so that the channels are spectral samples rather than Rec. 709 primaries does not
//     matter).
//  2. Threshold T = 20 x P99, P99 the solid-angle-weighted 99th percentile of the luminance over
//     the whole sphere. A sun disc of radius up to 5 deg covers under 0.2% of the sphere, so
//     P99 is the brightest sky (a circumsolar aureole or lit clouds), not the sun. The sun is
//     1e4-1e5 times brighter than that in an unclipped HDR and still tens of times in a clipped
//     one; 20 is a judgement between that and the contrast within a sky (a cloud edge, the
//     aureole a degree or more from the sun), not a value fitted to a set of photographs.
//     With P99 = 0 (a black sky) every lit texel is above T.
//  3. Regions: the 8-connected sets of texels with luminance > T, connected across the azimuth
//     seam (column W - 1 touches column 0) and over the poles (row 0 touches row 0 half a turn
//     away). Regions lying wholly below the horizon are ignored (a glint on water or glass in
//     the photograph's lower half is not the sun). The sun is the region of the largest
//     luminance x solid angle; if its solid angle exceeds that of a disc of 5 deg radius
//     (0.0239 sr: the sun's 0.27 deg with room for a photograph's bloom), it is not a sun, and
//     none is reported (sun_search() says why).
//  4. Fill: each texel of the region gets, per channel, the smaller of its own value and the
//     solid-angle-weighted mean of a ring of the texels within 2 texels of the region (not in
//     it), so the sky left behind is smooth and never brighter than before.
//  5. The sun: irradiance = sum over the region of (L - L_fill) Ω; direction = the centroid of
//     the texel-centre directions weighted by luminance(L - L_fill) Ω (a texel the disc only
//     partly covers counts by its share; for a clipped, flat sun this is the solid-angle-weighted
//     centroid); solid angle = sum of Ω luminance(L - L_fill) / max luminance(L - L_fill) (the
//     disc's area when edge texels are partly covered, not the area of the texels it touches);
//     angular radius r from solid angle = 2 pi (1 - cos r).
//  Nothing is lost: the removed (L - L_fill) Ω of the texels add up to the sun's irradiance.
class EnvironmentMap {
 public:
  // Reads an equirectangular HDR image (any format OpenImageIO reads; EXR expected) with
  // thalassa::read_image. Throws EnvironmentMapError naming `path` when the file cannot be
  // read, its width is not exactly twice its height (no tolerance: a 2:1 map is what makes
  // texels square in angle, and an almost-2:1 image is usually not equirectangular), it is
  // smaller than 8 x 4, or a pixel is negative or not finite (with the count and the first
  // such pixel). Alpha is ignored.
  explicit EnvironmentMap(const std::string& path, const EnvironmentMapOptions& options = {});
  // The same from pixels already in memory; `name` stands for the file in messages.
  explicit EnvironmentMap(const Image& image, const EnvironmentMapOptions& options = {},
                          std::string_view name = "in-memory image");

  int width() const { return width_; }
  int height() const { return height_; }
  const EnvironmentMapOptions& options() const { return options_; }

  // The sun taken out of the map, if one was found (and options.extract_sun).
  const std::optional<ExtractedSun>& sun() const { return sun_; }
  // One line saying what the search found, or why no sun was found ("no sun found: ...").
  const std::string& sun_search() const { return sun_search_; }
  // The sun's direction (unit, ENU) and irradiance (W m^-2 nm^-1, zero when no sun).
  std::optional<Vec3> sun_direction() const;
  Rgb sun_irradiance() const;

  // The radiance of the map (sun removed) in `direction`: bilinear between texel centres,
  // wrapping in azimuth, clamped at the centres of the first and last rows (the poles). Reads
  // the photograph in every direction, below the horizon too (its ground or sea).
  Rgb sky_radiance(const Vec3& direction) const;
  // The irradiance of the sky (sun removed) on a horizontal surface facing up,
  // E = ∫ L cos theta dω over the upper hemisphere, W m^-2 nm^-1: each texel's value times the
  // exact integral of cos theta over its part above the horizon (the row that straddles the
  // horizon, when the height is odd, counts its upper half). Computed once, at construction.
  Rgb sky_irradiance() const { return sky_irradiance_; }
  // The paper's radiance for directions below the horizon (sec. 6, "Multiple reflections": "an
  // average Fresnel reflectance times the sky irradiance"), as a radiance:
  // L = mean_water_fresnel() E_sky / pi, E_sky = sky_irradiance() (the sun excluded, as the
  // paper says "sky irradiance"). An approximation: light reflected below the horizon by one
  // wave is reflected again by another, and this treats what it meets there as a flat sea
  // under a uniform sky of the same irradiance.
  Rgb below_horizon_radiance() const { return below_horizon_radiance_; }
  // The ocean's sky: below_horizon_radiance() where direction.z < 0; where direction.z >= 0,
  // sky_radiance(direction) except that the bilinear lookup is clamped at the last row whose
  // top edge is above the horizon (the centre of the row just above it, for an even height), so
  // that directions within half a row above the horizon read the sky and never blend in the
  // photograph's ground: the same texels sky_irradiance() integrates.
  Rgb radiance(const Vec3& direction) const;

  // The ocean's stereographic sky map: a size x size RGBA float image (alpha 1), texel (i, j)
  // (column i left to right, row j top first) covering u_x in [-extent + 2 extent i / size,
  // -extent + 2 extent (i + 1) / size] and u_y in [extent - 2 extent (j + 1) / size,
  // extent - 2 extent j / size]: row 0 is u_y = +extent (north), column 0 is u_x = -extent
  // (west). Each texel is the average of radiance(stereographic_direction(u)) over its square in
  // u (the area average the GPU's filtering assumes; the texel straddling the horizon mixes sky
  // and below-horizon radiance by area), from an n x n grid of sample points at the centres of
  // n x n sub-squares, n the smallest integer >= 4 that makes the samples at most one photograph
  // row apart at the zenith (where one u unit spans the most angle, 2 rad), at most 16. Throws
  // std::invalid_argument unless size >= 1 and extent is finite and > 0.
  // `north_azimuth` (radians clockwise from north, finite) turns the sky about the zenith: the
  // map's north (+u_y, row 0) looks at that azimuth of the photograph, and u at azimuth a in the
  // map at a + north_azimuth. 0 gives the map in the ENU frame; the sky-map array puts the
  // photograph's sun north with it (SkyProvider::sky_map_array).
  Image stereographic_map(int size = 512, double extent = kSkyMapExtent,
                          double north_azimuth = 0.0) const;
  // An equirectangular panorama, width x width / 2 (width even, >= 2), RGBA float, alpha 1, in
  // the photograph's convention with the left edge at azimuth `north_offset` (radians clockwise
  // from north; 0: the left edge looks north), sun removed, the photograph's own ground below
  // the horizon: each texel the average of sky_radiance() over an n x n grid in (azimuth,
  // zenith angle) within it, weighted by sin theta (an area average), n = the ceiling of the
  // photograph's width over `width` (1 when not smaller), at most 16. Throws
  // std::invalid_argument for an odd or too small width or a non-finite north_offset.
  Image panorama(int width, double north_offset = 0.0) const;

 private:
  void load(const Image& image, std::string_view name);
  void extract_sun(std::string_view name);
  // Bilinear radiance at zenith angle theta and azimuth alpha (radians), the rows clamped to
  // [0, last_row] (last_row >= 1).
  Rgb lookup(double theta, double alpha, int last_row) const;
  // The last row whose top edge is above the horizon: the rows the sky side reads.
  int last_sky_row() const { return (height_ - 1) / 2; }
  Rgb texel(int x, int y) const;

  EnvironmentMapOptions options_;
  int width_ = 0;
  int height_ = 0;
  std::vector<float> rgb_;  // the photograph's values (unscaled), 3 per texel, rows top first
  std::vector<double> solid_angle_;  // per row, sr
  std::optional<ExtractedSun> sun_;
  std::string sun_search_;
  Rgb sky_irradiance_{};
  Rgb below_horizon_radiance_{};
};

}  // namespace thalassa::atmosphere
