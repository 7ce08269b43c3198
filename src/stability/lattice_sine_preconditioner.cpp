#include "sphstab/stability/lattice_sine_preconditioner.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/core/threads.hpp"

namespace sphstab {

/// One in-place 2D RODFT00 plan of an n x n contiguous buffer (fftw_malloc alignment), executed on other buffers of
/// the same alignment through the new-array interface (thread-safe).
struct LatticeSinePreconditioner::Plan {
  fftw_plan plan = nullptr;
  ~Plan() {
    if (plan) fftw_destroy_plan(plan);
  }
};

namespace {

struct FftwBuffer {
  explicit FftwBuffer(std::size_t count) : p(fftw_alloc_real(count)) {
    if (!p) throw std::bad_alloc();
  }
  ~FftwBuffer() { fftw_free(p); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  double* p;
};

/// Diagonal (cc) symbol sum_d S(d)_cc cos(kx di + ky dj) on the grid k = pi m / (n + 1), m = 1..n, both directions;
/// out[c][j n + i] at (kx, ky) = (k_i, k_j). Separable: cos(a + b) = cos a cos b - sin a sin b, O(n^2 radius).
void diagonal_symbol(const LatticeStencil& st, bool of_k, int n, std::vector<double> out[2]) {
  const int r = st.radius, w = st.width();
  std::vector<double> cs(static_cast<std::size_t>(n) * w), sn(static_cast<std::size_t>(n) * w);
  for (int m = 0; m < n; ++m)
    for (int d = -r; d <= r; ++d) {
      const double a = std::numbers::pi * (m + 1) / (n + 1) * d;
      cs[static_cast<std::size_t>(m) * w + d + r] = std::cos(a);
      sn[static_cast<std::size_t>(m) * w + d + r] = std::sin(a);
    }
  for (int c = 0; c < 2; ++c) {
    // a(dj, i) = sum_di S_cc(di, dj) cos(k_i di), b(dj, i) = sum_di S_cc(di, dj) sin(k_i di)
    std::vector<double> a(static_cast<std::size_t>(w) * n, 0.0), b(static_cast<std::size_t>(w) * n, 0.0);
    for (int dj = -r; dj <= r; ++dj)
      for (int i = 0; i < n; ++i) {
        double sa = 0, sb = 0;
        for (int di = -r; di <= r; ++di) {
          const double s = (of_k ? st.k_at(di, dj) : st.l_at(di, dj))(c, c);
          sa += s * cs[static_cast<std::size_t>(i) * w + di + r];
          sb += s * sn[static_cast<std::size_t>(i) * w + di + r];
        }
        a[static_cast<std::size_t>(dj + r) * n + i] = sa;
        b[static_cast<std::size_t>(dj + r) * n + i] = sb;
      }
    out[c].assign(static_cast<std::size_t>(n) * n, 0.0);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double v = 0;
        for (int dj = -r; dj <= r; ++dj)
          v += a[static_cast<std::size_t>(dj + r) * n + i] * cs[static_cast<std::size_t>(j) * w + dj + r] -
               b[static_cast<std::size_t>(dj + r) * n + i] * sn[static_cast<std::size_t>(j) * w + dj + r];
        out[c][static_cast<std::size_t>(j) * n + i] = v;
      }
  }
}

}  // namespace

LatticeSinePreconditioner::LatticeSinePreconditioner(const LatticeStencil& st, int n, double margin, bool measure) {
  const std::string who = "LatticeSinePreconditioner";
  if (n < 1) throw std::invalid_argument(who + ": need n >= 1 particles per side (got " + std::to_string(n) + ")");
  if (!(margin > 0) || !std::isfinite(margin))
    throw std::invalid_argument(who + ": margin must be finite and > 0 (got " + format_number(margin, 3) + ")");
  if (st.radius < 0 || st.k.size() != static_cast<std::size_t>(st.width() * st.width()) || st.l.size() != st.k.size())
    throw std::invalid_argument(who + ": stencil blocks do not match its radius (use probe_lattice_stencil)");
  m_n = n;
  std::vector<double> kh[2], lh[2];
  diagonal_symbol(st, true, n, kh);
  diagonal_symbol(st, false, n, lh);
  const std::size_t nn = static_cast<std::size_t>(n) * n;
  double top = -std::numeric_limits<double>::infinity();
  for (int c = 0; c < 2; ++c)
    for (std::size_t q = 0; q < nn; ++q) {
      if (!(kh[c][q] > 0))
        throw std::invalid_argument(who + ": the symbol of K (component " + std::to_string(c) + ") is " +
                                    format_number(kh[c][q], 3) + " <= 0 at grid point (i, j) = (" +
                                    std::to_string(q % n) + ", " + std::to_string(q / n) +
                                    "): K = A0 is not positive definite on the lattice interior");
      top = std::max(top, lh[c][q] / kh[c][q]);
    }
  if (!(top > 0))
    throw std::invalid_argument(who + ": the symbol ratio L/K is <= 0 on the whole grid (max " + format_number(top, 3) +
                                "): no instability of the lattice interior in this direction, use no preconditioner");
  m_symbol_max = top;
  m_sigma = (1 + margin) * top;
  const double norm = 1.0 / (4.0 * (n + 1.0) * (n + 1.0));
  m_scaled.resize(2 * nn);
  for (int c = 0; c < 2; ++c)
    for (std::size_t q = 0; q < nn; ++q) m_scaled[c * nn + q] = norm / (m_sigma * kh[c][q] - lh[c][q]);

  FftwBuffer buf(nn);
  m_plan = std::make_unique<Plan>();
  m_plan->plan =
      fftw_plan_r2r_2d(n, n, buf.p, buf.p, FFTW_RODFT00, FFTW_RODFT00, measure ? FFTW_MEASURE : FFTW_ESTIMATE);
  if (!m_plan->plan)
    throw std::runtime_error(who + ": FFTW could not plan a " + std::to_string(n) + " x " + std::to_string(n) +
                             " DST-I");
}

LatticeSinePreconditioner::~LatticeSinePreconditioner() = default;
LatticeSinePreconditioner::LatticeSinePreconditioner(LatticeSinePreconditioner&&) noexcept = default;
LatticeSinePreconditioner& LatticeSinePreconditioner::operator=(LatticeSinePreconditioner&&) noexcept = default;

double LatticeSinePreconditioner::eigenvalue(int c, int i, int j) const {
  if (c < 0 || c > 1 || i < 0 || i >= m_n || j < 0 || j >= m_n)
    throw std::invalid_argument("LatticeSinePreconditioner::eigenvalue: (c, i, j) = (" + std::to_string(c) + ", " +
                                std::to_string(i) + ", " + std::to_string(j) + ") outside c in {0, 1}, i, j in [0, " +
                                std::to_string(m_n) + ")");
  const std::size_t nn = static_cast<std::size_t>(m_n) * m_n;
  return m_scaled[c * nn + static_cast<std::size_t>(j) * m_n + i] * 4.0 * (m_n + 1.0) * (m_n + 1.0);
}

void LatticeSinePreconditioner::apply(const Eigen::Ref<const Eigen::MatrixXd>& x, Eigen::Ref<Eigen::MatrixXd> y) const {
  if (x.rows() != dofs() || y.rows() != dofs() || x.cols() != y.cols() || x.cols() < 1)
    throw std::invalid_argument("LatticeSinePreconditioner::apply: x is " + std::to_string(x.rows()) + " x " +
                                std::to_string(x.cols()) + " and y " + std::to_string(y.rows()) + " x " +
                                std::to_string(y.cols()) + ", need dofs = " + std::to_string(dofs()) +
                                " rows and the same number (>= 1) of columns");
  const int b = static_cast<int>(x.cols()), tasks = 2 * b, n = m_n;
  const std::size_t nn = static_cast<std::size_t>(n) * n;
  const int threads = std::max(1, std::min(max_threads(), tasks));
  const fftw_plan plan = m_plan->plan;
  const double* scaled = m_scaled.data();
#pragma omp parallel num_threads(threads)
  {
    FftwBuffer buf(nn);
#pragma omp for schedule(static)
    for (int t = 0; t < tasks; ++t) {
      const int v = t / 2, c = t % 2;
      const double* xv = x.col(v).data();
      for (std::size_t q = 0; q < nn; ++q) buf.p[q] = xv[2 * q + c];
      fftw_execute_r2r(plan, buf.p, buf.p);
      const double* s = scaled + c * nn;
      for (std::size_t q = 0; q < nn; ++q) buf.p[q] *= s[q];
      fftw_execute_r2r(plan, buf.p, buf.p);
      double* yv = y.col(v).data();
      for (std::size_t q = 0; q < nn; ++q) yv[2 * q + c] = buf.p[q];
    }
  }
}

}  // namespace sphstab
