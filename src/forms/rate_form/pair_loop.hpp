#pragma once
/// \file pair_loop.hpp
/// Internal to src/forms: RateFormScheme's pair loop (PairLoop::Pairs, rate_form.hpp) for the plain gradient with
/// symmetric momentum (the antisymmetric form is the same for the plain gradient) on real states. Each pair (i, j > i)
/// of the neighbour list is visited once; pairs at or beyond the kernel support are dropped before any kernel work.
/// With r = x_i - x_j, g = grad_i W_ij = (dW/dr / r) r (grad_j W_ji = -g), the pair terms of rate_form.hpp are
/// symmetric in i and j (sigma_i/rho_i^2 + sigma_j/rho_j^2, Pi_ij: v_ij . r_ij and rhobar_ij are, f_ij^n, R_i + R_j),
/// so with T = (sigma_i/rho_i^2 + sigma_j/rho_j^2
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
#include <type_traits>
#include <vector>

#include "artificial_stress.hpp"
#include "kernel_rows.hpp"
#include "pair_viscosity.hpp"
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

/// What a pair reads of its particles, packed so that a neighbour's data are one or two cache lines: position,
/// velocity, density, mass, and the symmetric sigma / rho^2 and R as xx (, yy, xy).
template <int Dim>
struct PairParticle {
  static constexpr int kSym = Dim * (Dim + 1) / 2;
  Eigen::Matrix<double, Dim, 1> x, v;
  double rho, mass;
  std::array<double, kSym> s, R;
};
/// What the velocity-gradient sweep reads of a particle and adds to it.
template <int Dim>
struct GradientParticle {
  Eigen::Matrix<double, Dim, 1> vhat;
  double vol, mass;
};
template <int Dim>
struct GradientSums {
  Eigen::Matrix<double, Dim, Dim> L;
  double drho;
};
/// The first sweep's sums: acceleration and XSPH increment.
template <int Dim>
struct MotionSums {
  Eigen::Matrix<double, Dim, 1> acc, dvhat;
};

/// Scratch of the pair loop, kept between calls (the scheme's workspace).
template <int Dim>
struct PairLoopScratch {
  std::vector<double> row;                                   // the row arrays (SoA)
  std::vector<int> row_j, kept_j, kept_count;                // a row's neighbours; j of each kept pair, pairs per row
  std::vector<Eigen::Matrix<double, Dim, 1>> row_r, kept_g;  // a row's r_ij; g of each kept pair (XSPH)
  std::vector<PairParticle<Dim>> particle;
  std::vector<MotionSums<Dim>> motion;
  std::vector<GradientParticle<Dim>> gradient_particle;
  std::vector<GradientSums<Dim>> gradient;
};

/// p g for a symmetric p stored as xx (, yy, xy).
template <int Dim>
SPHSTAB_ALWAYS_INLINE inline Eigen::Matrix<double, Dim, 1> symmetric_times(
    const std::array<double, Dim*(Dim + 1) / 2>& p, const Eigen::Matrix<double, Dim, 1>& g) {
  if constexpr (Dim == 1)
    return Eigen::Matrix<double, 1, 1>(p[0] * g[0]);
  else
    return Eigen::Vector2d(p[0] * g[0] + p[2] * g[1], p[2] * g[0] + p[1] * g[1]);
}

/// Packs what a pair reads of each particle (PairParticle) and zeroes the sums.
template <int Dim>
void pack_particles(const PairLoopArrays<Dim>& A, PairLoopScratch<Dim>& s) {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  const int n = A.n;
  s.particle.resize(n);
  s.motion.resize(n);
  s.gradient.resize(n);
  for (int i = 0; i < n; ++i) {
    PairParticle<Dim>& P = s.particle[i];
    P.x = A.x[i];
    P.v = A.v[i];
    P.rho = A.rho[i];
    P.mass = A.mass[i];
    const Mat &sr = A.sigma_rho2[i], &R = A.R[i];
    P.s[0] = sr(0, 0);
    P.R[0] = R(0, 0);
    if constexpr (Dim == 2) {
      P.s[1] = sr(1, 1);
      P.s[2] = sr(0, 1);
      P.R[1] = R(1, 1);
      P.R[2] = R(0, 1);
    }
    s.motion[i].acc.setZero();
    s.motion[i].dvhat.setZero();
    s.gradient[i].L.setZero();
    s.gradient[i].drho = 0;
  }
}

/// The second sweep with XSPH: every vhat known, L and drho from the kept pairs (j, g).
template <int Dim>
void gradient_sweep(const PairLoopArrays<Dim>& A, PairLoopScratch<Dim>& s) {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  const int n = A.n;
  const MotionSums<Dim>* const ms = s.motion.data();
  s.gradient_particle.resize(n);
  for (int i = 0; i < n; ++i) {
    A.vhat[i] = A.xsph_moves[i] ? Vec(A.v[i] + ms[i].dvhat) : A.v[i];
    s.gradient_particle[i] = {A.vhat[i], A.vol[i], A.mass[i]};
  }
  const GradientParticle<Dim>* const gp = s.gradient_particle.data();
  GradientSums<Dim>* const gs = s.gradient.data();
  const int* kj = s.kept_j.data();
  const Vec* kg = s.kept_g.data();
  for (int i = 0; i < n; ++i) {
    const Vec vh_i = gp[i].vhat;
    const double m_i = gp[i].mass, vol_i = gp[i].vol;
    Mat L_i = Mat::Zero();
    double drho_i = 0;
    const int len = s.kept_count[i];
    for (int q = 0; q < len; ++q) {
      const int j = kj[q];
      const Vec& g = kg[q];
      const Vec d = gp[j].vhat - vh_i;
      const Mat dg = d * g.transpose();
      L_i += gp[j].vol * dg;
      gs[j].L += vol_i * dg;
      if (A.summation) {
        const double dd = d.dot(g);
        drho_i -= gp[j].mass * dd;
        gs[j].drho -= m_i * dd;
      }
    }
    gs[i].L += L_i;
    gs[i].drho += drho_i;
    kj += len;
    kg += len;
  }
}

/// The first sweep: each pair (i, j > i) in support once, its kernel, the momentum of both particles, and either the
/// XSPH increments (keeping j and g of the pair for gradient_sweep) or L and drho.
template <int Dim, ViscositySwitch kViscosity, bool kStress, bool kXsph, class KernelRows>
void motion_sweep(const PairLoopArrays<Dim>& A, const KernelRows& kf, const PairFactor& pair_factor,
                  PairLoopScratch<Dim>& s) {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  constexpr int kSym = PairParticle<Dim>::kSym;
  constexpr bool kViscous = kViscosity != ViscositySwitch::Off;
  const int n = A.n;
  std::size_t longest = 0, upper_pairs = 0;
  for (int i = 0; i < n; ++i) {
    longest = std::max(longest, static_cast<std::size_t>(A.offsets[i + 1] - A.upper[i]));
    upper_pairs += A.offsets[i + 1] - A.upper[i];
  }
  const std::size_t stride = longest + 1;  // the compaction writes one slot past the kept pairs
  constexpr int kArrays = 9;
  if (s.row.size() < kArrays * stride) s.row.resize(kArrays * stride);
  if (s.row_j.size() < stride) s.row_j.resize(stride);
  if (s.row_r.size() < stride) s.row_r.resize(stride);
  Vec* const rv = s.row_r.data();  // r_ij (a vector per pair: g = (dW/dr / r) r is one packed product)
  double* const r2 = s.row.data();
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
  }
  const PairParticle<Dim>* const pp = s.particle.data();
  MotionSums<Dim>* const ms = s.motion.data();

  bool periodic = false;
  for (int a = 0; a < Dim; ++a) periodic = periodic || A.half_box[a] < std::numeric_limits<double>::infinity();
  std::size_t kept = 0;  // pairs kept so far (XSPH)
  const long *const offsets = A.offsets, *const upper = A.upper;
  const int* const indices = A.indices;
  const double support2 = A.support2;
  for (int i = 0; i < n; ++i) {
    const PairParticle<Dim>& Pi = pp[i];
    const Vec xi = Pi.x, vi = Pi.v;
    const double rho_i = Pi.rho, m_i = Pi.mass;
    // Gather the row's pairs in support (compaction without a branch: the slot is overwritten when dropped).
    const auto gather = [&](auto periodic_tag) SPHSTAB_ALWAYS_INLINE {
      std::size_t m = 0;
      const long k1 = offsets[i + 1];
      for (long k = upper[i]; k < k1; ++k) {
        const int j = indices[k];
        const PairParticle<Dim>& Pj = pp[j];
        Vec r = xi - Pj.x;
        if constexpr (decltype(periodic_tag)::value)
          for (int a = 0; a < Dim; ++a) {
            if (r[a] > A.half_box[a])
              r[a] -= A.box[a];
            else if (r[a] < -A.half_box[a])
              r[a] += A.box[a];
          }
        const double rsq = r.squaredNorm();
        jj[m] = j;
        rv[m] = r;
        r2[m] = rsq;
        if constexpr (kViscous || kXsph) rhoj[m] = Pj.rho;
        if constexpr (kViscous) vr[m] = (vi - Pj.v).dot(r);
        m += rsq < support2;
      }
      return m;
    };
    const std::size_t len = periodic ? gather(std::true_type{}) : gather(std::false_type{});
    // Pair scalars as whole-row loops.
    Eigen::Map<Eigen::ArrayXd>(rr, len) = Eigen::Map<const Eigen::ArrayXd>(r2, len).sqrt();
    row_pairs(kf, len, rr, w, gf);
    if constexpr (kStress) pair_factor.row_by_reciprocal(len, w, f);
    if constexpr (kViscous || kXsph)
      for (std::size_t q = 0; q < len; ++q) ib[q] = 2.0 / (rho_i + rhoj[q]);
    if constexpr (kViscous)
      for (std::size_t q = 0; q < len; ++q) {
        const double mu_ij = viscosity_mu(A.h, vr[q], r2[q], A.eta2);  // pair_viscosity.hpp
        const double pi = viscosity_pi(mu_ij, A.alpha_c0, A.beta, kViscosity == ViscositySwitch::Compression);
        const double cq = pi * ib[q];
        if constexpr (kViscosity == ViscositySwitch::Compression)
          c[q] = vr[q] < 0 ? cq : 0.0;
        else
          c[q] = cq;
      }
    // Scatter to both particles.
    Vec acc_i = Vec::Zero(), dvh_i = Vec::Zero();
    Mat L_i = Mat::Zero();
    double drho_i = 0;
    const bool moves_i = kXsph && A.xsph_moves[i];
    for (std::size_t q = 0; q < len; ++q) {
      const int j = jj[q];
      const PairParticle<Dim>& Pj = pp[j];
      const Vec g = gf[q] * rv[q];
      std::array<double, kSym> P;
      for (int e = 0; e < kSym; ++e) {
        P[e] = Pi.s[e] + Pj.s[e];
        if constexpr (kStress) P[e] += f[q] * (Pi.R[e] + Pj.R[e]);
      }
      Vec T = symmetric_times<Dim>(P, g);
      if constexpr (kViscous) T -= c[q] * g;
      acc_i += Pj.mass * T;
      ms[j].acc -= m_i * T;
      if constexpr (kXsph) {
        const double cx = A.xsph * w[q] * ib[q];
        const Vec d = Pj.v - vi;
        if (moves_i) dvh_i += (cx * Pj.mass) * d;
        if (A.xsph_moves[j]) ms[j].dvhat -= (cx * m_i) * d;
        s.kept_j[kept + q] = j;
        s.kept_g[kept + q] = g;
      } else {
        const Vec d = Pj.v - vi;
        const Mat dg = d * g.transpose();
        L_i += A.vol[j] * dg;
        s.gradient[j].L += A.vol[i] * dg;
        if (A.summation) {
          const double dd = d.dot(g);
          drho_i -= Pj.mass * dd;
          s.gradient[j].drho -= m_i * dd;
        }
      }
    }
    ms[i].acc += acc_i;
    if constexpr (kXsph) {
      ms[i].dvhat += dvh_i;
      s.kept_count[i] = static_cast<int>(len);
      kept += len;
    } else {
      s.gradient[i].L += L_i;
      s.gradient[i].drho += drho_i;
    }
  }
}

/// The pair loop with the viscosity switch, artificial stress and XSPH compiled in (kf: kernel_rows.hpp).
template <int Dim, ViscositySwitch kViscosity, bool kStress, bool kXsph, class KernelRows>
void pair_loop(const PairLoopArrays<Dim>& A, const KernelRows& kf, const PairFactor& pair_factor,
               PairLoopScratch<Dim>& s) {
  static_assert(Dim == 1 || Dim == 2, "pair_loop: Dim 1 or 2");
  const int n = A.n;
  pack_particles(A, s);
  motion_sweep<Dim, kViscosity, kStress, kXsph>(A, kf, pair_factor, s);
  if constexpr (kXsph) {
    gradient_sweep(A, s);
  } else {
    for (int i = 0; i < n; ++i) A.vhat[i] = A.v[i];
  }
  const MotionSums<Dim>* const ms = s.motion.data();
  for (int i = 0; i < n; ++i) {
    A.acc[i] = ms[i].acc;
    A.L[i] = s.gradient[i].L;
    A.drho[i] = s.gradient[i].drho;
  }
}

}  // namespace sphstab::rate_form_detail
