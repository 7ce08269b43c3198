#include "sphstab/forms/hourglass_control.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"

namespace sphstab {

template <int Dim>
HourglassControl<Dim>::HourglassControl(const Discretisation<Dim>& d, double young, const Eigen::VectorXd& rho,
                                        HourglassOptions options, const char* who)
    : m_options(options) {
  const double chg = m_options.coefficient;
  if (!(chg >= 0) || !std::isfinite(chg))
    throw std::invalid_argument(std::string(who) + ": hourglass coefficient must be finite and >= 0 (got " +
                                format_number(chg) + "; 0 switches the term off)");
  if (chg == 0) return;
  m_offsets.assign(1, 0);
  for (int i : d.free) {
    for (long k = d.neighbours.offsets[i]; k < d.neighbours.offsets[i + 1]; ++k) {
      const int j = d.neighbours.indices[k];
      if (j == i) continue;
      const Eigen::Matrix<double, Dim, 1> Xij = -d.particles.separation(i, j).transpose();  // X_j - X_i
      const double r = Xij.norm();
      if (!(r > 0)) continue;  // coincident reference points carry no bond direction
      const double w = d.kernel.value(r, d.h);
      if (w == 0) continue;
      m_j.push_back(j);
      m_c.push_back(chg * young * d.particles.volume[j] * w / (r * r) / rho[i]);  // V_i cancels with m_i
      m_X.push_back(Xij);
    }
    m_offsets.push_back(static_cast<int>(m_j.size()));
  }
}

template <int Dim>
template <class Scalar>
void HourglassControl<Dim>::add(const Discretisation<Dim>& d, const Positions<Dim, Scalar>& uall,
                                const std::vector<Deformation<Scalar, Dim>>& F,
                                Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  using Vec = Eigen::Matrix<Scalar, Dim, 1>;
  const bool full = m_options.projection == HourglassProjection::Full;
  for (int f = 0; f < d.free_count(); ++f) {
    const int i = d.free[f];
    Vec ai = Vec::Zero();
    for (int k = m_offsets[f]; k < m_offsets[f + 1]; ++k) {
      const int j = m_j[k];
      const Vec X = m_X[k].template cast<Scalar>();
      const Vec x = X + (uall.row(j) - uall.row(i)).transpose();          // x_ij, current
      const Scalar r = std::sqrt(Scalar((x.array() * x.array()).sum()));  // analytic (no conjugate): complex step
      const Vec eps = Scalar(0.5) * ((F[i] + F[j]) * X) - x;              // (eps^i_ij - eps^j_ji) / 2
      if (full) {
        ai -= m_c[k] * eps;  // the whole mean error (HourglassProjection::Full)
        continue;
      }
      const Scalar delta = (eps.array() * x.array()).sum() / r;  // along the bond
      ai -= (m_c[k] * delta / r) * x;  // [Ganzenmueller2015]: -c E V_i V_j W_ij / |X_ij|^2 delta_ij x^_ij / m_i
    }
    for (int c = 0; c < Dim; ++c) a[f * Dim + c] += ai[c];
  }
}

template class HourglassControl<1>;
template class HourglassControl<2>;
template void HourglassControl<1>::add<double>(const Discretisation<1>&, const Positions<1, double>&,
                                               const std::vector<Deformation<double, 1>>&, Eigen::VectorXd&) const;
template void HourglassControl<2>::add<double>(const Discretisation<2>&, const Positions<2, double>&,
                                               const std::vector<Deformation<double, 2>>&, Eigen::VectorXd&) const;
template void HourglassControl<1>::add<std::complex<double>>(const Discretisation<1>&,
                                                             const Positions<1, std::complex<double>>&,
                                                             const std::vector<Deformation<std::complex<double>, 1>>&,
                                                             Eigen::VectorXcd&) const;
template void HourglassControl<2>::add<std::complex<double>>(const Discretisation<2>&,
                                                             const Positions<2, std::complex<double>>&,
                                                             const std::vector<Deformation<std::complex<double>, 2>>&,
                                                             Eigen::VectorXcd&) const;

}  // namespace sphstab
