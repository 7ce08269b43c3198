#include "sphstab/spectral/tension_estimates.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/core/format.hpp"

namespace sphstab {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Smallest T > 0 with c0 - n T c1 < 0: c0 / (n c1) for c1 > 0 (0 if c0 <= 0), inf otherwise.
double root(double c0, double c1, int n) {
  if (n <= 0 || !(c1 > 0)) return kInf;
  return c0 <= 0 ? 0.0 : c0 / (n * c1);
}
}  // namespace

double second_minor_tension(double k_ii, double l_ii, double k_next, double l_next, int n) {
  // Eigenvalues of the 2x2 block: A_ii - A_i,i+1 and A_ii + A_i,i+1, each linear in T.
  return std::min(root(k_ii - k_next, l_ii - l_next, n), root(k_ii + k_next, l_ii + l_next, n));
}

TensionEstimates1D tension_estimates_1d(const Kernel<1>& kernel, double h, double dx, int n) {
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("tension_estimates_1d: h must be finite and > 0 (got " + format_number(h) + ")");
  if (!(dx > 0) || !std::isfinite(dx))
    throw std::invalid_argument("tension_estimates_1d: dx must be finite and > 0 (got " + format_number(dx) + ")");
  if (n < 0) throw std::invalid_argument("tension_estimates_1d: n must be >= 0 (got " + std::to_string(n) + ")");
  const double support = kernel.support_radius(h);
  // g[m] = G_{i,i+m} for m = -M..M stored at offset M; H_m for m >= 1.
  int mmax = 0;
  while ((mmax + 1) * dx < support) ++mmax;  // strict, like find_neighbours
  TensionEstimates1D e;
  if (mmax == 0) {  // no neighbour inside the support: A = 0, every estimate is undefined (not infinite)
    const double nan = std::numeric_limits<double>::quiet_NaN();
    e.first_minor = e.second_minor = e.nearest_neighbour = e.nearest_neighbour_minor = e.swegle = nan;
    return e;
  }
  std::vector<double> g(2 * mmax + 1, 0.0);
  for (int m = 1; m <= mmax; ++m) {
    const double w1 = kernel.d1(m * dx, h) * dx, w2 = kernel.d2(m * dx, h) * dx;
    g[mmax + m] = -w1;  // x_i - x_j = -m dx < 0: dW/dx_i = W'(r) * (-1)
    g[mmax - m] = w1;
    e.l_ii += 2 * w2;
  }
  for (int m = -mmax; m <= mmax; ++m) {
    e.k_ii += g[mmax + m] * g[mmax + m];
    if (m - 1 >= -mmax) e.k_next += g[mmax + m] * g[mmax + m - 1];
  }
  const double w1 = kernel.d1(dx, h) * dx, w2 = kernel.d2(dx, h) * dx;
  e.l_next = mmax >= 1 ? -w2 : 0.0;
  e.first_minor = root(e.k_ii, e.l_ii, n);
  e.second_minor = second_minor_tension(e.k_ii, e.l_ii, e.k_next, e.l_next, n);
  const bool nn = mmax >= 1;
  e.nearest_neighbour = nn ? root(w1 * w1, w2, n) : kInf;
  e.nearest_neighbour_minor = nn ? root(2.0 / 3.0 * w1 * w1, w2, n) : kInf;
  e.swegle = (n > 0 && nn && w2 > 0) ? 0.0 : kInf;
  return e;
}

TensionEstimates1D tension_estimates_1d(const Linearisation& jac, int row, int n) {
  if (row < 0 || row + 1 >= jac.dofs())
    throw std::invalid_argument("tension_estimates_1d: row " + std::to_string(row) + " needs row + 1 < " +
                                std::to_string(jac.dofs()));
  if (n < 0) throw std::invalid_argument("tension_estimates_1d: n must be >= 0 (got " + std::to_string(n) + ")");
  TensionEstimates1D e;
  e.k_ii = jac.A0.coeff(row, row);
  e.l_ii = -jac.A1.coeff(row, row);
  e.k_next = jac.A0.coeff(row, row + 1);
  e.l_next = -jac.A1.coeff(row, row + 1);
  e.first_minor = root(e.k_ii, e.l_ii, n);
  e.second_minor = second_minor_tension(e.k_ii, e.l_ii, e.k_next, e.l_next, n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  e.nearest_neighbour = e.nearest_neighbour_minor = e.swegle = nan;
  return e;
}

}  // namespace sphstab
