#pragma once
/// \file corrected_rows.hpp
/// Internal to src/forms: the row loop of the rate form for the corrected gradient (NCSPH, Powell (1.19)) and the local
/// means of C_ij (Powell (4.10)) and S-SPH (Powell algorithm 4.2), on real and complex states. These read per-pair
/// arrays in later passes: grad W (always), r (NCSPH or viscosity), r^2 (viscosity), W (NCSPH, XSPH, artificial stress
/// or the first-step Shepard means), the corrected gradient Ghat_ij (V_j included).
#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "dispatch.hpp"
#include "evaluation.hpp"
#include "pair_viscosity.hpp"
#include "sphstab/core/format.hpp"
#include "xsph.hpp"

namespace sphstab::rate_form_detail {

/// The pairs' r_ij, |r_ij|^2, W_ij and grad W_ij (the arrays the options read), and Ghat_ij = V_j grad W_ij.
template <int Dim, class Scalar>
void pair_arrays(Evaluation<Dim, Scalar>& e) {
  using Vec = typename Evaluation<Dim, Scalar>::Vec;
  using std::sqrt;
  const RateFormOptions& o = e.o;
  const NeighbourList& nl = e.nl;
  const bool plain = o.gradient == RateFormGradient::Plain, viscous = o.viscosity != ViscositySwitch::Off;
  const bool keep_r = !plain || viscous, keep_r2 = viscous;
  const bool keep_w = !plain || o.xsph > 0 || o.artificial_stress > 0 || o.first_step_shepard;
  const long nnz = nl.nonzeros();
  auto& ws = e.ws;
  ws.grad.resize(nnz);
  if (keep_r) ws.rij.resize(nnz);
  if (keep_r2) ws.r2s.resize(nnz);
  if (keep_w) ws.w.resize(nnz);
  const auto separation = e.separation;
#pragma omp parallel for schedule(static) num_threads(e.threads)
  for (int i = 0; i < e.n; ++i)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (j == i) {
        if (keep_r) ws.rij[k].setZero();
        ws.grad[k].setZero();
        if (keep_w) ws.w[k] = Scalar(e.kernel.value(0.0, e.h));
        if (keep_r2) ws.r2s[k] = Scalar(0);
        continue;
      }
      Vec r;
      Scalar r2;
      separation(i, j, r, r2);
      const Scalar rr = sqrt(r2);
      if (keep_r) ws.rij[k] = r;
      if (keep_r2) ws.r2s[k] = r2;
      if (keep_w) ws.w[k] = e.kernel.value(rr, e.h);
      ws.grad[k] = (e.kernel.d1(rr, e.h) / rr) * r;
    }
  ws.gh.resize(nnz);
#pragma omp parallel for schedule(static) num_threads(e.threads)
  for (int i = 0; i < e.n; ++i)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) ws.gh[k] = ws.vol[nl.indices[k]] * ws.grad[k];
}

/// Powell (1.19): the Shepard gradient (S_i grad W_ij V_j - W_ij V_j g_i) / S_i^2, then times M_i^-1 with M_i^ab =
/// sum_j (x_j^a - x_i^a) gradW~^b_ij, so that sum_j (x_j - x_i) Ghat_ij^T = I. A singular moment matrix is reported
/// for its lowest particle (as one thread would), after the loop.
template <int Dim, class Scalar>
void ncsph_gradient(Evaluation<Dim, Scalar>& e) {
  using Vec = typename Evaluation<Dim, Scalar>::Vec;
  using Mat = typename Evaluation<Dim, Scalar>::Mat;
  const NeighbourList& nl = e.nl;
  auto& ws = e.ws;
  int bad = e.n;
  std::string bad_reason;
#pragma omp parallel for schedule(static) num_threads(e.threads)
  for (int i = 0; i < e.n; ++i) {
    Scalar shep(0);
    Vec g = Vec::Zero();
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      shep += ws.vol[nl.indices[k]] * ws.w[k];
      g += ws.gh[k];
    }
    Mat M = Mat::Zero();
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      ws.gh[k] = (ws.gh[k] * shep - (ws.vol[nl.indices[k]] * ws.w[k]) * g) / (shep * shep);
      M -= ws.rij[k] * ws.gh[k].transpose();
    }
    const Eigen::Matrix<double, Dim, Dim> Mr = M.unaryExpr([](const Scalar& z) { return detail::re(z); });
    // JacobiSVD stops early on a non-finite matrix and leaves its singular values unset: refuse first.
    std::string reason;
    if (!Mr.allFinite()) {
      reason = "is not finite (non-finite positions or densities in the state)";
    } else {
      const Eigen::JacobiSVD<Eigen::Matrix<double, Dim, Dim>> svd(Mr);
      const double smax = svd.singularValues()(0), smin = svd.singularValues()(Dim - 1);
      if (!(smin > 1e-12 * smax)) reason = "is singular (rcond " + format_number(smax > 0 ? smin / smax : 0.0) + ")";
    }
    if (!reason.empty()) {
#pragma omp critical(sphstab_rate_form_error)
      if (i < bad) {
        bad = i;
        bad_reason = reason;
      }
      continue;
    }
    const Mat Minv_t = M.inverse().transpose();
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) ws.gh[k] = Minv_t * ws.gh[k];
  }
  if (bad < e.n)
    throw std::domain_error("RateFormScheme: NCSPH moment matrix of particle " + std::to_string(bad) + " " +
                            bad_reason);
}

/// XSPH velocities (xsph.hpp) from the kept W_ij; fixed particles do not move, driven ones move with v.
template <int Dim, class Scalar>
void xsph_velocities(Evaluation<Dim, Scalar>& e) {
  const NeighbourList& nl = e.nl;
  auto& ws = e.ws;
  const double eps = e.o.xsph;
#pragma omp parallel for schedule(static) num_threads(e.threads)
  for (int i = 0; i < e.n; ++i) {
    ws.vhat[i] = ws.v[i];
    if (eps > 0 && e.x_off[i] >= 0 && !e.is_driven(i))
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        if (j == i) continue;
        ws.vhat[i] += xsph_weight(eps, e.mass[j], ws.w[k], ws.rho[i], ws.rho[j]) * (ws.v[j] - ws.v[i]);
      }
  }
}

/// The means' pattern (rate_form.hpp): the list's pairs within the support at the discretisation's positions.
template <int Dim, class Scalar>
SPHSTAB_ALWAYS_INLINE inline bool in_pattern(const Evaluation<Dim, Scalar>& e, long k) {
  return e.in_support.empty() || e.in_support[k];
}

/// Local means of algorithm 4.1 of P_ij = V_j grad W_ij (C_ij, S-SPH): row mean r_i, column mean c_j = (1/n_j) sum_k
/// P_kj = -(V_j / n_j) sum_k grad W_jk, mean of column means m_i. m_i skips the entries outside the pattern; r_i and
/// c_j are kernel sums over the whole list. With first_step_shepard all three are of Powell's (4.18) P~_ij.
template <int Dim, class Scalar>
void local_means(Evaluation<Dim, Scalar>& e) {
  using Vec = typename Evaluation<Dim, Scalar>::Vec;
  const NeighbourList& nl = e.nl;
  auto& ws = e.ws;
  ws.row_mean.assign(e.n, Vec::Zero());
  ws.col_mean.assign(e.n, Vec::Zero());
  ws.mean_mean.assign(e.n, Vec::Zero());
#pragma omp parallel for schedule(static) num_threads(e.threads)
  for (int i = 0; i < e.n; ++i) {
    Vec gs = Vec::Zero();
    if (!e.o.first_step_shepard) {
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        ws.row_mean[i] += ws.gh[k];
        gs += ws.grad[k];
      }
      ws.row_mean[i] /= e.counts[i];
      ws.col_mean[i] = (-ws.vol[i] / e.counts[i]) * gs;
      continue;
    }
    // Powell (4.18): P~_ij = V_j (grad W_ij S0_i - W_ij G0_i) / S0_i^2. Row mean: sum_j P~_ij = (sum_j V_j grad W_ij
    // S0_i - sum_j V_j W_ij G0_i) / S0_i^2; column mean of column i: sum_j P~_ji with grad W_ji = -grad W_ij.
    Scalar wsum(0);
    const double s0 = e.shepard_sum[i];
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      ws.row_mean[i] += ws.gh[k];
      wsum += ws.vol[j] * ws.w[k];
      const double sj = e.shepard_sum[j];
      gs -= (ws.grad[k] * sj + ws.w[k] * e.shepard_grad[j].template cast<Scalar>()) / (sj * sj);
    }
    ws.row_mean[i] = (ws.row_mean[i] * s0 - wsum * e.shepard_grad[i].template cast<Scalar>()) / (s0 * s0 * e.counts[i]);
    ws.col_mean[i] = (ws.vol[i] / e.counts[i]) * gs;
  }
#pragma omp parallel for schedule(static) num_threads(e.threads)
  for (int i = 0; i < e.n; ++i) {
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
      if (in_pattern(e, k)) ws.mean_mean[i] += ws.col_mean[nl.indices[k]];
    ws.mean_mean[i] /= e.counts[i];
  }
}

/// The S-SPH switch per particle and component (stabilised_sph.hpp), on the real parts (frozen under a complex step);
/// |sum| below a relative tolerance counts as zero so that the unstressed lattice sits on the "off" branch of the
/// tension rule.
template <int Dim, class Scalar>
void ssph_switch(Evaluation<Dim, Scalar>& e) {
  const NeighbourList& nl = e.nl;
  auto& ws = e.ws;
  const double tol = 1e-14 * (e.K + 4.0 * e.mu / 3.0);
  ws.on.assign(e.n, Eigen::Matrix<bool, Dim, 1>::Constant(false));
#pragma omp parallel for schedule(static) num_threads(e.threads)
  for (int i = 0; i < e.n; ++i) {
    if (e.excluded[i]) continue;
    for (int a = 0; a < Dim; ++a) {
      double sum = 0;
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
        if (in_pattern(e, k)) sum += detail::re(ws.sigma[nl.indices[k]](a, a));
      if (std::abs(sum) <= tol) sum = 0;
      switch (e.o.switch_rule) {
        case SwitchRule::Tension:
          ws.on[i][a] = sum > 0;
          break;
        case SwitchRule::AsPrinted:
          ws.on[i][a] = sum <= 0;
          break;
        case SwitchRule::Always:
          ws.on[i][a] = true;
          break;
        case SwitchRule::Never:
          ws.on[i][a] = false;
          break;
      }
    }
  }
}

/// The pair terms on the plain gradient, every momentum form: -Pi_ij / rhobar_ij I (pair_viscosity.hpp) and
/// f_ij^n (R_i + R_j) (artificial_stress.hpp).
template <int Dim, class Scalar>
SPHSTAB_ALWAYS_INLINE inline typename Evaluation<Dim, Scalar>::Mat pair_terms(const Evaluation<Dim, Scalar>& e, int i,
                                                                              int j, long k) {
  using Vec = typename Evaluation<Dim, Scalar>::Vec;
  using Mat = typename Evaluation<Dim, Scalar>::Mat;
  const RateFormOptions& o = e.o;
  const auto& ws = e.ws;
  Mat pair = Mat::Zero();
  if (o.viscosity != ViscositySwitch::Off) {
    const Vec vij = ws.v[i] - ws.v[j];
    const Scalar vr = vij.cwiseProduct(ws.rij[k]).sum();
    if (o.viscosity == ViscositySwitch::Always || detail::re(vr) < 0) {
      const Scalar mu_ij = viscosity_mu(e.h, vr, ws.r2s[k], e.eta2), rho_bar = 0.5 * (ws.rho[i] + ws.rho[j]);
      const Scalar pi =
          viscosity_pi(mu_ij, -o.viscosity_alpha * e.c0, o.viscosity_beta, o.viscosity == ViscositySwitch::Compression);
      pair -= (pi / rho_bar) * Mat::Identity();
    }
  }
  if (o.artificial_stress > 0) pair += e.pair_factor(ws.w[k]) * (ws.R[i] + ws.R[j]);
  return pair;
}

/// The momentum of pair (i, j) (list entry k, j != i) for the scheme's momentum form.
template <int Dim, class Scalar>
SPHSTAB_ALWAYS_INLINE inline typename Evaluation<Dim, Scalar>::Vec pair_momentum(
    const Evaluation<Dim, Scalar>& e, int i, int j, long k, const typename Evaluation<Dim, Scalar>::Mat& pair) {
  using Vec = typename Evaluation<Dim, Scalar>::Vec;
  using Mat = typename Evaluation<Dim, Scalar>::Mat;
  const auto& ws = e.ws;
  const bool plain = e.o.gradient == RateFormGradient::Plain;
  const Vec& gk = ws.grad[k];
  const Mat &si = ws.sigma_rho2[i], &sj = ws.sigma_rho2[j];
  const double m_j = e.mass[j];
  switch (e.o.momentum) {
    case RateFormMomentum::Symmetric:  // Powell (1.36): m_j grad W_ij = rho_j Ghat_ij
      if (plain) return m_j * ((si + sj + pair) * gk);
      return ws.rho[j] * ((si + sj) * ws.gh[k]) + m_j * (pair * gk);
    case RateFormMomentum::Antisymmetric: {
      if (plain) return m_j * ((si + sj + pair) * gk);  // grad W_ji = -grad W_ij: the symmetric form
      const Vec ga = 0.5 * (ws.gh[k] / ws.vol[j] - ws.gh[e.transpose[k]] / ws.vol[i]);
      return m_j * ((si + sj) * ga + pair * gk);
    }
    case RateFormMomentum::Cij:  // Powell (4.10), C_ij of (4.9); C_ij = P_ij outside the pattern
      if (in_pattern(e, k))
        return (ws.sigma[j] / ws.rho[j]) * (ws.gh[k] - ws.row_mean[i] - ws.col_mean[j] + ws.mean_mean[i]) +
               m_j * (pair * gk);
      return (ws.sigma[j] / ws.rho[j]) * ws.gh[k] + m_j * (pair * gk);
    case RateFormMomentum::StabilisedSph: {  // Powell algorithm 4.2: a_i += (f_ij + g_ij - f_ji - g_ji) / 2
      const Mat Sij = ws.sigma[i] / ws.rho[i] + ws.sigma[j] / ws.rho[j];
      Vec gij = -(Sij * (ws.row_mean[i] + ws.col_mean[j] - ws.mean_mean[i]));
      Vec gji = -(Sij * (ws.row_mean[j] + ws.col_mean[i] - ws.mean_mean[j]));
      for (int a = 0; a < Dim; ++a) {
        if (!ws.on[i][a] || !in_pattern(e, k)) gij[a] = Scalar(0);
        if (!ws.on[j][a] || !in_pattern(e, k)) gji[a] = Scalar(0);
      }
      return 0.5 * ((ws.vol[i] + ws.vol[j]) * (Sij * gk) + gij - gji) + m_j * (pair * gk);
    }
  }
  return Vec::Zero();
}

/// Sums of every row: L, the continuity and the momentum, then the particle's rates.
template <int Dim, class Scalar>
void corrected_sums(Evaluation<Dim, Scalar>& e) {
  using Vec = typename Evaluation<Dim, Scalar>::Vec;
  using Mat = typename Evaluation<Dim, Scalar>::Mat;
  const NeighbourList& nl = e.nl;
  const RateFormOptions& o = e.o;
  const auto& ws = e.ws;
  const bool plain = o.gradient == RateFormGradient::Plain;
  const bool summation = o.continuity == ContinuityForm::Summation;
#pragma omp parallel for schedule(static) num_threads(e.threads)
  for (int i = e.first; i < e.last; ++i) {
    const bool free = e.x_off[i] >= 0;
    if (!free && e.rho_off[i] < 0) continue;
    Mat L = Mat::Zero();
    Scalar drho(0);
    Vec acc = Vec::Zero();
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (j == i) {  // only a corrected gradient has a self term (it makes the rows sum to zero)
        if (free && o.momentum == RateFormMomentum::Symmetric && !plain)
          acc += (2.0 / ws.rho[i]) * (ws.sigma[i] * ws.gh[k]);
        if (free && o.momentum == RateFormMomentum::Cij)
          acc += (ws.sigma[i] / ws.rho[i]) * (ws.gh[k] - ws.row_mean[i] - ws.col_mean[i] + ws.mean_mean[i]);
        continue;
      }
      const Vec dv = ws.vhat[j] - ws.vhat[i];
      if (plain) {  // continuity.hpp
        add_velocity_gradient(L, ws.vol[j] * dv, ws.grad[k]);
        if (summation) drho -= continuity_term(e.mass[j], dv, ws.grad[k]);
      } else {
        add_velocity_gradient(L, dv, ws.gh[k]);
        if (summation) drho -= continuity_term(ws.rho[j], dv, ws.gh[k]);
      }
      if (!free) continue;
      acc += pair_momentum(e, i, j, k, pair_terms(e, i, j, k));
    }
    e.finish(i, free, L, drho, acc);
  }
}

/// The corrected-gradient and local-means loop: per-pair arrays, NCSPH, XSPH, bulk viscosity and stresses, the local
/// means and switch, then the sums.
template <int Dim, class Scalar>
void corrected_rows(Evaluation<Dim, Scalar>& e) {
  pair_arrays(e);
  if (e.o.gradient == RateFormGradient::Ncsph) ncsph_gradient(e);
  xsph_velocities(e);
  if (e.bulk) e.bulk_pressure(&e.ws.gh);
  e.stresses();
  if (uses_local_means(e.o.momentum)) local_means(e);
  if (e.o.momentum == RateFormMomentum::StabilisedSph) ssph_switch(e);
  e.dydt.resize(e.scheme.size());
  corrected_sums(e);
}

}  // namespace sphstab::rate_form_detail
