// thalassa — error metrics of a rendering method against the reference image of the same view
// (issue 6, point 3; docs/validation.md gives the definitions with the choices made):
//
// - each image row's total radiance and its ratio to the reference's (Bruneton, Neyret &
//   Holzschuch 2010, sec. 7.2 and the right column of fig. 10);
// - relative L1 and RMS errors over the pixels that see the sea;
// - the near-horizon metric of Tessendorf, Gao & Reinhardt 2023 (sec. 5 and 6): the
//   azimuth-averaged mean and standard deviation of the luminance difference, binned by the angle
//   below the horizon from 0 to 5 degrees;
// - temporal flicker between consecutive frames.
//
// Everything is in double on the CPU, on linear RGB float images (thalassa::Image: spectral
// radiance, W m^-2 sr^-1 nm^-1 at 680, 550, 440 nm). The functions only take images: the caller
// renders each light term (sun, sky, sea) as its own image and compares them one by one.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "thalassa/engine/image.hpp"
#include "thalassa/engine/scene.hpp"
#include "thalassa/ocean/sea_surface.hpp"
#include "thalassa/planet/camera_frame.hpp"

namespace thalassa::validation {

// Luminance of linear RGB with the Rec. 709 / sRGB weights, as the GPU tests and the environment
// map do (the channels are radiance at 680, 550 and 440 nm, near enough to Rec. 709's primaries
// for a weighting that only ranks and averages).
inline constexpr double kLuminanceR = 0.2126;
inline constexpr double kLuminanceG = 0.7152;
inline constexpr double kLuminanceB = 0.0722;
double luminance(const float* rgb);

// One quantity for the luminance and for each channel (units: those of the quantity).
struct ChannelValues {
  double l = 0.0;  // luminance (kLuminance* weights)
  double r = 0.0;  // 680 nm
  double g = 0.0;  // 550 nm
  double b = 0.0;  // 440 nm
};

// Which pixels a metric covers: inside[y * width + x] != 0, rows top first as in Image.
struct PixelMask {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> inside;

  bool operator()(int x, int y) const {
    return inside[static_cast<std::size_t>(y) * width + x] != 0;
  }
  int count() const;
  static PixelMask all(int width, int height);  // every pixel
};

// The view of a scene, per pixel, in the east-north-up frame at the camera's nadir (x east,
// y north, z up; metres), in double: whether the pixel's centre ray meets the sea at rest (the
// WGS84 or spherical quadric of ocean/sea_surface.hpp), its angle below the horizon in its own
// azimuth, and its area in the (azimuth, angle below the horizon) plane. Pixel (x, y) has its
// centre at u = 2 (x + 0.5) / width - 1, v = 1 - 2 (y + 0.5) / height, as the renderer's.
class ViewGeometry {
 public:
  // From the scene's image size, camera and planet.
  explicit ViewGeometry(const Scene& scene);

  int width() const { return width_; }
  int height() const { return height_; }
  // The pixels whose centre ray meets the sea at rest (ocean::sea_surface_distance).
  const PixelMask& sea_mask() const { return sea_; }
  // Radians below the horizon of the pixel centre's ray, in the ray's own azimuth:
  // beta = atan(ray's tan(dip)) - atan(ocean::sea_surface_horizon_dip of its azimuth); positive
  // below the horizon (the ray meets the sea exactly when beta >= 0), negative above it.
  double below_horizon(int x, int y) const { return beta_[index(x, y)]; }
  // |d(azimuth, beta) / d(x, y)|: the pixel's area in the plane of azimuth (clockwise from
  // north) and angle below the horizon, rad^2 per pixel (central differences at +-0.5 pixel).
  // Weighting a pixel by it makes a sum over pixels an integral d(azimuth) d(beta), so that an
  // average over a band is uniform in azimuth as paper 004's equirectangular rows are.
  double azimuth_weight(int x, int y) const { return weight_[index(x, y)]; }
  // The unit direction of pixel (x, y)'s centre ray (nadir ENU).
  glm::dvec3 ray(double x, double y) const;
  const ocean::SeaSurface& sea_surface() const { return surface_; }
  double camera_height() const { return camera_height_; }  // m above the sea at rest

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  // Azimuth (rad, clockwise from north) and beta (rad) of the ray through (x, y) (pixels).
  glm::dvec2 azimuth_and_beta(double x, double y) const;

  int width_ = 0, height_ = 0;
  CameraBasis basis_;
  double tan_half_fov_y_ = 0.0, aspect_ = 1.0;
  ocean::SeaSurface surface_;
  double camera_height_ = 0.0;
  PixelMask sea_;
  std::vector<double> beta_, weight_;
};

// The image averaged over blocks of factor x factor pixels (every channel, alpha too), for a
// method drawn at `factor` times the reference's pixels (SuiteMethod::supersample): pixel (x, y)
// of the result is the mean of pixels [factor x, factor (x + 1)) x [factor y, factor (y + 1)),
// in double. A mean, so that radiance stays radiance: a row of the result totals (row_totals)
// 1 / factor^2 of its factor rows' totals together. Throws std::invalid_argument unless factor
// >= 1 divides both the width and the height.
Image box_filter(const Image& image, int factor);
// What the metrics compare of a method drawn at `factor` times the reference's pixels:
// box_filter's means, but at each pixel whose centre sees the sea (`sea_mask`, the view's
// ViewGeometry::sea_mask at the reference's size) the mean of its block's pixels that see the
// sea too (`image_sea`, the same at the image's size; all of them where none does). The sea alone
// there, as reference_for_comparison compares the reference's: at the pixels the horizon crosses
// the plain mean holds the sky above it, up to 16 % of the horizon band's sea at 4 x 4 in stop
// 53's first run. Throws std::invalid_argument as box_filter does, or for masks of other sizes.
Image supersampled_for_comparison(const Image& image, int factor, const PixelMask& image_sea,
                                  const PixelMask& sea_mask);

// ---------------------------------------------------------------------------------------------
// Per-row radiance (paper 000, fig. 10, right column).

// Each row's sum of the pixels inside `mask` (every pixel when null), top row first,
// W m^-2 sr^-1 nm^-1 summed over pixels; NaN (undefined) for a row with no pixel inside the
// mask (a row of sky, or one the reference's sun does not resolve), which is not a black row.
std::vector<ChannelValues> row_totals(const Image& image, const PixelMask* mask = nullptr);
// A row's ratio is defined only where the reference's row total (luminance) is at least this
// fraction of its brightest row's. The sun's term lights rows far from the glint by next to
// nothing (1e-12 of the brightest was seen): there a ratio of float noise to float noise reaches
// 1e6 and would hide fig. 10's curve and decide max_row_deviation. The same fraction below which
// the reference's convergence test ignores a row (planet/src/renderer.cpp, kNegligibleRow).
inline constexpr double kSignificantRowFraction = 1e-3;
// method / reference per row and channel; NaN where the ratio is undefined: where the reference's
// luminance total is not positive (a row without sea, or black in that term) or below
// kSignificantRowFraction of its brightest row's.
std::vector<ChannelValues> row_ratios(const std::vector<ChannelValues>& method,
                                      const std::vector<ChannelValues>& reference);
// The largest |ratio - 1| of the luminance over the rows where it is defined (NaN when none is:
// until stop 23 0, which read as a perfect match where nothing was compared): one number for
// "each row's total within x% of the reference" (issue 6, point 1).
double max_row_deviation(const std::vector<ChannelValues>& ratios);
// The mean |ratio - 1| of the luminance over the rows where it is defined (NaN when none is):
// fig. 10's comparison of the energy per distance over the whole view, which one row (a few
// glints of the reference's sea in it) does not decide as it decides max_row_deviation.
double mean_row_deviation(const std::vector<ChannelValues>& ratios);
// The relative L1 error of the row totals (luminance) over the rows where the ratio is defined:
// sum |T_method - T_reference| / sum T_reference (NaN when no row is defined or the reference's
// sum is 0). The energy per distance, weighted by the reference's energy: where the reference's
// sea holds a few glints a row, a faint row's ratio is the realization's luck, and each row
// counting once (mean_row_deviation) lets those rows decide. |k - 1| for k times the reference.
double row_error(const std::vector<ChannelValues>& method_totals,
                 const std::vector<ChannelValues>& reference_totals,
                 const std::vector<ChannelValues>& ratios);

// The reference's relative uncertainty of each image row's total (top row first), from its two
// convergence tests (issue 6, point 1): the larger of the row's change at the last doubling of
// the samples (RenderStats::sample_row_changes) and, for a term with the sun, of its lattice
// against one of half the cells (RenderStats::sun_lattice_row_changes). The samples' change,
// (second half's mean - first half's) / 2, is one draw of the same spread as the error of the
// mean of all of them (so a row may read low by chance); the lattice's, a deterministic
// discretisation converging with the cells' size, is about the coarser lattice's error, an upper
// estimate of the finer one's. A row
// that a test measured elsewhere but not in it (NaN there: a row below the test's floor of 1e-3
// of the brightest, or past the coarser lattice's cap) takes that test's largest change: nothing
// says it converged better. A test that measured nothing (empty, or NaN everywhere) adds
// nothing; every row is NaN when neither measured anything.
std::vector<double> reference_row_uncertainty(std::span<const double> sample_row_changes,
                                              std::span<const double> lattice_row_changes,
                                              int rows);

// How far the difference of two row errors against one reference, row_error(a) - row_error(b),
// can move toward the other order when each of the reference's row totals r_y is uncertain by up
// to u_y r_y (`uncertainty`, reference_row_uncertainty; NaN counts as 0). Their order is the sign
// of D = sum_y g_y(0) alone, g_y(d) = |a_y - r_y - d| - |b_y - r_y - d| (the common denominator
// sum_y r_y is positive). Over every reference within those bounds D rises by at most
// sum_y max over |d| <= u_y r_y of (g_y(d) - g_y(0)) and falls by at most the same sum of
// (g_y(0) - g_y(d)) (each row's d is free; g_y is piecewise linear, so each extreme lies at
// d = +-u_y r_y or at a kink, d = a_y - r_y or b_y - r_y). Returns the rise when D < 0 (a is
// the closer: how far toward b's being closer), the fall when D > 0, the larger when D = 0,
// divided by sum_y r_y: in the row errors' unit, so that |row_error(a) - row_error(b)| larger
// than it keeps its order for every such reference. A row adds 0 where a and b lie on the same
// side of the reference and outside its bounds (its error moves both alike), at most 2 u_y r_y.
// Over the rows where `ratios` is defined (row_error's); luminance. NaN when no row is defined,
// or every u_y there is NaN.
double row_error_difference_bound(const std::vector<ChannelValues>& a,
                                  const std::vector<ChannelValues>& b,
                                  const std::vector<ChannelValues>& reference,
                                  const std::vector<ChannelValues>& ratios,
                                  std::span<const double> uncertainty);

// ---------------------------------------------------------------------------------------------
// Relative errors over the sea.

struct ErrorStats {
  int pixels = 0;  // pixels inside the mask
  // sum |m - r| / sum |r|: the relative L1 error (NaN when the reference is 0 everywhere in the
  // mask and the method is not; 0 when both are; NaN over no pixel).
  ChannelValues relative_l1;
  // sqrt(sum (m - r)^2 / sum r^2): the relative RMS error (same conventions).
  ChannelValues relative_rms;
  ChannelValues mean_abs;        // sum |m - r| / pixels, W m^-2 sr^-1 nm^-1
  ChannelValues reference_mean;  // sum r / pixels, W m^-2 sr^-1 nm^-1 (for scale)
};
ErrorStats relative_errors(const Image& method, const Image& reference, const PixelMask& mask);

// ---------------------------------------------------------------------------------------------
// Near the horizon (paper 004, sec. 5 and 6).

struct HorizonBandOptions {
  double depth_deg = 5.0;  // the band: from the horizon to this angle below it, degrees
  double bin_deg = 0.5;    // width of an angle bin, degrees (10 bins in 5 degrees)
};

struct HorizonBin {
  double beta_lo_deg = 0.0, beta_hi_deg = 0.0;  // degrees below the horizon, [lo, hi)
  int pixels = 0;                               // pixel centres inside the bin
  double weight = 0.0;  // sum of ViewGeometry::azimuth_weight, rad^2 (the bin's area seen)
  // Luminance of D = L_method - L_reference over the bin, each pixel weighted by its
  // azimuth_weight: the azimuth-averaged mean and standard deviation (W m^-2 sr^-1 nm^-1);
  // NaN when the bin is empty.
  double mean = 0.0;
  double std = 0.0;
  double reference_mean = 0.0;  // the reference's mean luminance over the bin, same weights
};

struct HorizonBand {
  std::vector<HorizonBin> bins;  // from the horizon down, depth_deg / bin_deg of them (rounded up)
  // Averages over the non-empty bins, each bin counting once (uniform in angle, as paper 004's
  // fig. 14 averages its curves over 0 to 5 degrees); NaN when every bin is empty (the horizon
  // is not in view).
  double mean = 0.0;
  double std = 0.0;
  double reference_mean = 0.0;
  int pixels = 0;  // pixels in the band
};

// Pixels whose centre lies from 0 (inclusive) to depth_deg (exclusive) below the horizon (and,
// when `compared` is given, inside it).
HorizonBand horizon_band(const Image& method, const Image& reference, const ViewGeometry& view,
                         const HorizonBandOptions& options = {},
                         const PixelMask* compared = nullptr);

// The band of several images of one view taken together (paper 004 averages its metric over many
// realizations of the sea; thalassa validate --seas draws a case over several): per bin the
// pixels of every band as one set, weighted as horizon_band weighs them, so that the pooled
// bands of disjoint `compared` masks are the band of their union (to rounding). The bins must be
// the same in every band (std::invalid_argument otherwise); an empty span gives no bins and NaN.
HorizonBand pool_horizon_bands(std::span<const HorizonBand> bands);
// Whether two bands have the same bins (the same angles, from the same depth and bin width), so
// that they pool.
bool same_horizon_bins(const HorizonBand& a, const HorizonBand& b);

// ---------------------------------------------------------------------------------------------
// Temporal flicker.

// Frames of one view at equal time steps: the mean over consecutive pairs of
//   sum_mask |L_{k+1} - L_k| / sum_mask (L_{k+1} + L_k) / 2        (luminance),
// the relative change of the sea from one frame to the next (0 for identical frames; NaN with
// fewer than two frames or a black sea). The true sea moves, so the reference flickers too: a
// method flickers more than the truth when its value exceeds the reference's.
double flicker(std::span<const Image> frames, const PixelMask& mask);
// How far a method's frame-to-frame changes are from the reference's:
//   sum_k sum_mask |dL_method - dL_reference| / sum_k sum_mask |dL_reference|,
// dL = L_{k+1} - L_k (luminance); 0 when the method changes exactly as the reference does, NaN
// when the reference does not change and the method does, or with fewer than two frames.
double temporal_error(std::span<const Image> method, std::span<const Image> reference,
                      const PixelMask& mask);

// ---------------------------------------------------------------------------------------------
// Everything at once, for one light term of one method (the reference compared with itself
// gives ratios of 1 and zero errors).

struct TermMetrics {
  // Some pixels are compared, and no channel of any of the reference's reaches compare_images'
  // black level (none compared: not black, nothing measured): the
  // term shows nothing there (the 10 m/s sea seen from 8 km with the sun 50 degrees high
  // reflects no glint into the view; its reference's sun is 1e-25 on average, the Gaussian
  // tail of the sun's disc, the methods' 1e-7, their BRDF's). Its row ratios, row error and
  // relative errors are then undefined (NaN), as a ratio of two invisible tails would read
  // 1e17; the relative errors are 0 when the method is black too.
  bool reference_black = false;
  std::vector<ChannelValues> row_totals;  // over the compared pixels, top row first (NaN: none)
  std::vector<ChannelValues> row_ratios;  // to the reference's row totals (NaN: undefined)
  double max_row_deviation = 0.0;         // of row_ratios
  double mean_row_deviation = 0.0;        // of row_ratios (NaN: no row defined)
  double row_error = 0.0;                 // of row_totals against the reference's (NaN: none)
  ErrorStats error;                       // over the sea mask
  HorizonBand horizon;
};
// `compared`: the pixels measured (the view's sea mask when null); the validation passes the sea
// pixels of the rows where the reference's sun resolved every wave (resolved_rows_mask).
// `black_level` (W m^-2 sr^-1 nm^-1): the radiance below which the reference counts as black
// (TermMetrics::reference_black); the validation passes png_black_level of the scene's exposure,
// 0 (the default) never calls a reference black.
TermMetrics compare_images(const Image& method, const Image& reference, const ViewGeometry& view,
                           const HorizonBandOptions& options = {},
                           const PixelMask* compared = nullptr, double black_level = 0.0);

// The pixels of `mask` in the rows whose resolved fraction (RenderStats::resolved_rows, top row
// first) is at least min_fraction; `mask` itself when resolved_rows is empty (a reference without
// the sun term).
PixelMask resolved_rows_mask(const PixelMask& mask, const std::vector<double>& resolved_rows,
                             double min_fraction);

// The reference image the other methods are measured against: `reference` (Renderer::image,
// each pixel's samples of sky and sea averaged over the pixel) where the pixel's centre sees the
// sky or where none of its samples saw the sea, and its sea alone (`sea`, Renderer::
// reference_sea_image: alpha the fraction of samples that saw the sea) where the pixel's centre
// sees the sea (`sea_mask`, ViewGeometry::sea_mask). The other methods shade the sea at a sea
// pixel's centre, so at the pixels the horizon crosses the box-filtered reference would measure
// the sky's share of the pixel, not their sea (stop 16 saw it as the sea term's relative RMS of
// 0.99 for every method). `sea` empty (0 x 0): `reference` itself.
Image reference_for_comparison(const Image& reference, const Image& sea, const PixelMask& sea_mask);

}  // namespace thalassa::validation
