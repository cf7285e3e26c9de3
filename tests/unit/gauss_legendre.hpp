// Gauss-Legendre quadrature for the tests, written independently of the library's own copy
// (atmosphere/src/sh_brdf.cpp) so that the tests do not check the library with itself.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

namespace thalassa::test {

struct Quadrature1d {
  std::vector<double> x, w;
};

// Nodes and weights on [-1, 1] with n points (exact for polynomials of degree <= 2n - 1):
// Newton's method on P_n from the three-term recurrence k P_k = (2k - 1) x P_(k-1) - (k - 1)
// P_(k-2) (no factorials), started at Tricomi's estimate cos(pi (i + 3/4) / (n + 1/2)).
// Weights 2 / ((1 - x^2) P_n'(x)^2) (Abramowitz & Stegun 25.4.29).
inline Quadrature1d gauss_legendre(int n) {
  Quadrature1d q;
  q.x.resize(n);
  q.w.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double derivative = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p_prev = 1.0, p = x;
      for (int k = 2; k <= n; ++k) {
        const double next = ((2.0 * k - 1.0) * x * p - (k - 1.0) * p_prev) / k;
        p_prev = p;
        p = next;
      }
      derivative = n * (x * p - p_prev) / (x * x - 1.0);
      const double dx = p / derivative;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    q.x[i] = x;
    q.w[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return q;
}

}  // namespace thalassa::test
