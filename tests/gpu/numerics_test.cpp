// The ocean's shared GLSL functions in float (on the GPU) against their double-precision C++
// references (the same source compiled as C++), over the stiff sweeps of
// tests/unit/ocean_numerics_test.cpp (issue 7, point 2): Lambda(a) for a from 1e-4 to 1e4, the
// horizon, 1 - sqrt(1 - x), sigma -> 0, theta_v -> 90 deg, the nadir of the stereographic
// mapping. Each input is rounded to float first and the reference is evaluated on exactly that
// float, so the errors measured are those of float arithmetic (and of the driver's exp, pow,
// sqrt), not of the inputs' rounding. Prints the table of docs/numerics.md:
//   THALASSA_TEST_BACKEND=egl build/tests/gpu_tests --gtest_filter='GpuNumerics*'
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "model_reference.hpp"
#include "ross_brdf_reference.hpp"
#include "test_support.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/ocean/effective_fresnel.hpp"
#include "thalassa/ocean/gl/effective_fresnel_texture.hpp"
#include "trochoids_reference.hpp"

namespace thalassa {
namespace {

constexpr int kWidth = 256;  // pixels per row of a sweep

// Below this magnitude a reference counts as having underflowed in float (llvmpipe, like most
// GPUs, flushes float subnormals, below 1.2e-38, to 0): the GPU must return a value as small.
constexpr double kFloatUnderflow = 1e-36;

double Relative(double gpu, double expected, double floor) {
  return std::abs(gpu - expected) / std::max(std::abs(expected), floor);
}

// The rows of the table: function, region, worst relative error, where, and the bound asserted.
struct TableRow {
  std::string function, region;
  double worst = 0.0;
  std::string where;
  double bound = 0.0;
  int samples = 0;
};

std::vector<TableRow>& Table() {
  static std::vector<TableRow> table;
  return table;
}

class GpuNumericsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = test::make_test_context();
    library_ = std::make_unique<gl::ShaderLibrary>(
        std::vector<std::filesystem::path>{THALASSA_SOURCE_DIR "/tests/gpu/shaders"});
  }

  static void TearDownTestSuite() {
    std::printf("\n| function | region | samples | worst relative error | at | asserted |\n");
    std::printf("|---|---|---|---|---|---|\n");
    for (const TableRow& row : Table()) {
      std::printf("| %s | %s | %d | %.2g | %s | %.0e |\n", row.function.c_str(), row.region.c_str(),
                  row.samples, row.worst, row.where.c_str(), row.bound);
    }
    Table().clear();
  }

  // Evaluates FUNCTION of tests/gpu/shaders/numerics.frag on one input per pixel; `uniforms`
  // sets the program's uniforms. Returns one vec4 per input, in order.
  std::vector<glm::vec4> evaluate(int function, const std::vector<glm::vec4>& inputs,
                                  const std::function<void(GLuint)>& uniforms = {}) {
    const int height = int((inputs.size() + kWidth - 1) / kWidth);
    std::vector<glm::vec4> texels(std::size_t(kWidth) * height, glm::vec4(0.5f));
    std::copy(inputs.begin(), inputs.end(), texels.begin());
    const GLuint program = library_->program({.vertex = "engine/fullscreen.vert",
                                              .fragment = "numerics.frag",
                                              .defines = {{"FUNCTION", std::to_string(function)}}});
    if (uniforms) uniforms(program);
    std::vector<glm::vec4> out = test::evaluate_fragment(program, texels, kWidth, height);
    out.resize(inputs.size());
    return out;
  }

  std::unique_ptr<GlContext> context_;
  std::unique_ptr<gl::ShaderLibrary> library_;
};

// Accumulates one row of the table: feed (gpu, expected, floor, description) per sample; every
// GPU value must be finite; the row's worst error must stay within `bound`.
class Region {
 public:
  Region(std::string function, std::string region, double bound) : index_(Table().size()) {
    row_.function = std::move(function);
    row_.region = std::move(region);
    row_.bound = bound;
    Table().push_back(row_);  // its place in the table, in the order of declaration
  }
  ~Region() {
    EXPECT_LE(row_.worst, row_.bound)
        << row_.function << ", " << row_.region << " at " << row_.where;
    Table()[index_] = row_;
  }
  double worst() const { return row_.worst; }
  void add(double error, const std::string& where) {
    ++row_.samples;
    EXPECT_TRUE(std::isfinite(error)) << row_.function << ", " << row_.region << " at " << where;
    if (!(error <= row_.worst)) {
      row_.worst = error;
      row_.where = where;
    }
  }

 private:
  std::size_t index_;
  TableRow row_;
};

// v rounded to float, componentwise: the value the GPU sees in a float uniform or texel.
// (Through a volatile: GCC 12 at -O3 was seen to fold double(float(x)) to x for some x, which
// left the reference with unrounded inputs.)
double RoundToFloat(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}
glm::dvec3 RoundToFloat(const glm::dvec3& v) {
  return glm::dvec3(RoundToFloat(v.x), RoundToFloat(v.y), RoundToFloat(v.z));
}

std::string Format(const char* format, double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, x);
  return buffer;
}

TEST_F(GpuNumericsTest, SmithLambda) {
  // a log-spaced from 1e-4 to 1e4, 50 points per decade, plus both sides of each boundary.
  std::vector<glm::vec4> inputs;
  for (int i = 0; i <= 400; ++i)
    inputs.emplace_back(float(std::pow(10.0, -4.0 + i / 50.0)), 0, 0, 0);
  for (double edge : {1.2, 6.0, 28.0}) {
    inputs.emplace_back(float(edge), 0, 0, 0);
    inputs.emplace_back(std::nextafter(float(edge), 0.0f), 0, 0, 0);
  }
  const auto gpu = evaluate(1, inputs);
  Region small("Lambda(a)", "a in [1e-4, 1.2): A&S polynomial", 1e-5);
  Region middle("Lambda(a)", "a in [1.2, 6): continued fraction", 1e-5);
  Region large("Lambda(a)", "a in [6, 8.7): asymptotic series", 5e-5);
  Region underflow("Lambda(a)", "a in [8.7, 1e4], reference < 1e-36: abs(gpu), absolute", 1e-36);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const double a = inputs[i].x;
    const double expected = glsl::OceanSmithLambda(a);
    const std::string where = Format("a = %.4g", a);
    if (expected < kFloatUnderflow) {
      underflow.add(std::abs(double(gpu[i].x)), where);
    } else {
      (a < 1.2   ? small
       : a < 6.0 ? middle
                 : large)
          .add(Relative(gpu[i].x, expected, kFloatUnderflow), where);
    }
  }
}

TEST_F(GpuNumericsTest, SmithCosLambdaToTheHorizon) {
  // cos theta Lambda and cos theta (1 + Lambda) for cos theta from 1 down to 1e-10 and 0, for a
  // calm sea's sigma_sin (1e-3), a rough one's (0.1) and the largest (1).
  std::vector<glm::vec4> inputs;
  for (float sigma_sin : {1e-3f, 0.1f, 1.0f}) {
    inputs.emplace_back(0.0f, sigma_sin, 0, 0);
    for (int i = 0; i <= 200; ++i)
      inputs.emplace_back(float(std::pow(10.0, -i / 20.0)), sigma_sin, 0, 0);
  }
  const auto gpu = evaluate(2, inputs);
  Region grazing("cos Lambda, facing area", "a < 1e-3 (grazing, to cos theta = 0)", 1e-5);
  Region small("cos Lambda, facing area", "a in [1e-3, 1.2)", 1e-5);
  Region middle("cos Lambda, facing area", "a in [1.2, 6)", 1e-5);
  Region large("cos Lambda, facing area", "a >= 6 (normal float)", 5e-5);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const double cos_theta = inputs[i].x, sigma_sin = inputs[i].y;
    const double a = cos_theta / sigma_sin;
    Region& region = a < 1e-3 ? grazing : a < 1.2 ? small : a < 6.0 ? middle : large;
    const std::string where = Format("a = %.3g", a) + Format(", sigma_sin %g", sigma_sin);
    const double cos_lambda = glsl::OceanSmithCosLambda(cos_theta, sigma_sin);
    if (cos_lambda >= kFloatUnderflow) {
      region.add(Relative(gpu[i].x, cos_lambda, kFloatUnderflow), where);
    } else {
      EXPECT_LE(std::abs(gpu[i].x), kFloatUnderflow) << where;
    }
    region.add(Relative(gpu[i].y, glsl::OceanSmithFacingArea(cos_theta, sigma_sin), 0.0), where);
  }
}

TEST_F(GpuNumericsTest, TrochoidSlopeVariance) {
  // 1 - sqrt(1 - s^2): s from 1e-8 (variance 5e-17) to 0.5, and toward the cusp s = 1 - 2^-k.
  std::vector<glm::vec4> inputs;
  for (int i = 0; i <= 160; ++i) {
    const float s = float(std::pow(10.0, -8.0 + i / 20.0));
    if (s <= 0.5f) inputs.emplace_back(s, 0, 0, 0);
  }
  for (int k = 1; k <= 24; ++k) inputs.emplace_back(float(1.0 - std::ldexp(1.0, -k)), 0, 0, 0);
  const auto gpu = evaluate(3, inputs);
  Region small("trochoid variance 1 - sqrt(1 - s^2)", "s in [1e-8, 0.5]", 1e-6);
  Region cusp("trochoid variance 1 - sqrt(1 - s^2)", "s = 1 - 2^-k, k = 1..24 (the cusp)", 1e-6);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const double s = inputs[i].x;
    (s <= 0.5 ? small : cusp)
        .add(Relative(gpu[i].x, glsl::TrochoidSlopeVariance(s), 0.0), Format("s = %.9g", s));
  }
}

// The reference's lattice differences a wave's field between corners a subcell apart (3.9e-5 m
// at 128 cells per wavelength of the 0.04 m wave and 8 x 8 subcells), up to 25 m from the frame's
// origin, where phase - k.x is some 3,900 rad. TrochoidArgumentFrom keeps that difference: over
// points o + l (o up to 25 m away, l within 0.3 m of it), the change of sin(theta) between l and
// l + step on the GPU against double from the same floats, relative to its largest |k| |step|.
// Measured on llvmpipe: at most 7.5e-4 of it (k.l's own rounding, 3.8e-6 rad at 47 rad); the
// bound leaves room for a GPU's sin. TrochoidArgument at the float o + l, as the lattice computed
// it until stop 31, is printed for comparison: at most 0.036 and 0.081 of it (the noise stop 31
// removed).
TEST_F(GpuNumericsTest, TrochoidArgumentFromAnOrigin) {
  const double wavelength = 0.04;  // m, the 4 m cases' shortest wave
  const double k = 2.0 * M_PI / wavelength;
  const glm::dvec2 wave_vector(RoundToFloat(k * 0.6), RoundToFloat(-k * 0.8));
  const double phase = RoundToFloat(1.234);
  const double subcell = wavelength / 128.0 / 8.0;
  for (const glm::dvec2 step : {glm::dvec2(RoundToFloat(subcell), 0.0),
                                glm::dvec2(0.0, RoundToFloat(subcell))}) {
    std::vector<glm::vec4> inputs;
    for (int i = 0; i < 2000; ++i) {
      const double distance = i < 1000 ? 8.0 : 25.0;  // m ahead (heading south, as the suite)
      const double a = 0.001 * (i % 1000);
      inputs.emplace_back(float(3.0 * std::sin(7.1 * a)), float(-distance + std::cos(3.3 * a)),
                          float(0.3 * std::fmod(0.618034 * i, 1.0)),
                          float(0.3 * std::fmod(0.414214 * i, 1.0)));
    }
    const auto gpu = evaluate(11, inputs, [&](GLuint program) {
      glProgramUniform2f(program, glGetUniformLocation(program, "wave_vector"),
                         float(wave_vector.x), float(wave_vector.y));
      glProgramUniform1f(program, glGetUniformLocation(program, "wave_phase"), float(phase));
      glProgramUniform2f(program, glGetUniformLocation(program, "step"), float(step.x),
                         float(step.y));
    });
    const double largest = glm::length(wave_vector) * glm::length(step);
    Region from("TrochoidArgumentFrom, sin's change over a subcell",
                step.x > 0.0 ? "0.04 m wave, 8-25 m away, step along x"
                             : "0.04 m wave, 8-25 m away, step along y",
                2e-3);
    double before = 0.0;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const glm::dvec2 o(inputs[i].x, inputs[i].y), l(inputs[i].z, inputs[i].w);
      const auto exact = [&](glm::dvec2 local) {
        return std::sin(phase - glm::dot(wave_vector, o + local));
      };
      const double change = exact(l + step) - exact(l);
      const std::string where = Format("y %.4g m", o.y);
      from.add(std::abs((gpu[i].y - gpu[i].x) - change) / largest, where);
      before = std::max(before, std::abs((gpu[i].w - gpu[i].z) - change) / largest);
    }
    std::printf("sin's change over a subcell, worst error against its largest: %.2g from the "
                "origin, %.2g at the float o + l\n",
                from.worst(), before);
  }
}

// A unit vector at angle alpha from m, toward azimuth psi about it.
glm::dvec3 Around(const glm::dvec3& m, double alpha, double psi) {
  const glm::dvec3 helper = std::abs(m.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const glm::dvec3 t1 = glm::normalize(glm::cross(helper, m));
  const glm::dvec3 t2 = glm::cross(m, t1);
  return std::cos(alpha) * m + std::sin(alpha) * (std::cos(psi) * t1 + std::sin(psi) * t2);
}

TEST_F(GpuNumericsTest, ReflectedSunAndBrdfAsSigmaVanishes) {
  // The glint of a sun at 30 and 80 deg, for slope variances from 1e-2 to 0 (the sun term's
  // clamp holds them at 1.35e-6): views within 4 lobe widths of the mirror direction. Errors are
  // relative to max(|reference|, 1e-6 x the sweep's peak): the far tail's 1e-40 are not compared.
  for (double zenith : {30.0, 80.0}) {
    const glm::dvec3 l = RoundToFloat(glm::dvec3(std::sin(zenith * M_PI / 180) * std::cos(0.4),
                                                 std::sin(zenith * M_PI / 180) * std::sin(0.4),
                                                 std::cos(zenith * M_PI / 180)));
    const glm::dvec3 m(-l.x, -l.y, l.z);
    for (double variance : {1e-2, 1e-4, 1e-6, 1e-8, 0.0}) {
      const glm::dvec2 s2(RoundToFloat(variance), RoundToFloat(0.5 * variance));
      const double lobe = 2.0 * std::sqrt(std::max(variance, 1.35e-6));
      std::vector<glm::vec4> inputs;
      for (int i = 0; i < 64; ++i) {
        for (int j = 0; j < 16; ++j) {
          const glm::vec3 v(Around(m, 4.0 * lobe * i / 63.0, 2.0 * M_PI * j / 16.0));
          inputs.emplace_back(v.x, v.y, v.z, 0.0f);
        }
      }
      const auto gpu = evaluate(4, inputs, [&](GLuint program) {
        glProgramUniform3f(program, glGetUniformLocation(program, "light"), l.x, l.y, l.z);
        glProgramUniform2f(program, glGetUniformLocation(program, "slope_variance"), s2.x, s2.y);
      });
      double peak_sun = 0.0, peak_brdf = 0.0;
      for (const glm::vec4& v : inputs) {
        peak_sun = std::max(peak_sun, glsl::OceanReflectedSun(glm::dvec3(v), l, s2, 0.02));
        peak_brdf = std::max(peak_brdf, glsl::OceanRossBrdf(glm::dvec3(v), l, s2, 0.02));
      }
      const std::string region =
          Format("theta_l %.0f deg, ", zenith) + Format("sigma^2 = %g", variance);
      Region sun("reflected sun (eq. 15)", region, 2e-5);
      Region brdf("Ross BRDF (eq. 13)", region, 2e-5);
      for (std::size_t i = 0; i < inputs.size(); ++i) {
        const glm::dvec3 v(inputs[i]);
        const std::string where = Format("%.3g lobe widths", std::acos(glm::dot(v, m)) / lobe);
        sun.add(Relative(gpu[i].x, glsl::OceanReflectedSun(v, l, s2, 0.02), 1e-6 * peak_sun),
                where);
        if (variance > 0.0) {  // at sigma = 0 the unclamped BRDF is a Dirac (the floor's 1e-10)
          brdf.add(Relative(gpu[i].y, glsl::OceanRossBrdf(v, l, s2, 0.02), 1e-6 * peak_brdf),
                   where);
        }
      }
    }
  }
}

TEST_F(GpuNumericsTest, GrazingView) {
  // theta_v -> 90 deg: cos theta_v = 10^-k (k = 0..10) and 0, toward the glint of a sun at 80
  // deg and across it, for a 10 m/s sea's slope variances.
  const glm::dvec3 l =
      RoundToFloat(glm::dvec3(-std::sin(80 * M_PI / 180), 0.0, std::cos(80 * M_PI / 180)));
  const glm::dvec2 s2(glm::vec2(0.02f, 0.01f));
  std::vector<glm::vec4> inputs;
  for (double azimuth : {0.0, 10.0, 45.0, 90.0}) {
    for (int k = 0; k <= 41; ++k) {
      const double z = k == 41 ? 0.0 : std::pow(10.0, -k / 4.0);
      const double horizontal = std::sqrt(1.0 - z * z);
      inputs.emplace_back(horizontal * std::cos(azimuth * M_PI / 180),
                          horizontal * std::sin(azimuth * M_PI / 180), z, 0.0f);
    }
  }
  const auto gpu = evaluate(4, inputs, [&](GLuint program) {
    glProgramUniform3f(program, glGetUniformLocation(program, "light"), l.x, l.y, l.z);
    glProgramUniform2f(program, glGetUniformLocation(program, "slope_variance"), s2.x, s2.y);
  });
  const auto fresnel_gpu = evaluate(5, [&] {
    std::vector<glm::vec4> fresnel_inputs;
    for (const glm::vec4& v : inputs)
      fresnel_inputs.emplace_back(v.z, float(glsl::OceanSlopeVarianceToward(glm::dvec3(v), s2)),
                                  0.0f, 0.0f);
    return fresnel_inputs;
  }());
  Region sun("reflected sun (eq. 15)", "theta_v -> 90 deg (cos 1 .. 1e-10, 0)", 2e-5);
  Region brdf("Ross BRDF (eq. 13)", "theta_v -> 90 deg (cos 1 .. 1e-10, 0)", 2e-5);
  Region fresnel("effective Fresnel (eq. 26)", "theta_v -> 90 deg (cos 1 .. 1e-10, 0)", 1e-5);
  double peak_sun = 0.0, peak_brdf = 0.0;
  for (const glm::vec4& v : inputs) {
    peak_sun = std::max(peak_sun, glsl::OceanReflectedSun(glm::dvec3(v), l, s2, 0.02));
    peak_brdf = std::max(peak_brdf, glsl::OceanRossBrdf(glm::dvec3(v), l, s2, 0.02));
  }
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::dvec3 v(inputs[i]);
    const std::string where = Format("cos theta_v = %.3g", v.z) +
                              Format(", azimuth %.0f", std::atan2(v.y, v.x) * 180 / M_PI);
    sun.add(Relative(gpu[i].x, glsl::OceanReflectedSun(v, l, s2, 0.02), 1e-6 * peak_sun), where);
    brdf.add(Relative(gpu[i].y, glsl::OceanRossBrdf(v, l, s2, 0.02), 1e-6 * peak_brdf), where);
    const double view_variance = double(float(glsl::OceanSlopeVarianceToward(v, s2)));
    fresnel.add(
        Relative(fresnel_gpu[i].x, glsl::OceanEffectiveFresnel(v.z, view_variance, 0.02), 0.0),
        where);
  }
}

TEST_F(GpuNumericsTest, EffectiveFresnel) {
  // Eq. 26 for sigma_v^2 from 1 down to 1e-14 and 0 (-> Schlick), cos theta_v from 1 to 1e-9
  // and 0 (grazing); and beyond the documented range, sigma_v^2 = 1e6, where the exponent
  // 5 exp(-2.69 sigma_v) underflows (pow(0, 0) at normal incidence).
  std::vector<glm::vec4> inputs;
  std::vector<float> cosines = {1.0f, 0.0f};
  for (int k = 0; k <= 36; ++k) cosines.push_back(float(std::pow(10.0, -k / 4.0)));
  cosines.push_back(0.99999f);
  for (float cos_theta : cosines) {
    inputs.emplace_back(cos_theta, 0.0f, 0, 0);
    for (int k = 0; k <= 14; ++k) inputs.emplace_back(cos_theta, float(std::pow(10.0, -k)), 0, 0);
    inputs.emplace_back(cos_theta, 1e6f, 0, 0);
  }
  const auto gpu = evaluate(5, inputs);
  Region to_schlick("effective Fresnel (eq. 26)", "sigma_v^2 <= 1e-6 (-> Schlick)", 1e-5);
  Region grazing("effective Fresnel (eq. 26)", "cos theta_v <= 1e-3, sigma_v^2 > 1e-6", 1e-5);
  Region other("effective Fresnel (eq. 26)", "elsewhere, sigma_v^2 in (1e-6, 1]", 1e-5);
  Region extreme("effective Fresnel (eq. 26)", "sigma_v^2 = 1e6 (out of range)", 1e-5);
  Region schlick("Schlick (eq. 14)", "cos theta_v from 1 to 0", 1e-5);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const double cos_theta = inputs[i].x, variance = inputs[i].y;
    const std::string where =
        Format("cos theta_v = %.3g", cos_theta) + Format(", sigma_v^2 = %g", variance);
    const double error =
        Relative(gpu[i].x, glsl::OceanEffectiveFresnel(cos_theta, variance, 0.02), 0.0);
    (variance > 1.0      ? extreme
     : variance <= 1e-6  ? to_schlick
     : cos_theta <= 1e-3 ? grazing
                         : other)
        .add(error, where);
    schlick.add(Relative(gpu[i].y, glsl::OceanSchlickFresnel(cos_theta, 0.02), 0.0), where);
  }
}

TEST_F(GpuNumericsTest, EffectiveFresnelTable) {
  // Eq. 24's table as the lighting reads it (ocean.effective_fresnel = "table") against its CPU
  // twin (EffectiveFresnelTable::lookup, bilinear in double) at the samples, between them and
  // beyond the table (cos theta_v to 0 and 1, variances from 0 to 1e6, across from 0 to 4 times
  // along). The GPU's bilinear weights have 8 bits on some hardware (1/256 of a cell's change; on
  // llvmpipe they are floats): the bound is 1/256 of the table's largest step between neighbours.
  const ocean::EffectiveFresnelTable& table = ocean::effective_fresnel_table();
  double largest_step = 0.0;
  for (int j = 0; j < table.sigma_size; ++j)
    for (int i = 0; i + 1 < table.cos_size; ++i) {
      const std::size_t k = 4 * (std::size_t(j) * table.cos_size + i);
      largest_step =
          std::max(largest_step, double(std::abs(table.values[k + 4] - table.values[k])));
    }
  std::vector<glm::vec4> inputs;
  for (int j = 0; j <= 2 * (table.sigma_size - 1); ++j)
    for (int i = 0; i <= 2 * (table.cos_size - 1); i += 3) {
      const glm::dvec2 node = glsl::OceanEffectiveFresnelTableNode(0.5 * i, 0.5 * j);
      const double along = node.y * node.y;
      inputs.emplace_back(float(node.x), float(along), float((j % 5) * 0.5 * along), 0.0f);
    }
  for (float cos_theta : {0.0f, 1e-6f, 1e-3f, 0.5f, 1.0f})
    for (float along : {0.0f, 1e-12f, 1e-4f, 0.25f, 1.0f, 1e6f})
      inputs.emplace_back(cos_theta, along, along, 0.0f);
  OceanSettings settings;
  settings.effective_fresnel = "table";
  settings.sky_lobe_centre = "fresnel_weighted";
  const auto texture = ocean::EffectiveFresnelTexture::make_if_used(settings, true, true);
  ASSERT_TRUE(texture);
  const auto gpu = evaluate(12, inputs, [&](GLuint) { texture->bind(); });
  Region region("effective Fresnel (eq. 24's table)", "samples, between and beyond",
                largest_step / 256.0);
  // The lobe's centre (ocean.sky_lobe_centre = "fresnel_weighted"), a slope along the view
  // (x here): within 1e-5 of the CPU twin's, and 0 across.
  Region centre("sky lobe's centre (the table's)", "samples, between and beyond", 1e-5);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::dvec4 p(inputs[i]);
    // The shader's along and across: eq. 25 of the variances raised to their floor.
    const glm::dvec3 v(std::sqrt(std::max(1.0 - p.x * p.x, 0.0)), 0.0, p.x);
    const glm::dvec2 s2 = glsl::OceanClampedSlopeVariance(glm::dvec2(p.y, p.z));
    const double along = glsl::OceanSlopeVarianceToward(v, s2);
    const double expected = table.lookup(p.x, along, s2.x + s2.y - along, 0.02);
    const std::string where =
        Format("cos theta_v = %.3g", p.x) + Format(", along %g", p.y) + Format(", across %g", p.z);
    region.add(std::abs(gpu[i].x - expected), where);
    const double slope = v.x > 0.0 ? table.fresnel_weighted_mean_slope(p.x, along, 0.02) : 0.0;
    centre.add(std::max(std::abs(gpu[i].y - slope), std::abs(double(gpu[i].z))), where);
  }
}

TEST_F(GpuNumericsTest, StereographicMappingNearTheNadir) {
  // r at a distance eps from the nadir, eps = 2^-k from 1 rad to 1e-6 rad (the radius cap of
  // OCEAN_SKY_MAP_MAX_RADIUS = 1000 is at eps = 2e-3); U(r) and its derivative along a fixed dr.
  const glm::dvec3 dr = RoundToFloat(glm::dvec3(0.3, -0.5, 0.2));
  std::vector<glm::vec4> inputs;
  std::vector<double> eps;
  for (int k = 0; k <= 20; ++k) {
    for (double azimuth : {0.1, 1.3, 2.9, 4.4}) {
      const double e = std::ldexp(1.0, -k);
      inputs.emplace_back(std::sin(e) * std::cos(azimuth), std::sin(e) * std::sin(azimuth),
                          -std::cos(e), 0.0f);
      eps.push_back(e);
    }
  }
  const auto gpu = evaluate(6, inputs, [&](GLuint program) {
    glProgramUniform3f(program, glGetUniformLocation(program, "dr"), dr.x, dr.y, dr.z);
  });
  Region far("stereographic U and dU/ds, r given", "nadir distance >= 0.1 rad", 1e-5);
  Region near("stereographic U and dU/ds, r given", "nadir distance in [2e-3, 0.1) rad", 1e-5);
  Region cap("stereographic U and dU/ds, r given", "nadir distance < 2e-3 rad (radius cap)", 1e-5);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::dvec3 r(inputs[i]);
    const glm::dvec2 u = glsl::OceanStereographic(r);
    const glm::dvec2 du = glsl::OceanStereographicDerivative(r, dr);
    Region& region = eps[i] >= 0.1 ? far : eps[i] >= 2e-3 ? near : cap;
    const std::string where = Format("eps = %.3g rad", eps[i]);
    region.add(glm::length(glm::dvec2(gpu[i].x, gpu[i].y) - u) / glm::length(u), where);
    region.add(glm::length(glm::dvec2(gpu[i].z, gpu[i].w) - du) / glm::length(du), where);
  }
}

TEST_F(GpuNumericsTest, SkyMapCoordinatesNearTheNadir) {
  // Algorithm 5.1's u(v, 0) and du/dzeta for a steep facet (normal 56 deg from the zenith) seen
  // from behind, so that the reflected ray r = 2 (v.n) n - v, computed in float, reaches the
  // nadir: there 1 + r_z cancels, and r_z's rounding (6e-8) is amplified by 2 / eps^2 unless
  // 1 + r_z is computed from r_x, r_y (ross_brdf.glsl, OceanStereographicDenominator).
  const glm::dvec3 n = RoundToFloat(glm::normalize(glm::dvec3(0.5, 0.6, 0.55)));
  const glm::dvec3 t_x = RoundToFloat(glm::normalize(glm::cross(glm::dvec3(0, 0, 1), n)));
  const glm::dvec3 t_y = RoundToFloat(glm::cross(n, t_x));
  std::vector<glm::vec4> inputs;
  std::vector<double> eps;
  for (int k = 0; k <= 20; ++k) {
    for (double azimuth : {0.1, 1.3, 2.9, 4.4}) {
      const double e = std::ldexp(1.0, -k);
      const glm::dvec3 r(std::sin(e) * std::cos(azimuth), std::sin(e) * std::sin(azimuth),
                         -std::cos(e));
      const glm::dvec3 v = 2.0 * glm::dot(r, n) * n - r;  // the reflection is an involution
      inputs.emplace_back(v.x, v.y, v.z, 0.0f);
      eps.push_back(e);
    }
  }
  const auto uniforms = [&](GLuint program) {
    glProgramUniform3f(program, glGetUniformLocation(program, "frame_x"), t_x.x, t_x.y, t_x.z);
    glProgramUniform3f(program, glGetUniformLocation(program, "frame_y"), t_y.x, t_y.y, t_y.z);
    glProgramUniform3f(program, glGetUniformLocation(program, "frame_n"), n.x, n.y, n.z);
  };
  const auto gpu_x = evaluate(7, inputs, uniforms);
  const auto gpu_y = evaluate(8, inputs, uniforms);
  // Bound: float's 6e-8 on r_x, r_y over eps (3e-5 at eps = 2e-3) with a margin; the form
  // 1 + r_z gave 3.6e-2 at eps = 3.9e-3.
  Region far("sky-map u0, du/dzeta (r computed)", "nadir distance >= 0.1 rad", 2e-4);
  Region near("sky-map u0, du/dzeta (r computed)", "nadir distance in [2e-3, 0.1) rad", 2e-4);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::dvec3 v(inputs[i]);
    glm::dvec2 u0, du_x, du_y;
    glsl::OceanSkyMapGradients(v, t_x, t_y, n, u0, du_x, du_y);
    if (eps[i] < 2e-3) {
      // Within the cap the direction of (r_x, r_y) is itself ill-conditioned (1e-7 / eps in
      // float): only finite values and the cap's radius are asked for.
      EXPECT_NEAR(std::hypot(gpu_x[i].x, gpu_x[i].y), 1000.0, 1e-3) << eps[i];
      EXPECT_TRUE(std::isfinite(gpu_x[i].z) && std::isfinite(gpu_x[i].w) &&
                  std::isfinite(gpu_y[i].x) && std::isfinite(gpu_y[i].y));
      continue;
    }
    Region& region = eps[i] >= 0.1 ? far : near;
    const std::string where = Format("eps = %.3g rad", eps[i]);
    region.add(glm::length(glm::dvec2(gpu_x[i].x, gpu_x[i].y) - u0) / glm::length(u0), where);
    region.add(glm::length(glm::dvec2(gpu_x[i].z, gpu_x[i].w) - du_x) / glm::length(du_x), where);
    region.add(glm::length(glm::dvec2(gpu_y[i].x, gpu_y[i].y) - du_y) / glm::length(du_y), where);
  }
}

TEST_F(GpuNumericsTest, AtmosphereRaySphereDistances) {
  // model.glsl's ray-sphere distances in float over the stiff regions of
  // tests/unit/atmosphere_numerics_test.cpp: a camera h above the ground (h from 0.5 m, float's
  // step at the Earth's radius, to 10 km) looking down and grazing the horizon from either side,
  // h below the top looking up and along the top's tangent. Radii and (r, mu) are floats; the
  // reference is the double model (exact to 8 eps (1 + kappa)) on the same floats. For the
  // ground, errors are over 1 + kappa, kappa = (r mu)^2 / disc the condition number of the near
  // root (1 for rays straight down, unbounded at the horizon); "previous" is the form
  // -r mu +- sqrt(disc) in float (FUNCTION 10).
  const double bottom = RoundToFloat(6371008.8), top = RoundToFloat(6371008.8 + 60000.0);
  glsl::AtmosphereParameters atmosphere{};
  atmosphere.bottom_radius = bottom;
  atmosphere.top_radius = top;
  std::vector<glm::vec4> inputs;
  std::vector<int> region;  // 0: ground, steep; 1: ground, grazing; 2: top, up; 3: top, tangent;
                            // 4: top, grazing the ground from above
  const auto add = [&](double r, double mu, int which) {
    inputs.emplace_back(float(r), float(mu), 0.0f, 0.0f);
    region.push_back(which);
  };
  for (int k = -1; k <= 15; ++k) {
    const double h = 0.5 * std::ldexp(1.0, k) / 2.0;  // 0.25 m (-> 0.5 m in float) .. 8.4 km
    const double r_low = RoundToFloat(bottom + std::max(h, 0.5));
    const double mu_h = -std::sqrt(1.0 - (bottom / r_low) * (bottom / r_low));
    for (int i = 0; i <= 40; ++i) add(r_low, -1.0 + (1.0 + 1.1 * mu_h) * i / 40.0, 0);
    for (int j = 2; j <= 7; ++j) {
      add(r_low, mu_h * (1.0 + std::pow(10.0, -j)), 1);
      add(r_low, mu_h * (1.0 - std::pow(10.0, -j)), 4);
    }
    const double r_high = RoundToFloat(top - std::max(h, 0.5));
    for (int i = 0; i <= 36; ++i) add(r_high, std::pow(10.0, -3.0 + i / 12.0), 2);
    for (int j = 1; j <= 8; ++j) {
      add(r_high, std::pow(10.0, -j), 3);
      add(r_high, -std::pow(10.0, -j), 3);
    }
  }
  const auto uniforms = [&](GLuint program) {
    glProgramUniform2f(program, glGetUniformLocation(program, "radii"), float(bottom), float(top));
  };
  const auto gpu = evaluate(9, inputs, uniforms);
  const auto previous = evaluate(10, inputs, uniforms);
  Region steep("DistanceToBottom, error / (1 + kappa)", "h in [0.5 m, 8 km], mu in [-1, 1.1 mu_h]",
               1e-6);
  Region steep_before("DistanceToBottom, previous form", "same (not asserted)",
                      std::numeric_limits<double>::infinity());
  Region grazing("DistanceToBottom, error / (1 + kappa)", "mu = mu_h (1 + 10^-k), k = 2..7", 1e-6);
  Region up("DistanceToTop", "top - r in [0.5 m, 8 km], mu in [1e-3, 1]", 1e-6);
  Region up_before("DistanceToTop, previous form", "same (not asserted)",
                   std::numeric_limits<double>::infinity());
  Region tangent("DistanceToTop", "top - r in [0.5 m, 8 km], mu = +-10^-k, k = 1..8", 1e-6);
  Region above("DistanceToTop", "mu = mu_h (1 - 10^-k), k = 2..7, h in [0.5 m, 8 km]", 1e-6);
  Region texels("transmittance u, texels", "mu from mu_h to 1 (the rows above)", 5e-4);
  int classified = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const double r = inputs[i].x, mu = inputs[i].y;
    const std::string where =
        (region[i] == 2 || region[i] == 3 ? Format("top - r = %.4g m, ", top - r)
                                          : Format("h = %.4g m, ", r - bottom)) +
        Format("mu = %.4g", mu);
    const double disc = glsl::SphereDiscriminant(r, mu, bottom);
    const bool ground = mu < 0.0 && disc >= 0.0;
    if (region[i] <= 1) {
      if (!ground) continue;  // float's mu rounded across the horizon (k = 7)
      const double kappa = r * mu * r * mu / disc;
      const double expected = glsl::DistanceToBottomAtmosphereBoundary(atmosphere, r, mu);
      (region[i] == 0 ? steep : grazing)
          .add(Relative(gpu[i].y, expected, 0.0) / (1.0 + kappa), where);
      if (region[i] == 0)
        steep_before.add(Relative(previous[i].y, expected, 0.0) / (1.0 + kappa), where);
    } else {
      const double expected = glsl::DistanceToTopAtmosphereBoundary(atmosphere, r, mu);
      (region[i] == 2   ? up
       : region[i] == 3 ? tangent
                        : above)
          .add(Relative(gpu[i].x, expected, 0.0), where);
      if (region[i] == 2) up_before.add(Relative(previous[i].x, expected, 0.0), where);
      if (!ground) {
        const double u = glsl::GetTransmittanceTextureUvFromRMu(atmosphere, r, mu).x;
        texels.add(std::abs(gpu[i].z - u) * glsl::TRANSMITTANCE_TEXTURE_WIDTH, where);
      }
    }
    // The ground test agrees with the double one except within float's rounding of the
    // discriminant (6e-8 (r mu)^2, over its derivative 2 r^2 |mu|) of the horizon.
    if (std::abs(disc) > 4.0 * 6e-8 * r * mu * r * mu) {
      ++classified;
      EXPECT_EQ(gpu[i].w == 1.0f, ground) << where;
    }
  }
  EXPECT_GT(classified, 1000);
  // The cancellation the rewrite removes: in float it reached errors of order 1.
  EXPECT_GT(steep_before.worst(), 0.1);
  EXPECT_GT(up_before.worst(), 1e-3);
}

}  // namespace
}  // namespace thalassa
