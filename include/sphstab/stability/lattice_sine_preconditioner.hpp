#pragma once
/// \file lattice_sine_preconditioner.hpp
/// A sine-transform preconditioner T ~ (sigma_p K - L)^{-1} for the pencil L x = lambda K x of the 2D critical
/// strain on an n x n square or n x n x n cubic lattice (K = A0, L = -sgn A1; matrix_free_critical_load.hpp, method
/// BlockLobpcg). Written below for 2D; 3D is the same with a third direction (3D DST-I, 3 x 3 symbols, 3 components).
///
/// With the interior stencils S_K(d), S_L(d) of lattice_stencil.hpp, the 2 x 2 Fourier symbols are
/// \f$\hat K(k) = \sum_d S_K(d) \cos(k \cdot d)\f$ (real part of \f$\sum_d S(d) e^{i k \cdot d}\f$), likewise
/// \f$\hat L\f$. Per displacement component c in {x, y} separately (the xy block of the symbol is odd in both
/// directions and has no DST-I representation: it is dropped), T applies
/// \f[ T_c = \mathcal{S} \, \mathrm{diag}\big(1 / (\sigma_p \hat K_{cc}(k) - \hat L_{cc}(k))\big) \, \mathcal{S}, \f]
/// with \f$\mathcal{S}\f$ the orthonormal 2D DST-I (type-1 sine transform in both lattice directions, FFTW
/// RODFT00) of the n x n field of component c, on the grid \f$k = \pi m / (n + 1)\f$, m = 1..n, per direction. This
/// is the tau-algebra (Dirichlet sine) approximation of the banded block-Toeplitz operator [BiniCapovani1983]; it is
/// exact for the 1D three-point stencil and spectrally close for the wider SPH stencil. The shift
/// \f$\sigma_p = (1 + \mathrm{margin}) \max_{k, c} \hat L_{cc}(k) / \hat K_{cc}(k)\f$ over that grid makes
/// \f$\sigma_p \hat K_{cc} - \hat L_{cc}\f$ positive, so T is symmetric positive definite; sigma_p sits just above
/// the top of the (decoupled) lattice spectrum, so T amplifies the wanted zone-boundary modes (a shift-invert
/// without a factorisation). Measured with block LOBPCG (Python prototype in
/// benchmarks/prototypes/lattice-preconditioner, n = 32-512): 32-54 iterations independent of n, margin 0.02-1 all
/// converge.
///
/// Cost per vector: 2 two-dimensional DST-I of n x n (O(n^2 log n)): the two components of a vector are the real and
/// imaginary parts of one complex field (the DST is real-linear), transformed line by line as complex DFTs of length
/// 2 (n + 1) of the odd extension, 8 lines per batched FFTW plan, which runs FFTW's SIMD complex codelets: about 3
/// times faster than FFTW's real RODFT00 of each component (measured in one process at n = 1000, 1 thread: 0.073 s ->
/// 0.023 s for the 2D transform of both components; in 3D the 3 b fields of a block pair up in (column, component)
/// order). Memory: the 2 n^2 inverse symbol values plus one complex n x n field and 8 extended lines per thread, kept
/// from the first application to the next (on Linux in transparent huge pages): a new field per application cost
/// 4096 page faults at n = 1000.
/// Threads (core/threads.hpp): the pairs of fields of a block of b vectors run side by side, each on its own buffers
/// (same bits for any thread count).
///
/// **Why the grid is the lattice's own.** When n + 1 is prime the DFT length 2 (n + 1) has a large prime factor and
/// FFTW runs Rader's algorithm: at n = 100 (202 = 2 x 101) 13-15 ns per line element against about 2 ns at a length
/// of FFTW's fast sizes (measured 2026-12-07, one thread, 8 interleaved lines). Running the transforms on a larger
/// fast grid with the lattice inside (T = R T_m R^T, still symmetric positive definite) was tried and rejected: the
/// shift sits 2 % above the top of the spectrum, where the padded operator's modes miss the block's, and the block
/// steps grew from 40 to 83 (m = n + 1) and 125 (m = n + 3) at n = 48 in 3D (n = 16: 45 -> 118 with m = 17).
///
/// \note The stencil may come from a larger lattice of the same kernel, h, material and form than the n of the
///       preconditioner (lattice_stencil.hpp needs n >= 11 at h = 1.3 dx).
///
/// \code{.cpp}
/// auto st = sphstab::probe_lattice_stencil(lin, sphstab::LoadDirection::Tension);
/// sphstab::LatticeSinePreconditioner t(st, st.n);   // margin 0.02; LatticeSinePreconditioner<2> deduced
/// Eigen::MatrixXd r = Eigen::MatrixXd::Random(lin.dofs(), 4), w(lin.dofs(), 4);
/// t.apply(r, w);                                     // w = T r
/// \endcode
///
/// References: [BiniCapovani1983] D. Bini, M. Capovani, Spectral and computational properties of band symmetric
/// Toeplitz matrices, Linear Algebra Appl. 52/53 (1983) 99-126; FFTW: [FrigoJohnson2005] (docs/references.md).
#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "sphstab/stability/lattice_stencil.hpp"

namespace sphstab {

template <int Dim>
class LatticeSinePreconditioner {
  static_assert(Dim == 2 || Dim == 3, "LatticeSinePreconditioner: 2D or 3D");

 public:
  /// Sets up T for an n^Dim lattice (dofs Dim n^Dim, DOF order of lattice_stencil.hpp) from `stencil` (probed on any
  /// lattice). Plans the FFTW transforms once (`measure`: FFTW_MEASURE, slower setup, possibly faster transforms;
  /// otherwise FFTW_ESTIMATE). Throws std::invalid_argument for n < 1, margin <= 0 or not finite, a symbol
  /// \f$\hat K_{cc}\f$ that is not positive on the grid, or a grid maximum of \f$\hat L_{cc}/\hat K_{cc}\f$ that is
  /// not positive (no sigma_p > 0 exists: the lattice interior has no instability in this direction).
  LatticeSinePreconditioner(const LatticeStencil<Dim>& stencil, int n, double margin = 0.02, bool measure = false);
  ~LatticeSinePreconditioner();
  LatticeSinePreconditioner(LatticeSinePreconditioner&&) noexcept;
  LatticeSinePreconditioner& operator=(LatticeSinePreconditioner&&) noexcept;
  LatticeSinePreconditioner(const LatticeSinePreconditioner&) = delete;
  LatticeSinePreconditioner& operator=(const LatticeSinePreconditioner&) = delete;

  int n() const { return m_n; }
  long sites() const;  ///< n^Dim
  long dofs() const { return Dim * sites(); }
  /// The shift sigma_p = (1 + margin) symbol_max().
  double sigma() const { return m_sigma; }
  /// \f$\max_{k, c} \hat L_{cc}(k) / \hat K_{cc}(k)\f$ over the DST-I grid: the decoupled lattice estimate of lambda.
  double symbol_max() const { return m_symbol_max; }
  /// \f$1 / (\sigma_p \hat K_{cc}(k) - \hat L_{cc}(k))\f$ at grid point (i, j[, k]) (wavevector pi (i + 1, j + 1[,
  /// k + 1]) / (n + 1)), component c: the eigenvalues of T.
  template <class... I>
  double eigenvalue(int c, I... site) const requires(sizeof...(I) == Dim) {
    return eigenvalue_at(c, {static_cast<int>(site)...});
  }
  double eigenvalue_at(int c, const std::array<int, Dim>& site) const;

  /// y = T x for a block: x and y dofs() x b (b >= 1); y may be x (in place). Throws std::invalid_argument on sizes.
  void apply(const Eigen::Ref<const Eigen::MatrixXd>& x, Eigen::Ref<Eigen::MatrixXd> y) const;

 private:
  struct Plan;
  int m_n = 0;
  double m_sigma = 0, m_symbol_max = 0;
  double m_transform_scale = 0;  ///< (2 (n + 1))^Dim: FFTW's unnormalised RODFT00, applied twice
  std::vector<double> m_scaled;  ///< Dim n^Dim: eigenvalue / m_transform_scale
  std::unique_ptr<Plan> m_plan;
};

/// \f$\max_{k, c} \hat L_{cc}(k) / \hat K_{cc}(k)\f$ over the DST-I grid of an n^Dim lattice (the preconditioner's
/// symbol_max()), without planning transforms: <= 0 means no instability of the lattice interior in this load
/// direction (e.g. compression on the square lattice), where no LatticeSinePreconditioner exists. Throws
/// std::invalid_argument for n < 1, a malformed stencil or a symbol of K that is not positive.
template <int Dim>
double lattice_symbol_ratio_max(const LatticeStencil<Dim>& stencil, int n);

}  // namespace sphstab
