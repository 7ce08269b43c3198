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
///
/// Threads: the owner computes, with a halo. One thread adds to a particle k first the j-side terms of the rows
/// i < k, in ascending i (list order within a row), then k's own row sum. The particles are cut into contiguous chunks
/// [a, b) (pair_loop_chunks, split_rows); the thread that takes a chunk visits the rows from its halo start lo (the
/// lowest neighbour of a particle of the chunk) to b - 1: the halo rows i < a for their pairs with j in [a, b), j side
/// only, and the chunk's own rows, their j side only for j < b (j >= b is a later chunk's, added in its halo). So
/// every particle's terms arrive in the one-thread order. A pair's terms do not depend on the other pairs of its row:
/// every row array is computed lane by lane (IEEE sqrt; the kernel's SSE2 lanes and its scalar tail are the same
/// operations, kernel_rows.hpp; no FMA in the x86-64 baseline), so a halo row that holds only some of the row's pairs
/// gives them the same bits. Hence the same bits for any chunks and thread count (tests/forms/
/// threads_determinism_test.cpp). The price: a pair across two chunks is computed by both owners.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

#include "artificial_stress.hpp"
#include "kernel_rows.hpp"
#include "pair_lanes.hpp"
#include "pair_viscosity.hpp"
#include "sphstab/core/huge_page_allocator.hpp"
#include "sphstab/core/threads.hpp"
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

/// One thread's row arrays, grown on demand.
template <int Dim>
struct PairRowScratch {
  static constexpr int kArrays = 9;
  std::vector<double> row;                       // the row arrays (SoA), `stride` entries each
  std::vector<int> j;                            // the row's neighbours
  std::vector<Eigen::Matrix<double, Dim, 1>> r;  // the row's r_ij
  std::size_t stride = 0;
  /// Room for `pairs` pairs: the compaction writes one slot past the kept ones, and pair_lanes.hpp's vectors reach
  /// to the next multiple of kMaxPairLanes.
  void reserve(std::size_t pairs) {
    if (pairs < stride) return;
    stride = (std::max(pairs + 1, 2 * stride) + kMaxPairLanes - 1) / kMaxPairLanes * kMaxPairLanes;
    row.resize(kArrays * stride);
    j.resize(stride);
    r.resize(stride);
  }
};

/// Scratch of the pair loop, kept between calls (the scheme's workspace).
template <int Dim>
struct PairLoopScratch {
  std::vector<PairRowScratch<Dim>> rows;  // per thread
  std::vector<int> bound, halo;           // chunk c owns [bound[c], bound[c + 1]); its halo rows start at halo[c]
  // XSPH: j and g of the pairs in support of each row, row i's from kept_start[i], kept_count[i] of them. A chunk's
  // rows keep theirs one after the other from its first list entry (room enough: its rows have no more pairs than
  // entries), so that each chunk's owner writes its own part whichever thread takes which chunk.
  // The arrays of a list's size or of particles are huge-page work arrays (core/huge_page_allocator.hpp): a run's
  // first evaluation touches them all.
  HugePageVector<int> kept_j, kept_count;
  HugePageVector<long> kept_start;
  HugePageVector<Eigen::Matrix<double, Dim, 1>> kept_g;
  HugePageVector<PairParticle<Dim>> particle;
  HugePageVector<MotionSums<Dim>> motion;
  HugePageVector<GradientParticle<Dim>> gradient_particle;
  HugePageVector<GradientSums<Dim>> gradient;
};

/// The chunks of the pair loop for `threads` threads: one for one thread (no halo), else kChunksPerThread per thread,
/// taken in turn (schedule(dynamic, 1)), so that while one thread is descheduled (the machine busy with another
/// process) the other can take its second chunk instead of waiting at the barrier. Not more: every chunk boundary
/// adds its halo, the pairs across it computed twice (measured, pairs computed twice over all pairs at 2 / 4 / 8
/// chunks: GMS rings dp = 0.05 0 / 0.6 / 2.3 %, the 100 x 100 lattice with fixed layers 3.5 / 6.4 / 11 %, the
/// default plate 1.3 / 3.9 / 9.2 %; a shuffled numbering 50 / 75 / 88 %), and with the other core busy, 2 threads over
/// 8 chunks took 3 % (rings) and 9 % (lattice) longer per evaluation than over 2 chunks, over 4 chunks 1 and 3.5 %.
inline constexpr int kChunksPerThread = 2;
inline int pair_loop_chunks(int threads, int n) {
  return threads <= 1 ? 1 : std::max(1, std::min(n, kChunksPerThread * threads));
}

/// Chunk bounds balanced by list entries (the work of a row grows with its neighbours): bound[c] is the first row
/// whose entries start at or after c / chunks of them (offsets is their prefix sum).
inline void split_rows(const long* offsets, int n, int chunks, std::vector<int>& bound) {
  bound.resize(chunks + 1);
  const long entries = offsets[n];
  bound[0] = 0;
  for (int c = 1; c < chunks; ++c)
    bound[c] = static_cast<int>(std::lower_bound(offsets, offsets + n, entries * c / chunks) - offsets);
  bound[chunks] = n;
}

/// p g for a symmetric p stored as xx (, yy, xy).
template <int Dim>
SPHSTAB_ALWAYS_INLINE inline Eigen::Matrix<double, Dim, 1> symmetric_times(
    const std::array<double, Dim*(Dim + 1) / 2>& p, const Eigen::Matrix<double, Dim, 1>& g) {
  if constexpr (Dim == 1)
    return Eigen::Matrix<double, 1, 1>(p[0] * g[0]);
  else
    return Eigen::Vector2d(p[0] * g[0] + p[2] * g[1], p[2] * g[0] + p[1] * g[1]);
}

/// Packs what a pair reads of particle i (PairParticle).
template <int Dim>
SPHSTAB_ALWAYS_INLINE inline void pack_particle(const PairLoopArrays<Dim>& A, PairParticle<Dim>& P, int i) {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
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
}

/// The sweeps of one chunk [a, b): the rows its owner visits and what each adds (see the file comment).
template <int Dim, ViscositySwitch kViscosity, bool kStress, bool kXsph, class KernelRows>
struct PairSweeps {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  static constexpr int kSym = PairParticle<Dim>::kSym;
  static constexpr bool kViscous = kViscosity != ViscositySwitch::Off;

  const PairLoopArrays<Dim>& A;
  const KernelRows& kf;
  const PairFactor& pair_factor;
  PairLoopScratch<Dim>& s;
  bool periodic;
  // The cubic spline (with GMS's f^4 when the artificial stress is on): the row scalars by pair_lanes.hpp, its AVX2
  // clone when `avx2`; other kernels and exponents by the kernel's and PairFactor's row functions.
  bool lanes = false, avx2 = false;
  PairLaneConstants lane{};

  /// The first row with a pair into [a, b): the lowest neighbour of its particles (rows are sorted and hold i).
  int halo_start(int a, int b) const {
    if (a == 0) return 0;  // one chunk (one thread): no halo, and no pass over the rows' first entries
    int lo = a;
    for (int k = a; k < b; ++k)
      if (A.offsets[k] < A.offsets[k + 1]) lo = std::min(lo, A.indices[A.offsets[k]]);
    return lo;
  }

  /// The first sweep over chunk c: zeroes its sums, adds the halo rows' and its own rows' terms; then its particles'
  /// sums are complete (vhat with XSPH; every output without).
  template <class Done>
  void motion(PairRowScratch<Dim>& rs, int c, Done& done) {
    const int a = s.bound[c], b = s.bound[c + 1];
    const int lo = halo_start(a, b);
    s.halo[c] = lo;
    for (int k = a; k < b; ++k) {
      s.motion[k].acc.setZero();
      s.motion[k].dvhat.setZero();
      if constexpr (!kXsph) {
        s.gradient[k].L.setZero();
        s.gradient[k].drho = 0;
      }
    }
    const int* const indices = A.indices;
    long kept = A.offsets[a];  // XSPH: where the next own row keeps its pairs
    for (int i = lo; i < a; ++i) {
      // The pairs (i, j) with j in [a, b): one run of the sorted row.
      const int *const row0 = indices + A.upper[i], *const row1 = indices + A.offsets[i + 1];
      if (row0 == row1 || row1[-1] < a) continue;
      const int* const k0 = std::lower_bound(row0, row1, a);
      const int* const k1 = std::lower_bound(k0, row1, b);
      if (k0 < k1) motion_row<false>(rs, i, k0 - indices, k1 - indices, b, kept);
    }
    for (int i = a; i < b; ++i) motion_row<true>(rs, i, A.upper[i], A.offsets[i + 1], b, kept);
    if constexpr (kXsph) {
      for (int k = a; k < b; ++k) {
        A.vhat[k] = A.xsph_moves[k] ? Vec(A.v[k] + s.motion[k].dvhat) : A.v[k];
        s.gradient_particle[k] = {A.vhat[k], A.vol[k], A.mass[k]};
      }
    } else {
      for (int k = a; k < b; ++k) A.vhat[k] = A.v[k];
      copy_out(a, b);
      done(a, b);
    }
  }

  /// The second sweep (XSPH) over chunk c: L and drho from the kept pairs, every vhat known.
  template <class Done>
  void gradient(int c, Done& done) {
    const int a = s.bound[c], b = s.bound[c + 1], lo = s.halo[c];
    for (int k = a; k < b; ++k) {
      s.gradient[k].L.setZero();
      s.gradient[k].drho = 0;
    }
    const int* const kj = s.kept_j.data();
    for (int i = lo; i < a; ++i) {
      const int *const row0 = kj + s.kept_start[i], *const row1 = row0 + s.kept_count[i];
      if (row0 == row1 || row1[-1] < a) continue;
      const int* const q0 = std::lower_bound(row0, row1, a);
      const int* const q1 = std::lower_bound(q0, row1, b);
      gradient_row<false>(i, q0 - kj, q1 - kj, b);
    }
    for (int i = a; i < b; ++i) gradient_row<true>(i, s.kept_start[i], s.kept_start[i] + s.kept_count[i], b);
    copy_out(a, b);
    done(a, b);
  }

 private:
  void copy_out(int a, int b) const {
    for (int k = a; k < b; ++k) {
      A.acc[k] = s.motion[k].acc;
      A.L[k] = s.gradient[k].L;
      A.drho[k] = s.gradient[k].drho;
    }
  }

  /// Row i's pairs at the kept slots [q0, q1): with kOwn, the i side and the j side of j < b; else the j side.
  template <bool kOwn>
  SPHSTAB_ALWAYS_INLINE void gradient_row(int i, long q0, long q1, int b) {
    const GradientParticle<Dim>* const gp = s.gradient_particle.data();
    GradientSums<Dim>* const gs = s.gradient.data();
    const int* const kj = s.kept_j.data();
    const Vec* const kg = s.kept_g.data();
    const Vec vh_i = gp[i].vhat;
    const double m_i = gp[i].mass, vol_i = gp[i].vol;
    Mat L_i = Mat::Zero();
    double drho_i = 0;
    const bool summation = A.summation;  // a local: the stores to gs[j] could alias A as far as the compiler knows
    const auto pair = [&](long q, auto i_side, auto j_side) SPHSTAB_ALWAYS_INLINE {
      const int j = kj[q];
      const Vec& g = kg[q];
      const Vec d = gp[j].vhat - vh_i;
      const Mat dg = d * g.transpose();
      if constexpr (decltype(i_side)::value) L_i += gp[j].vol * dg;
      if constexpr (decltype(j_side)::value) gs[j].L += vol_i * dg;
      if (summation) {
        const double dd = d.dot(g);
        if constexpr (decltype(i_side)::value) drho_i -= gp[j].mass * dd;
        if constexpr (decltype(j_side)::value) gs[j].drho -= m_i * dd;
      }
    };
    if constexpr (kOwn) {
      const long qb = q0 == q1 || kj[q1 - 1] < b ? q1 : std::lower_bound(kj + q0, kj + q1, b) - kj;
      for (long q = q0; q < qb; ++q) pair(q, std::true_type{}, std::true_type{});
      for (long q = qb; q < q1; ++q) pair(q, std::true_type{}, std::false_type{});
      gs[i].L += L_i;
      gs[i].drho += drho_i;
    } else {
      for (long q = q0; q < q1; ++q) pair(q, std::false_type{}, std::true_type{});
    }
  }

  /// Row i's pairs at the list entries [k0, k1) that are in support: their kernel, and with kOwn the i side and the
  /// j side of j < b (keeping every pair for gradient() with XSPH); else the j side.
  template <bool kOwn>
  SPHSTAB_ALWAYS_INLINE void motion_row(PairRowScratch<Dim>& rs, int i, long k0, long k1, int b, long& kept) {
    rs.reserve(static_cast<std::size_t>(k1 - k0));
    const std::size_t stride = rs.stride;
    Vec* const rv = rs.r.data();  // r_ij (a vector per pair: g = (dW/dr / r) r is one packed product)
    double* const r2 = rs.row.data();
    double* const rr = r2 + stride;    // |r|
    double* const w = rr + stride;     // W
    double* const gf = w + stride;     // dW/dr / r
    double* const f = gf + stride;     // f^n
    double* const rhoj = f + stride;   // rho_j
    double* const vr = rhoj + stride;  // v_ij . r_ij
    double* const c = vr + stride;     // Pi_ij / rhobar_ij
    double* const ib = c + stride;     // 1 / rhobar_ij
    int* const jj = rs.j.data();
    const PairParticle<Dim>* const pp = s.particle.data();
    MotionSums<Dim>* const ms = s.motion.data();
    const int* const indices = A.indices;
    const double support2 = A.support2;

    const PairParticle<Dim>& Pi = pp[i];
    const Vec xi = Pi.x, vi = Pi.v;
    const double rho_i = Pi.rho, m_i = Pi.mass;
    // Gather the pairs in support (compaction without a branch: the slot is overwritten when dropped).
    const auto gather = [&](auto periodic_tag) SPHSTAB_ALWAYS_INLINE {
      std::size_t m = 0;
      for (long k = k0; k < k1; ++k) {
        const int j = indices[k];
        const PairParticle<Dim>& Pj = pp[j];
        Vec r = xi - Pj.x;
        if constexpr (decltype(periodic_tag)::value)
          for (int e = 0; e < Dim; ++e) {
            if (r[e] > A.half_box[e])
              r[e] -= A.box[e];
            else if (r[e] < -A.half_box[e])
              r[e] += A.box[e];
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
    // Pair scalars as whole-row loops (lane by lane: a pair's values do not depend on the row's other pairs).
    if (lanes) {
      const PairLaneRow lane_row{len, rho_i, r2, vr, rhoj, w, gf, f, ib, c};  // PairLaneRow's order
      pair_lanes<kViscosity, kStress, kXsph>(avx2, lane, lane_row);
    } else {
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
    }
    // Scatter to both particles.
    Vec acc_i = Vec::Zero(), dvh_i = Vec::Zero();
    Mat L_i = Mat::Zero();
    double drho_i = 0;
    const bool moves_i = kXsph && A.xsph_moves[i];
    // In locals: the scatter's stores could alias the arrays' holders as far as the compiler knows, so it would
    // reload each of these per pair.
    const double xsph = A.xsph;
    const char* const moves = A.xsph_moves;
    const double* const vol = A.vol;
    const bool summation = A.summation;
    int* const kept_j = kXsph ? s.kept_j.data() + kept : nullptr;
    Vec* const kept_g = kXsph ? s.kept_g.data() + kept : nullptr;
    GradientSums<Dim>* const gs = s.gradient.data();
    const auto pair = [&](std::size_t q, auto i_side, auto j_side) SPHSTAB_ALWAYS_INLINE {
      constexpr bool kI = decltype(i_side)::value, kJ = decltype(j_side)::value;
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
      if constexpr (kI) acc_i += Pj.mass * T;
      if constexpr (kJ) ms[j].acc -= m_i * T;
      if constexpr (kXsph) {
        const double cx = xsph * w[q] * ib[q];
        const Vec d = Pj.v - vi;
        if constexpr (kI)
          if (moves_i) dvh_i += (cx * Pj.mass) * d;
        if constexpr (kJ)
          if (moves[j]) ms[j].dvhat -= (cx * m_i) * d;
        if constexpr (kI) {
          kept_j[q] = j;
          kept_g[q] = g;
        }
      } else {
        const Vec d = Pj.v - vi;
        const Mat dg = d * g.transpose();
        if constexpr (kI) L_i += vol[j] * dg;
        if constexpr (kJ) gs[j].L += vol[i] * dg;
        if (summation) {
          const double dd = d.dot(g);
          if constexpr (kI) drho_i -= Pj.mass * dd;
          if constexpr (kJ) gs[j].drho -= m_i * dd;
        }
      }
    };
    if constexpr (kOwn) {
      // The pairs with j < b first (the row is sorted): theirs both sides; the rest only i's.
      const std::size_t qb = len == 0 || jj[len - 1] < b ? len : std::lower_bound(jj, jj + len, b) - jj;
      for (std::size_t q = 0; q < qb; ++q) pair(q, std::true_type{}, std::true_type{});
      for (std::size_t q = qb; q < len; ++q) pair(q, std::true_type{}, std::false_type{});
      ms[i].acc += acc_i;
      if constexpr (kXsph) {
        ms[i].dvhat += dvh_i;
        s.kept_start[i] = kept;
        s.kept_count[i] = static_cast<int>(len);
        kept += len;
      } else {
        s.gradient[i].L += L_i;
        s.gradient[i].drho += drho_i;
      }
    } else {
      for (std::size_t q = 0; q < len; ++q) pair(q, std::false_type{}, std::true_type{});
    }
  }
};

/// The pair loop with the viscosity switch, artificial stress and XSPH compiled in (kf: kernel_rows.hpp), in one
/// parallel region of `threads` threads over `chunks` chunks (0: pair_loop_chunks): prepare(i) and the packing of each
/// particle, then the sweeps by chunk; done(a, b) is called once per chunk when the outputs of the particles [a, b)
/// are written (row-parallel: for their rates). The first exception of prepare or done is rethrown after the region.
template <int Dim, ViscositySwitch kViscosity, bool kStress, bool kXsph, class KernelRows, class Prepare, class Done>
void pair_loop(const PairLoopArrays<Dim>& A, const KernelRows& kf, const PairFactor& pair_factor,
               PairLoopScratch<Dim>& s, int threads, int chunks, Prepare&& prepare, Done&& done) {
  static_assert(Dim == 1 || Dim == 2, "pair_loop: Dim 1 or 2");
  const int n = A.n;
  threads = std::max(1, threads);
  if (chunks <= 0) chunks = pair_loop_chunks(threads, n);
  split_rows(A.offsets, n, chunks, s.bound);
  s.halo.resize(chunks);
  if (static_cast<int>(s.rows.size()) < threads) s.rows.resize(threads);
  s.particle.resize(n);
  s.motion.resize(n);
  s.gradient.resize(n);
  if constexpr (kXsph) {
    s.kept_j.resize(A.offsets[n]);
    s.kept_g.resize(A.offsets[n]);
    s.kept_count.resize(n);
    s.kept_start.resize(n);
    s.gradient_particle.resize(n);
  }
  bool periodic = false;
  for (int e = 0; e < Dim; ++e) periodic = periodic || A.half_box[e] < std::numeric_limits<double>::infinity();
  PairSweeps<Dim, kViscosity, kStress, kXsph, KernelRows> sweeps{A, kf, pair_factor, s, periodic};
  if constexpr (std::is_same_v<KernelRows, CubicFunctions<Dim>>) {
    if (!kStress || pair_factor.fourth_power()) {
      const std::array<double, 4> c = kf.pair_constants();
      sweeps.lanes = true;
      sweeps.avx2 = avx2_enabled();
      const double inv_w_dp = kStress ? pair_factor.reciprocal_w_dp() : 0.0;  // PairLaneConstants' order
      sweeps.lane = {c[0], c[1], c[2], c[3], inv_w_dp, A.h, A.eta2, A.alpha_c0, A.beta};
    }
  }
  FirstException first_error;
#pragma omp parallel num_threads(threads)
  {
    PairRowScratch<Dim>& rs = s.rows[thread_index()];
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i)
      first_error.run([&] {
        prepare(i);
        pack_particle(A, s.particle[i], i);
      });
    // The barriers: after the packing (every particle's data), after the first sweep with XSPH (every vhat and kept
    // pair), at the region's end (no other: the last loop is nowait).
    if constexpr (kXsph) {
#pragma omp for schedule(dynamic, 1)
      for (int c = 0; c < chunks; ++c) first_error.run([&] { sweeps.motion(rs, c, done); });
#pragma omp for schedule(dynamic, 1) nowait
      for (int c = 0; c < chunks; ++c) first_error.run([&] { sweeps.gradient(c, done); });
    } else {
#pragma omp for schedule(dynamic, 1) nowait
      for (int c = 0; c < chunks; ++c) first_error.run([&] { sweeps.motion(rs, c, done); });
    }
  }
  first_error.rethrow();
}

/// The pair loop alone (no per-particle preparation or completion): the tests' entry, with any threads and chunks.
template <int Dim, ViscositySwitch kViscosity, bool kStress, bool kXsph, class KernelRows>
void pair_loop(const PairLoopArrays<Dim>& A, const KernelRows& kf, const PairFactor& pair_factor,
               PairLoopScratch<Dim>& s, int threads = 1, int chunks = 0) {
  pair_loop<Dim, kViscosity, kStress, kXsph>(
      A, kf, pair_factor, s, threads, chunks, [](int) {}, [](int, int) {});
}

}  // namespace sphstab::rate_form_detail
