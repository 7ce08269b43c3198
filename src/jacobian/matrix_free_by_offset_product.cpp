// The products of MatrixFreeLinearisation with ByOffset storage (header comment of matrix_free_linearisation.hpp):
// A0 and A1 as stencil sweeps over the padded grids of the free box, from the offset tables that
// matrix_free_linearisation.cpp builds (build_by_offset). The sweeps are compiled twice, for the x86-64 baseline and
// for AVX2, and the one the CPU supports runs: the same bits (core/simd_dispatch.hpp).
#include <algorithm>
#include <array>

#include "sphstab/core/simd_dispatch.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"

namespace sphstab {

namespace {

/// Line segments of the lattice loops: short enough that the per-line accumulators stay in the L1 cache.
constexpr int kChunk = 128;

/// The grid index of the first site of line `line` of a box whose lines (along x) start at grid coordinate `lo` on
/// every axis and number `lines_of[a]` per axis a >= 1.
template <int Dim>
long line_start(long line, const std::array<int, Dim>& lines_of, int lo, const std::array<long, Dim>& stride) {
  long g = lo;
  for (int a = 1; a < Dim; ++a) {
    g += (lo + line % lines_of[a]) * stride[a];
    line /= lines_of[a];
  }
  return g;
}

/// The three sweeps of a product, each over whole lines along x (so that any split of the lines between threads
/// gives the same bits).
enum class Sweep {
  Scatter,    ///< x into the padded grids
  Stress,     ///< steps 1-2: the displacement gradient and sigma on the free box padded by r
  Divergence  ///< step 3 and A1 on the free box, into y (and y1)
};

/// What the sweeps read and write: the linearisation's offset tables, grids and constants for one product.
template <int Dim>
struct ByOffsetProduct {
  bool with_a0, with_a1;
  int r;
  long grid, half;
  const long* shift;
  const double* og;
  const double* ob;
  double* u;
  double* sg;
  double lam, mu, a0_scale, c1;
  double b0[Dim][Dim];
  std::array<int, Dim> free_lines, stress_lines;  ///< lines per axis (axis 0: the sites of a line)
  std::array<long, Dim> stride;
  const double* x;
  double* y;
  double* y1;
};

/// Lines [l0, l1) of one sweep. Inlined into a baseline and an AVX2 build below; no OpenMP region inside (GCC
/// outlines a region before inlining, so a region here would run the baseline build in both).
template <int Dim>
__attribute__((always_inline)) inline void sweep_lines(const ByOffsetProduct<Dim>& w, Sweep which, long l0, long l1) {
  constexpr int S = MatrixFreeLinearisation<Dim>::kSymmetric;
  constexpr auto voigt = MatrixFreeLinearisation<Dim>::voigt;
  const int r = w.r, n0 = w.free_lines[0];
  const long grid = w.grid, half = w.half;
  const long* shift = w.shift;
  const double *og = w.og, *ob = w.ob;
  double *u = w.u, *sg = w.sg;

  if (which == Sweep::Scatter) {
    // The free box starts at grid coordinate 2 r; the rest stays zero.
    for (long line = l0; line < l1; ++line) {
      const long g = line_start<Dim>(line, w.free_lines, 2 * r, w.stride);
      const double* xl = w.x + Dim * n0 * line;
      for (int c = 0; c < Dim; ++c)
        for (int i = 0; i < n0; ++i) u[c * grid + g + i] = xl[Dim * i + c];
    }
    return;
  }

  if (which == Sweep::Stress) {
    // (grad x)_j^{cd} = sum_{D+} G^d(o) (x^c_{j+o} - x^c_{j-o}), then sigma_j; each line summed in offset order.
    const int len = w.stress_lines[0];
    for (long line = l0; line < l1; ++line) {
      const long g0 = line_start<Dim>(line, w.stress_lines, r, w.stride);
      for (int x0 = 0; x0 < len; x0 += kChunk) {
        const int m = std::min(kChunk, len - x0);
        const long g = g0 + x0;
        double gr[Dim * Dim][kChunk] = {};  // gr[Dim c + d]: component c, derivative d
        for (long o = 0; o < half; ++o) {
          const double* go = og + Dim * o;
          const double* up = u + g + shift[o];
          const double* um = u + g - shift[o];
#pragma omp simd
          for (int i = 0; i < m; ++i)
            for (int c = 0; c < Dim; ++c) {
              const double dv = up[c * grid + i] - um[c * grid + i];
              for (int e = 0; e < Dim; ++e) gr[Dim * c + e][i] += go[e] * dv;
            }
        }
#pragma omp simd
        for (int i = 0; i < m; ++i) {
          double tr = gr[0][i];
          for (int c = 1; c < Dim; ++c) tr += gr[Dim * c + c][i];
          for (int c = 0; c < Dim; ++c) sg[c * grid + g + i] = w.lam * tr + 2 * w.mu * gr[Dim * c + c][i];
          for (int c = 0; c < Dim; ++c)
            for (int e = c + 1; e < Dim; ++e)
              sg[voigt(c, e) * grid + g + i] = w.mu * (gr[Dim * c + e][i] + gr[Dim * e + c][i]);
        }
      }
    }
    return;
  }

  // y = -(c0/rho) sum_{D+} G^b(o) (sigma^{ab}_{i+o} - sigma^{ab}_{i-o}) + c1 (B(0) x_i + sum_{D+} B(o) (x_{i+o} +
  // x_{i-o})).
  for (long line = l0; line < l1; ++line) {
    const long g0 = line_start<Dim>(line, w.free_lines, 2 * r, w.stride);
    double* yl = w.y + Dim * n0 * line;
    for (int x0 = 0; x0 < n0; x0 += kChunk) {
      const int m = std::min(kChunk, n0 - x0);
      const long g = g0 + x0;
      double div[Dim][kChunk] = {}, a1[Dim][kChunk] = {};
      if (w.with_a0)
        for (long o = 0; o < half; ++o) {
          const double* go = og + Dim * o;
          const double* sp = sg + g + shift[o];
          const double* sm = sg + g - shift[o];
#pragma omp simd
          for (int i = 0; i < m; ++i) {
            double ds[S];
            for (int k = 0; k < S; ++k) ds[k] = sp[k * grid + i] - sm[k * grid + i];
            for (int a = 0; a < Dim; ++a) {
              double t = go[0] * ds[voigt(a, 0)];
              for (int b = 1; b < Dim; ++b) t += go[b] * ds[voigt(a, b)];
              div[a][i] += t;
            }
          }
        }
      if (w.with_a1) {
#pragma omp simd
        for (int i = 0; i < m; ++i)
          for (int a = 0; a < Dim; ++a) {
            double t = w.b0[a][0] * u[g + i];
            for (int c = 1; c < Dim; ++c) t += w.b0[a][c] * u[c * grid + g + i];
            a1[a][i] = t;
          }
        for (long o = 0; o < half; ++o) {
          const double* bo = ob + Dim * Dim * o;
          const double* up = u + g + shift[o];
          const double* um = u + g - shift[o];
#pragma omp simd
          for (int i = 0; i < m; ++i) {
            double v[Dim];
            for (int c = 0; c < Dim; ++c) v[c] = up[c * grid + i] + um[c * grid + i];
            for (int a = 0; a < Dim; ++a) {
              double t = bo[Dim * a] * v[0];
              for (int c = 1; c < Dim; ++c) t += bo[Dim * a + c] * v[c];
              a1[a][i] += t;
            }
          }
        }
      }
      if (w.y1) {  // the two products apart, each bit as its own call gives it (0 + t there: a -0 becomes +0)
        double* y1l = w.y1 + Dim * n0 * line;
        for (int i = 0; i < m; ++i)
          for (int a = 0; a < Dim; ++a) {
            yl[Dim * (x0 + i) + a] = w.with_a0 ? w.a0_scale * div[a][i] : 0.0;
            y1l[Dim * (x0 + i) + a] = w.with_a1 ? 0.0 + w.c1 * a1[a][i] : 0.0;
          }
        continue;
      }
      for (int i = 0; i < m; ++i)
        for (int a = 0; a < Dim; ++a) {
          double out = 0;
          if (w.with_a0) out = w.a0_scale * div[a][i];
          if (w.with_a1) out += w.c1 * a1[a][i];
          yl[Dim * (x0 + i) + a] = out;
        }
    }
  }
}

template <int Dim>
void sweep_lines_portable(const ByOffsetProduct<Dim>& w, Sweep which, long l0, long l1) {
  sweep_lines(w, which, l0, l1);
}

#if SPHSTAB_HAS_AVX2_CLONES
template <int Dim>
SPHSTAB_TARGET_AVX2 void sweep_lines_avx2(const ByOffsetProduct<Dim>& w, Sweep which, long l0, long l1) {
  sweep_lines(w, which, l0, l1);
}
#endif

}  // namespace

template <int Dim>
void MatrixFreeLinearisation<Dim>::apply_by_offset(double c0, double c1, const double* xp, double* yp,
                                                   double* y1p) const {
  ByOffsetProduct<Dim> w{.with_a0 = c0 != 0.0,
                         .with_a1 = c1 != 0.0 && m_a1_factor != 0.0,
                         .r = m_reach,
                         .grid = m_grid,
                         .half = static_cast<long>(m_shift.size()),
                         .shift = m_shift.data(),
                         .og = m_og.data(),
                         .ob = m_ob.data(),
                         .u = m_u.data(),
                         .sg = m_sgrid.data(),
                         .lam = m_lambda,
                         .mu = m_mu,
                         .a0_scale = -c0 * m_inv_rho,
                         .c1 = c1,
                         .b0 = {},
                         .free_lines = m_box,
                         .stress_lines = m_box,
                         .stride = m_stride,
                         .x = xp,
                         .y = yp,
                         .y1 = y1p};
  for (int a = 0; a < Dim; ++a)
    for (int c = 0; c < Dim; ++c) w.b0[a][c] = m_b0(a, c);
  long lines_free = 1, lines_stress = 1;
  for (int a = 0; a < Dim; ++a) w.stress_lines[a] += 2 * m_reach;
  for (int a = 1; a < Dim; ++a) {
    lines_free *= w.free_lines[a];
    lines_stress *= w.stress_lines[a];
  }
  const bool avx2 = avx2_enabled();
  // Each sweep's lines in one contiguous block per thread (OpenMP's static schedule); the sweeps one after another.
  const auto run = [&](Sweep which, long lines, int sites_per_line) {
    const int threads = threads_for(lines * sites_per_line);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int t = 0; t < threads; ++t) {
      const long l0 = lines * t / threads, l1 = lines * (t + 1) / threads;
#if SPHSTAB_HAS_AVX2_CLONES
      if (avx2) {
        sweep_lines_avx2(w, which, l0, l1);
        continue;
      }
#endif
      sweep_lines_portable(w, which, l0, l1);
    }
  };
  run(Sweep::Scatter, lines_free, m_box[0]);
  if (w.with_a0) run(Sweep::Stress, lines_stress, w.stress_lines[0]);
  run(Sweep::Divergence, lines_free, m_box[0]);
}

// The member alone: matrix_free_linearisation.cpp instantiates the class.
template void MatrixFreeLinearisation<2>::apply_by_offset(double, double, const double*, double*, double*) const;
template void MatrixFreeLinearisation<3>::apply_by_offset(double, double, const double*, double*, double*) const;

}  // namespace sphstab
