#pragma once
/// \file matrix_free_linearisation.hpp
/// The linearisation A(e) = A0 + e A1 of analytic_jacobian_2d.hpp, in 2D and 3D (Dim), applied to vectors without
/// assembling it, in O(N) memory. The assembled A0 couples neighbours of neighbours (~130 nonzeros per row at h = 1.3
/// dx, 8 GB at 10^6 particles); its factors G, H couple neighbours only (~21 per row). Applying the factors in sequence
/// costs about as much as one SpMV with A0 and stores only G on the rows within one hop of a free particle, H on the
/// free rows, and their row sums (storage PerPair), or, on a perfect lattice, G and H once per lattice offset
/// (storage ByOffset, below).
///
/// With the notation of analytic_jacobian_2d.hpp (Dm^d = G^d - diag(g^d), P^b = G^b + alpha diag(g^b), alpha = 1
/// for the conservative A0, L^{bc} = diag(eta^{bc}) - H^{bc} on the free block), y = A0 x is, for free x:
///   1. strain (derivation item 1): (grad x)_j^{cd} = sum_{k free} Dm^d_jk x_k^c on every particle j next to a free
///      particle (fixed particles carry zero displacement);
///   2. stress (item 1): sigma_j^{ab} = C^{abcd} (grad x)_j^{cd} = lambda delta_ab tr(grad x)_j + mu ((grad x)_j^{ab}
///      + (grad x)_j^{ba});
///   3. divergence (items 2, 3): y_i^a = -(1/rho) sum_j P^b_ij sigma_j^{ab} on the free rows i.
/// Substituting 1 and 2 into 3 gives the header's A0_ik = -(1/rho) sum_j [lambda p q^T + mu q p^T + mu (p.q) I].
/// y = A1 x is one hop: -((1 + alpha)/rho) s0 (L x)_i for uncorrected / plus / minus, and -(2/rho) (s0 (L x)_i +
/// (L s0 x)_i) for the conservative form, where (L v)_i = eta_i v_i - sum_{k free} H_ik v_k.
///
/// DOF ordering as Linearisation: dof = Dim f + a over the free particles in ascending index.
///
/// 3D: the derivation of analytic_jacobian_2d.hpp never uses the dimension (sums over a, b, c, d in {x, y, z}); C is
/// the isotropic 3D stiffness and s0 the 3D pre-stress per unit pre-strain (prestress()): isotropic (3 lambda +
/// 2 mu) I, uniaxial-x diag(lambda + 2 mu, lambda, lambda). Checked against the TL acceleration of LinearElasticSph<3>
/// (A0) and a finite difference of the kernel-gradient sum (A1) in
/// tests/jacobian/matrix_free_linearisation_3d_test.cpp. At 100^3 free particles (h = 1.3 dx, cubic spline, 81
/// neighbours) the stored values take about 7 GB per pair, 0.1 GB by offset.
///
/// Storage ByOffset (issue 35: values by offset, not per pair). When the free particles fill an n_0 x n_1 [x n_2]
/// box of a lattice of spacing dx in DOF order (f = i_0 + n_0 i_1 [+ n_0 n_1 i_2], i_0 along x), no axis is periodic,
/// and every free particle's neighbour list is the same symmetric set of lattice offsets d (every neighbour on its
/// lattice site to 1e-9 dx, all of one volume V), the pair values are functions of the offset alone: G_{i,i+d} = G(d),
/// H_{i,i+d} = H(d), computed once from the kernel at separation -d dx with G(-d) = -G(d), H(-d) = H(d) imposed
/// exactly. Then on every free row g_i = sum_d G(d) = 0 exactly (summed in +-d pairs), so Dm = P = G there and
///   1. (grad x)_j = sum_{d in D+} G(d) (x_{j+d} - x_{j-d}), D+ = one of each pair +-d,
///   3. y_i^a = -(1/rho) sum_{d in D+} G^b(d) (sigma_{i+d}^{ab} - sigma_{i-d}^{ab}),
///   A1: y_i = B(0) x_i + sum_{d in D+} B(d) (x_{i+d} + x_{i-d}), B(0) = -f s0 eta, B(d) = f s0 H(d) (plain forms,
///       f = (1 + alpha)/rho) or B(0) = -f (s0 eta + eta s0), B(d) = f (s0 H(d) + H(d) s0) (conservative, f = 2/rho),
///       eta = 2 sum_{d in D+} H(d),
/// evaluated as lattice loops on a grid of the free box padded by 2 r (r = max |d_a|) holding x with zeros outside the
/// free box; step 1 runs on the free box padded by r (the sites where sigma is read). Why the fixed particles'
/// neighbourhoods, truncated at the edge of the particle set, do not matter: step 1 at a fixed site j needs only
/// sum_{k free} G_jk x_k, whose terms are the offsets d with j + d free, and each such j + d = k has j = k - d in k's
/// (checked) neighbour list, so G_jk = G(d) by the symmetry of the neighbour relation; pairs of j outside the free box
/// meet zeros; j's own row sum g_j multiplies x_j = 0 (fixed particles carry zero displacement). Step 3 and A1 read
/// sigma and x only at i +- d of free rows i, all checked particles. No fixed particle's row is therefore used, and
/// nothing is stored per pair: the grids (Dim + kSymmetric values per padded site) and the free positions. The sums run
/// in another order than PerPair's (round-off only: ~1e-15 relative, tests/jacobian/matrix_free_storage_test.cpp).
/// Auto (the default) takes ByOffset when it applies (lattice_refusal() empty), else PerPair; the constructor from
/// given Operators is PerPair (the values might be corrected: they are not the kernel's).
///
/// \note Same coverage as analytic_jacobian_2d: plain kernel gradient, rest state, zero fixed displacements, no
///       additional momentum terms. Agreement with the assembled matrices is checked on random vectors in
///       tests/jacobian/matrix_free_linearisation_test.cpp.
/// \note apply_* use an internal stress buffer: one object must not apply from two threads at once. Each apply runs its
///       two row loops on the threads of core/threads.hpp (whole rows per thread: the same bits for any count).
///
/// \code{.cpp}
/// auto set = sphstab::strain_lattice_2d(sphstab::LatticeType::Square, kernel, 1.3, 1000);
/// auto disc = sphstab::make_discretisation(set, kernel, 1.3);
/// sphstab::MatrixFreeLinearisation lin(*disc, sphstab::ElasticMaterial::from_lame(1, 1, 1),
///                                      sphstab::MomentumForm::Conservative, sphstab::PreStrainKind::Isotropic);
/// Eigen::VectorXd x = Eigen::VectorXd::Random(lin.dofs()), y(lin.dofs());
/// lin.apply(1e-3, x, y);   // y = A(e = 1e-3) x
/// \endcode
#include <Eigen/Core>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/jacobian/linearisation.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// Where MatrixFreeLinearisation keeps the values of G and H: per neighbour pair, or once per lattice offset on a
/// perfect lattice (header comment); Auto: ByOffset when it applies, else PerPair.
enum class MatrixFreeStorage { Auto, PerPair, ByOffset };
/// Parses "auto", "per-pair", "by-offset"; throws std::invalid_argument otherwise.
MatrixFreeStorage parse_matrix_free_storage(const std::string& name);
/// The name accepted by parse_matrix_free_storage.
std::string matrix_free_storage_name(MatrixFreeStorage storage);

/// Pre-stress sigma0 per unit pre-strain: 2D plane strain (PreStrain::stress), 3D isotropic (3 lambda + 2 mu) I or
/// uniaxial-x diag(lambda + 2 mu, lambda, lambda).
template <int Dim>
Eigen::Matrix<double, Dim, Dim> prestress(PreStrainKind kind, const ElasticMaterial& material);

template <int Dim>
class MatrixFreeLinearisation {
  static_assert(Dim == 2 || Dim == 3, "MatrixFreeLinearisation: 2D or 3D");

 public:
  using Stress = Eigen::Matrix<double, Dim, Dim>;
  /// Stored components of a symmetric Dim x Dim tensor (3 in 2D, 6 in 3D).
  static constexpr int kSymmetric = Dim * (Dim + 1) / 2;

  /// From operators G, H assembled at the rest positions with the neighbour-list pattern of `discretisation` (as
  /// analytic_jacobian_2d), stored PerPair. Throws std::invalid_argument for an invalid material or missing /
  /// mis-sized operators, MemoryLimitError when the stored values do not fit the memory limit (checked before
  /// anything is copied).
  MatrixFreeLinearisation(const Discretisation<Dim>& discretisation, const Operators<Dim>& operators,
                          const ElasticMaterial& material, MomentumForm form, PreStrainKind kind);
  /// As above, computing the values of G and H from the kernel without assembling the matrices: pair by pair (PerPair,
  /// the same bits as assemble_operators) or offset by offset (ByOffset); memory is only what is stored. Throws
  /// std::invalid_argument also for ByOffset on a particle set where it does not apply (lattice_refusal()).
  MatrixFreeLinearisation(const Discretisation<Dim>& discretisation, const ElasticMaterial& material, MomentumForm form,
                          PreStrainKind kind, MatrixFreeStorage storage = MatrixFreeStorage::Auto);
  /// The linearisation of a 2D force function's form, material and pre-strain kind. Throws std::invalid_argument for
  /// a non-plain gradient provider, non-zero fixed displacements or additional momentum terms (not covered).
  /// (A constructor template, so that the explicit instantiation of the 3D class does not instantiate it: clang 14
  /// instantiates constrained members of an explicitly instantiated class regardless of their constraints.)
  template <int D = Dim>
  requires(D == 2 && D == Dim) explicit MatrixFreeLinearisation(const ElasticForm2D& force);

  int dofs() const { return Dim * free_count(); }
  int free_count() const { return static_cast<int>(m_free.size()); }
  /// Particle index of each free particle (ascending): the DOF order.
  const std::vector<int>& free_index() const { return m_free; }
  /// Reference positions of the free particles, free_count x Dim in DOF order (for geometric preconditioners).
  const Eigen::MatrixXd& free_positions() const { return m_free_positions; }
  MomentumForm form() const { return m_form; }
  /// As Linearisation::symmetric / complete (same definitions as analytic_jacobian_2d).
  bool symmetric() const { return m_symmetric; }
  bool complete() const { return m_complete; }
  bool periodic() const { return m_periodic; }  ///< every axis of the particle set is periodic
  /// The storage in use (PerPair or ByOffset, never Auto).
  MatrixFreeStorage storage() const { return m_storage; }
  /// Empty when ByOffset applies to `discretisation` (header comment), else why not, in one line (the first failed
  /// condition). O(pairs of the free rows).
  static std::string lattice_refusal(const Discretisation<Dim>& discretisation);
  /// Bytes held by this object (stored operator values, indices, row sums, buffers).
  double memory_bytes() const;

  /// y = A0 x. x and y: dofs() entries, distinct storage. Throws std::invalid_argument otherwise.
  void apply_A0(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const;
  /// y = A1 x (zero for the minus form). Sizes as apply_A0.
  void apply_A1(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const;
  /// y = A(load) x = (A0 + load A1) x in one pass. Sizes as apply_A0.
  void apply(double load, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const {
    apply_combination(1.0, load, x, y);
  }
  /// y = (c0 A0 + c1 A1) x; a zero coefficient skips its operator. Sizes as apply_A0.
  void apply_combination(double c0, double c1, const Eigen::Ref<const Eigen::VectorXd>& x,
                         Eigen::Ref<Eigen::VectorXd> y) const;
  /// y0 = A0 x and y1 = c1 A1 x, the same bits as apply_A0(x, y0) and apply_combination(0, c1, x, y1), in one call:
  /// with ByOffset storage x goes into the padded grid once and step 3 sweeps the free box once for both (the
  /// stiffness and load products of a block eigensolver's basis vector); PerPair storage makes the two calls. y0 and y1
  /// must not share storage with x or each other. Sizes as apply_A0.
  void apply_A0_and_A1(double c1, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y0,
                       Eigen::Ref<Eigen::VectorXd> y1) const;

  /// Estimated bytes of a MatrixFreeLinearisation of `discretisation` with `storage` (Auto resolved as the constructor
  /// does; exact up to vector capacity slack), the figure require_memory() is asked for before construction.
  static double estimated_bytes(const Discretisation<Dim>& discretisation,
                                MatrixFreeStorage storage = MatrixFreeStorage::Auto);

  /// Index of (a, b) in the stress buffer: the diagonal first, then xy[, xz, yz].
  static constexpr int voigt(int a, int b) {
    if (a == b) return a;
    if (a > b) std::swap(a, b);
    return Dim == 2 ? 2 : (a == 0 ? 2 + b : 5);
  }

 private:
  struct Lattice;  // the free box and offset set of ByOffset, or why there is none (matrix_free_linearisation.cpp)
  static Lattice find_lattice(const Discretisation<Dim>& d);
  static double bytes_of(const Discretisation<Dim>& d, const Lattice* lattice);
  void build(const Discretisation<Dim>& d, const Operators<Dim>* ops, const ElasticMaterial& material,
             MomentumForm form, PreStrainKind kind, MatrixFreeStorage storage);
  void build_by_offset(const Discretisation<Dim>& d, const Lattice& lattice);
  /// y = (c0 A0 + c1 A1) x on the lattice grids (matrix_free_by_offset_product.cpp); with y1, y = c0 A0 x and
  /// y1 = c1 A1 x instead.
  void apply_by_offset(double c0, double c1, const double* x, double* y, double* y1 = nullptr) const;
  void check_vectors(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<Eigen::VectorXd>& y,
                     const char* who) const;

  MomentumForm m_form = MomentumForm::Conservative;
  double m_inv_rho = 1, m_lambda = 1, m_mu = 1;
  double m_alpha = 1;      ///< P = G + alpha diag(g) (conservative: 1)
  double m_a1_factor = 0;  ///< (1 + alpha)/rho (plain forms), 2/rho (conservative)
  Stress m_s0 = Stress::Zero();
  bool m_symmetric = false, m_complete = false, m_periodic = false;

  std::vector<int> m_free;           ///< free particle indices (ascending)
  Eigen::MatrixXd m_free_positions;  ///< free_count x Dim
  std::vector<int> m_free_slot;      ///< N entries: free slot or -1
  std::vector<long> m_offsets;       ///< neighbour-list CSR of all N rows
  std::vector<int> m_indices;
  std::vector<double> m_g;              ///< G^a_ij (Dim values) per pair, all rows
  std::vector<double> m_gsum;           ///< g^a_i (Dim values) per particle
  std::vector<int> m_stress_rows;       ///< particles j with a free neighbour (where sigma_j is needed), ascending
  std::vector<long> m_h_offsets;        ///< free_count + 1: start of free row f in m_h
  std::vector<double> m_h;              ///< H^{ab}_ij, a <= b row by row (2D: xx, xy, yy), per pair of the free rows
  std::vector<double> m_eta;            ///< eta^{ab} (same order) per free particle
  mutable std::vector<double> m_sigma;  ///< kSymmetric per particle (diagonal, then xy[, xz, yz]): buffer of step 2

  // ByOffset (the per-pair vectors above stay empty): grids of the free box padded by 2 r, x fastest.
  MatrixFreeStorage m_storage = MatrixFreeStorage::PerPair;
  std::array<int, Dim> m_box{};         ///< free particles per axis
  std::array<long, Dim> m_stride{};     ///< padded grid strides (m_stride[0] = 1)
  long m_grid = 0;                      ///< values between component grids (sites, rounded up: component_stride)
  int m_reach = 0;                      ///< r = max |d_a| over the offsets
  std::vector<long> m_shift;            ///< flat grid shift of each offset of D+
  std::vector<double> m_og;             ///< G(d), Dim per offset of D+
  std::vector<double> m_ob;             ///< A1 block B(d), Dim x Dim row-major per offset of D+
  Stress m_b0 = Stress::Zero();         ///< A1 block B(0)
  mutable std::vector<double> m_u;      ///< Dim grids (component-major): x, zero off the free box
  mutable std::vector<double> m_sgrid;  ///< kSymmetric grids (component-major): sigma of step 2
};

MatrixFreeLinearisation(const ElasticForm2D&)->MatrixFreeLinearisation<2>;

/// The assembled Linearisation (jacobian/linearisation.hpp: A0, A1, dofs_per_particle = Dim, free_index, x, flags)
/// of `lin`, column by column from products with unit vectors (exact zeros dropped): dofs() products of O(N) each,
/// so for small problems and cross-checks only, e.g. in 3D, where no analytic assembly exists, to hand a 3D problem
/// to critical_load or the distributed route. Throws MemoryLimitError when dofs^2 / 8 bytes (a generous bound of
/// the stored nonzeros) does not fit.
template <int Dim>
Linearisation assemble_by_products(const MatrixFreeLinearisation<Dim>& lin);

}  // namespace sphstab
