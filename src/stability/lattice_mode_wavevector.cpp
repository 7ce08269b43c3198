#include "sphstab/stability/lattice_mode_wavevector.hpp"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace sphstab {

namespace {
Eigen::MatrixXd sine_basis(int n) {
  Eigen::MatrixXd phi(n, n);  // phi(i, m - 1) = sqrt(2/(n+1)) sin(m pi (i+1)/(n+1)), orthonormal
  const double s = std::sqrt(2.0 / (n + 1));
  for (int i = 0; i < n; ++i)
    for (int m = 1; m <= n; ++m) phi(i, m - 1) = s * std::sin(m * std::numbers::pi * (i + 1) / (n + 1));
  return phi;
}
}  // namespace

LatticeModeEstimate dominant_wavevector_2d(const Eigen::VectorXd& field, const Eigen::MatrixX2d& x, double spacing) {
  const char* who = "dominant_wavevector_2d";
  const Eigen::Index n = x.rows();
  if (n == 0 || field.size() != 2 * n)
    throw std::invalid_argument(std::string(who) + ": field needs 2 values per position (got " +
                                std::to_string(field.size()) + " for " + std::to_string(n) + " positions)");
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw std::invalid_argument(std::string(who) + ": spacing must be finite and > 0 (got " + std::to_string(spacing) +
                                ")");
  const Eigen::RowVector2d lo = x.colwise().minCoeff();
  Eigen::MatrixXi idx(n, 2);
  for (Eigen::Index p = 0; p < n; ++p)
    for (int a = 0; a < 2; ++a) {
      const double s = (x(p, a) - lo[a]) / spacing;
      idx(p, a) = static_cast<int>(std::lround(s));
      if (std::abs(s - idx(p, a)) > 1e-6)
        throw std::invalid_argument(std::string(who) + ": position " + std::to_string(p) + " is not on the lattice");
    }
  LatticeModeEstimate out;
  out.nx = idx.col(0).maxCoeff() + 1;
  out.ny = idx.col(1).maxCoeff() + 1;
  if (static_cast<Eigen::Index>(out.nx) * out.ny != n)
    throw std::invalid_argument(std::string(who) + ": positions do not fill a " + std::to_string(out.nx) + " x " +
                                std::to_string(out.ny) + " grid");
  Eigen::MatrixXi seen = Eigen::MatrixXi::Zero(out.nx, out.ny);
  std::array<Eigen::MatrixXd, 2> grid{Eigen::MatrixXd::Zero(out.nx, out.ny), Eigen::MatrixXd::Zero(out.nx, out.ny)};
  for (Eigen::Index p = 0; p < n; ++p) {
    if (seen(idx(p, 0), idx(p, 1))++)
      throw std::invalid_argument(std::string(who) + ": two positions on one grid point");
    for (int c = 0; c < 2; ++c) grid[c](idx(p, 0), idx(p, 1)) = field[2 * p + c];
  }
  const Eigen::MatrixXd px = sine_basis(out.nx), py = sine_basis(out.ny);
  double total = 0, best = -1;
  for (int c = 0; c < 2; ++c) {
    const Eigen::MatrixXd coef = px.transpose() * grid[c] * py;
    total += coef.squaredNorm();
    for (int m = 0; m < out.nx; ++m)
      for (int l = 0; l < out.ny; ++l)
        if (coef(m, l) * coef(m, l) > best) {
          best = coef(m, l) * coef(m, l);
          out.mx = m + 1;
          out.my = l + 1;
          out.component = c;
        }
  }
  if (total > 0) {
    out.fraction = best / total;
    out.kx = static_cast<double>(out.mx) / (out.nx + 1);
    out.ky = static_cast<double>(out.my) / (out.ny + 1);
  } else {
    out.mx = out.my = 0;
    out.component = -1;
  }
  return out;
}

}  // namespace sphstab
