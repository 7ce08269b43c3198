#pragma once
// Dense algebra on tall blocks (dofs x a few columns, column-major) for the block LOBPCG of
// stability/matrix_free_critical_load.cpp: Gram matrices a^T b, products q c, and the copies between them.
//
// Threads: fixed row chunks of kRowChunk rows (the boundaries do not depend on the thread count) and partial Gram
// matrices summed in chunk order, so the results are the same bits for any thread count (core/threads.hpp).
// SIMD: the kernels run on 4 rows at a time in 4 lanes of one vector type (GCC vector extensions), compiled twice,
// for AVX2 and for the baseline x86-64 (SSE2: each 4-lane operation as two 2-lane ones), chosen at run time
// (target_clones). Each lane does the same IEEE operations in the same order in both (no FMA: neither target has it),
// so the results are the same bits on any x86-64 machine; only the speed differs.
#include <Eigen/Core>
#include <cstddef>
#include <initializer_list>
#include <vector>

namespace sphstab::tall {

using ConstCols = Eigen::Ref<const Eigen::MatrixXd>;
using Cols = Eigen::Ref<Eigen::MatrixXd>;

/// Rows per chunk: a chunk of 12 columns (384 KB) stays in a 1 MB L2 cache while the tiles of a kernel re-read it.
constexpr Eigen::Index kRowChunk = 4096;

/// One sweep over the row chunks that runs a sequence of operations on each chunk in the order they were added:
/// the operations that follow one another in the block LOBPCG without a reduction between them (an update of a block
/// and the Gram matrix of the updated block, say) read each row of a block from main memory once instead of once per
/// operation (the blocks are 16 MB per column at n = 1000, the chunk's columns stay in the L2 cache). Each operation
/// does on a chunk exactly what it does alone (the functions below are one-operation passes), so a fused pass gives
/// the same bits as its operations one after the other. The small coefficient matrices are copied; the tall operands
/// and the outputs must live until run().
class RowPass {
 public:
  RowPass();
  ~RowPass();
  /// y -= z c (as subtract_product).
  RowPass& subtract(Cols y, ConstCols z, const Eigen::MatrixXd& c);
  /// As transform_columns.
  RowPass& transform(Eigen::MatrixXd& q, Eigen::Index c0, const Eigen::MatrixXd& c, Eigen::Index out0,
                     const Eigen::MatrixXd& tail = Eigen::MatrixXd());
  /// out = a^T b (as gram), after run().
  RowPass& gram(ConstCols a, ConstCols b, Eigen::MatrixXd& out);
  /// g, h as ritz_grams, after run().
  RowPass& ritz_grams(ConstCols v, ConstCols kv, ConstCols lv, const std::vector<int>& widths, Eigen::MatrixXd& g,
                      Eigen::MatrixXd& h);
  void run();

 private:
  struct Op;
  void add(Op&& op, std::initializer_list<Eigen::Index> rows, bool shapes_match);
  std::vector<Op> m_ops;
  Eigen::Index m_rows = -1;  ///< rows of every operand (checked)
};

/// a^T b: each entry summed over 4 row lanes (rows r = l mod 4 in lane l, in row order), the lanes added as
/// (l0 + l1) + (l2 + l3), per chunk; the chunks' partial matrices added in chunk order.
Eigen::MatrixXd gram(const ConstCols& a, const ConstCols& b);

/// y -= z c, each entry as y - (sum_k z_k c_kj) with the sum in ascending k.
void subtract_product(Cols y, const ConstCols& z, const Eigen::MatrixXd& c);

/// Columns [out0, out0 + c.cols()) of q <- columns [c0, c0 + c.rows()) of q times c, chunk by chunk through a
/// chunk-sized per-thread buffer (each chunk reads its rows before writing them, so the ranges may overlap). With
/// `tail` (rows nt x w, nt < c.rows()), w more columns follow: the last nt of those input columns times tail (a
/// product whose leading rows would be zero, without their flops).
void transform_columns(Eigen::MatrixXd& q, Eigen::Index c0, const Eigen::MatrixXd& c, Eigen::Index out0,
                       const Eigen::MatrixXd& tail = Eigen::MatrixXd());

/// The Rayleigh-Ritz Gram matrices of K and L: g = v^T kv and h = v^T lv, symmetrised, for v = [X | P | W] with
/// column blocks of the given widths. Only the blocks on and right of the diagonal are computed, in one pass over
/// the rows (the lower blocks are their transposes; each diagonal block is averaged with its transpose): 2/3 of the
/// flops of the full products for three blocks.
void ritz_grams(const ConstCols& v, const ConstCols& kv, const ConstCols& lv, const std::vector<int>& widths,
                Eigen::MatrixXd& g, Eigen::MatrixXd& h);

/// dst = src.
void copy(const ConstCols& src, Cols dst);

/// r = l - k diag(theta) (the block residuals L X - K X Theta).
void residuals(const ConstCols& l, const ConstCols& k, const Eigen::VectorXd& theta, Cols r);

/// Asks Linux for transparent huge pages (2 MB) on the whole 2 MB pages inside [p, p + bytes), to be called before
/// the memory is first written: with the kernel's default THP mode "madvise" a large buffer otherwise takes one page
/// fault per 4 KB (at n = 1000 the 576 MB basis of the block LOBPCG and a 16 MB preconditioner buffer per application:
/// 285 000 faults, 1.9 s of system time in one solve) and one TLB entry per 4 KB of its streams. A hint: no effect
/// elsewhere, or when the kernel has no huge page to give; never changes a value.
void advise_huge_pages(const void* p, std::size_t bytes);

}  // namespace sphstab::tall
