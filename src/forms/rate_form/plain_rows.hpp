#pragma once
/// \file plain_rows.hpp
/// Internal to src/forms: the row loop of the rate form for the plain gradient with symmetric or antisymmetric momentum
/// (the same for the plain gradient), on real and complex states, with no per-pair arrays over the whole list.
///
/// Each neighbour row in two steps. Pair functions: gather r_ij and |r_ij|^2 (and what the pair terms read), then the
/// pairs' scalar functions (|r|, W, dW/dr / r, f^n, the viscosity's Pi / rhobar) as whole-row array loops (vectorised
/// for real states), the row particle's XSPH velocity (it reads v only), and grad W, Pi / rhobar, f^n kept per pair.
/// Sums: L, the continuity and the momentum over the row in neighbour order, which read the neighbours' XSPH
/// velocities. So with XSPH the sums of a row wait until the pair functions of its last neighbour have run, and its
/// kept pair results wait in a ring buffer that holds the pairs of the rows in between (a lattice ordered by rows needs
/// a few lattice rows); the rows whose neighbours lie farther (across a periodic boundary) are summed at the end, their
/// pair functions run again. Without XSPH each row is summed right after its pair functions. With threads (or a row
/// partition) two passes over the rows: the XSPH velocities, then each row's pair functions and sums.
#include <Eigen/Core>
#include <algorithm>
#include <bit>
#include <cstdint>
#include <exception>
#include <type_traits>
#include <vector>

#include "evaluation.hpp"
#include "pair_viscosity.hpp"
#include "xsph.hpp"

namespace sphstab::rate_form_detail {

/// The row loop with the viscosity switch and the artificial stress compiled in; kf: kernel_rows.hpp.
template <int Dim, class Scalar, ViscositySwitch kViscosity, bool kStressTerm, class KernelRows>
class PlainRows {
  using E = Evaluation<Dim, Scalar>;
  using Vec = typename E::Vec;
  using Mat = typename E::Mat;
  static constexpr bool kViscous = kViscosity != ViscositySwitch::Off;
  /// grad W (Dim), Pi / rhobar, f^n per pair.
  using Kept = Eigen::Matrix<Scalar, Dim + 2, 1>;
  static constexpr int kRowArrays = 8;
  static constexpr std::size_t kNow = ~std::size_t(0);  // "sum from the row arrays", not from the ring

 public:
  PlainRows(E& e, const KernelRows& kf) : e(e), kf(kf), xsph(e.o.xsph > 0) {}

  void run() {
    plan();
    if (e.threads > 1 || e.partial)
      two_passes();
    else if (!xsph)
      one_pass();
    else
      ring_pass();
  }

 private:
  /// The arrays the row loops read and write, as plain pointers copied into the loops (the vector stores of the row
  /// arrays may alias anything, which would otherwise reload every vector's data pointer after each).
  struct Arrays {
    const long* off;
    const int* idx;
    const Vec *v, *vhat;
    Vec* vhat_out;
    const Scalar *rho, *vol;
    const double* mass;
    const Mat *sigma_rho2, *R;
    Kept* kept;
    Vec* r;                                         // row arrays: r_ij
    Scalar *r2, *rr, *w, *gf, *f, *rho_j, *vr, *c;  // |r|^2, |r|, W, dW/dr / r, f^n, rho_j, v_ij . r_ij, weights
    double* m;                                      // m_j
  };

  E& e;
  const KernelRows& kf;
  const bool xsph;
  std::size_t longest = 0, ring = 0;

  /// Sizes: the longest row, the ring (rows i .. ready[i] of kept pair results for about 9 rows in 10; the others are
  /// summed at the end), and one set of row arrays per thread.
  void plan();
  Arrays arrays(int t) const;
  /// Whether row i's pair results fit the ring until its last neighbour's pair functions have run.
  bool kept(int i) const {
    const NeighbourList& nl = e.nl;
    return static_cast<std::size_t>(nl.offsets[e.ws.ready[i] + 1] - nl.offsets[i]) + longest <= ring;
  }
  /// Pair functions of row i: the XSPH velocity (kXsph) and the pair results for the sums (keep), copied to the ring
  /// from slot `base` on unless `base` is kNow (summed right away, from the row arrays).
  template <bool kXsph>
  SPHSTAB_ALWAYS_INLINE inline void pair_functions(const Arrays A, int i, bool keep, std::size_t base) const;
  /// Sums of row i from its pair results (the ring from slot `base` on, or the row arrays) and the XSPH velocities.
  template <bool kRing>
  SPHSTAB_ALWAYS_INLINE inline void sums(const Arrays A, int i, std::size_t base) const;
  void two_passes();
  void one_pass();
  void ring_pass();
};

template <int Dim, class Scalar, ViscositySwitch kViscosity, bool kStressTerm, class KernelRows>
void PlainRows<Dim, Scalar, kViscosity, kStressTerm, KernelRows>::plan() {
  const NeighbourList& nl = e.nl;
  const int n = e.n;
  for (int i = 0; i < n; ++i) longest = std::max(longest, static_cast<std::size_t>(nl.offsets[i + 1] - nl.offsets[i]));
  // Ring: the rows' kept pair results one after the other (a row that would cross the end starts again at 0).
  // Row i is summed after the pair functions of row ready[i]; in between the ring takes the pairs of rows i ..
  // ready[i] (plus at most one row's length left unused at the end). Its size holds that for about 9 rows in 10
  // (and for all rows without XSPH); rows that need more are summed at the end.
  std::vector<long>& ready = e.ws.ready;  // the row's last neighbour (XSPH) or the row itself
  ready.resize(n);
  ring = 2 * longest;
  if (xsph && e.threads == 1) {  // threads: two passes, no ring
    // The size from every 8th row (an estimate suffices: kept() decides per row).
    std::vector<long>& need = e.ws.ring_start;  // borrowed: the pairs of rows i .. ready[i]
    need.clear();
    for (int i = 0; i < n; ++i) {
      const long k0 = nl.offsets[i], k1 = nl.offsets[i + 1];
      int last = i;
      for (long k = k0; k < k1; ++k) last = std::max(last, nl.indices[k]);
      ready[i] = last;
      if (i % 8 == 0 && e.summed(i)) need.push_back(nl.offsets[last + 1] - k0);
    }
    if (!need.empty()) {
      const auto q90 = need.begin() + std::min(need.size() - 1, (9 * need.size()) / 10);
      std::nth_element(need.begin(), q90, need.end());
      ring = std::max(ring, static_cast<std::size_t>(*q90) + 2 * longest);
    }
  } else {
    for (int i = 0; i < n; ++i) ready[i] = i;
  }
  e.ws.ring_start.resize(n);
  if (xsph && e.ws.ring.size() < ring) e.ws.ring.resize(ring);
  const std::size_t slots = static_cast<std::size_t>(e.threads);  // one set of row arrays per thread
  if (e.ws.row_r.size() < slots * longest) e.ws.row_r.resize(slots * longest);
  if (e.ws.row.size() < slots * kRowArrays * longest) e.ws.row.resize(slots * kRowArrays * longest);
  if (e.ws.row_mass.size() < slots * longest) e.ws.row_mass.resize(slots * longest);
}

template <int Dim, class Scalar, ViscositySwitch kViscosity, bool kStressTerm, class KernelRows>
auto PlainRows<Dim, Scalar, kViscosity, kStressTerm, KernelRows>::arrays(int t) const -> Arrays {
  auto& ws = e.ws;
  double* const mb = ws.row_mass.data() + t * longest;           // m_j
  Vec* const rb = ws.row_r.data() + t * longest;                 // r_ij
  Scalar* const r2b = ws.row.data() + t * kRowArrays * longest;  // |r|^2
  Scalar* const rrb = r2b + longest;                             // |r|
  Scalar* const wb = rrb + longest;                              // W
  Scalar* const gfb = wb + longest;                              // dW/dr / r
  Scalar* const fb = gfb + longest;                              // f_ij^n
  Scalar* const rhob = fb + longest;                             // rho_j
  Scalar* const vrb = rhob + longest;                            // v_ij . r_ij
  Scalar* const cb = vrb + longest;                              // XSPH weight; Pi_ij / rhobar_ij
  return Arrays{.off = e.nl.offsets.data(),
                .idx = e.nl.indices.data(),
                .v = ws.v.data(),
                .vhat = ws.vhat.data(),
                .vhat_out = ws.vhat.data(),
                .rho = ws.rho.data(),
                .vol = ws.vol.data(),
                .mass = e.mass.data(),
                .sigma_rho2 = ws.sigma_rho2.data(),
                .R = ws.R.data(),
                .kept = ws.ring.data(),
                .r = rb,
                .r2 = r2b,
                .rr = rrb,
                .w = wb,
                .gf = gfb,
                .f = fb,
                .rho_j = rhob,
                .vr = vrb,
                .c = cb,
                .m = mb};
}

template <int Dim, class Scalar, ViscositySwitch kViscosity, bool kStressTerm, class KernelRows>
template <bool kXsph>
void PlainRows<Dim, Scalar, kViscosity, kStressTerm, KernelRows>::pair_functions(const Arrays A, int i, bool keep,
                                                                                 std::size_t base) const {
  using std::sqrt;
  const RateFormOptions& o = e.o;
  const auto separation = e.separation;
  const bool free = e.x_off[i] >= 0, terms = keep && free;
  const long k0 = A.off[i];
  const std::size_t len = A.off[i + 1] - k0;
  for (std::size_t q = 0; q < len; ++q) {
    const int j = A.idx[k0 + q];
    separation(i, j, A.r[q], A.r2[q]);
    if constexpr (kXsph) A.m[q] = A.mass[j];
    if (kXsph || (kViscous && terms)) A.rho_j[q] = A.rho[j];
    if (kViscous && terms) {
      const Vec vij = A.v[i] - A.v[j];
      A.vr[q] = vij.cwiseProduct(A.r[q]).sum();
    }
  }
  if constexpr (std::is_same_v<Scalar, double>)
    Eigen::Map<Eigen::ArrayXd>(A.rr, len) = Eigen::Map<const Eigen::ArrayXd>(A.r2, len).sqrt();
  else
    for (std::size_t q = 0; q < len; ++q) A.rr[q] = sqrt(A.r2[q]);
  if (!keep)
    kf.row_values(len, A.rr, A.w);
  else if (kXsph || (kStressTerm && free))
    kf.template row_slopes<true>(len, A.rr, A.w, A.gf);
  else
    kf.template row_slopes<false>(len, A.rr, A.w, A.gf);
  const Scalar rho_i = A.rho[i];
  if constexpr (kXsph) {  // xsph.hpp
    for (std::size_t q = 0; q < len; ++q) A.c[q] = xsph_weight(o.xsph, A.m[q], A.w[q], rho_i, A.rho_j[q]);
    Vec vh = A.v[i];
    for (std::size_t q = 0; q < len; ++q) {
      const int j = A.idx[k0 + q];
      if (j == i) continue;
      vh += A.c[q] * (A.v[j] - A.v[i]);
    }
    A.vhat_out[i] = vh;
  }
  if (!keep) return;
  if (kStressTerm && free) e.pair_factor.row(len, A.w, A.f);
  if (kViscous && free) {
    const double alpha_c0 = -o.viscosity_alpha * e.c0;
    for (std::size_t q = 0; q < len; ++q) {  // pair_viscosity.hpp
      const Scalar mu_ij = viscosity_mu(e.h, A.vr[q], A.r2[q], e.eta2), rho_bar = 0.5 * (rho_i + A.rho_j[q]);
      const Scalar pi = viscosity_pi(mu_ij, alpha_c0, o.viscosity_beta, kViscosity == ViscositySwitch::Compression);
      const Scalar c = pi / rho_bar;
      // Compression: 0 for a receding pair, selected here rather than branched on in the sums (the sign of
      // v_ij . r_ij is random); 0 - 0 I leaves the zero pair matrix as it is.
      if constexpr (kViscosity != ViscositySwitch::Compression) {
        A.c[q] = c;
      } else if constexpr (std::is_same_v<Scalar, double>) {  // as below, by a mask (the loop vectorises)
        const std::uint64_t approaching = -static_cast<std::uint64_t>(A.vr[q] < 0);
        A.c[q] = std::bit_cast<double>(std::bit_cast<std::uint64_t>(c) & approaching);
      } else {
        A.c[q] = detail::re(A.vr[q]) < 0 ? c : Scalar(0);
      }
    }
  }
  if (base == kNow) return;
  Kept* const out = A.kept + base;
  for (std::size_t q = 0; q < len; ++q) {
    out[q].template head<Dim>() = A.gf[q] * A.r[q];  // grad_i W_ij
    if (kViscous && free) out[q][Dim] = A.c[q];
    if (kStressTerm && free) out[q][Dim + 1] = A.f[q];
  }
}

template <int Dim, class Scalar, ViscositySwitch kViscosity, bool kStressTerm, class KernelRows>
template <bool kRing>
void PlainRows<Dim, Scalar, kViscosity, kStressTerm, KernelRows>::sums(const Arrays A, int i, std::size_t base) const {
  const bool free = e.x_off[i] >= 0;
  const bool summation = e.o.continuity == ContinuityForm::Summation;
  const long k0 = A.off[i];
  const std::size_t len = A.off[i + 1] - k0;
  Mat L = Mat::Zero();
  Scalar drho(0);
  Vec acc = Vec::Zero();
  const Mat& si = A.sigma_rho2[i];
  const Kept* const in = kRing ? A.kept + base : nullptr;
  for (std::size_t q = 0; q < len; ++q) {
    const int j = A.idx[k0 + q];
    if (j == i) continue;
    Vec gk;  // grad_i W_ij
    if constexpr (kRing)
      gk = in[q].template head<Dim>();
    else
      gk = A.gf[q] * A.r[q];
    const Vec dv = A.vhat[j] - A.vhat[i];
    add_velocity_gradient(L, A.vol[j] * dv, gk);  // continuity.hpp
    if (summation) drho -= continuity_term(A.mass[j], dv, gk);
    if (!free) continue;
    if constexpr (!kViscous && !kStressTerm) {
      // Powell (1.36): m_j grad W_ij = rho_j Ghat_ij. (Adding the zero pair matrix would change no result: acc starts
      // at +0, so a zero's sign cannot reach it.)
      acc += A.mass[j] * ((si + A.sigma_rho2[j]) * gk);
    } else {
      // Pair terms: viscosity and artificial stress.
      Mat pair = Mat::Zero();
      if constexpr (kViscous) pair -= (kRing ? in[q][Dim] : A.c[q]) * Mat::Identity();
      if constexpr (kStressTerm) pair += (kRing ? in[q][Dim + 1] : A.f[q]) * (A.R[i] + A.R[j]);
      acc += A.mass[j] * ((si + A.sigma_rho2[j] + pair) * gk);
    }
  }
  e.finish(i, free, L, drho, acc);
}

template <int Dim, class Scalar, ViscositySwitch kViscosity, bool kStressTerm, class KernelRows>
void PlainRows<Dim, Scalar, kViscosity, kStressTerm, KernelRows>::two_passes() {
  // The same operations as the rows summed late in ring_pass, so the same bits as one thread. A failure is kept, not
  // thrown, so that every thread reaches both loops' barriers. A partition sums its rows and needs the XSPH velocities
  // of their neighbours, rows [lo, hi).
  const NeighbourList& nl = e.nl;
  const int first = e.first, last = e.last;
  int lo = first, hi = last;
  if (e.partial)
    for (long k = nl.offsets[first]; k < nl.offsets[last]; ++k) {
      lo = std::min(lo, nl.indices[k]);
      hi = std::max(hi, nl.indices[k] + 1);
    }
  std::exception_ptr error;
#pragma omp parallel num_threads(e.threads)
  {
    const Arrays At = arrays(thread_index());
#pragma omp for schedule(static)
    for (int t = lo; t < hi; ++t) try {
        if (xsph && e.x_off[t] >= 0 && !e.is_driven(t))
          pair_functions<true>(At, t, false, 0);
        else
          e.ws.vhat[t] = e.ws.v[t];
      } catch (...) {
#pragma omp critical(sphstab_rate_form_error)
        if (!error) error = std::current_exception();
      }
#pragma omp for schedule(static)
    for (int t = first; t < last; ++t) try {
        if (!e.summed(t)) continue;
        pair_functions<false>(At, t, true, kNow);
        sums<false>(At, t, kNow);
      } catch (...) {
#pragma omp critical(sphstab_rate_form_error)
        if (!error) error = std::current_exception();
      }
  }
  if (error) std::rethrow_exception(error);
}

template <int Dim, class Scalar, ViscositySwitch kViscosity, bool kStressTerm, class KernelRows>
void PlainRows<Dim, Scalar, kViscosity, kStressTerm, KernelRows>::one_pass() {
  // vhat = v: each row summed right after its pair functions.
  const Arrays A = arrays(0);
  for (int t = 0; t < e.n; ++t) e.ws.vhat[t] = e.ws.v[t];
  for (int t = 0; t < e.n; ++t)
    if (e.summed(t)) {
      pair_functions<false>(A, t, true, kNow);
      sums<false>(A, t, kNow);
    }
}

template <int Dim, class Scalar, ViscositySwitch kViscosity, bool kStressTerm, class KernelRows>
void PlainRows<Dim, Scalar, kViscosity, kStressTerm, KernelRows>::ring_pass() {
  const Arrays A = arrays(0);
  const NeighbourList& nl = e.nl;
  const int n = e.n;
  const std::vector<long>& ready = e.ws.ready;
  std::vector<long>& ring_start = e.ws.ring_start;  // where row i's kept pair results start
  std::vector<int>& late = e.ws.late;               // rows summed at the end
  late.clear();
  int next = 0;  // the next row to sum, in index order
  const auto sum_ready = [&](int t) {
    for (; next <= t; ++next) {
      if (!e.summed(next)) continue;
      if (!kept(next)) {
        late.push_back(next);
        continue;
      }
      if (ready[next] > t) break;
      sums<true>(A, next, ring_start[next]);
    }
  };
  std::size_t position = 0;
  for (int t = 0; t < n; ++t) {
    // Fixed particles do not move; driven ones move with v.
    const bool with_xsph = e.x_off[t] >= 0 && !e.is_driven(t), keep = e.summed(t) && kept(t);
    if (!with_xsph) e.ws.vhat[t] = e.ws.v[t];
    if (keep) {
      const std::size_t len = nl.offsets[t + 1] - nl.offsets[t];
      if (position + len > ring) position = 0;
      ring_start[t] = position;
      position += len;
    }
    if (with_xsph)
      pair_functions<true>(A, t, keep, keep ? ring_start[t] : 0);
    else if (keep)
      pair_functions<false>(A, t, true, ring_start[t]);
    sum_ready(t);
  }
  sum_ready(n - 1);
  for (int i : late) {
    pair_functions<false>(A, i, true, kNow);
    sums<false>(A, i, kNow);
  }
}

/// The plain row loop for the scheme's kernel and active terms.
template <int Dim, class Scalar>
void plain_rows(Evaluation<Dim, Scalar>& e) {
  with_kernel_functions(e.kernel, e.h, [&](const auto& kf) {
    with_term_tags(e.o.viscosity, e.o.artificial_stress > 0, [&](auto viscosity_tag, auto stress_tag) {
      PlainRows<Dim, Scalar, decltype(viscosity_tag)::value, decltype(stress_tag)::value, std::decay_t<decltype(kf)>>(
          e, kf)
          .run();
    });
  });
}

}  // namespace sphstab::rate_form_detail
