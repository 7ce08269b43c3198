#include "sphstab/numerics/quadrature.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace sphstab {

namespace {

struct GaussLegendre16 {
  std::array<double, 16> x{}, w{};
  GaussLegendre16() {
    // Newton iteration on P_16 from the Chebyshev guesses (Numerical Recipes gauleg).
    const int n = 16;
    for (int i = 0; i < n; ++i) {
      double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), pp = 0;
      for (int it = 0; it < 100; ++it) {
        double p1 = 1, p2 = 0;
        for (int j = 1; j <= n; ++j) {
          double p3 = p2;
          p2 = p1;
          p1 = ((2.0 * j - 1) * z * p2 - (j - 1.0) * p3) / j;
        }
        pp = n * (z * p1 - p2) / (z * z - 1);
        double dz = p1 / pp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x[i] = z;
      w[i] = 2.0 / ((1 - z * z) * pp * pp);
    }
  }
};

}  // namespace

double integrate_gauss_legendre(const std::function<double(double)>& f, double a, double b, int panels) {
  static const GaussLegendre16 rule;
  double sum = 0, width = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    double lo = a + p * width, mid = lo + 0.5 * width;
    for (int i = 0; i < 16; ++i) sum += rule.w[i] * f(mid + 0.5 * width * rule.x[i]);
  }
  return 0.5 * width * sum;
}

}  // namespace sphstab
