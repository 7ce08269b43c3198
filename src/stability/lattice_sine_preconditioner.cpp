#include "sphstab/stability/lattice_sine_preconditioner.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

#include "../linalg/tall_block_algebra.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/threads.hpp"

namespace sphstab {

/// One in-place batched complex DFT of length 2 (n + 1) (kBatch lines, line-interleaved: element t of line b at
/// t kBatch + b, so FFTW's SIMD codelets run across the lines), executed on other buffers of the same (fftw_malloc)
/// alignment through the new-array interface (thread-safe).
template <int Dim>
struct LatticeSinePreconditioner<Dim>::Plan {
  fftw_plan plan = nullptr;
  /// apply's per-thread buffers, kept between calls (a new z per call, 16 MB at n = 1000, cost 4096 page faults
  /// each time); one apply at a time uses them (a concurrent call on the same object allocates its own).
  struct Free {
    void operator()(void* p) const { fftw_free(p); }
  };
  struct Buffers {  ///< a thread's: the complex n^Dim field z and the kBatch extended lines e of sine_transform_axis
    std::unique_ptr<fftw_complex[], Free> z, e;
  };
  std::mutex mutex;
  std::vector<Buffers> buffers;
  ~Plan() {
    if (plan) fftw_destroy_plan(plan);
  }
};

namespace {

/// Lines per batched DFT: 8 lines of 2 (n + 1) complex values (256 KB at n = 1000) stay in the L2 cache.
constexpr int kBatch = 8;

template <class T>
struct FftwBuffer {
  explicit FftwBuffer(std::size_t count) : p(static_cast<T*>(fftw_malloc(count * sizeof(T)))) {
    if (!p) throw std::bad_alloc();
  }
  ~FftwBuffer() { fftw_free(p); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  T* p;
};

/// In place, the unnormalised DST-I of FFTW (RODFT00: Y_k = 2 sum_t z_t sin(pi (t + 1)(k + 1) / (n + 1))) along
/// `axis` of the complex n^Dim field z (index i + n j [+ n^2 k]); real and imaginary parts are two real fields, the
/// transform being real-linear. Each line goes into its odd extension e = (0, z_0..z_{n-1}, 0, -z_{n-1}..-z_0) of
/// length N = 2 (n + 1), whose DFT E_k = sum_t e_t exp(-2 pi i t k / N) = -2i sum_t z_t sin(pi (t + 1) k / (n + 1)),
/// so Y_k = i E_{k+1} (FFTW's own definition of RODFT00 as the DFT of that odd extension, [FrigoJohnson2005]). `e`
/// holds N kBatch values, `plan` the batched DFT of Plan.
void sine_transform_axis(fftw_complex* z, int n, int dim, int axis, fftw_complex* e, fftw_plan plan) {
  const long N = 2L * (n + 1);
  long step = 1, lines = 1;  // n^axis between the elements of a line; n^(dim - 1) lines
  for (int a = 0; a < axis; ++a) step *= n;
  for (int a = 1; a < dim; ++a) lines *= n;
  long base[kBatch];
  for (long l0 = 0; l0 < lines; l0 += kBatch) {
    const int m = static_cast<int>(std::min<long>(kBatch, lines - l0));
    for (int b = 0; b < kBatch; ++b) {
      const long l = l0 + b;
      base[b] = l % step + l / step * step * n;  // the other coordinates of line l, the lowest axis fastest
      for (long t : {0L, n + 1L}) e[t * kBatch + b][0] = e[t * kBatch + b][1] = 0;
    }
    for (long t = 0; t < n; ++t) {
      fftw_complex* up = e + (t + 1) * kBatch;
      fftw_complex* down = e + (N - 1 - t) * kBatch;
      for (int b = 0; b < m; ++b) {
        const double* src = z[base[b] + t * step];
        up[b][0] = src[0];
        up[b][1] = src[1];
        down[b][0] = -src[0];
        down[b][1] = -src[1];
      }
      for (int b = m; b < kBatch; ++b) up[b][0] = up[b][1] = down[b][0] = down[b][1] = 0;
    }
    fftw_execute_dft(plan, e, e);
    for (long t = 0; t < n; ++t) {
      const fftw_complex* row = e + (t + 1) * kBatch;
      for (int b = 0; b < m; ++b) {
        z[base[b] + t * step][0] = -row[b][1];
        z[base[b] + t * step][1] = row[b][0];
      }
    }
  }
}

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

  const int N = 2 * (n + 1);
  FftwBuffer<fftw_complex> buf(static_cast<std::size_t>(N) * kBatch);
  m_plan = std::make_unique<Plan>();
  m_plan->plan = fftw_plan_many_dft(1, &N, kBatch, buf.p, nullptr, kBatch, 1, buf.p, nullptr, kBatch, 1, FFTW_FORWARD,
                                    measure ? FFTW_MEASURE : FFTW_ESTIMATE);
  if (!m_plan->plan)
    throw std::runtime_error(who + ": FFTW could not plan " + std::to_string(kBatch) + " DFTs of length " +
                             std::to_string(N));
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
  // The Dim b real fields (column v, component c) in the order f = Dim v + c, two at a time as the real and imaginary
  // parts of one complex field (the last one alone when Dim b is odd): half the transforms, in FFTW's SIMD complex
  // codelets. Round-off of a field then scales with its partner's size too (twiddle products mix real and imaginary
  // parts), which is relative to the block, as a preconditioner needs. Pairs are fixed, each on its own buffers, and
  // each reads its fields before writing them: the same bits for any thread count, and y may be x.
  const int fields = Dim * static_cast<int>(x.cols()), pairs = (fields + 1) / 2;
  const long nn = sites();
  const int threads = std::max(1, std::min(max_threads(), pairs));
  const fftw_plan plan = m_plan->plan;
  const double* scaled = m_scaled.data();
  std::unique_lock<std::mutex> lock(m_plan->mutex, std::try_to_lock);
  std::vector<typename Plan::Buffers> own;
  std::vector<typename Plan::Buffers>& buffers = lock.owns_lock() ? m_plan->buffers : own;
  while (static_cast<int>(buffers.size()) < threads) {
    typename Plan::Buffers b;
    b.z.reset(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * nn)));
    b.e.reset(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * 2 * (m_n + 1L) * kBatch)));
    if (!b.z || !b.e) throw std::bad_alloc();
    tall::advise_huge_pages(b.z.get(), sizeof(fftw_complex) * nn);  // before the first write
    buffers.push_back(std::move(b));
  }
#pragma omp parallel num_threads(threads)
  {
    fftw_complex* z = buffers[thread_index()].z.get();
    fftw_complex* e = buffers[thread_index()].e.get();
#pragma omp for schedule(static)
    for (int p = 0; p < pairs; ++p) {
      const int f0 = 2 * p, f1 = 2 * p + 1;
      const int v0 = f0 / Dim, c0 = f0 % Dim, v1 = f1 / Dim, c1 = f1 % Dim;
      const bool two = f1 < fields;
      const double* x0 = x.col(v0).data() + c0;
      const double* x1 = two ? x.col(v1).data() + c1 : x0;
      for (long q = 0; q < nn; ++q) {
        z[q][0] = x0[Dim * q];
        z[q][1] = two ? x1[Dim * q] : 0.0;
      }
      for (int a = 0; a < Dim; ++a) sine_transform_axis(z, m_n, Dim, a, e, plan);
      const double* s0 = scaled + c0 * nn;
      const double* s1 = scaled + (two ? c1 : c0) * nn;
      for (long q = 0; q < nn; ++q) {
        z[q][0] *= s0[q];
        z[q][1] = two ? z[q][1] * s1[q] : 0.0;
      }
      for (int a = 0; a < Dim; ++a) sine_transform_axis(z, m_n, Dim, a, e, plan);
      double* y0 = y.col(v0).data() + c0;
      if (!two) {
        for (long q = 0; q < nn; ++q) y0[Dim * q] = z[q][0];
        continue;
      }
      double* y1 = y.col(v1).data() + c1;
      for (long q = 0; q < nn; ++q) {
        y0[Dim * q] = z[q][0];
        y1[Dim * q] = z[q][1];
      }
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
