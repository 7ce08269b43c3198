#include "sphstab/growth/growth_rate.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sphstab/growth/system_spectrum.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"

namespace sphstab {

GrowthAnalysis growth_rate(const Eigen::MatrixXd& a, const Eigen::VectorXd& x, bool periodic, double tolerance) {
  if (a.rows() != a.cols() || a.rows() == 0)
    throw std::invalid_argument("growth_rate: matrix must be square and non-empty (got " + std::to_string(a.rows()) +
                                " x " + std::to_string(a.cols()) + ")");
  if (x.size() != a.rows())
    throw std::invalid_argument("growth_rate: " + std::to_string(x.size()) + " positions for a " +
                                std::to_string(a.rows()) + " x " + std::to_string(a.rows()) + " matrix");
  GrowthAnalysis out;
  out.tolerance = tolerance >= 0 ? tolerance : 1e-6 * std::sqrt(a.norm());
  DenseGeneralEigen eig = general_eigen(a, true);
  out.status = eig.status;
  if (eig.status != Status::Successful) return out;
  out.eigenvalues = eig.values;
  const int n = static_cast<int>(a.rows());
  for (int k = 0; k < n; ++k) {
    const std::complex<double> mu = eig.values[k];
    const double g = mode_growth(mu);
    out.growth_rate = std::max(out.growth_rate, g);
    if (mu.imag() < 0) continue;  // the conjugate partner (positive imaginary part) represents the pair
    if (!(g > out.tolerance)) continue;
    UnstableMode m;
    m.mu = mu;
    m.growth = g;
    m.shape = real_mode_shape(eig.vectors.col(k));
    m.wavenumber = dominant_wavenumber(m.shape, x, periodic);
    out.unstable.push_back(std::move(m));
  }
  std::sort(out.unstable.begin(), out.unstable.end(),
            [](const UnstableMode& p, const UnstableMode& q) { return p.growth > q.growth; });
  return out;
}

}  // namespace sphstab
