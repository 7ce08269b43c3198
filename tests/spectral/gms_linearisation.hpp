#pragma once
// Test-only reference: the GMS (2001) SPH equations on a periodic 2D lattice, written out particle by particle,
// and their Bloch-reduced Jacobian by complex-step differentiation. An independent route to the dispersion
// relation (5.8)/(5.9): nothing here uses the lattice sums.
//
// State per particle (8 values): x, y, vx, vy, rho, Sxx, Syy, Sxy. Equations (no artificial viscosity):
//   vhat_a = v_a + 1/2 sum_b (m_b / rhobar_ab)(v_b - v_a) W_ab                      (3.6), dx_a/dt = vhat_a
//   dv_a/dt = sum_b m_b (sigma_a/rho_a^2 + sigma_b/rho_b^2) grad_a W_ab + artificial stress   (3.1 + 3.12)
//   drho_a/dt = sum_b m_b (vhat_a - vhat_b) . grad_a W_ab                            (3.8)
//   (dvhat^j/dx^i)_a = -sum_b (m_b/rho_b)(vhat_a^j - vhat_b^j) dW_ab/dx_a^i             (3.10)
//   dS/dt = 2 mu (epsdot - 1/3 tr epsdot I) + S^ik Omega^jk + Omega^ik S^kj             (2.3)
//   sigma = -P I + S, P = P0 + c0^2 (rho - rho0)                                      (2.7), offset P0
#include <Eigen/Eigenvalues>
#include <complex>
#include <vector>

#include "sphstab/models/artificial_stress.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/lattice_dispersion.hpp"

namespace sphstab::test {

using Complex = std::complex<double>;

struct GmsLattice {
  ParticleSet<2> set;
  NeighbourList nl;
  Kernel<2> kernel{KernelType::CubicSpline};
  double h = 1;
  UniformState state;
  double epsilon = 0;   ///< artificial stress coefficient (live R only)
  double exponent = 4;  ///< n
  bool live_r = false;  ///< false: R frozen at the uniform state's (rxx, ryy) as in GMS (5.13); true: R(sigma)
  double w_dp = 1;
};

inline GmsLattice make_gms_lattice(LatticeType type, int n, double h, const UniformState& state, double epsilon,
                                   bool live_r, double exponent = 4) {
  GmsLattice g;
  g.h = h;
  g.state = state;
  g.epsilon = epsilon;
  g.exponent = exponent;
  g.live_r = live_r;
  g.set = make_lattice<2>(type, n, {.spacing = 1.0, .periodic = true});
  g.nl = find_neighbours(g.set, g.kernel.support_radius(h));
  g.w_dp = artificial_stress_reference_kernel(g.kernel, h, 1.0);
  return g;
}

/// The right-hand side d(state)/dt; state is N x 8 (x, y, vx, vy, rho, Sxx, Syy, Sxy).
inline Eigen::Matrix<Complex, Eigen::Dynamic, 8> gms_rhs(const GmsLattice& g,
                                                         const Eigen::Matrix<Complex, Eigen::Dynamic, 8>& u) {
  const int N = g.set.size();
  const auto& st = g.state;
  Positions<2, Complex> x = u.leftCols<2>();
  auto ops = assemble_operators<2, Complex>(g.set, g.nl, g.kernel, g.h, {.kernel = true, .gradient = true}, &x);
  const Eigen::VectorXd& V = g.set.volume;
  const Eigen::VectorXd mass = st.density * V;  // m_b = rho0 V_b, constant
  Eigen::Matrix<Complex, Eigen::Dynamic, 8> du = Eigen::Matrix<Complex, Eigen::Dynamic, 8>::Zero(N, 8);
  Eigen::Matrix<Complex, Eigen::Dynamic, 2> vhat = u.middleCols<2>(2);
  auto for_pairs = [&](int i, auto&& f) {
    for (SparseMatrix<Complex>::InnerIterator it(ops.W, i); it; ++it) {
      const int j = static_cast<int>(it.col());
      if (j == i) continue;
      const Complex w = it.value() / V[j];
      const Complex gx = ops.G[0].coeff(i, j) / V[j], gy = ops.G[1].coeff(i, j) / V[j];
      f(j, w, gx, gy);
    }
  };
  for (int a = 0; a < N; ++a)
    for_pairs(a, [&](int b, Complex w, Complex, Complex) {
      const Complex rho_ab = 0.5 * (u(a, 4) + u(b, 4));
      for (int d = 0; d < 2; ++d) vhat(a, d) += 0.5 * mass[b] / rho_ab * (u(b, 2 + d) - u(a, 2 + d)) * w;
    });
  // sigma and R per particle
  TensorField2<Complex> sigma(N, 3);
  for (int a = 0; a < N; ++a) {
    const Complex P = st.pressure + st.sound_speed * st.sound_speed * (u(a, 4) - st.density);
    sigma(a, 0) = -P + u(a, 5);
    sigma(a, 1) = -P + u(a, 6);
    sigma(a, 2) = u(a, 7);
  }
  TensorField2<Complex> R = TensorField2<Complex>::Zero(N, 3);
  if (g.live_r) {
    R = artificial_stress<Complex>(sigma, u.col(4), g.epsilon);
  } else {
    R.col(0).setConstant(st.rxx);
    R.col(1).setConstant(st.ryy);
  }
  Eigen::Matrix<Complex, Eigen::Dynamic, 2> acc =
      artificial_stress_acceleration<Complex>(ops, mass, V, R, g.w_dp, g.exponent);
  for (int a = 0; a < N; ++a) {
    Eigen::Matrix<Complex, 2, 2> L = Eigen::Matrix<Complex, 2, 2>::Zero();  // L(i, j) = d vhat^j / d x^i
    Complex drho = 0;
    for_pairs(a, [&](int b, Complex, Complex gx, Complex gy) {
      const Complex g2[2] = {gx, gy};
      const Complex ra2 = u(a, 4) * u(a, 4), rb2 = u(b, 4) * u(b, 4);
      for (int i = 0; i < 2; ++i) {
        const int c = i == 0 ? 0 : 1;  // sigma column of (i, i)
        acc(a, i) += mass[b] * ((sigma(a, c) / ra2 + sigma(b, c) / rb2) * g2[i] +
                                (sigma(a, 2) / ra2 + sigma(b, 2) / rb2) * g2[1 - i]);
      }
      for (int d = 0; d < 2; ++d) drho += mass[b] * (vhat(a, d) - vhat(b, d)) * g2[d];
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) L(i, j) -= mass[b] / u(b, 4) * (vhat(a, j) - vhat(b, j)) * g2[i];
    });
    // dv^i/dx^j = L(j, i)
    Eigen::Matrix<Complex, 2, 2> grad = L.transpose();
    Eigen::Matrix<Complex, 2, 2> eps = 0.5 * (grad + grad.transpose());
    Eigen::Matrix<Complex, 2, 2> omega = 0.5 * (grad - grad.transpose());
    Eigen::Matrix<Complex, 2, 2> S;
    S << u(a, 5), u(a, 7), u(a, 7), u(a, 6);
    const Complex tr = eps.trace();
    Eigen::Matrix<Complex, 2, 2> dS =
        2 * st.shear_modulus * (eps - tr / 3.0 * Eigen::Matrix<Complex, 2, 2>::Identity()) + S * omega.transpose() +
        omega * S;  // S^ik Omega^jk + Omega^ik S^kj
    du(a, 0) = vhat(a, 0);
    du(a, 1) = vhat(a, 1);
    du(a, 2) = acc(a, 0);
    du(a, 3) = acc(a, 1);
    du(a, 4) = drho;
    du(a, 5) = dS(0, 0);
    du(a, 6) = dS(1, 1);
    du(a, 7) = dS(0, 1);
  }
  return du;
}

/// The uniform base state (lattice positions, v = 0, rho, S).
inline Eigen::Matrix<Complex, Eigen::Dynamic, 8> gms_base_state(const GmsLattice& g) {
  const int N = g.set.size();
  Eigen::Matrix<Complex, Eigen::Dynamic, 8> u = Eigen::Matrix<Complex, Eigen::Dynamic, 8>::Zero(N, 8);
  u.leftCols<2>() = g.set.x.cast<Complex>();
  u.col(4).setConstant(g.state.density);
  u.col(5).setConstant(g.state.sxx);
  u.col(6).setConstant(g.state.syy);
  return u;
}

/// Bloch-reduced Jacobian J(k) (8 x 8): J applied to U exp(i k.x_b), read at particle `a`, divided by
/// exp(i k.x_a). Each column from two real complex-step directions (cos and sin patterns).
inline Eigen::Matrix<Complex, 8, 8> gms_bloch_jacobian(const GmsLattice& g, const Eigen::Vector2d& k, int a = 0) {
  const double step = 1e-30;
  const int N = g.set.size();
  const auto base = gms_base_state(g);
  Eigen::Matrix<Complex, 8, 8> J;
  for (int q = 0; q < 8; ++q) {
    Complex column[8] = {};
    for (int part = 0; part < 2; ++part) {
      auto u = base;
      for (int b = 0; b < N; ++b) {
        const double ph = k.dot(g.set.x.row(b).transpose());
        u(b, q) += Complex(0, step * (part == 0 ? std::cos(ph) : std::sin(ph)));
      }
      const auto du = gms_rhs(g, u);
      for (int p = 0; p < 8; ++p) column[p] += (part == 0 ? Complex(1) : Complex(0, 1)) * du(a, p).imag() / step;
    }
    const Complex back = std::exp(Complex(0, -k.dot(g.set.x.row(a).transpose())));
    for (int p = 0; p < 8; ++p) J(p, q) = column[p] * back;
  }
  return J;
}

/// omega^2 = -lambda^2 for the eigenvalues lambda of J(k), sorted by |lambda| descending (the four non-zero
/// ones are the two wave pairs).
inline std::vector<Complex> gms_bloch_omega2(const GmsLattice& g, const Eigen::Vector2d& k) {
  Eigen::ComplexEigenSolver<Eigen::Matrix<Complex, 8, 8>> es(gms_bloch_jacobian(g, k));
  std::vector<Complex> lambda(es.eigenvalues().data(), es.eigenvalues().data() + 8);
  std::sort(lambda.begin(), lambda.end(), [](Complex p, Complex q) { return std::abs(p) > std::abs(q); });
  std::vector<Complex> w2;
  for (auto l : lambda) w2.push_back(-l * l);
  return w2;
}

}  // namespace sphstab::test
