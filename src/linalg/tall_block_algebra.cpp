#include "tall_block_algebra.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "sphstab/core/threads.hpp"

// The 4-lane vector type is used only inside this file's inlined kernels: its ABI on the baseline target is moot.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace sphstab::tall {

namespace {

typedef double Lanes __attribute__((vector_size(4 * sizeof(double))));

[[gnu::always_inline]] inline Lanes load(const double* p) {
  Lanes v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(double* p, Lanes v) { __builtin_memcpy(p, &v, sizeof v); }

/// g(i, j) = sum_r a(r, i) b(r, j) for TI columns of a and TJ of b (column strides lda, ldb; g column-major, ldg):
/// lane l sums the rows r = l mod 4 of the multiples of 4, then (l0 + l1) + (l2 + l3), then the last len mod 4 rows.
template <int TI, int TJ>
[[gnu::always_inline]] inline void gram_tile(long len, const double* a, long lda, const double* b, long ldb, double* g,
                                             long ldg) {
  Lanes acc[TI][TJ] = {};
  long r = 0;
  for (; r + 4 <= len; r += 4) {
    Lanes av[TI], bv[TJ];
    for (int i = 0; i < TI; ++i) av[i] = load(a + i * lda + r);
    for (int j = 0; j < TJ; ++j) bv[j] = load(b + j * ldb + r);
    for (int i = 0; i < TI; ++i)
      for (int j = 0; j < TJ; ++j) acc[i][j] += av[i] * bv[j];
  }
  for (int i = 0; i < TI; ++i)
    for (int j = 0; j < TJ; ++j) {
      double s = (acc[i][j][0] + acc[i][j][1]) + (acc[i][j][2] + acc[i][j][3]);
      for (long t = r; t < len; ++t) s += a[i * lda + t] * b[j * ldb + t];
      g[i + j * ldg] = s;
    }
}

/// g = a^T b for ka columns of a and kb of b over len rows, in 2 x 2 tiles (4 accumulators and 4 loads per 4 rows:
/// 8 AVX2 registers, 16 SSE2 ones); the chunk's columns are re-read from the L2 cache by the other tiles.
__attribute__((target_clones("avx2", "default"))) void gram_kernel(long len, int ka, const double* a, long lda, int kb,
                                                                   const double* b, long ldb, double* g, long ldg) {
  int i = 0;
  for (; i + 2 <= ka; i += 2) {
    int j = 0;
    for (; j + 2 <= kb; j += 2) gram_tile<2, 2>(len, a + i * lda, lda, b + j * ldb, ldb, g + i + j * ldg, ldg);
    if (j < kb) gram_tile<2, 1>(len, a + i * lda, lda, b + j * ldb, ldb, g + i + j * ldg, ldg);
  }
  if (i < ka) {
    int j = 0;
    for (; j + 2 <= kb; j += 2) gram_tile<1, 2>(len, a + i * lda, lda, b + j * ldb, ldb, g + i + j * ldg, ldg);
    if (j < kb) gram_tile<1, 1>(len, a + i * lda, lda, b + j * ldb, ldb, g + i + j * ldg, ldg);
  }
}

/// TJ columns of out = in c (Subtract: out -= in c), in k columns (stride ldi), c k x TJ (column stride ldc): each
/// entry sum_q in(r, q) c(q, j) in ascending q, then subtracted from or stored in out (stride ldo).
template <int TJ, bool Subtract>
[[gnu::always_inline]] inline void product_tile(long len, int k, const double* in, long ldi, const double* c, long ldc,
                                                double* out, long ldo) {
  long r = 0;
  for (; r + 4 <= len; r += 4) {
    Lanes acc[TJ];
    Lanes x = load(in + r);
    for (int j = 0; j < TJ; ++j) acc[j] = x * c[j * ldc];
    for (int q = 1; q < k; ++q) {
      x = load(in + q * ldi + r);
      for (int j = 0; j < TJ; ++j) acc[j] += x * c[q + j * ldc];
    }
    for (int j = 0; j < TJ; ++j) store(out + j * ldo + r, Subtract ? load(out + j * ldo + r) - acc[j] : acc[j]);
  }
  for (; r < len; ++r)
    for (int j = 0; j < TJ; ++j) {
      double s = in[r] * c[j * ldc];
      for (int q = 1; q < k; ++q) s += in[q * ldi + r] * c[q + j * ldc];
      out[j * ldo + r] = Subtract ? out[j * ldo + r] - s : s;
    }
}

/// out = in c (subtract: out -= in c) for in len x k, c k x w (k >= 1), 4 output columns at a time (4 accumulators:
/// the input is read from the L1 cache once per 4 output columns).
template <bool Subtract>
[[gnu::always_inline]] inline void product_columns(long len, int k, const double* in, long ldi, int w, const double* c,
                                                   long ldc, double* out, long ldo) {
  int j = 0;
  for (; j + 4 <= w; j += 4) product_tile<4, Subtract>(len, k, in, ldi, c + j * ldc, ldc, out + j * ldo, ldo);
  switch (w - j) {
    case 3:
      product_tile<3, Subtract>(len, k, in, ldi, c + j * ldc, ldc, out + j * ldo, ldo);
      break;
    case 2:
      product_tile<2, Subtract>(len, k, in, ldi, c + j * ldc, ldc, out + j * ldo, ldo);
      break;
    case 1:
      product_tile<1, Subtract>(len, k, in, ldi, c + j * ldc, ldc, out + j * ldo, ldo);
      break;
    default:
      break;
  }
}

__attribute__((target_clones("avx2", "default"))) void product_kernel(long len, int k, const double* in, long ldi,
                                                                      int w, const double* c, long ldc, double* out,
                                                                      long ldo, bool subtract) {
  if (k == 0) {
    if (!subtract)
      for (int j = 0; j < w; ++j) std::fill(out + j * ldo, out + j * ldo + len, 0.0);
    return;
  }
  if (subtract)
    product_columns<true>(len, k, in, ldi, w, c, ldc, out, ldo);
  else
    product_columns<false>(len, k, in, ldi, w, c, ldc, out, ldo);
}

long chunk_count(Eigen::Index rows) { return static_cast<long>((rows + kRowChunk - 1) / kRowChunk); }

template <class F>
void for_row_chunks(Eigen::Index rows, F&& f) {
  const long chunks = chunk_count(rows);
  const int threads = static_cast<int>(std::max<long>(1, std::min<long>(max_threads(), chunks)));
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long c = 0; c < chunks; ++c) {
    const Eigen::Index r0 = c * kRowChunk;
    f(c, r0, std::min(kRowChunk, rows - r0));
  }
}

/// The block of rows [r0, r0 + len) and columns [c0, c0 + cols) of m as a kernel argument.
template <class M>
auto at(M& m, Eigen::Index r0, Eigen::Index c0) {
  return m.data() + r0 + c0 * m.outerStride();
}

}  // namespace

/// A pass operation: `chunk` runs it on rows [r0, r0 + len) of chunk c, writing a Gram partial into parts[c] of its
/// sums; `finish` turns the summed partials into the outputs.
struct RowPass::Op {
  std::function<void(long c, Eigen::Index r0, Eigen::Index len, std::vector<Eigen::MatrixXd>* parts)> chunk;
  int sums = 0;  ///< Gram matrices summed over the chunks (0, 1 or 2)
  std::function<void(std::vector<Eigen::MatrixXd>* sums)> finish;
  std::vector<Eigen::MatrixXd> parts[2];
};

RowPass::RowPass() = default;
RowPass::~RowPass() = default;

void RowPass::add(Op&& op, std::initializer_list<Eigen::Index> rows, bool shapes_match) {
  if (!shapes_match) throw std::invalid_argument("tall::RowPass: coefficient matrix of the wrong shape");
  for (Eigen::Index r : rows) {
    if (m_rows >= 0 && r != m_rows)
      throw std::invalid_argument("tall::RowPass: operands of " + std::to_string(r) + " and " + std::to_string(m_rows) +
                                  " rows in one pass");
    m_rows = r;
  }
  m_ops.push_back(std::move(op));
}

RowPass& RowPass::subtract(Cols y, ConstCols z, const Eigen::MatrixXd& c) {
  Op op;
  op.chunk = [y, z, c](long, Eigen::Index r0, Eigen::Index len, std::vector<Eigen::MatrixXd>*) mutable {
    product_kernel(len, static_cast<int>(z.cols()), at(z, r0, 0), z.outerStride(), static_cast<int>(c.cols()), c.data(),
                   c.outerStride(), at(y, r0, 0), y.outerStride(), true);
  };
  add(std::move(op), {y.rows(), z.rows()}, z.cols() == c.rows() && y.cols() == c.cols());
  return *this;
}

RowPass& RowPass::transform(Eigen::MatrixXd& q, Eigen::Index c0, const Eigen::MatrixXd& c, Eigen::Index out0,
                            const Eigen::MatrixXd& tail) {
  Op op;
  op.chunk = [&q, c0, c, out0, tail](long, Eigen::Index r0, Eigen::Index len, std::vector<Eigen::MatrixXd>*) {
    const Eigen::Index w = c.cols() + tail.cols(), t0 = c0 + c.rows() - tail.rows();
    thread_local std::vector<double> buffer;
    if (buffer.size() < static_cast<std::size_t>(len * w)) buffer.resize(len * w);
    product_kernel(len, static_cast<int>(c.rows()), at(q, r0, c0), q.outerStride(), static_cast<int>(c.cols()),
                   c.data(), c.outerStride(), buffer.data(), len, false);
    if (tail.cols() > 0)
      product_kernel(len, static_cast<int>(tail.rows()), at(q, r0, t0), q.outerStride(), static_cast<int>(tail.cols()),
                     tail.data(), tail.outerStride(), buffer.data() + len * c.cols(), len, false);
    q.block(r0, out0, len, w) = Eigen::Map<const Eigen::MatrixXd>(buffer.data(), len, w);
  };
  add(std::move(op), {q.rows()},
      c0 >= 0 && c0 + c.rows() <= q.cols() && out0 >= 0 && out0 + c.cols() + tail.cols() <= q.cols() &&
          tail.rows() <= c.rows());
  return *this;
}

RowPass& RowPass::gram(ConstCols a, ConstCols b, Eigen::MatrixXd& out) {
  Op op;
  op.sums = 1;
  op.chunk = [a, b](long c, Eigen::Index r0, Eigen::Index len, std::vector<Eigen::MatrixXd>* parts) {
    Eigen::MatrixXd& part = parts[0][c];
    part.resize(a.cols(), b.cols());
    gram_kernel(len, static_cast<int>(a.cols()), at(a, r0, 0), a.outerStride(), static_cast<int>(b.cols()),
                at(b, r0, 0), b.outerStride(), part.data(), part.outerStride());
  };
  op.finish = [&out, rows = a.cols(), cols = b.cols()](std::vector<Eigen::MatrixXd>* parts) {
    out = Eigen::MatrixXd::Zero(rows, cols);
    for (const Eigen::MatrixXd& p : parts[0]) out += p;
  };
  add(std::move(op), {a.rows(), b.rows()}, true);
  return *this;
}

RowPass& RowPass::ritz_grams(ConstCols v, ConstCols kv, ConstCols lv, const std::vector<int>& widths,
                             Eigen::MatrixXd& g, Eigen::MatrixXd& h) {
  const Eigen::Index m = v.cols();
  Op op;
  op.sums = 2;
  op.chunk = [v, kv, lv, widths, m](long c, Eigen::Index r0, Eigen::Index len, std::vector<Eigen::MatrixXd>* parts) {
    Eigen::MatrixXd &gpart = parts[0][c], &hpart = parts[1][c];
    gpart.setZero(m, m);
    hpart.setZero(m, m);
    Eigen::Index b0 = 0;
    for (int bw : widths) {
      const int rest = static_cast<int>(m - b0);
      gram_kernel(len, bw, at(v, r0, b0), v.outerStride(), rest, at(kv, r0, b0), kv.outerStride(),
                  gpart.data() + b0 + b0 * m, m);
      gram_kernel(len, bw, at(v, r0, b0), v.outerStride(), rest, at(lv, r0, b0), lv.outerStride(),
                  hpart.data() + b0 + b0 * m, m);
      b0 += bw;
    }
  };
  op.finish = [&g, &h, widths, m](std::vector<Eigen::MatrixXd>* parts) {
    g.setZero(m, m);
    h.setZero(m, m);
    for (std::size_t c = 0; c < parts[0].size(); ++c) {
      g += parts[0][c];
      h += parts[1][c];
    }
    Eigen::Index b0 = 0;
    for (int bw : widths) {
      for (Eigen::MatrixXd* a : {&g, &h}) {
        a->block(b0, b0, bw, bw) = 0.5 * (a->block(b0, b0, bw, bw) + a->block(b0, b0, bw, bw).transpose()).eval();
        a->block(b0 + bw, b0, m - b0 - bw, bw) = a->block(b0, b0 + bw, bw, m - b0 - bw).transpose();
      }
      b0 += bw;
    }
  };
  add(std::move(op), {v.rows(), kv.rows(), lv.rows()}, kv.cols() == m && lv.cols() == m);
  return *this;
}

void RowPass::run() {
  if (m_ops.empty()) return;
  const long chunks = chunk_count(m_rows);
  for (Op& op : m_ops)
    for (int s = 0; s < op.sums; ++s) op.parts[s].assign(chunks, Eigen::MatrixXd());
  for_row_chunks(m_rows, [&](long c, Eigen::Index r0, Eigen::Index len) {
    for (Op& op : m_ops) op.chunk(c, r0, len, op.parts);
  });
  for (Op& op : m_ops)
    if (op.finish) op.finish(op.parts);
  m_ops.clear();
  m_rows = -1;
}

Eigen::MatrixXd gram(const ConstCols& a, const ConstCols& b) {
  Eigen::MatrixXd g;
  RowPass().gram(a, b, g).run();
  return g;
}

void subtract_product(Cols y, const ConstCols& z, const Eigen::MatrixXd& c) { RowPass().subtract(y, z, c).run(); }

void transform_columns(Eigen::MatrixXd& q, Eigen::Index c0, const Eigen::MatrixXd& c, Eigen::Index out0,
                       const Eigen::MatrixXd& tail) {
  RowPass().transform(q, c0, c, out0, tail).run();
}

void ritz_grams(const ConstCols& v, const ConstCols& kv, const ConstCols& lv, const std::vector<int>& widths,
                Eigen::MatrixXd& g, Eigen::MatrixXd& h) {
  RowPass().ritz_grams(v, kv, lv, widths, g, h).run();
}

void copy(const ConstCols& src, Cols dst) {
  for_row_chunks(src.rows(),
                 [&](long, Eigen::Index r0, Eigen::Index len) { dst.middleRows(r0, len) = src.middleRows(r0, len); });
}

void residuals(const ConstCols& l, const ConstCols& k, const Eigen::VectorXd& theta, Cols r) {
  for_row_chunks(r.rows(), [&](long, Eigen::Index r0, Eigen::Index len) {
    r.middleRows(r0, len) = l.middleRows(r0, len) - k.middleRows(r0, len) * theta.asDiagonal();
  });
}

void advise_huge_pages(const void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(p) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // a hint: errors ignored
#else
  (void)p;
  (void)bytes;
#endif
}

}  // namespace sphstab::tall
