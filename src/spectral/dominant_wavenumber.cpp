#include "sphstab/spectral/dominant_wavenumber.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace sphstab {

WavenumberEstimate dominant_wavenumber(const Eigen::VectorXd& mode, const Eigen::VectorXd& x, bool periodic,
                                       int projection_limit) {
  const int n = static_cast<int>(mode.size());
  if (n == 0 || x.size() != n)
    throw std::invalid_argument("dominant_wavenumber: mode and x must have the same, non-zero size (got " +
                                std::to_string(mode.size()) + " and " + std::to_string(x.size()) + ")");
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return x[a] < x[b]; });
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = mode[order[i]];

  WavenumberEstimate est;
  // Sign changes.
  const double vmax = v.cwiseAbs().maxCoeff();
  std::vector<double> nonzero;
  for (int i = 0; i < n; ++i)
    if (std::abs(v[i]) > 1e-12 * vmax) nonzero.push_back(v[i]);
  int z = 0;
  for (size_t i = 1; i < nonzero.size(); ++i) z += (nonzero[i] > 0) != (nonzero[i - 1] > 0);
  if (periodic && nonzero.size() > 1) z += (nonzero.front() > 0) != (nonzero.back() > 0);
  est.sign_changes = z;
  est.k_sign_changes = periodic ? std::min(1.0, double(z) / n) : double(z + 1) / (n + 1);

  // Projection.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (n > projection_limit || vmax == 0.0) {
    est.k_projection = nan;
    est.projection_fraction = nan;
    return est;
  }
  const double norm2 = v.squaredNorm();
  double best = -1, best_k = 0;
  if (!periodic) {
    // c_m = sum_i v_i sin(m theta (i+1)), theta = pi/(n+1); sum |c_m|^2 = (n+1)/2 |v|^2.
    const double theta = M_PI / (n + 1);
    for (int m = 1; m <= n; ++m) {
      const std::complex<double> step = std::polar(1.0, m * theta);
      std::complex<double> e = step;
      double c = 0;
      for (int i = 0; i < n; ++i) {
        c += v[i] * e.imag();
        e *= step;
      }
      const double p = c * c * 2.0 / (n + 1);
      if (p > best) {
        best = p;
        best_k = double(m) / (n + 1);
      }
    }
  } else {
    // Real Fourier basis: |sum v_i e^{-i k x_i}|^2 normalised to the share of |v|^2 carried by cos and sin at k_m.
    for (int m = 0; m <= n / 2; ++m) {
      const std::complex<double> step = std::polar(1.0, -2.0 * M_PI * m / n);
      std::complex<double> e = 1.0, c = 0.0;
      for (int i = 0; i < n; ++i) {
        c += v[i] * e;
        e *= step;
      }
      const bool single = (m == 0) || (2 * m == n);  // real basis function only
      const double p = std::norm(c) * (single ? 1.0 : 2.0) / n;
      if (p > best) {
        best = p;
        best_k = 2.0 * m / n;
      }
    }
  }
  est.k_projection = best_k;
  est.projection_fraction = best / norm2;
  return est;
}

}  // namespace sphstab
