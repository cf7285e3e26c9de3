// Double-precision CPU side of the atmosphere model: shaders/atmosphere/model.glsl compiled as
// C++ (Number = double) in namespace thalassa::glsl, with CPU textures that filter exactly as
// OpenGL's GL_LINEAR with GL_CLAMP_TO_EDGE does (texel centres at (i + 0.5) / size), so the
// same table lookups give the same values on both sides up to float rounding. Used by the
// precomputation (atmosphere/src/precompute.cpp) and the tests. Needs shaders/ on the include
// path; a file including it cannot use IN, OUT or INOUT as names.

#ifndef THALASSA_ATMOSPHERE_SRC_MODEL_REFERENCE_HPP_
#define THALASSA_ATMOSPHERE_SRC_MODEL_REFERENCE_HPP_

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/glsl_cpp.hpp"

namespace thalassa::glsl {

// RGB tables stored in float (what the GPU gets), filtered in double.
class Texture2D {
 public:
  Texture2D() = default;
  Texture2D(int width, int height) : width_(width), height_(height), data_(3u * width * height) {}
  int width() const { return width_; }
  int height() const { return height_; }
  void set(int x, int y, const vec3& v) {
    float* p = &data_[3u * (static_cast<std::size_t>(y) * width_ + x)];
    p[0] = static_cast<float>(v.x);
    p[1] = static_cast<float>(v.y);
    p[2] = static_cast<float>(v.z);
  }
  vec3 get(int x, int y) const {
    const float* p = &data_[3u * (static_cast<std::size_t>(y) * width_ + x)];
    return vec3(p[0], p[1], p[2]);
  }
  std::vector<float>& data() { return data_; }
  const std::vector<float>& data() const { return data_; }

  // GL_LINEAR, GL_CLAMP_TO_EDGE.
  vec4 sample(const vec2& uv) const {
    int x0, x1, y0, y1;
    double fx, fy;
    axis(uv.x, width_, x0, x1, fx);
    axis(uv.y, height_, y0, y1, fy);
    const vec3 v = (get(x0, y0) * (1.0 - fx) + get(x1, y0) * fx) * (1.0 - fy) +
                   (get(x0, y1) * (1.0 - fx) + get(x1, y1) * fx) * fy;
    return vec4(v, 1.0);
  }

  // Texel coordinates of a normalised coordinate along an axis of `size` texels, as GL computes
  // them: the two texels around u * size - 0.5 and the weight of the second, clamped to edge.
  static void axis(double u, int size, int& i0, int& i1, double& f) {
    const double t = u * size - 0.5;
    const double fl = std::floor(t);
    f = t - fl;
    const int i = static_cast<int>(std::clamp(fl, -1.0, static_cast<double>(size)));
    i0 = std::clamp(i, 0, size - 1);
    i1 = std::clamp(i + 1, 0, size - 1);
  }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<float> data_;
};

class Texture3D {
 public:
  Texture3D() = default;
  Texture3D(int width, int height, int depth)
      : width_(width), height_(height), depth_(depth), data_(3u * width * height * depth) {}
  int width() const { return width_; }
  int height() const { return height_; }
  int depth() const { return depth_; }
  std::size_t index(int x, int y, int z) const {
    return 3u * ((static_cast<std::size_t>(z) * height_ + y) * width_ + x);
  }
  void set(int x, int y, int z, const vec3& v) {
    float* p = &data_[index(x, y, z)];
    p[0] = static_cast<float>(v.x);
    p[1] = static_cast<float>(v.y);
    p[2] = static_cast<float>(v.z);
  }
  vec3 get(int x, int y, int z) const {
    const float* p = &data_[index(x, y, z)];
    return vec3(p[0], p[1], p[2]);
  }
  std::vector<float>& data() { return data_; }
  const std::vector<float>& data() const { return data_; }

  vec4 sample(const vec3& uvw) const {
    int x0, x1, y0, y1, z0, z1;
    double fx, fy, fz;
    Texture2D::axis(uvw.x, width_, x0, x1, fx);
    Texture2D::axis(uvw.y, height_, y0, y1, fy);
    Texture2D::axis(uvw.z, depth_, z0, z1, fz);
    auto plane = [&](int z) {
      return (get(x0, y0, z) * (1.0 - fx) + get(x1, y0, z) * fx) * (1.0 - fy) +
             (get(x0, y1, z) * (1.0 - fx) + get(x1, y1, z) * fx) * fy;
    };
    return vec4(plane(z0) * (1.0 - fz) + plane(z1) * fz, 1.0);
  }

 private:
  int width_ = 0;
  int height_ = 0;
  int depth_ = 0;
  std::vector<float> data_;
};

using TransmittanceTexture = Texture2D;
using IrradianceTexture = Texture2D;
using ScatteringTexture = Texture3D;

inline vec4 texture(const Texture2D& t, const vec2& uv) { return t.sample(uv); }
inline vec4 texture(const Texture3D& t, const vec3& uvw) { return t.sample(uvw); }

}  // namespace thalassa::glsl

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace thalassa::glsl {
namespace {
#include "atmosphere/model.glsl"
}  // namespace
}  // namespace thalassa::glsl
#pragma GCC diagnostic pop

#endif  // THALASSA_ATMOSPHERE_SRC_MODEL_REFERENCE_HPP_
