// What is not finite in a rendered frame, said in one line (renderer.hpp): what `render`, `fly`
// and `validate` print when they refuse a frame.
#include <cstdio>
#include <string>

#include "thalassa/planet/renderer.hpp"

namespace thalassa {
namespace {
std::string sum_text(float value) {  // %.9g: a float to the last digit
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", static_cast<double>(value));
  return text;
}
}  // namespace

std::string nonfinite_report(const Image& image, const Renderer& renderer) {
  std::string report = nonfinite_pixels(image);
  if (report.empty()) return report;
  const RenderStats stats = renderer.stats();
  if (stats.method != "reference") return report;
  const std::string per_pixel = std::to_string(stats.samples);
  report += "; the reference's samples (" + per_pixel +
            " per pixel): " + std::to_string(stats.reference_nonfinite_samples) +
            " not finite, in " + std::to_string(stats.reference_nonfinite_pixels) + " pixels";
  if (stats.reference_first_nonfinite_x < 0) return report;
  // The first pixel with a sample that is not finite (read top-down, as the image's pixels): the
  // first whose mean is not, since the means of finite samples are finite.
  const int x = stats.reference_first_nonfinite_x, y = stats.reference_first_nonfinite_y;
  report += ", " + std::to_string(stats.reference_first_nonfinite_samples) + " of " + per_pixel +
            " at x " + std::to_string(x) + ", y " + std::to_string(y);
  const Image sums = renderer.reference_sun_sums();
  if (x < sums.width && y < sums.height) {
    const float* s = sums.pixel(x, y);
    report += "; the sun's sums there (sum omega sun, sum omega, unresolved, hidden; sr): " +
              sum_text(s[0]) + ", " + sum_text(s[1]) + ", " + sum_text(s[2]) + ", " +
              sum_text(s[3]);
  }
  return report;
}

}  // namespace thalassa
