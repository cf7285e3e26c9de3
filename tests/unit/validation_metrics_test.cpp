// The validation metrics (validation/include/thalassa/validation/metrics.hpp): identities that
// any correct implementation satisfies, and the horizon band against a brute-force search.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <stdexcept>
#include <vector>

#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/geodesy.hpp"
#include "thalassa/planet/nadir_frame.hpp"
#include "thalassa/validation/metrics.hpp"

namespace thalassa::validation {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

Scene view_scene(int width, int height) {
  Scene scene;  // the defaults: 4 m above the sea, pitch -5, fov_y 45, WGS84
  scene.image.width = width;
  scene.image.height = height;
  return scene;
}

// A sky-and-sea-like image: random positive radiance per channel (W m^-2 sr^-1 nm^-1).
Image random_image(int width, int height, unsigned seed) {
  Image image{width, height, std::vector<float>(static_cast<std::size_t>(width) * height * 4)};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> radiance(0.01f, 0.5f);
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    image.rgba[i] = radiance(rng);
    image.rgba[i + 1] = radiance(rng);
    image.rgba[i + 2] = radiance(rng);
    image.rgba[i + 3] = 1.0f;
  }
  return image;
}

Image scaled(const Image& image, float k) {
  Image out = image;
  for (std::size_t i = 0; i < out.rgba.size(); i += 4)
    for (int c = 0; c < 3; ++c) out.rgba[i + c] *= k;
  return out;
}

// Grey of luminance `value` in every channel (the luminance weights sum to 1).
void set_grey(Image& image, int x, int y, double value) {
  float* p = image.pixel(x, y);
  p[0] = p[1] = p[2] = static_cast<float>(value);
  p[3] = 1.0f;
}

TEST(ValidationMetrics, LuminanceWeightsSumToOne) {
  EXPECT_NEAR(kLuminanceR + kLuminanceG + kLuminanceB, 1.0, 1e-15);
  const float grey[3] = {0.25f, 0.25f, 0.25f};
  EXPECT_NEAR(luminance(grey), 0.25, 1e-15);
}

TEST(ValidationMetrics, IdenticalImagesGiveZeroErrorAndRowRatiosOfOne) {
  const Scene scene = view_scene(96, 64);
  const ViewGeometry view(scene);
  const Image image = random_image(96, 64, 7);
  const TermMetrics m = compare_images(image, image, view);
  ASSERT_GT(view.sea_mask().count(), 1000);  // the sea fills the lower part of the view
  EXPECT_EQ(m.error.pixels, view.sea_mask().count());
  for (double e :
       {m.error.relative_l1.l, m.error.relative_l1.r, m.error.relative_l1.g, m.error.relative_l1.b,
        m.error.relative_rms.l, m.error.relative_rms.b, m.error.mean_abs.l}) {
    EXPECT_EQ(e, 0.0);
  }
  int defined = 0;
  for (std::size_t y = 0; y < m.row_ratios.size(); ++y) {
    if (m.row_totals[y].l > 0.0) {
      ++defined;
      EXPECT_EQ(m.row_ratios[y].l, 1.0) << "row " << y;
      EXPECT_EQ(m.row_ratios[y].g, 1.0) << "row " << y;
    } else {
      EXPECT_TRUE(std::isnan(m.row_ratios[y].l)) << "row " << y << " has no sea";
    }
  }
  EXPECT_GT(defined, 20);
  EXPECT_LT(defined, 64);  // rows above the horizon see no sea: ratios undefined there
  EXPECT_EQ(m.max_row_deviation, 0.0);
  EXPECT_EQ(m.mean_row_deviation, 0.0);
  EXPECT_EQ(m.row_error, 0.0);
  ASSERT_GT(m.horizon.pixels, 0);
  EXPECT_EQ(m.horizon.mean, 0.0);
  EXPECT_EQ(m.horizon.std, 0.0);
}

TEST(ValidationMetrics, ImageScaledByKGivesRowRatiosKAndRelativeErrorsAbsKMinusOne) {
  const Scene scene = view_scene(80, 60);
  const ViewGeometry view(scene);
  const Image reference = random_image(80, 60, 11);
  for (float k : {0.5f, 1.37f, 3.0f}) {
    const Image method = scaled(reference, k);
    const TermMetrics m = compare_images(method, reference, view);
    // float products round at 6e-8 relative; sums in double keep that.
    const double tolerance = 1e-6 * k;
    for (std::size_t y = 0; y < m.row_ratios.size(); ++y) {
      if (!(m.row_totals[y].l > 0.0)) continue;
      EXPECT_NEAR(m.row_ratios[y].l, k, tolerance) << "row " << y;
      EXPECT_NEAR(m.row_ratios[y].r, k, tolerance) << "row " << y;
      EXPECT_NEAR(m.row_ratios[y].b, k, tolerance) << "row " << y;
    }
    EXPECT_NEAR(m.max_row_deviation, std::abs(k - 1.0), tolerance);
    EXPECT_NEAR(m.mean_row_deviation, std::abs(k - 1.0), tolerance);
    EXPECT_NEAR(m.row_error, std::abs(k - 1.0), tolerance);
    EXPECT_NEAR(m.error.relative_l1.l, std::abs(k - 1.0), tolerance);
    EXPECT_NEAR(m.error.relative_l1.g, std::abs(k - 1.0), tolerance);
    EXPECT_NEAR(m.error.relative_rms.l, std::abs(k - 1.0), tolerance);
    EXPECT_NEAR(m.error.relative_rms.b, std::abs(k - 1.0), tolerance);
    EXPECT_NEAR(m.error.mean_abs.l, std::abs(k - 1.0) * m.error.reference_mean.l, tolerance);
  }
}

// box_filter: each pixel the mean of its block (factor 1: the image itself), every row's total
// 1 / factor^2 of its block of rows' together, and a factor that does not divide a side refused.
TEST(ValidationMetrics, BoxFilterAveragesEachBlockAndKeepsTheRowsTotals) {
  const Image image = random_image(12, 6, 7);
  const Image same = box_filter(image, 1);
  EXPECT_EQ(same.width, 12);
  EXPECT_EQ(same.rgba, image.rgba);
  const Image third = box_filter(image, 3);
  ASSERT_EQ(third.width, 4);
  ASSERT_EQ(third.height, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (int k = 0; k < 4; ++k) {
        double sum = 0.0;
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) sum += image.pixel(3 * x + i, 3 * y + j)[k];
        EXPECT_NEAR(third.pixel(x, y)[k], sum / 9.0, 1e-7) << x << ", " << y << ", " << k;
      }
  const std::vector<ChannelValues> fine = row_totals(image);
  const std::vector<ChannelValues> coarse = row_totals(third);
  for (int y = 0; y < 2; ++y)
    EXPECT_NEAR(coarse[y].g, (fine[3 * y].g + fine[3 * y + 1].g + fine[3 * y + 2].g) / 9.0, 1e-6);
  EXPECT_THROW(box_filter(image, 4), std::invalid_argument);  // 6 rows
  EXPECT_THROW(box_filter(image, 5), std::invalid_argument);
  EXPECT_THROW(box_filter(image, 0), std::invalid_argument);
  EXPECT_THROW(box_filter(image, -2), std::invalid_argument);
}

// supersampled_for_comparison: at a sea pixel the mean of its block's sea pixels only (all of them
// where none is sea), elsewhere box_filter's mean; masks of the wrong size refused.
TEST(ValidationMetrics, SupersampledForComparisonAveragesTheSeaAloneAtSeaPixels) {
  const Image image = random_image(6, 4, 11);
  PixelMask fine{6, 4, std::vector<std::uint8_t>(24, 0)};
  // Block (0, 0): its lower row is sea; block (1, 0): none is; block (2, 1): one pixel is.
  fine.inside[1 * 6 + 0] = fine.inside[1 * 6 + 1] = 1;
  fine.inside[3 * 6 + 5] = 1;
  PixelMask coarse{3, 2, std::vector<std::uint8_t>(6, 0)};
  coarse.inside[0] = coarse.inside[1] = coarse.inside[1 * 3 + 2] = 1;
  const Image plain = box_filter(image, 2);
  const Image sea = supersampled_for_comparison(image, 2, fine, coarse);
  ASSERT_EQ(sea.width, 3);
  ASSERT_EQ(sea.height, 2);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(sea.pixel(0, 0)[k], (image.pixel(0, 1)[k] + image.pixel(1, 1)[k]) / 2.0, 1e-7);
    EXPECT_EQ(sea.pixel(1, 0)[k], plain.pixel(1, 0)[k]);  // sea, but no fine pixel of it is
    EXPECT_EQ(sea.pixel(2, 1)[k], image.pixel(5, 3)[k]);
    EXPECT_EQ(sea.pixel(0, 1)[k], plain.pixel(0, 1)[k]);  // not sea: every pixel
    EXPECT_EQ(sea.pixel(2, 0)[k], plain.pixel(2, 0)[k]);
  }
  EXPECT_NE(sea.pixel(0, 0)[1], plain.pixel(0, 0)[1]);
  EXPECT_THROW(supersampled_for_comparison(image, 2, coarse, coarse), std::invalid_argument);
  EXPECT_THROW(supersampled_for_comparison(image, 2, fine, fine), std::invalid_argument);
  EXPECT_THROW(supersampled_for_comparison(image, 3, fine, coarse), std::invalid_argument);
}

TEST(ValidationMetrics, RowTotalsAreSumsOverTheMask) {
  Image image{3, 2, std::vector<float>(24, 0.0f)};
  set_grey(image, 0, 0, 1.0);
  set_grey(image, 1, 0, 2.0);
  set_grey(image, 2, 0, 4.0);
  set_grey(image, 0, 1, 8.0);
  PixelMask mask = PixelMask::all(3, 2);
  EXPECT_DOUBLE_EQ(row_totals(image, &mask)[0].l, 7.0);
  EXPECT_DOUBLE_EQ(row_totals(image, &mask)[1].r, 8.0);
  mask.inside[1] = 0;  // (1, 0) left out
  EXPECT_DOUBLE_EQ(row_totals(image, &mask)[0].g, 5.0);
  EXPECT_DOUBLE_EQ(row_totals(image)[0].b, 7.0);  // no mask: every pixel
  // A row with no pixel in the mask has no total (not a black row: nothing was compared there).
  mask.inside[3] = mask.inside[4] = mask.inside[5] = 0;
  EXPECT_TRUE(std::isnan(row_totals(image, &mask)[1].l));
  EXPECT_TRUE(std::isnan(row_totals(image, &mask)[1].b));
  EXPECT_DOUBLE_EQ(row_totals(image, &mask)[0].l, 5.0);
  set_grey(image, 1, 1, 0.0);
  set_grey(image, 0, 1, 0.0);
  mask.inside[4] = 1;
  EXPECT_EQ(row_totals(image, &mask)[1].l, 0.0);  // a black row inside the mask is 0
  const PixelMask wrong = PixelMask::all(2, 3);
  EXPECT_THROW(row_totals(image, &wrong), std::invalid_argument);
  EXPECT_THROW(relative_errors(image, random_image(3, 3, 1), mask), std::invalid_argument);
}

// A row the reference lights by next to nothing (the sun's term far from the glint) has no ratio:
// the boundary is kSignificantRowFraction of the brightest row, on either side of it.
TEST(ValidationMetrics, RowRatiosAreUndefinedBelowTheSignificantFractionOfTheBrightestRow) {
  const double bright = 2.0;
  const double just_above = 1.01 * kSignificantRowFraction * bright;
  const double just_below = 0.99 * kSignificantRowFraction * bright;
  const std::vector<ChannelValues> reference = {{bright, bright, bright, bright},
                                                {just_above, just_above, just_above, just_above},
                                                {just_below, just_below, just_below, just_below},
                                                {1e-12, 1e-12, 1e-12, 1e-12}};
  std::vector<ChannelValues> method = reference;
  for (ChannelValues& row : method) row = {row.l * 3.0, row.r * 3.0, row.g * 3.0, row.b * 3.0};
  method[3] = {1e-6, 1e-6, 1e-6, 1e-6};  // float noise: a ratio of 1e6 if it counted
  const std::vector<ChannelValues> ratios = row_ratios(method, reference);
  ASSERT_EQ(ratios.size(), 4u);
  EXPECT_NEAR(ratios[0].l, 3.0, 1e-12);
  EXPECT_NEAR(ratios[1].l, 3.0, 1e-12);
  EXPECT_NEAR(ratios[1].g, 3.0, 1e-12);
  EXPECT_TRUE(std::isnan(ratios[2].l));
  EXPECT_TRUE(std::isnan(ratios[2].r));
  EXPECT_TRUE(std::isnan(ratios[3].l));
  EXPECT_NEAR(max_row_deviation(ratios), 2.0, 1e-12);
  EXPECT_NEAR(mean_row_deviation(ratios), 2.0, 1e-12);  // the two defined rows only
}

// The mean deviation is over the defined rows only, each counting once, and undefined (not 0)
// when no row is: a term the reference does not light has no fig. 10 curve to be close to.
TEST(ValidationMetrics, MeanRowDeviationAveragesTheDefinedRows) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<ChannelValues> ratios = {
      {nan, nan, nan, nan}, {1.5, 9, 9, 9}, {0.25, 9, 9, 9}, {1.0, 9, 9, 9}};
  EXPECT_NEAR(mean_row_deviation(ratios), (0.5 + 0.75 + 0.0) / 3.0, 1e-15);
  EXPECT_NEAR(max_row_deviation(ratios), 0.75, 1e-15);
  EXPECT_TRUE(std::isnan(mean_row_deviation({{nan, nan, nan, nan}})));
  EXPECT_TRUE(std::isnan(mean_row_deviation({})));
  EXPECT_TRUE(std::isnan(max_row_deviation({})));
  EXPECT_TRUE(std::isnan(max_row_deviation({{nan, nan, nan, nan}})));
}

// The row error weighs each row by the reference's energy, over the defined rows only: a faint
// row's large ratio (a few glints of one realization) counts for its share of the energy.
TEST(ValidationMetrics, RowErrorIsTheRelativeL1OfTheDefinedRowTotals) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<ChannelValues> reference = {{10, 0, 0, 0}, {0.1, 0, 0, 0}, {5, 0, 0, 0}};
  const std::vector<ChannelValues> method = {{11, 0, 0, 0}, {0.5, 0, 0, 0}, {2, 0, 0, 0}};
  std::vector<ChannelValues> ratios = row_ratios(method, reference);
  EXPECT_NEAR(row_error(method, reference, ratios), (1.0 + 0.4 + 3.0) / 15.1, 1e-15);
  EXPECT_NEAR(mean_row_deviation(ratios), (0.1 + 4.0 + 0.6) / 3.0, 1e-15);  // the faint row's 4
  ratios[2] = {nan, nan, nan, nan};                                         // a row not compared
  EXPECT_NEAR(row_error(method, reference, ratios), 1.4 / 10.1, 1e-15);
  for (ChannelValues& r : ratios) r = {nan, nan, nan, nan};
  EXPECT_TRUE(std::isnan(row_error(method, reference, ratios)));
  EXPECT_THROW(row_error(method, {reference[0]}, ratios), std::invalid_argument);
}

// Per row the larger of the two tests; a row one test skipped takes that test's largest change.
TEST(ValidationMetrics, ReferenceRowUncertaintyTakesTheLargerTestPerRow) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> samples = {nan, 0.01, 0.03, 0.002, nan};
  const std::vector<double> lattice = {nan, 0.2, 0.01, nan, 0.05};
  const std::vector<double> both = reference_row_uncertainty(samples, lattice, 5);
  ASSERT_EQ(both.size(), 5u);
  EXPECT_DOUBLE_EQ(both[0], 0.2);   // neither measured it: each test's largest
  EXPECT_DOUBLE_EQ(both[1], 0.2);   // the lattice's
  EXPECT_DOUBLE_EQ(both[2], 0.03);  // the samples'
  EXPECT_DOUBLE_EQ(both[3], 0.2);   // the lattice skipped it: its largest
  EXPECT_DOUBLE_EQ(both[4], 0.05);
  const std::vector<double> samples_only = reference_row_uncertainty(samples, {}, 5);
  EXPECT_DOUBLE_EQ(samples_only[0], 0.03);
  EXPECT_DOUBLE_EQ(samples_only[3], 0.002);
  const std::vector<double> all_nan(5, nan);  // a test that counted no row adds nothing
  EXPECT_EQ(reference_row_uncertainty(samples, all_nan, 5), samples_only);
  for (double u : reference_row_uncertainty({}, {}, 3)) EXPECT_TRUE(std::isnan(u));
  EXPECT_THROW(reference_row_uncertainty(samples, std::vector<double>{0.1, 0.2}, 5),
               std::invalid_argument);
}

// The bound against brute force. Each row's reference is moved over a fine grid of its interval
// toward the other order (the rows are independent, so the sum's extreme is the sum of the rows'
// extremes); the shifted reference so built moves the difference by the bound (within the
// grid's step) and no reference of the grid moves it further; and it reverses the two row
// errors, measured against it with row_error itself, exactly when their difference is within the
// bound.
TEST(ValidationMetrics, RowErrorDifferenceBoundIsTheExtremeOverReferencesWithinTheirBounds) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int reversed = 0, kept = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int rows = 1 + trial % 7;
    std::vector<ChannelValues> a(rows), b(rows), r(rows), ratios(rows);
    std::vector<double> u(rows);
    for (int y = 0; y < rows; ++y) {
      r[y].l = 0.1 + unit(rng);
      a[y].l = r[y].l * (0.5 + unit(rng));
      b[y].l = r[y].l * 1.6 * unit(rng);
      ratios[y].l = trial % 5 == 0 && y == 0 ? nan : 1.0;  // a row not compared: left out
      u[y] = trial % 3 == 0 && y == 1 ? nan : 0.4 * unit(rng);
    }
    const auto g = [&](int y, double d) {
      return std::abs(a[y].l - r[y].l - d) - std::abs(b[y].l - r[y].l - d);
    };
    double order = 0.0, total = 0.0, slack = 0.0;
    bool any_uncertainty = false;
    for (int y = 0; y < rows; ++y) {
      if (!std::isfinite(ratios[y].l)) continue;
      order += g(y, 0.0);
      total += r[y].l;
      any_uncertainty = any_uncertainty || std::isfinite(u[y]);
    }
    const double got = row_error_difference_bound(a, b, r, ratios, u);
    if (!any_uncertainty) {  // no row compared, or none with an uncertainty: not measured
      EXPECT_TRUE(std::isnan(got)) << "trial " << trial;
      continue;
    }
    if (order == 0.0) continue;
    const double toward = order < 0.0 ? 1.0 : -1.0;  // the direction of the other order
    std::vector<ChannelValues> shifted = r;
    double moved = 0.0;
    constexpr int kSteps = 20000;
    for (int y = 0; y < rows; ++y) {
      if (!std::isfinite(ratios[y].l)) continue;
      const double half = std::isfinite(u[y]) ? u[y] * r[y].l : 0.0;
      double best = 0.0, best_shift = 0.0;
      for (int k = 0; k <= kSteps; ++k) {
        const double d = -half + 2.0 * half * k / kSteps;
        const double change = toward * (g(y, d) - g(y, 0.0));
        if (change > best) {
          best = change;
          best_shift = d;
        }
      }
      moved += best;
      shifted[y].l = r[y].l + best_shift;
      slack += 2.0 * half / kSteps;  // g's slope is at most 2, a kink half a step from the grid
    }
    EXPECT_NEAR(got, moved / total, slack / total + 1e-15) << "trial " << trial;
    EXPECT_GE(got + 1e-12, moved / total) << "trial " << trial;
    // Against the shifted reference: the order reverses where the difference is within the bound.
    const std::vector<ChannelValues> shifted_ratios = row_ratios(a, shifted);
    std::vector<ChannelValues> compared = shifted_ratios;
    for (int y = 0; y < rows; ++y)
      if (!std::isfinite(ratios[y].l)) compared[y] = {nan, nan, nan, nan};
    const double before = toward * (row_error(a, r, ratios) - row_error(b, r, ratios));
    const double after =
        toward * (row_error(a, shifted, compared) - row_error(b, shifted, compared));
    const double margin = slack / total + 1e-12;
    if (std::abs(order) / total > got + margin) {
      EXPECT_LT(after, 0.0) << "trial " << trial << ": reversed beyond the bound";
      ++kept;
    } else if (std::abs(order) / total < got - margin) {
      EXPECT_GE(after, 0.0) << "trial " << trial << ": not reversed within the bound";
      ++reversed;
    }
    EXPECT_LT(before, 0.0) << "trial " << trial;
  }
  EXPECT_GT(reversed, 20);  // both outcomes occur among the trials
  EXPECT_GT(kept, 20);
}

TEST(ValidationMetrics, RowErrorDifferenceBoundInSimpleCases) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<ChannelValues> r = {{1, 0, 0, 0}};
  const std::vector<ChannelValues> one = {{1, 0, 0, 0}};
  // Both below the reference and outside its 10 %: its error moves them alike.
  EXPECT_EQ(row_error_difference_bound({{0.8, 0, 0, 0}}, {{0.3, 0, 0, 0}}, r, one,
                                       std::vector<double>{0.1}),
            0.0);
  // a above the reference, b below: a reference lower by u r moves the difference by 2 u r
  // toward b (|a - r'| - |b - r'| from -0.45 to -0.25 at r' = 0.9).
  EXPECT_NEAR(row_error_difference_bound({{1.05, 0, 0, 0}}, {{0.5, 0, 0, 0}}, r, one,
                                         std::vector<double>{0.1}),
              0.2, 1e-15);
  EXPECT_NEAR(row_error_difference_bound({{1.0, 0, 0, 0}}, {{1.01, 0, 0, 0}}, r, one,
                                         std::vector<double>{0.1}),
              0.02, 1e-15);  // at r' = 1.01 the order is reversed: -0.01 to +0.01
  EXPECT_TRUE(std::isnan(row_error_difference_bound({{1, 0, 0, 0}}, {{2, 0, 0, 0}}, r, one,
                                                    std::vector<double>{nan})));
  EXPECT_TRUE(std::isnan(row_error_difference_bound({{1, 0, 0, 0}}, {{2, 0, 0, 0}}, r,
                                                    {{nan, 0, 0, 0}}, std::vector<double>{0.1})));
  EXPECT_THROW(row_error_difference_bound(one, one, r, one, std::vector<double>{}),
               std::invalid_argument);
}

TEST(ValidationMetrics, RelativeErrorOfABlackReferenceIsUndefinedUnlessTheMethodIsBlackToo) {
  Image black{2, 2, std::vector<float>(16, 0.0f)};
  const PixelMask mask = PixelMask::all(2, 2);
  EXPECT_EQ(relative_errors(black, black, mask).relative_l1.l, 0.0);
  Image lit = black;
  set_grey(lit, 1, 1, 0.5);
  const ErrorStats e = relative_errors(lit, black, mask);
  EXPECT_TRUE(std::isnan(e.relative_l1.l));
  EXPECT_TRUE(std::isnan(e.relative_rms.l));
  EXPECT_DOUBLE_EQ(e.mean_abs.l, 0.125);  // 0.5 over 4 pixels, defined
}

// No pixel compared (a reference whose sun resolves no row of the sea): no error, not a
// perfect 0 (the H200's full_waves120 "all" on wind10_100m_high_sun read 0 over 0 pixels).
TEST(ValidationMetrics, RelativeErrorOverNoPixelIsUndefined) {
  const Image a = random_image(3, 2, 1), b = random_image(3, 2, 2);
  const PixelMask none{3, 2, std::vector<std::uint8_t>(6, 0)};
  const ErrorStats e = relative_errors(a, b, none);
  EXPECT_EQ(e.pixels, 0);
  EXPECT_TRUE(std::isnan(e.relative_l1.l));
  EXPECT_TRUE(std::isnan(e.relative_rms.l));
  EXPECT_TRUE(std::isnan(e.mean_abs.l));
}

// A reference term that no compared pixel shows in its PNG (the sun's Gaussian tail where the
// sea reflects no glint into the view: 1e-25 against the methods' 1e-7) has no relative error,
// row ratio or row error: their ratio of two invisible tails read 3e17 in stop 22's report.
TEST(ValidationMetrics, AReferenceBelowTheBlackLevelHasNoRelativeErrors) {
  const Scene scene = view_scene(64, 48);
  const ViewGeometry view(scene);
  const double black = png_black_level(scene.image.exposure);
  const Image tail = scaled(random_image(64, 48, 5), static_cast<float>(1e-18 * black));
  const Image faint = scaled(random_image(64, 48, 6), static_cast<float>(0.9 * black));
  const Image lit = random_image(64, 48, 7);
  const Image one_glint = [&] {
    Image image = tail;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        if (view.sea_mask()(x, y)) {
          image.pixel(x, y)[1] = static_cast<float>(1.01 * black);
          return image;
        }
    return image;
  }();

  // Both black: nothing a viewer sees differs (relative errors 0), and no row to compare.
  TermMetrics m = compare_images(faint, tail, view, {}, nullptr, black);
  EXPECT_TRUE(m.reference_black);
  EXPECT_EQ(m.error.relative_l1.l, 0.0);
  EXPECT_EQ(m.error.relative_rms.g, 0.0);
  EXPECT_GT(m.error.mean_abs.l, 0.0);  // the absolute difference stays reported
  EXPECT_TRUE(std::isnan(m.row_error));
  EXPECT_TRUE(std::isnan(m.max_row_deviation));
  EXPECT_TRUE(std::isnan(m.mean_row_deviation));
  for (const ChannelValues& r : m.row_ratios) EXPECT_TRUE(std::isnan(r.l));

  // The method visible: undefined, not 1e17.
  m = compare_images(lit, tail, view, {}, nullptr, black);
  EXPECT_TRUE(m.reference_black);
  EXPECT_TRUE(std::isnan(m.error.relative_l1.l));
  EXPECT_TRUE(std::isnan(m.error.relative_rms.b));

  // One reference pixel in one channel at the black level: not black, measured as before.
  m = compare_images(lit, one_glint, view, {}, nullptr, black);
  EXPECT_FALSE(m.reference_black);
  EXPECT_GT(m.error.relative_l1.l, 1e6);
  EXPECT_TRUE(std::isfinite(m.row_error));

  // No pixel compared (the reference's sun resolved no row): nothing measured, not black.
  const PixelMask none{64, 48, std::vector<std::uint8_t>(64 * 48, 0)};
  EXPECT_FALSE(compare_images(faint, tail, view, {}, &none, black).reference_black);

  // Without a black level (the default) nothing is black: the tail is compared as it is.
  m = compare_images(faint, tail, view);
  EXPECT_FALSE(m.reference_black);
  EXPECT_GT(m.error.relative_l1.l, 1e15);
}

// The band's pixels and their angle below the horizon against a brute-force search: for each
// pixel, the horizon's dip in the pixel's azimuth found by bisection on the dip of rays that
// meet the sea (ocean::sea_surface_distance), for a pitched and rolled camera on the WGS84 sea
// at 45 degrees of latitude, where the horizon's dip depends on the azimuth.
TEST(ValidationMetrics, HorizonBandSelectionMatchesABruteForceSearchOnTheWgs84Sea) {
  Scene scene = view_scene(160, 120);
  scene.camera.lat = 45.0;
  scene.camera.height = 1000.0;  // the horizon 1.0 degree below the horizontal
  scene.camera.heading = 30.0;
  scene.camera.pitch = -4.0;
  scene.camera.roll = 20.0;
  scene.camera.fov_y = 30.0;
  const ViewGeometry view(scene);
  const ocean::SeaSurface surface =
      make_nadir_frame(Planet(scene.planet), scene.camera).sea_surface;
  const CameraBasis basis =
      camera_basis(scene.camera.heading, scene.camera.pitch, scene.camera.roll);
  const double tan_half = std::tan(0.5 * scene.camera.fov_y * kDegree);
  const double aspect = double(scene.image.width) / scene.image.height;
  const double depth = 5.0 * kDegree;
  // Angles closer than this to a band edge may fall either side by rounding.
  constexpr double kEdge = 1e-9;  // rad
  int band = 0, sea = 0;
  Image ones{160, 120, std::vector<float>(160 * 120 * 4, 1.0f)};
  Image zeros{160, 120, std::vector<float>(160 * 120 * 4, 0.0f)};
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) {
      const double u = 2.0 * (x + 0.5) / 160 - 1.0, v = 1.0 - 2.0 * (y + 0.5) / 120;
      const glm::dvec3 d = glm::normalize(view_ray(basis, tan_half, aspect, u, v));
      const double horizontal = std::hypot(d.x, d.y);
      const glm::dvec2 a = glm::dvec2(d.x, d.y) / horizontal;
      const auto hits = [&](double dip) {
        const glm::dvec3 r(a.x * std::cos(dip), a.y * std::cos(dip), -std::sin(dip));
        return ocean::sea_surface_distance(surface, scene.camera.height, r).has_value();
      };
      double lo = 0.0, hi = 0.5 * kPi;  // a horizontal ray misses, a vertical one hits
      ASSERT_FALSE(hits(lo));
      ASSERT_TRUE(hits(hi));
      for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
        const double mid = 0.5 * (lo + hi);
        (hits(mid) ? hi : lo) = mid;
      }
      const double beta = std::atan2(-d.z, horizontal) - hi;
      EXPECT_NEAR(view.below_horizon(x, y), beta, 1e-10) << x << ", " << y;
      const bool in_band = beta >= 0.0 && beta < depth;
      if (std::abs(beta) > kEdge && std::abs(beta - depth) > kEdge) {
        EXPECT_EQ(view.below_horizon(x, y) >= 0.0 && view.below_horizon(x, y) < depth, in_band);
        EXPECT_EQ(view.sea_mask()(x, y) != 0, beta >= 0.0) << x << ", " << y;
      }
      band += in_band;
      sea += beta >= 0.0;
    }
  }
  ASSERT_GT(band, 500);  // the rolled horizon crosses the view
  ASSERT_LT(sea, 160 * 120);
  const HorizonBand h = horizon_band(ones, zeros, view);
  EXPECT_EQ(h.pixels, band);
  EXPECT_EQ(h.bins.size(), 10u);  // 5 degrees in bins of 0.5
  EXPECT_EQ(view.sea_mask().count(), sea);
}

// D = L_method - L_reference = g * beta (beta in degrees below the horizon) in the band, on a
// rolled view: each bin's azimuth-averaged mean is g times the bin's middle angle, and its
// standard deviation that of a uniform distribution over the bin, g * bin / sqrt(12), to the
// sampling of the bin by pixel centres (about 7 pixels across a bin here).
TEST(ValidationMetrics, KnownGradientBelowTheHorizonGivesTheExpectedBandMeanAndStd) {
  Scene scene = view_scene(400, 300);
  scene.camera.height = 100.0;
  scene.camera.pitch = -2.0;
  scene.camera.roll = 15.0;
  scene.camera.fov_y = 20.0;  // 0.067 degree per pixel
  const ViewGeometry view(scene);
  const double g = 0.02;          // W m^-2 sr^-1 nm^-1 per degree
  const double background = 0.3;  // reference luminance
  Image reference{400, 300, std::vector<float>(400 * 300 * 4, 0.0f)};
  Image method = reference;
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 400; ++x) {
      set_grey(reference, x, y, background);
      set_grey(method, x, y, background + g * view.below_horizon(x, y) / kDegree);
    }
  HorizonBandOptions options;
  options.bin_deg = 0.5;
  const HorizonBand h = horizon_band(method, reference, view, options);
  ASSERT_EQ(h.bins.size(), 10u);
  for (const HorizonBin& b : h.bins) {
    ASSERT_GT(b.pixels, 1000) << b.beta_lo_deg;
    const double middle = 0.5 * (b.beta_lo_deg + b.beta_hi_deg);
    // Pixel centres sample the bin every ~0.07 degree: the mean is the middle to within a few
    // per cent of the bin, the std to within 5%; float images round D at ~3e-8.
    EXPECT_NEAR(b.mean, g * middle, 0.02 * g * options.bin_deg) << b.beta_lo_deg;
    EXPECT_NEAR(b.std, g * options.bin_deg / std::sqrt(12.0),
                0.05 * g * options.bin_deg / std::sqrt(12.0))
        << b.beta_lo_deg;
    EXPECT_NEAR(b.reference_mean, background, 1e-6);
  }
  EXPECT_NEAR(h.mean, g * 2.5, 0.02 * g * options.bin_deg);  // the band's middle, 2.5 degrees
  // A constant difference: mean exactly it, standard deviation 0 (two passes, no cancellation).
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 400; ++x) set_grey(method, x, y, background + 0.125);
  const HorizonBand c = horizon_band(method, reference, view, options);
  for (const HorizonBin& b : c.bins) {
    EXPECT_NEAR(b.mean, 0.125, 1e-7);
    EXPECT_LT(b.std, 1e-12);
  }
}

// thalassa validate --seas pools the bands of a case's seas (pool_horizon_bands): per bin the
// pixels of every band as one set. The identity: the pooled bands of disjoint masks are the band
// of their union. A rolled view (its bins cross the image's rows) and random images; the image
// cut into three masks of different sizes (columns left of 150, a checkerboard of the rest, and
// what remains), one of them leaving a bin empty.
TEST(ValidationMetrics, PooledHorizonBandsOfDisjointMasksAreTheBandOfTheirUnion) {
  Scene scene = view_scene(400, 300);
  scene.camera.height = 100.0;
  scene.camera.pitch = -2.0;
  scene.camera.roll = 15.0;
  scene.camera.fov_y = 20.0;
  const ViewGeometry view(scene);
  const Image reference = random_image(400, 300, 11);
  const Image method = random_image(400, 300, 12);
  PixelMask left = PixelMask::all(400, 300), checks = left, rest = left;
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 400; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * 400 + x;
      const bool in_left = x < 150;
      const bool in_checks = !in_left && (x / 7 + y / 5) % 2 == 0;
      left.inside[i] = in_left;
      checks.inside[i] = in_checks;
      // The rest leaves out the band's deepest bin (4.5-5 degrees): an empty bin in one band.
      rest.inside[i] = !in_left && !in_checks && view.below_horizon(x, y) < 4.5 * kDegree;
    }
  PixelMask all = left;
  for (std::size_t i = 0; i < all.inside.size(); ++i)
    all.inside[i] = left.inside[i] || checks.inside[i] || rest.inside[i];
  HorizonBandOptions options;
  const HorizonBand whole = horizon_band(method, reference, view, options, &all);
  const std::vector<HorizonBand> parts = {horizon_band(method, reference, view, options, &left),
                                          horizon_band(method, reference, view, options, &checks),
                                          horizon_band(method, reference, view, options, &rest)};
  ASSERT_EQ(parts[2].bins.back().pixels, 0);
  ASSERT_TRUE(std::isnan(parts[2].bins.back().mean));
  const HorizonBand pooled = pool_horizon_bands(parts);
  ASSERT_EQ(pooled.bins.size(), whole.bins.size());
  EXPECT_EQ(pooled.pixels, whole.pixels);
  for (std::size_t k = 0; k < whole.bins.size(); ++k) {
    const HorizonBin& a = pooled.bins[k];
    const HorizonBin& b = whole.bins[k];
    ASSERT_GT(b.pixels, 500) << k;
    EXPECT_EQ(a.beta_lo_deg, b.beta_lo_deg);
    EXPECT_EQ(a.beta_hi_deg, b.beta_hi_deg);
    EXPECT_EQ(a.pixels, b.pixels) << k;
    EXPECT_NEAR(a.weight, b.weight, 1e-12 * b.weight) << k;
    EXPECT_NEAR(a.mean, b.mean, 1e-12 * b.std) << k;
    EXPECT_NEAR(a.std, b.std, 1e-12 * b.std) << k;
    EXPECT_NEAR(a.reference_mean, b.reference_mean, 1e-12 * b.reference_mean) << k;
    // The parts differ: pooling is not a plain average of their values.
    EXPECT_NE(parts[0].bins[k].mean, parts[1].bins[k].mean) << k;
  }
  EXPECT_NEAR(pooled.mean, whole.mean, 1e-12 * whole.std);
  EXPECT_NEAR(pooled.std, whole.std, 1e-12 * whole.std);
  EXPECT_NEAR(pooled.reference_mean, whole.reference_mean, 1e-12 * whole.reference_mean);

  // One band pools to itself; bands of one constant difference to a standard deviation of 0.
  const HorizonBand self = pool_horizon_bands(std::span(parts).first(1));
  for (std::size_t k = 0; k < self.bins.size(); ++k) {
    EXPECT_DOUBLE_EQ(self.bins[k].mean, parts[0].bins[k].mean);
    EXPECT_NEAR(self.bins[k].std, parts[0].bins[k].std, 1e-15);
  }
  const Image shifted = [&] {
    Image out = reference;
    for (std::size_t i = 0; i < out.rgba.size(); i += 4)
      for (int c = 0; c < 3; ++c) out.rgba[i + c] += 0.125f;
    return out;
  }();
  const std::vector<HorizonBand> constant = {
      horizon_band(shifted, reference, view, options, &left),
      horizon_band(shifted, reference, view, options, &checks)};
  for (const HorizonBin& b : pool_horizon_bands(constant).bins) {
    EXPECT_NEAR(b.mean, 0.125, 1e-7);
    EXPECT_LT(b.std, 1e-7);  // float rounding of the shifted pixels, not cancellation
  }

  // No band: no bins, NaN; bands of other bins are refused.
  const HorizonBand none = pool_horizon_bands({});
  EXPECT_TRUE(none.bins.empty());
  EXPECT_EQ(none.pixels, 0);
  EXPECT_TRUE(std::isnan(none.mean));
  HorizonBandOptions finer = options;
  finer.bin_deg = 0.25;
  const std::vector<HorizonBand> mixed = {parts[0],
                                          horizon_band(method, reference, view, finer, &checks)};
  EXPECT_THROW(pool_horizon_bands(mixed), std::invalid_argument);
}

// The band weights pixels by their area in the (azimuth, angle) plane, so that the mean is
// uniform in azimuth: an image whose difference depends on the azimuth only, as sin(azimuth -
// heading), averages to 0 over a view symmetric about its heading, although the pixels of a
// perspective image are not uniform in azimuth.
TEST(ValidationMetrics, HorizonBandMeanIsUniformInAzimuth) {
  Scene scene = view_scene(240, 120);
  scene.camera.height = 10.0;
  scene.camera.pitch = 0.0;
  scene.camera.heading = 0.0;
  scene.camera.fov_y = 60.0;  // 120 degrees wide: strongly non-uniform pixel azimuths
  const ViewGeometry view(scene);
  Image reference{240, 120, std::vector<float>(240 * 120 * 4, 0.0f)};
  Image method = reference;
  double pixel_average = 0.0;
  int n = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 240; ++x) {
      const glm::dvec3 d = view.ray(x, y);
      const double azimuth = std::atan2(d.x, d.y);
      // |sin| makes the plain pixel average differ from the azimuth average (pixels crowd
      // toward the edges of a wide view in azimuth).
      const double value = std::abs(std::sin(azimuth));
      set_grey(method, x, y, value);
      const double beta = view.below_horizon(x, y);
      if (beta >= 0.0 && beta < 5.0 * kDegree) {
        pixel_average += value;
        ++n;
      }
    }
  pixel_average /= n;
  // Over azimuths uniform in [-a, a] (a = the half width at the horizon), the mean of |sin| is
  // (1 - cos a) / a.
  const double half_width = std::atan(std::tan(30.0 * kDegree) * 2.0);
  const double azimuth_average = (1.0 - std::cos(half_width)) / half_width;
  const HorizonBand h = horizon_band(method, reference, view);
  EXPECT_NEAR(h.mean, azimuth_average, 0.01);
  EXPECT_GT(std::abs(pixel_average - azimuth_average), 0.03);  // the weights matter here
}

TEST(ValidationMetrics, FlickerOfIdenticalFramesIsZero) {
  const Image a = random_image(32, 24, 3);
  const PixelMask mask = PixelMask::all(32, 24);
  const std::vector<Image> still = {a, a, a};
  EXPECT_EQ(flicker(still, mask), 0.0);
  EXPECT_EQ(temporal_error(still, still, mask), 0.0);
  // One frame scaled by k: |k - 1| L / ((1 + k) L / 2) for that pair.
  const std::vector<Image> step = {a, scaled(a, 1.5f)};
  EXPECT_NEAR(flicker(step, mask), 0.5 / 1.25, 1e-6);
  // The method changes as the reference does: no temporal error; standing still while the
  // reference changes: an error of 1.
  EXPECT_NEAR(temporal_error(step, step, mask), 0.0, 1e-12);
  const std::vector<Image> frozen = {a, a};
  EXPECT_NEAR(temporal_error(frozen, step, mask), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(flicker(std::vector<Image>{a}, mask)));
}

}  // namespace
}  // namespace thalassa::validation

namespace thalassa::validation {
namespace {

// The reference's resolved rows narrow the compared pixels row by row, keep the mask as it is
// without them (a reference without the sun), and refuse rows that do not match the image.
TEST(ValidationMetrics, ResolvedRowsMaskKeepsOnlyResolvedRows) {
  PixelMask mask = PixelMask::all(3, 4);
  mask.inside[0] = 0;  // pixel (0, 0) is not sea
  const PixelMask kept = resolved_rows_mask(mask, {1.0, 0.5, 0.99, 0.0}, 0.99);
  EXPECT_EQ(kept.count(), 2 + 0 + 3 + 0);
  EXPECT_FALSE(kept(0, 0));
  EXPECT_TRUE(kept(1, 0));
  EXPECT_FALSE(kept(1, 1));
  EXPECT_TRUE(kept(2, 2));
  EXPECT_EQ(resolved_rows_mask(mask, {}, 0.99).inside, mask.inside);
  EXPECT_THROW(resolved_rows_mask(mask, {1.0, 1.0}, 0.99), std::invalid_argument);
}

// The reference compared with the other methods: its sea alone where the pixel's centre sees
// the sea and some of its samples did, its whole pixel elsewhere; itself without a sea image;
// images of other sizes refused.
TEST(ValidationMetrics, ReferenceForComparisonTakesTheSeaAloneAtSeaPixels) {
  Image reference{3, 2, std::vector<float>(3 * 2 * 4, 1.0f)};
  Image sea{3, 2, std::vector<float>(3 * 2 * 4, 0.0f)};
  const auto set = [](Image& image, int x, int y, float value, float alpha) {
    float* p = image.pixel(x, y);
    p[0] = p[1] = p[2] = value;
    p[3] = alpha;
  };
  set(sea, 0, 1, 0.25f, 1.0f);    // all sea
  set(sea, 1, 1, 0.5f, 0.375f);   // the horizon crosses it: 3 of 8 samples saw the sea
  set(sea, 1, 0, 0.75f, 0.125f);  // its centre sees the sky, one sample a crest
  // (2, 1): its centre sees the sea, none of its samples did (alpha 0)
  PixelMask mask = PixelMask::all(3, 2);
  for (int x = 0; x < 3; ++x) mask.inside[x] = 0;  // the top row's centres see the sky
  const Image out = reference_for_comparison(reference, sea, mask);
  EXPECT_EQ(out.pixel(0, 1)[1], 0.25f);
  EXPECT_EQ(out.pixel(1, 1)[1], 0.5f);
  EXPECT_EQ(out.pixel(1, 0)[1], 1.0f);
  EXPECT_EQ(out.pixel(2, 1)[1], 1.0f);
  EXPECT_EQ(out.pixel(0, 0)[1], 1.0f);
  EXPECT_EQ(reference_for_comparison(reference, Image{}, mask).rgba, reference.rgba);
  EXPECT_THROW(reference_for_comparison(reference, Image{2, 2, std::vector<float>(16, 0.0f)}, mask),
               std::invalid_argument);
}

}  // namespace
}  // namespace thalassa::validation
