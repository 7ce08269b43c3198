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

/// One in-place RODFT00 plan of an n^Dim contiguous buffer (fftw_malloc alignment), executed on other buffers of
/// the same alignment through the new-array interface (thread-safe).
template <int Dim>
struct LatticeSinePreconditioner<Dim>::Plan {
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

/// Diagonal (cc) symbol sum_d S(d)_cc cos(k . d) on the grid k = pi m / (n + 1), m = 1..n, every direction;
/// out[c][i + n j (+ n^2 k)]. Separable, one direction at a time with cos and sin parts (cos(a + b) = cos a cos b -
/// sin a sin b): O(n r^Dim + ... + n^Dim r).
template <int Dim>
void diagonal_symbol(const LatticeStencil<Dim>& st, bool of_k, int n, std::vector<double> out[Dim]) {
  const int r = st.radius, w = st.width();
  const std::size_t N = n, W = w;
  std::vector<double> cs(N * W), sn(N * W);
  for (int m = 0; m < n; ++m)
    for (int d = -r; d <= r; ++d) {
      const double a = std::numbers::pi * (m + 1) / (n + 1) * d;
      cs[m * W + d + r] = std::cos(a);
      sn[m * W + d + r] = std::sin(a);
    }
  std::size_t offsets = 1;  // offsets along the directions y[, z]
  for (int a = 1; a < Dim; ++a) offsets *= W;
  for (int c = 0; c < Dim; ++c) {
    std::size_t rest = offsets;  // offsets along the directions not yet transformed
    // Direction x: a(rest, i) = sum_di S_cc(di, rest) cos(k_i di), b(rest, i) = ... sin(k_i di).
    std::vector<double> a(rest * N, 0.0), b(rest * N, 0.0);
    for (std::size_t q = 0; q < rest; ++q)
      for (int i = 0; i < n; ++i) {
        double sa = 0, sb = 0;
        for (int di = -r; di <= r; ++di) {
          const double s = (of_k ? st.k : st.l)[q * W + di + r](c, c);
          sa += s * cs[i * W + di + r];
          sb += s * sn[i * W + di + r];
        }
        a[q * N + i] = sa;
        b[q * N + i] = sb;
      }
    std::size_t done = N;  // grid points of the directions already transformed
    if constexpr (Dim == 3) {
      // Direction y (complex): (a + i b)(rest = (dk), done = (i)) -> (dk, i + n j).
      rest /= W;
      std::vector<double> a2(rest * done * N, 0.0), b2(rest * done * N, 0.0);
      for (std::size_t q = 0; q < rest; ++q)
        for (int j = 0; j < n; ++j)
          for (std::size_t i = 0; i < done; ++i) {
            double re = 0, im = 0;
            for (int dj = -r; dj <= r; ++dj) {
              const std::size_t src = (q * W + dj + r) * done + i;
              const double cj = cs[j * W + dj + r], sj = sn[j * W + dj + r];
              re += a[src] * cj - b[src] * sj;
              im += a[src] * sj + b[src] * cj;
            }
            a2[(q * N + j) * done + i] = re;
            b2[(q * N + j) * done + i] = im;
          }
      a.swap(a2);
      b.swap(b2);
      done *= N;
    }
    // Last direction: the real part.
    out[c].assign(done * N, 0.0);
    for (int j = 0; j < n; ++j)
      for (std::size_t i = 0; i < done; ++i) {
        double v = 0;
        for (int dj = -r; dj <= r; ++dj)
          v += a[(dj + r) * done + i] * cs[j * W + dj + r] - b[(dj + r) * done + i] * sn[j * W + dj + r];
        out[c][j * done + i] = v;
      }
  }
}

/// max over the grid and components of lh / kh; throws when kh is not positive somewhere.
template <int Dim>
double symbol_ratio_max(const std::vector<double> kh[Dim], const std::vector<double> lh[Dim], int n,
                        const std::string& who) {
  double top = -std::numeric_limits<double>::infinity();
  for (int c = 0; c < Dim; ++c)
    for (std::size_t q = 0; q < kh[c].size(); ++q) {
      if (!(kh[c][q] > 0)) {
        std::string at = std::to_string(q % n);
        for (std::size_t rest = q / n, a = 1; a < Dim; ++a, rest /= n) at += ", " + std::to_string(rest % n);
        throw std::invalid_argument(who + ": the symbol of K (component " + std::to_string(c) + ") is " +
                                    format_number(kh[c][q], 3) + " <= 0 at grid point " +
                                    (Dim == 2 ? "(i, j) = (" : "(i, j, k) = (") + at +
                                    "): K = A0 is not positive definite on the lattice interior");
      }
      top = std::max(top, lh[c][q] / kh[c][q]);
    }
  return top;
}

}  // namespace

template <int Dim>
long LatticeSinePreconditioner<Dim>::sites() const {
  long s = 1;
  for (int a = 0; a < Dim; ++a) s *= m_n;
  return s;
}

template <int Dim>
LatticeSinePreconditioner<Dim>::LatticeSinePreconditioner(const LatticeStencil<Dim>& st, int n, double margin,
                                                          bool measure) {
  const std::string who = "LatticeSinePreconditioner";
  if (n < 1) throw std::invalid_argument(who + ": need n >= 1 particles per side (got " + std::to_string(n) + ")");
  if (!(margin > 0) || !std::isfinite(margin))
    throw std::invalid_argument(who + ": margin must be finite and > 0 (got " + format_number(margin, 3) + ")");
  if (st.radius < 0 || static_cast<long>(st.k.size()) != st.blocks() || st.l.size() != st.k.size())
    throw std::invalid_argument(who + ": stencil blocks do not match its radius (use probe_lattice_stencil)");
  m_n = n;
  std::vector<double> kh[Dim], lh[Dim];
  diagonal_symbol<Dim>(st, true, n, kh);
  diagonal_symbol<Dim>(st, false, n, lh);
  const std::size_t nn = sites();
  const double top = symbol_ratio_max<Dim>(kh, lh, n, who);
  if (!(top > 0))
    throw std::invalid_argument(who + ": the symbol ratio L/K is <= 0 on the whole grid (max " + format_number(top, 3) +
                                "): no instability of the lattice interior in this direction, use no preconditioner");
  m_symbol_max = top;
  m_sigma = (1 + margin) * top;
  m_transform_scale = 1;
  for (int a = 0; a < Dim; ++a) m_transform_scale *= 2.0 * (n + 1.0);
  const double norm = 1.0 / m_transform_scale;
  m_scaled.resize(Dim * nn);
  for (int c = 0; c < Dim; ++c)
    for (std::size_t q = 0; q < nn; ++q) m_scaled[c * nn + q] = norm / (m_sigma * kh[c][q] - lh[c][q]);

  FftwBuffer buf(nn);
  int dims[Dim];
  fftw_r2r_kind kinds[Dim];
  for (int a = 0; a < Dim; ++a) dims[a] = n, kinds[a] = FFTW_RODFT00;
  m_plan = std::make_unique<Plan>();
  m_plan->plan = fftw_plan_r2r(Dim, dims, buf.p, buf.p, kinds, measure ? FFTW_MEASURE : FFTW_ESTIMATE);
  if (!m_plan->plan)
    throw std::runtime_error(who + ": FFTW could not plan a " + std::to_string(n) + "^" + std::to_string(Dim) +
                             " DST-I");
}

template <int Dim>
LatticeSinePreconditioner<Dim>::~LatticeSinePreconditioner() = default;
template <int Dim>
LatticeSinePreconditioner<Dim>::LatticeSinePreconditioner(LatticeSinePreconditioner&&) noexcept = default;
template <int Dim>
LatticeSinePreconditioner<Dim>& LatticeSinePreconditioner<Dim>::operator=(LatticeSinePreconditioner&&) noexcept =
    default;

template <int Dim>
double LatticeSinePreconditioner<Dim>::eigenvalue_at(int c, const std::array<int, Dim>& site) const {
  bool inside = c >= 0 && c < Dim;
  std::size_t q = 0;
  for (int a = Dim - 1; a >= 0; --a) {
    inside = inside && site[a] >= 0 && site[a] < m_n;
    q = q * m_n + site[a];
  }
  if (!inside) {
    std::string at = std::to_string(site[0]);
    for (int a = 1; a < Dim; ++a) at += ", " + std::to_string(site[a]);
    throw std::invalid_argument("LatticeSinePreconditioner::eigenvalue: component " + std::to_string(c) +
                                ", grid point (" + at + ") outside c in [0, " + std::to_string(Dim) +
                                "), indices in [0, " + std::to_string(m_n) + ")");
  }
  return m_scaled[c * sites() + q] * m_transform_scale;
}

template <int Dim>
void LatticeSinePreconditioner<Dim>::apply(const Eigen::Ref<const Eigen::MatrixXd>& x,
                                           Eigen::Ref<Eigen::MatrixXd> y) const {
  if (x.rows() != dofs() || y.rows() != dofs() || x.cols() != y.cols() || x.cols() < 1)
    throw std::invalid_argument("LatticeSinePreconditioner::apply: x is " + std::to_string(x.rows()) + " x " +
                                std::to_string(x.cols()) + " and y " + std::to_string(y.rows()) + " x " +
                                std::to_string(y.cols()) + ", need dofs = " + std::to_string(dofs()) +
                                " rows and the same number (>= 1) of columns");
  const int b = static_cast<int>(x.cols()), tasks = Dim * b;
  const std::size_t nn = sites();
  const int threads = std::max(1, std::min(max_threads(), tasks));
  const fftw_plan plan = m_plan->plan;
  const double* scaled = m_scaled.data();
#pragma omp parallel num_threads(threads)
  {
    FftwBuffer buf(nn);
#pragma omp for schedule(static)
    for (int t = 0; t < tasks; ++t) {
      const int v = t / Dim, c = t % Dim;
      const double* xv = x.col(v).data();
      for (std::size_t q = 0; q < nn; ++q) buf.p[q] = xv[Dim * q + c];
      fftw_execute_r2r(plan, buf.p, buf.p);
      const double* s = scaled + c * nn;
      for (std::size_t q = 0; q < nn; ++q) buf.p[q] *= s[q];
      fftw_execute_r2r(plan, buf.p, buf.p);
      double* yv = y.col(v).data();
      for (std::size_t q = 0; q < nn; ++q) yv[Dim * q + c] = buf.p[q];
    }
  }
}

template <int Dim>
double lattice_symbol_ratio_max(const LatticeStencil<Dim>& st, int n) {
  const std::string who = "lattice_symbol_ratio_max";
  if (n < 1) throw std::invalid_argument(who + ": need n >= 1 particles per side (got " + std::to_string(n) + ")");
  if (st.radius < 0 || static_cast<long>(st.k.size()) != st.blocks() || st.l.size() != st.k.size())
    throw std::invalid_argument(who + ": stencil blocks do not match its radius (use probe_lattice_stencil)");
  std::vector<double> kh[Dim], lh[Dim];
  diagonal_symbol<Dim>(st, true, n, kh);
  diagonal_symbol<Dim>(st, false, n, lh);
  return symbol_ratio_max<Dim>(kh, lh, n, who);
}

template class LatticeSinePreconditioner<2>;
template class LatticeSinePreconditioner<3>;
template double lattice_symbol_ratio_max<2>(const LatticeStencil<2>&, int);
template double lattice_symbol_ratio_max<3>(const LatticeStencil<3>&, int);

}  // namespace sphstab
