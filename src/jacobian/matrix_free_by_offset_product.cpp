// The products of MatrixFreeLinearisation with ByOffset storage (header comment of matrix_free_linearisation.hpp):
// A0 and A1 as stencil sweeps over the padded grids of the free box, from the offset tables that
// matrix_free_linearisation.cpp builds (build_by_offset).
#include <algorithm>
#include <array>

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

}  // namespace

template <int Dim>
void MatrixFreeLinearisation<Dim>::apply_by_offset(double c0, double c1, const double* xp, double* yp,
                                                   double* y1p) const {
  constexpr int S = kSymmetric;
  const bool with_a0 = c0 != 0.0, with_a1 = c1 != 0.0 && m_a1_factor != 0.0;
  const int r = m_reach;
  const long grid = m_grid, half = static_cast<long>(m_shift.size());
  const long* shift = m_shift.data();
  const double* og = m_og.data();
  const double* ob = m_ob.data();
  double* u = m_u.data();
  double* sg = m_sgrid.data();
  const double lam = m_lambda, mu = m_mu, a0_scale = -c0 * m_inv_rho;
  std::array<int, Dim> free_lines = m_box, stress_lines = m_box;
  long lines_free = 1, lines_stress = 1;
  for (int a = 1; a < Dim; ++a) {
    stress_lines[a] += 2 * r;
    lines_free *= free_lines[a];
    lines_stress *= stress_lines[a];
  }
  const int n0 = m_box[0];

  // x into the padded grids (the free box starts at grid coordinate 2 r; the rest stays zero).
#pragma omp parallel for schedule(static) num_threads(threads_for(lines_free* n0))
  for (long line = 0; line < lines_free; ++line) {
    const long g = line_start<Dim>(line, free_lines, 2 * r, m_stride);
    const double* xl = xp + Dim * n0 * line;
    for (int c = 0; c < Dim; ++c)
      for (int i = 0; i < n0; ++i) u[c * grid + g + i] = xl[Dim * i + c];
  }

  if (with_a0) {
    // Steps 1-2 on the free box padded by r: (grad x)_j^{cd} = sum_{D+} G^d(o) (x^c_{j+o} - x^c_{j-o}), then sigma_j.
    // Whole lines per thread, each summed in offset order: the same bits for any thread count.
    const int len = n0 + 2 * r;
#pragma omp parallel for schedule(static) num_threads(threads_for(lines_stress* len))
    for (long line = 0; line < lines_stress; ++line) {
      const long g0 = line_start<Dim>(line, stress_lines, r, m_stride);
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
          for (int c = 0; c < Dim; ++c) sg[c * grid + g + i] = lam * tr + 2 * mu * gr[Dim * c + c][i];
          for (int c = 0; c < Dim; ++c)
            for (int e = c + 1; e < Dim; ++e)
              sg[voigt(c, e) * grid + g + i] = mu * (gr[Dim * c + e][i] + gr[Dim * e + c][i]);
        }
      }
    }
  }

  // Step 3 and A1 on the free box: y = -(c0/rho) sum_{D+} G^b(o) (sigma^{ab}_{i+o} - sigma^{ab}_{i-o})
  //                                    + c1 (B(0) x_i + sum_{D+} B(o) (x_{i+o} + x_{i-o})).
  const Stress b0 = m_b0;
#pragma omp parallel for schedule(static) num_threads(threads_for(lines_free* n0))
  for (long line = 0; line < lines_free; ++line) {
    const long g0 = line_start<Dim>(line, free_lines, 2 * r, m_stride);
    double* yl = yp + Dim * n0 * line;
    for (int x0 = 0; x0 < n0; x0 += kChunk) {
      const int m = std::min(kChunk, n0 - x0);
      const long g = g0 + x0;
      double div[Dim][kChunk] = {}, a1[Dim][kChunk] = {};
      if (with_a0)
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
      if (with_a1) {
#pragma omp simd
        for (int i = 0; i < m; ++i)
          for (int a = 0; a < Dim; ++a) {
            double t = b0(a, 0) * u[g + i];
            for (int c = 1; c < Dim; ++c) t += b0(a, c) * u[c * grid + g + i];
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
      if (y1p) {  // the two products apart, each bit as its own call gives it (0 + t there: a -0 becomes +0)
        double* y1l = y1p + Dim * n0 * line;
        for (int i = 0; i < m; ++i)
          for (int a = 0; a < Dim; ++a) {
            yl[Dim * (x0 + i) + a] = with_a0 ? a0_scale * div[a][i] : 0.0;
            y1l[Dim * (x0 + i) + a] = with_a1 ? 0.0 + c1 * a1[a][i] : 0.0;
          }
        continue;
      }
      for (int i = 0; i < m; ++i)
        for (int a = 0; a < Dim; ++a) {
          double out = 0;
          if (with_a0) out = a0_scale * div[a][i];
          if (with_a1) out += c1 * a1[a][i];
          yl[Dim * (x0 + i) + a] = out;
        }
    }
  }
}

// The member alone: matrix_free_linearisation.cpp instantiates the class.
template void MatrixFreeLinearisation<2>::apply_by_offset(double, double, const double*, double*, double*) const;
template void MatrixFreeLinearisation<3>::apply_by_offset(double, double, const double*, double*, double*) const;

}  // namespace sphstab
