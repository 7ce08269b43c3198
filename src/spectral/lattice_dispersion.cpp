// Derivation notes (GMS §5, re-derived; tension positive, r_ab = r_a - r_b, all particles equal):
//  * XSPH: vhat_a = v_a + 1/2 sum_b (m_b/rho_ab)(v_b - v_a) W_ab -> Vhat = (1 - beta) V, and dX/dt = Vhat.
//  * Position perturbation of grad W in the base-stress term 2 sigma/rho^2: sum_b (1 - cos k.r_ab) W_,ij X_j,
//    giving rho omega^2 V/(1-beta) = -2 sigma (B V) = 2 (P - S)(B V) (B = Hessian sum).
//  * Stress and density perturbations at b: sum_b exp(-i k.r_ab) grad W_ab = -i A / V_cell, so
//    a = -i rho A . delta(sigma / rho^2), delta(sigma/rho^2) = (delta sigma)/rho^2 - 2 sigma D / rho^3.
//  * Continuity (3.8): D = -rho (Vhat . A)/omega; velocity gradient (3.10): dvhat^j/dx^i = -i A_i Vhat^j; the
//    Jaumann rate (2.3) then gives T as in GMS (5.7). Together: the A-terms of (5.8)/(5.9), in particular
//    -(2(P - S^xx) - rho c0^2) A_x (A.V), i.e. the coefficient 2(P - S) also in the face-centred (5.25).
//  * Artificial stress (R frozen): m sum_b 2R f^n grad W = 2R / ((n+1) W(dp)^n) m sum_b grad(W^{n+1}); its
//    position perturbation is 2 rho R (f X), i.e. -2 rho^2 R (f V) in the frequency equation (5.13)-(5.16).
//  * Perturbed R (optional): m sum_b (dR_a + dR_b exp(-i k.r_ab)) f^n grad W = -i rho A^f . dR, so
//    rho omega^2 V = rho^2 A^f_j (omega dR^{ij}) with omega dR linear in omega dsigma = omega(-c0^2 D + T) and
//    omega D = -rho (Vhat . A); Vhat -> V after dividing by (1 - beta).
#include "sphstab/spectral/lattice_dispersion.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/models/artificial_stress.hpp"

namespace sphstab {

namespace {

void check_positive(const char* who, const char* what, double v) {
  if (!(v > 0) || !std::isfinite(v))
    throw std::invalid_argument(std::string(who) + ": " + what + " must be finite and > 0 (got " + format_number(v) +
                                ")");
}

void check_state(const char* who, const UniformState& s) {
  check_positive(who, "density", s.density);
  if (!(s.shear_modulus >= 0) || !(s.sound_speed >= 0))
    throw std::invalid_argument(std::string(who) + ": shear modulus and sound speed must be >= 0 (got " +
                                std::to_string(s.shear_modulus) + ", " + std::to_string(s.sound_speed) + ")");
  for (double v : {s.shear_modulus, s.sound_speed, s.pressure, s.sxx, s.syy, s.rxx, s.ryy})
    if (!std::isfinite(v)) throw std::invalid_argument(std::string(who) + ": the state has a non-finite entry");
}

DispersionRelation solve(const LatticeSums& sums, const UniformState& state, const Eigen::Vector2d& k,
                         bool perturbed_r = false) {
  DispersionRelation d;
  d.sums = sums;
  d.M = dispersion_matrix(sums, state, perturbed_r);
  Eigen::EigenSolver<Eigen::Matrix2d> es(d.M);
  Eigen::Vector2cd lambda = es.eigenvalues();
  Eigen::Matrix2cd vec = es.eigenvectors();
  for (int m = 0; m < 2; ++m) vec.col(m).normalize();
  // Quasi-longitudinal first: the eigenvector with the larger |V . khat| (the x mode for k = 0).
  const Eigen::Vector2d khat = k.norm() > 0 ? Eigen::Vector2d(k / k.norm()) : Eigen::Vector2d(1, 0);
  const double p0 = std::abs(vec.col(0).dot(khat.cast<std::complex<double>>()));
  const double p1 = std::abs(vec.col(1).dot(khat.cast<std::complex<double>>()));
  const int first = p1 > p0 ? 1 : 0;
  const double scale = (1 - sums.beta) / state.density;
  for (int m = 0; m < 2; ++m) {
    const int src = m == 0 ? first : 1 - first;
    d.omega2[m] = scale * lambda[src];
    d.modes.col(m) = vec.col(src);
  }
  return d;
}

}  // namespace

UniformState with_artificial_stress(UniformState state, double epsilon) {
  check_state("with_artificial_stress", state);
  const auto r =
      artificial_stress(SymmetricTensor2<double>{state.sigma_xx(), state.sigma_yy(), 0.0}, state.density, epsilon);
  state.rxx = r.xx;
  state.ryy = r.yy;
  state.epsilon = epsilon;
  return state;
}

LatticeSums lattice_sums(LatticeType type, const Kernel<2>& kernel, double h, const Eigen::Vector2d& k,
                         const LatticeSumOptions& opt) {
  const char* who = "lattice_sums";
  check_positive(who, "smoothing length h", h);
  check_positive(who, "spacing dp", opt.spacing);
  if (!(opt.exponent >= 0) || !std::isfinite(opt.exponent))
    throw std::invalid_argument(std::string(who) + ": exponent n must be finite and >= 0 (got " +
                                std::to_string(opt.exponent) + ")");
  if (!k.allFinite()) throw std::invalid_argument(std::string(who) + ": wavevector k must be finite");
  if (!(opt.max_distance > 0)) throw std::invalid_argument(std::string(who) + ": max_distance must be > 0");
  const double dp = opt.spacing;
  double dy = dp, shift = 0;  // row spacing, shift of odd rows
  switch (type) {
    case LatticeType::Square:
      break;
    case LatticeType::FaceCentred:
      shift = 0.5 * dp;
      break;
    case LatticeType::Hexagonal:
      shift = 0.5 * dp;
      dy = dp * std::sqrt(3.0) / 2;
      break;
    default:
      throw std::invalid_argument(std::string(who) + ": lattice '" + lattice_name(type) +
                                  "' is not supported (square, face-centred, hex)");
  }
  const double w_dp = artificial_stress_reference_kernel(kernel, h, dp);
  const double n = opt.exponent;
  const double support = kernel.support_radius(h);
  LatticeSums s;
  s.cell_volume = dp * dy;
  const double V = s.cell_volume;
  // Checked before the cast: a huge h / dp would overflow the int and the (2 reach)^2 loop would never end.
  const int jmax = static_cast<int>(checked_floor_count(std::ceil(support / dy), kMaxLatticeReach,
                                                        std::string(who) + ": lattice rows in the support")) +
                   1;
  const int imax = static_cast<int>(checked_floor_count(std::ceil(support / dp), kMaxLatticeReach,
                                                        std::string(who) + ": lattice columns in the support")) +
                   2;
  for (int j = -jmax; j <= jmax; ++j) {
    const double y = j * dy, x0 = (j & 1) ? shift : 0.0;
    for (int i = -imax; i <= imax; ++i) {
      const double x = x0 + i * dp;
      const double r = std::hypot(x, y);
      if (r == 0 || r >= support || r > opt.max_distance * (1 + 1e-12)) continue;
      const double w = kernel.value(r, h);
      if (!(w > 0)) continue;
      const double w1 = kernel.d1(r, h), w2 = kernel.d2(r, h);
      const double ex = x / r, ey = y / r;
      const double phase = k[0] * x + k[1] * y;
      const double half_sin = std::sin(0.5 * phase);
      const double omc = 2 * half_sin * half_sin;  // 1 - cos(k.r), accurate for long waves
      const double sn = std::sin(phase);
      // Hessian of a radial function F: F'' e e^T + F'/r (I - e e^T).
      auto hessian = [&](double f1, double f2, double& hxx, double& hyy, double& hxy) {
        hxx = f2 * ex * ex + f1 / r * (1 - ex * ex);
        hyy = f2 * ey * ey + f1 / r * (1 - ey * ey);
        hxy = (f2 - f1 / r) * ex * ey;
      };
      double hxx, hyy, hxy;
      hessian(w1, w2, hxx, hyy, hxy);
      s.A[0] += V * sn * w1 * ex;
      s.A[1] += V * sn * w1 * ey;
      s.Bx += V * omc * hxx;
      s.By += V * omc * hyy;
      s.C += V * omc * hxy;
      s.beta += 0.5 * V * omc * w;
      // Z d^2(W^{n+1}) with g = W/W(dp): (W^{n+1})' = (n+1) W^n W', (W^{n+1})'' = (n+1)(n W^{n-1} W'^2 + W^n W'').
      const double g = w / w_dp;
      const double gn = artificial_stress_power(g, n);
      const double f1 = gn * w1;
      const double gnm1 = n >= 1 ? artificial_stress_power(g, n - 1) : std::pow(g, n - 1);  // g > 0 here
      const double f2 = (n > 0 ? n * gnm1 * w1 * w1 / w_dp : 0.0) + gn * w2;
      s.Af[0] += V * sn * f1 * ex;  // f^n W' e = g^n W' e
      s.Af[1] += V * sn * f1 * ey;
      double fxx, fyy, fxy;
      hessian(f1, f2, fxx, fyy, fxy);
      s.fxx += V * omc * fxx;
      s.fyy += V * omc * fyy;
      s.fxy += V * omc * fxy;
      ++s.neighbours;
    }
  }
  return s;
}

Eigen::Matrix2d dispersion_matrix(const LatticeSums& s, const UniformState& st, bool perturbed_r) {
  check_state("dispersion_matrix", st);
  const double K0 = st.density * st.sound_speed * st.sound_speed;
  const double Kx = 2 * (st.pressure - st.sxx), Ky = 2 * (st.pressure - st.syy);
  const double mu = st.shear_modulus, zeta = 0.5 * (st.sxx - st.syy);
  const double ax = s.A[0], ay = s.A[1], rho2 = st.density * st.density;
  Eigen::Matrix2d M;
  // GMS (5.8) + (5.13)
  M(0, 0) =
      -(Kx - K0) * ax * ax + Kx * s.Bx + (4 * mu / 3) * ax * ax + (mu - zeta) * ay * ay - 2 * rho2 * st.rxx * s.fxx;
  M(0, 1) =
      -(Kx - K0) * ax * ay + Kx * s.C - (2 * mu / 3) * ay * ax + (mu + zeta) * ax * ay - 2 * rho2 * st.rxx * s.fxy;
  // GMS (5.9) + (5.17)
  M(1, 1) =
      -(Ky - K0) * ay * ay + Ky * s.By + (4 * mu / 3) * ay * ay + (mu + zeta) * ax * ax - 2 * rho2 * st.ryy * s.fyy;
  M(1, 0) =
      -(Ky - K0) * ay * ax + Ky * s.C - (2 * mu / 3) * ax * ay + (mu - zeta) * ay * ax - 2 * rho2 * st.ryy * s.fxy;
  if (perturbed_r) {
    // omega * (d sigma_xx, d sigma_yy, d sigma_xy, d rho) as rows acting on V (GMS 5.7, continuity 3.8).
    Eigen::Matrix<double, 4, 2> dq;
    const Eigen::RowVector2d a_dot(ax, ay);
    dq.row(3) = -st.density * a_dot;
    dq.row(0) = K0 * a_dot + (2 * mu / 3) * Eigen::RowVector2d(2 * ax, -ay);
    dq.row(1) = K0 * a_dot + (2 * mu / 3) * Eigen::RowVector2d(-ax, 2 * ay);
    dq.row(2) = mu * Eigen::RowVector2d(ay, ax) - zeta * Eigen::RowVector2d(ay, -ax);
    // dR/d(sxx, syy, sxy, rho) at the uniform state by complex step through artificial_stress().
    using C = std::complex<double>;
    const double step = 1e-30;
    Eigen::Matrix<double, 3, 4> J;
    for (int c = 0; c < 4; ++c) {
      SymmetricTensor2<C> sig{st.sigma_xx(), st.sigma_yy(), 0.0};
      C rho = st.density;
      C* slot[4] = {&sig.xx, &sig.yy, &sig.xy, &rho};
      *slot[c] += C(0, step);
      const auto r = artificial_stress(sig, rho, st.epsilon);
      J(0, c) = r.xx.imag() / step;
      J(1, c) = r.yy.imag() / step;
      J(2, c) = r.xy.imag() / step;
    }
    const Eigen::Matrix<double, 3, 2> dR = J * dq;  // omega (dR^xx, dR^yy, dR^xy) acting on V
    const double fx = s.Af[0], fy = s.Af[1];
    M.row(0) += rho2 * (fx * dR.row(0) + fy * dR.row(2));
    M.row(1) += rho2 * (fx * dR.row(2) + fy * dR.row(1));
  }
  return M;
}

DispersionRelation lattice_dispersion(LatticeType type, const Kernel<2>& kernel, double h, const Eigen::Vector2d& k,
                                      const UniformState& state, const LatticeSumOptions& options) {
  check_state("lattice_dispersion", state);
  return solve(lattice_sums(type, kernel, h, k, options), state, k, options.perturbed_artificial_stress);
}

DispersionRelation continuum_dispersion(const Eigen::Vector2d& k, const UniformState& state) {
  check_state("continuum_dispersion", state);
  if (!k.allFinite()) throw std::invalid_argument("continuum_dispersion: wavevector k must be finite");
  LatticeSums s;  // GMS (5.10) with W~ = 1
  s.A = -k;
  s.Bx = k[0] * k[0];
  s.By = k[1] * k[1];
  s.C = k[0] * k[1];
  UniformState no_r = state;
  no_r.rxx = no_r.ryy = 0;
  return solve(s, no_r, k);
}

}  // namespace sphstab
