// thalassa — the n-point Gauss-Legendre rule, for the atmosphere module's quadratures
// (environment_map.cpp's mean Fresnel reflectance, sh_brdf.cpp's BRDF projection). The tests keep
// their own, written independently (tests/unit/gauss_legendre.hpp), so that they do not check
// the library with itself.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace thalassa::atmosphere::detail {

// Nodes (descending, in (-1, 1)) and weights on [-1, 1], n points, exact for polynomials of
// degree < 2n: Newton's method on P_n from x0 = cos(pi (k + 3/4) / (n + 1/2)) (Tricomi's estimate
// of the zeros, Abramowitz & Stegun 22.16.6), P_n and P_n' by the three-term recurrence
// j P_j = (2j - 1) x P_(j-1) - (j - 1) P_(j-2); weights 2 / ((1 - x^2) P_n'(x)^2) (A&S 25.4.29).
// Newton stops when its step is below 1e-15 (the nodes' rounding), after 100 steps at most.
inline void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  constexpr double kNodeTolerance = 1e-15;
  constexpr int kMaxIterations = 100;
  nodes.assign(static_cast<std::size_t>(n), 0.0);
  weights.assign(static_cast<std::size_t>(n), 0.0);
  for (int k = 0; k < n; ++k) {
    double x = std::cos(std::numbers::pi * (k + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
      double p = 1.0, p_prev = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double next = ((2.0 * j - 1.0) * x * p - (j - 1.0) * p_prev) / j;
        p_prev = p;
        p = next;
      }
      derivative = n * (x * p - p_prev) / (x * x - 1.0);
      const double step = p / derivative;
      x -= step;
      if (std::abs(step) < kNodeTolerance) break;
    }
    nodes[static_cast<std::size_t>(k)] = x;
    weights[static_cast<std::size_t>(k)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
}

}  // namespace thalassa::atmosphere::detail
