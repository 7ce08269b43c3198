#pragma once
// The periodic-lattice tools of the tl-hourglass study: the hourglass patterns (translations and the alternating
// patterns at wavevectors with components in {0, pi}: the sawtooth in 1D), the symbol of the form's own strain
// operator along x (the kernel gradient's symbol g(k) vanishes at k = pi/dx [Powell2012, (3.40)], so the sawtooth has
// zero strain) and the Bloch symbol of A = -da/du at a wavevector, read from the Jacobian's block rows.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <complex>
#include <string>
#include <utility>
#include <vector>

#include "sphstab/forms/finite_strain_total_lagrangian.hpp"

namespace hourglass {

using namespace sphstab;

/// The periodic hourglass patterns: translations and, per wavevector with components in {0, pi} (not all 0), each
/// displacement component. 1D: translation + sawtooth; 2D: 2 translations + 3 wavevectors x 2 components.
template <int Dim>
std::vector<std::pair<std::string, Eigen::VectorXd>> patterns(const std::vector<std::array<int, Dim>>& g) {
  std::vector<std::pair<std::string, Eigen::VectorXd>> out;
  const int nk = 1 << Dim;
  for (int kbits = 0; kbits < nk; ++kbits)
    for (int c = 0; c < Dim; ++c) {
      Eigen::VectorXd p = Eigen::VectorXd::Zero(Dim * static_cast<long>(g.size()));
      for (std::size_t f = 0; f < g.size(); ++f) {
        int parity = 0;
        for (int a = 0; a < Dim; ++a)
          if (kbits >> a & 1) parity += g[f][a];
        p[Dim * f + c] = parity % 2 ? -1.0 : 1.0;
      }
      std::string name = kbits == 0 ? "translation" : (Dim == 1 ? "sawtooth" : "k=(");
      if (Dim == 2 && kbits) name += std::string(kbits & 1 ? "pi," : "0,") + (kbits & 2 ? "pi)" : "0)");
      if (Dim == 2) name += c == 0 ? " u_x" : " u_y";
      out.push_back({name, p / p.norm()});
    }
  return out;
}

/// Symbol of the form's own strain operator along x at free particle f of a periodic lattice, wavevector k e_x:
/// S(k) = sum_j K^x_ij (e^{i k X_ij} - 1) (difference; sum_j K^x_ij e^{i k X_ij} for the direct sum), read from
/// F_i^{xx} - 1 of the real fields u_x = cos(k (X - X_i)) and sin(k (X - X_i)) (k a multiple of 2 pi / (n dx)).
template <int Dim>
double strain_symbol(const FiniteStrainTotalLagrangian<Dim>& tl, int f, double k) {
  const Discretisation<Dim>& d = tl.discretisation();
  const double xi = d.particles.x(d.free[f], 0);
  Eigen::VectorXd uc = Eigen::VectorXd::Zero(tl.dofs()), us = uc;
  for (int g = 0; g < d.free_count(); ++g) {
    uc[Dim * g] = std::cos(k * (d.particles.x(d.free[g], 0) - xi));
    us[Dim * g] = std::sin(k * (d.particles.x(d.free[g], 0) - xi));
  }
  const double re = tl.deformation_gradients(uc)(d.free[f], 0) - 1;
  const double im = tl.deformation_gradients(us)(d.free[f], 0) - 1;
  return std::hypot(re, im);
}

/// The Bloch symbol of A (Dim x Dim) at wavevector k from the Jacobian block rows of free particle f (periodic).
template <int Dim>
Eigen::Matrix<std::complex<double>, Dim, Dim> bloch_symbol(const Eigen::MatrixXd& A, const Discretisation<Dim>& d,
                                                           int f, const Eigen::Matrix<double, Dim, 1>& k) {
  Eigen::Matrix<std::complex<double>, Dim, Dim> S = Eigen::Matrix<std::complex<double>, Dim, Dim>::Zero();
  const int i = d.free[f];
  for (int g = 0; g < d.free_count(); ++g) {
    const Eigen::Matrix<double, Dim, 1> X = -d.particles.separation(i, d.free[g]).transpose();
    const std::complex<double> e = std::exp(std::complex<double>(0, k.dot(X)));
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) S(a, b) += A(Dim * f + a, Dim * g + b) * e;
  }
  return S;
}

}  // namespace hourglass
