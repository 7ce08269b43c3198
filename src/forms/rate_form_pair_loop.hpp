#pragma once
/// \file rate_form_pair_loop.hpp
/// Internal to src/forms: RateFormScheme's pair loop (PairLoop::Pairs, rate_form.hpp) for the plain gradient with
/// symmetric momentum on real states. Each pair (i, j > i) of the neighbour list is visited once; pairs at or beyond
/// the kernel support are dropped before any kernel work. With r = x_i - x_j, g = grad_i W_ij = (dW/dr / r) r
/// (grad_j W_ji = -g), the pair terms of rate_form.hpp are symmetric in i and j (sigma_i/rho_i^2 + sigma_j/rho_j^2,
/// Pi_ij: v_ij . r_ij and rhobar_ij are, f_ij^n, R_i + R_j), so with T = (sigma_i/rho_i^2 + sigma_j/rho_j^2
/// - Pi_ij I + f_ij^n (R_i + R_j)) g and d = vhat_j - vhat_i:
///   acc_i += m_j T,            acc_j -= m_i T                    [Powell2012, (1.36)], [GMS2001, (3.1)]
///   L_i   += V_j d g^T,        L_j   += V_i d g^T                [GMS2001, (3.10)]
///   drho_i -= m_j d . g,       drho_j -= m_i d . g               [GMS2001, (3.8)] (summation only)
///   vhat_i += e_x m_j W / rhobar (v_j - v_i), vhat_j -= e_x m_i W / rhobar (v_j - v_i)   [GMS2001, (3.6)]
/// XSPH needs every vhat before the velocity gradients: the first sweep computes the kernel, the momentum and XSPH
/// and keeps (j, g) of each pair in support; the second sums L and drho from those. Without XSPH one sweep does all.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "kernel_rows.hpp"
#include "sphstab/forms/rate_form.hpp"

namespace sphstab::rate_form_detail {

/// What the pair loop reads (per particle arrays indexed by particle) and writes.
template <int Dim>
struct PairLoopArrays {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  int n = 0;
  const long *offsets = nullptr, *upper = nullptr;  // CSR rows; upper[i]: the first entry with j > i
  const int* indices = nullptr;
  const Vec *x = nullptr, *v = nullptr;
  const double *rho = nullptr, *vol = nullptr, *mass = nullptr;
  const Mat *sigma_rho2 = nullptr, *R = nullptr;  // sigma / rho^2 and the artificial stress (symmetric)
  const char* xsph_moves = nullptr;               // per particle: moves with its XSPH velocity (free, not driven)
  std::array<double, Dim> box{}, half_box{};      // periodic box length; +-L/2 of a periodic axis, +inf otherwise
  double support2 = 0;                            // (kernel support)^2
  double h = 0, eta2 = 0, alpha_c0 = 0, beta = 0, xsph = 0;
  bool summation = false;  // continuity by summation: drho from the pairs
  // Written: every particle's entry (zero where it has no pair).
  Vec *vhat = nullptr, *acc = nullptr;
  Mat* L = nullptr;
  double* drho = nullptr;
};

/// Scratch of the pair loop, kept between calls (the scheme's workspace).
template <int Dim>
struct PairLoopScratch {
  std::vector<double>& row;                            // the row arrays (SoA)
  std::vector<int>&row_j, &kept_j, &kept_count;        // a row's neighbours; j of each kept pair, pairs per row
  std::vector<Eigen::Matrix<double, Dim, 1>>& kept_g;  // g of each kept pair (XSPH)
  std::vector<Eigen::Matrix<double, Dim, 1>>& dvhat;   // XSPH velocity increments
};

/// The pair loop with the viscosity switch, artificial stress and XSPH compiled in (kf: kernel_rows.hpp).
template <int Dim, ViscositySwitch kViscosity, bool kStress, bool kXsph, class KernelRows>
void pair_loop(const PairLoopArrays<Dim>& A, const KernelRows& kf, const PairFactor& pair_factor,
               PairLoopScratch<Dim>& s) {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  constexpr bool kViscous = kViscosity != ViscositySwitch::Off;
  const int n = A.n;
  std::size_t longest = 0, upper_pairs = 0;
  for (int i = 0; i < n; ++i) {
    longest = std::max(longest, static_cast<std::size_t>(A.offsets[i + 1] - A.upper[i]));
    upper_pairs += A.offsets[i + 1] - A.upper[i];
  }
  const std::size_t stride = longest + 1;  // the compaction writes one slot past the kept pairs
  constexpr int kArrays = Dim + 9;
  if (s.row.size() < kArrays * stride) s.row.resize(kArrays * stride);
  if (s.row_j.size() < stride) s.row_j.resize(stride);
  std::array<double*, Dim> rc;
  for (int a = 0; a < Dim; ++a) rc[a] = s.row.data() + a * stride;  // r_ij
  double* const r2 = s.row.data() + Dim * stride;
  double* const rr = r2 + stride;    // |r|
  double* const w = rr + stride;     // W
  double* const gf = w + stride;     // dW/dr / r
  double* const f = gf + stride;     // f^n
  double* const rhoj = f + stride;   // rho_j
  double* const vr = rhoj + stride;  // v_ij . r_ij
  double* const c = vr + stride;     // Pi_ij / rhobar_ij
  double* const ib = c + stride;     // 1 / rhobar_ij
  int* const jj = s.row_j.data();
  if constexpr (kXsph) {
    s.kept_j.resize(upper_pairs);
    s.kept_g.resize(upper_pairs);
    s.kept_count.resize(n);
    s.dvhat.assign(n, Vec::Zero());
  }
  for (int i = 0; i < n; ++i) {
    A.acc[i].setZero();
    A.L[i].setZero();
    A.drho[i] = 0;
  }

  bool periodic = false;
  for (int a = 0; a < Dim; ++a) periodic = periodic || A.half_box[a] < std::numeric_limits<double>::infinity();
  std::size_t kept = 0;  // pairs kept so far (XSPH)
  for (int i = 0; i < n; ++i) {
    const Vec xi = A.x[i], vi = A.v[i];
    const double rho_i = A.rho[i], m_i = A.mass[i], vol_i = A.vol[i];
    // Gather the row's pairs in support (compaction without a branch: the slot is overwritten when dropped).
    std::size_t len = 0;
    for (long k = A.upper[i]; k < A.offsets[i + 1]; ++k) {
      const int j = A.indices[k];
      Vec r = xi - A.x[j];
      if (periodic)
        for (int a = 0; a < Dim; ++a) {
          if (r[a] > A.half_box[a])
            r[a] -= A.box[a];
          else if (r[a] < -A.half_box[a])
            r[a] += A.box[a];
        }
      const double rsq = r.squaredNorm();
      jj[len] = j;
      for (int a = 0; a < Dim; ++a) rc[a][len] = r[a];
      r2[len] = rsq;
      if constexpr (kViscous || kXsph) rhoj[len] = A.rho[j];
      if constexpr (kViscous) vr[len] = (vi - A.v[j]).dot(r);
      len += rsq < A.support2;
    }
    // Pair scalars as whole-row loops.
    Eigen::Map<Eigen::ArrayXd>(rr, len) = Eigen::Map<const Eigen::ArrayXd>(r2, len).sqrt();
    row_pairs(kf, len, rr, w, gf);
    if constexpr (kStress) pair_factor.row_by_reciprocal(len, w, f);
    if constexpr (kViscous || kXsph)
      for (std::size_t q = 0; q < len; ++q) ib[q] = 2.0 / (rho_i + rhoj[q]);
    if constexpr (kViscous)
      for (std::size_t q = 0; q < len; ++q) {
        const double mu_ij = A.h * vr[q] / (r2[q] + A.eta2);
        double pi = A.alpha_c0 * mu_ij;
        if constexpr (kViscosity == ViscositySwitch::Compression) pi += A.beta * mu_ij * mu_ij;
        const double cq = pi * ib[q];
        if constexpr (kViscosity == ViscositySwitch::Compression)
          c[q] = vr[q] < 0 ? cq : 0.0;
        else
          c[q] = cq;
      }
    // Scatter to both particles.
    const Mat& si = A.sigma_rho2[i];
    Vec acc_i = Vec::Zero(), dvh_i = Vec::Zero();
    Mat L_i = Mat::Zero();
    double drho_i = 0;
    const bool moves_i = kXsph && A.xsph_moves[i];
    for (std::size_t q = 0; q < len; ++q) {
      const int j = jj[q];
      Vec g;
      for (int a = 0; a < Dim; ++a) g[a] = gf[q] * rc[a][q];
      Mat P = si + A.sigma_rho2[j];
      if constexpr (kStress) P += f[q] * (A.R[i] + A.R[j]);
      Vec T = P * g;
      if constexpr (kViscous) T -= c[q] * g;  // not on P's diagonal: that store stalls the product's load
      acc_i += A.mass[j] * T;
      A.acc[j] -= m_i * T;
      if constexpr (kXsph) {
        const double cx = A.xsph * w[q] * ib[q];
        const Vec d = A.v[j] - vi;
        if (moves_i) dvh_i += (cx * A.mass[j]) * d;
        if (A.xsph_moves[j]) s.dvhat[j] -= (cx * m_i) * d;
        s.kept_j[kept + q] = j;
        s.kept_g[kept + q] = g;
      } else {
        const Vec d = A.v[j] - vi;
        const Mat dg = d * g.transpose();
        L_i += A.vol[j] * dg;
        A.L[j] += vol_i * dg;
        if (A.summation) {
          const double dd = d.dot(g);
          drho_i -= A.mass[j] * dd;
          A.drho[j] -= m_i * dd;
        }
      }
    }
    A.acc[i] += acc_i;
    if constexpr (kXsph) {
      s.dvhat[i] += dvh_i;
      s.kept_count[i] = static_cast<int>(len);
      kept += len;
    } else {
      A.L[i] += L_i;
      A.drho[i] += drho_i;
    }
  }
  if constexpr (!kXsph) {
    for (int i = 0; i < n; ++i) A.vhat[i] = A.v[i];
    return;
  }

  for (int i = 0; i < n; ++i) A.vhat[i] = A.xsph_moves[i] ? Vec(A.v[i] + s.dvhat[i]) : A.v[i];
  const int* kj = s.kept_j.data();
  const Vec* kg = s.kept_g.data();
  for (int i = 0; i < n; ++i) {
    const Vec vh_i = A.vhat[i];
    const double m_i = A.mass[i], vol_i = A.vol[i];
    Mat L_i = Mat::Zero();
    double drho_i = 0;
    const int len = s.kept_count[i];
    for (int q = 0; q < len; ++q) {
      const int j = kj[q];
      const Vec& g = kg[q];
      const Vec d = A.vhat[j] - vh_i;
      const Mat dg = d * g.transpose();
      L_i += A.vol[j] * dg;
      A.L[j] += vol_i * dg;
      if (A.summation) {
        const double dd = d.dot(g);
        drho_i -= A.mass[j] * dd;
        A.drho[j] -= m_i * dd;
      }
    }
    A.L[i] += L_i;
    A.drho[i] += drho_i;
    kj += len;
    kg += len;
  }
}

}  // namespace sphstab::rate_form_detail
