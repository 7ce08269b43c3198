#pragma once
/// \file rate_form.hpp
/// The rate-form SPH solid scheme that practitioners run (Powell's MCM code, Gray, Monaghan & Swift 2001, LS-DYNA
/// SPH) written once as a first-order system y' = F(y) (system/semi_discrete_system.hpp), in 1D (uniaxial strain)
/// and 2D (plane strain). Per particle: position x, velocity v, density rho, deviatoric stress S. Every term is
/// switchable (RateFormOptions) so that a scene carries only what it needs. Equations (tension-positive stress,
/// sigma = -p I + S; G_ij = grad_i W(x_i - x_j) at the current positions; sums over the neighbour list):
///
///   XSPH [GMS2001, (3.6)]       vhat_i = v_i + eps_x sum_j (m_j / rhobar_ij) (v_j - v_i) W_ij
///   motion                       dx_i/dt = vhat_i
///   velocity gradient [GMS2001, (3.10)]  L_i^ab = dv^a/dx^b = sum_j (m_j/rho_j) (vhat_j^a - vhat_i^a) G_ij^b
///                                (Powell (1.33) prints (v_i - v_j): a sign typo, docs/conventions.md)
///   continuity                   Summation [GMS2001, (3.8)]: drho_i/dt = sum_j m_j (vhat_i - vhat_j) . G_ij
///                                Divergence [GMS2001, (3.9)]:  drho_i/dt = -rho_i tr L_i
///                                (Powell (1.32) lacks the factor rho_i)
///   equation of state [GMS2001, (2.7)]  p_i = K (rho_i / rho0 - 1)
///   Jaumann rate [GMS2001, (2.3)]  dS/dt = 2 mu (D - tr(D)/3 I_3) + Omega S - S Omega,  D = sym L, Omega = skew L
///                                (3 x 3 with D_zz = 0; plane strain keeps S_zz = -(S_xx + S_yy), so it is derived,
///                                not stored; 1D uniaxial strain: dS_xx/dt = (4 mu / 3) L)
///   momentum [Powell2012, (1.36)], [GMS2001, (3.1)]
///       dv_i/dt = sum_j m_j [sigma_i/rho_i^2 + sigma_j/rho_j^2 - Pi_ij I + (R_i + R_j) f_ij^n] . G_ij
///   artificial viscosity [Monaghan1992]  Pi_ij = (-alpha c0 mu_ij + beta mu_ij^2) / rhobar_ij,
///       mu_ij = h v_ij . r_ij / (r_ij^2 + 0.01 h^2), for approaching pairs (v_ij . r_ij < 0) only (Compression) or
///       for every pair (Always; then beta is not used). It enters with a MINUS sign: [GMS2001, (3.1)] prints +Pi,
///       which is anti-dissipative (docs/conventions.md).
///   artificial stress [GMS2001, (6.1)-(6.9)]  R_i = -eps_a sigma_i^+ / rho_i^2 (tensile principal part),
///       f_ij = W_ij / W(dp), dp the lattice spacing of the discretisation.
///
/// Fixed particles keep their positions and zero velocity; with evolve_fixed (default) their density and stress
/// evolve by the same equations (their stress responds to the free particles, as in a block with fixed boundary
/// particles), otherwise they stay at the state they were given.
///
/// Driven particles (set_driven; [GMS2001, §7.3] pulls a slab by giving the particles near its ends a constant axial
/// acceleration): free particles with a prescribed constant acceleration a_i. dv_i/dt = a_i (the SPH force, viscosity
/// and artificial stress on them are ignored) and dx_i/dt = v_i (no XSPH of their own velocity), so that they follow
/// x0 + v0 t + a t^2/2 exactly; their density and stress evolve by the equations above, and they act on their
/// neighbours like any free particle (their v enters the neighbours' XSPH, L, continuity and viscosity). Both rate
/// overloads do this, so a complex-step Jacobian has zero dv/dt rows and identity dx/dt = v rows for them.
///
/// Absorbing particles (set_absorbing; [Powell2012, (2.62), (2.69), algorithm 2.3]): free particles whose momentum
/// equation is replaced by a first-order non-reflecting condition, dv_i/dt from their velocity gradient
/// (forms/absorbing_boundary.hpp); their motion, density and stress follow the equations above.
///
/// State layout (size()): per particle in index order, free particles [x (Dim), v (Dim), rho, S (1 in 1D; xx, yy, xy
/// in 2D)], fixed particles [rho, S] (or nothing when not evolving). The neighbour list is the discretisation's
/// (built once at the initial positions): runs whose particles move by more than the list's margin must rebuild it
/// (rebuilt(), RateFormRunOptions::neighbour_skin).
///
/// Neighbour list and kernel support: every kernel sum (all terms but the local means) reads only pairs with W != 0 or
/// grad W != 0, so a list with a margin (radius > support) gives the same rates as long as it holds every pair within
/// the support at the current positions. The local means of C_ij and S-SPH are sums over a pattern, not kernel sums
/// (C_ij = P_ij - r_i - c_j + m_i is nonzero beyond the support): their pattern N(i), the counts n_i, the mean of the
/// column means m_i, the correction terms and the S-SPH switch sums use the list's pairs within the kernel support at
/// the discretisation's positions (the neighbour search's own test, |x_i - x_j| < support), so the list radius does not
/// change the scheme. r_i and c_j sum P over the whole list (kernel sums, so that the rows of C_ij still sum to zero
/// when a pair has entered the support since the build).
///
/// \code{.cpp}
/// auto disc = sphstab::make_discretisation(sphstab::make_lattice<2>(sphstab::LatticeType::Square, 16,
///                                          {.spacing = 1.0, .periodic = true}), kernel, 1.3);
/// sphstab::RateFormScheme<2> scheme(disc, sphstab::ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8), {},
///                                   /*density=*/7.8 / 1.02);        // volume strain xi = 1.02
/// Eigen::VectorXd y = scheme.uniform_state();                       // equilibrium: v = 0, rho, S = 0
/// auto spectrum = sphstab::system_spectrum(scheme, y);              // full-state growth rate
/// \endcode
#include <Eigen/Core>
#include <complex>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sphstab/core/scratch.hpp"
#include "sphstab/forms/absorbing_boundary.hpp"
#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/stabilised_sph.hpp"
#include "sphstab/models/elastic_material.hpp"
#include "sphstab/operators/local_polish.hpp"
#include "sphstab/system/semi_discrete_system.hpp"

namespace sphstab {

enum class ContinuityForm { Summation, Divergence };
enum class ViscositySwitch { Off, Compression, Always };

/// The kernel gradient Ghat_ij (particle volume V_j = m_j / rho_j included) of the velocity gradient, the
/// continuity equation and the symmetric/antisymmetric momentum equations.
enum class RateFormGradient {
  Plain,  ///< V_j grad W_ij
  Ncsph   ///< Powell (1.19) with the current volumes: Shepard gradient times the inverse moment matrix
};

/// How the momentum equation uses the stresses (a_i, tension-positive sigma; sums over j in N(i), self included
/// where the gradient has a self term).
enum class RateFormMomentum {
  /// [Powell2012, (1.36)] a_i = sum_j rho_j (sigma_i/rho_i^2 + sigma_j/rho_j^2) . Ghat_ij. With NCSPH this is the
  /// "row" form MCM runs: the rows of Ghat sum to zero, so a uniform sigma exerts no force at any positions.
  Symmetric,
  /// (1.36) with Ghat_ij / V_j replaced by (Ghat_ij / V_j - Ghat_ji / V_i) / 2: equal and opposite pair forces
  /// (momentum conserving). Identical to Symmetric for the plain gradient.
  Antisymmetric,
  /// [Powell2012, (4.10)] a_i = sum_j (sigma_j / rho_j) . C_ij with the local polish C_ij of (4.9) (algorithm 4.1:
  /// mean of COLUMN means) of P_ij = V_j grad W_ij; (4.10) prints "f_i = m a_i" for a_i.
  Cij,
  /// [Powell2012, (4.13)-(4.17), algorithm 4.2] S-SPH: basic SPH (4.13) plus the correction g_ij (the last three
  /// terms of C_ij with S_ij = sigma_i/rho_i + sigma_j/rho_j) per component where the switch is on, pair
  /// interactions symmetrised: a_i = 1/2 sum_j [S_ij (V_i + V_j) grad W_ij + g_ij - g_ji].
  StabilisedSph
};

/// How the plain-gradient symmetric/antisymmetric scheme visits the neighbour pairs (the other forms use Rows).
enum class PairLoop {
  /// Row by row, every pair twice (once from each side), each particle's sums in neighbour order: the same bits for
  /// any thread count, and the same operations for the real and the complex (Jacobian) rate.
  Rows,
  /// Each pair once (j > i), its terms added to both particles: the pair terms are symmetric in i and j, so the two
  /// momentum contributions are equal and opposite up to the masses and the two velocity-gradient contributions share
  /// one outer product. Pairs of the list beyond the kernel support are skipped before any kernel work. About half
  /// Rows' arithmetic; the sums run in another order, so the rates agree with Rows to rounding, not bitwise. Threaded
  /// by chunks of particles with a halo, the same bits for any thread count (docs/architecture.md). Real states only:
  /// the complex rate (Jacobians) and a partitioned scheme (set_row_partition) use Rows.
  Pairs
};

/// The switchable terms. Defaults: plain SPH (no XSPH, no viscosity, no artificial stress), continuity by summation.
struct RateFormOptions {
  ContinuityForm continuity = ContinuityForm::Summation;
  double xsph = 0;  ///< eps_x of [GMS2001, (3.6)] (GMS use 1/2), >= 0; 0: off
  ViscositySwitch viscosity = ViscositySwitch::Off;
  double viscosity_alpha = 0.06;  ///< linear coefficient (MCM deck default 0.06)
  double viscosity_beta = 1.5;    ///< quadratic coefficient (MCM deck default 1.5; Compression only)
  /// MCM's bulk viscosity ([Powell2012, appendix, MCM input deck, material card: QBVC 1.5, LBVC 0.06]), the
  /// von Neumann-Richtmyer / DYNA form on the velocity divergence d_i = tr L_i of each particle (not a pair term):
  ///   q_i = rho_i l (Q1 l d_i^2 - Q2 c0 d_i)  where d_i < 0 (compression), 0 otherwise,   l = h, c0 = sqrt(K/rho0),
  /// added to the pressure in the momentum equation (sigma = S - (p + q) I). d_i is the divergence of the particle
  /// velocities v (not of the GMS XSPH velocity) with the scheme's gradient (plain V_j grad W_ij, or NCSPH's). Both
  /// coefficients >= 0; 0 and 0: off. The switch reads the real part (a complex-step Jacobian at rest takes it off).
  double bulk_viscosity_quadratic = 0;    ///< Q1 (QBVC; MCM deck 1.5)
  double bulk_viscosity_linear = 0;       ///< Q2 (LBVC; MCM deck 0.06)
  double artificial_stress = 0;           ///< eps_a of [GMS2001, (6.4)] (GMS use 0.3), >= 0; 0: off
  double artificial_stress_exponent = 4;  ///< n of f^n (GMS 4)
  bool evolve_fixed = true;               ///< fixed particles integrate rho and S
  RateFormGradient gradient = RateFormGradient::Plain;
  RateFormMomentum momentum = RateFormMomentum::Symmetric;
  /// Cij and StabilisedSph: the counts n_i of the means (Powell Fig. 4.3 boundary levels, or |N(i)|).
  NeighbourCounting counting = NeighbourCounting::Actual;
  /// StabilisedSph: when component alpha of particle i is corrected (stabilised_sph.hpp; Tension is (4.15)-(4.17),
  /// AsPrinted the test printed in algorithm 4.2). The switch reads real parts: a complex-step Jacobian freezes it.
  SwitchRule switch_rule = SwitchRule::Tension;
  /// StabilisedSph: particles with depth <= this never get the correction (0: the outer layer BP of algorithm 4.2;
  /// -1: none).
  int excluded_depth = 0;
  /// StabilisedSph: the means of algorithm 4.1 taken of the first-step Shepard gradient, [Powell2012, (4.18)]:
  /// V_j grad W~_ij = V_j (grad W_ij S0_i - W_ij G0_i) / S0_i^2 with S0_i = sum_k V_k W_ik and G0_i = sum_k V_k grad
  /// W_ik at the discretisation's positions and volumes (the self term included), kept fixed thereafter (rebuilt()
  /// keeps them); r_i, c_j and m_i all of it, as the displacement form's S-SPH (forms/stabilised_sph.hpp). So r_i = 0
  /// at the first step, where the raw row mean of a particle-deficient neighbourhood at a free surface is large.
  /// Powell prints the sums without V_k; with them W~ is a Shepard-normalised kernel of W's dimension (as NCSPH's
  /// (1.19)) and r_i(0) = 0 exactly (tests/forms/rate_form_corrections_test.cpp). false: the means of V_j grad W_ij.
  bool first_step_shepard = false;
  /// Plain gradient with symmetric or antisymmetric momentum: Rows or Pairs (the constructor refuses Pairs otherwise).
  PairLoop pair_loop = PairLoop::Rows;
};

/// Parses "summation" | "divergence" and "off" | "compression" | "always"; throws std::invalid_argument naming the
/// valid choices otherwise.
ContinuityForm parse_continuity_form(const std::string& name);
ViscositySwitch parse_viscosity_switch(const std::string& name);
/// Parses "plain" | "ncsph" and "symmetric" | "antisymmetric" | "cij" | "ssph" (throws naming the valid choices).
RateFormGradient parse_rate_form_gradient(const std::string& name);
RateFormMomentum parse_rate_form_momentum(const std::string& name);
/// Parses "rows" | "pairs" (throws naming the valid choices).
PairLoop parse_pair_loop(const std::string& name);

namespace rate_form_detail {
template <int Dim, class Scalar>
struct Evaluation;  // one call of rate() (src/forms/rate_form/evaluation.hpp)
}  // namespace rate_form_detail

/// Not thread-safe: rate() reuses scratch buffers owned by the object (kept between calls, one set per scalar type),
/// so one scheme object must not be evaluated from two threads at once; give each thread its own copy (a copy starts
/// with empty buffers of its own).
template <int Dim>
class RateFormScheme final : public SemiDiscreteSystem {
  static_assert(Dim == 1 || Dim == 2, "RateFormScheme: Dim must be 1 or 2");

 public:
  /// Stored deviatoric components per particle: 1 (1D: S_xx), 3 (2D: S_xx, S_yy, S_xy).
  static constexpr int kStress = Dim == 1 ? 1 : 3;

  /// @param disc     particles at their initial (current) positions, kernel, h, neighbour list
  /// @param material rho0, K, mu
  /// @param options  the terms
  /// @param density  the uniform initial density; the masses are m_i = density V_i (default, NaN: rho0). A lattice
  ///                 at volume strain xi = V / V0 has density rho0 / xi.
  /// @param deviator the uniform initial deviator (kStress entries; default 0): uniform_state()'s S and the frozen
  ///                 stress of fixed particles when they do not evolve
  /// Throws std::invalid_argument for a null discretisation, a bad material, negative coefficients, density <= 0 or
  /// a deviator of the wrong size.
  RateFormScheme(std::shared_ptr<const Discretisation<Dim>> disc, const ElasticMaterial& material,
                 const RateFormOptions& options = {}, double density = std::numeric_limits<double>::quiet_NaN(),
                 const Eigen::VectorXd& deviator = {});

  int size() const override { return m_size; }
  std::string name() const override;
  void rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) const override;
  void rate(const Eigen::VectorXcd& y, Eigen::VectorXcd& dydt) const override;
  SparsityPattern pattern() const override;
  /// Positions: the smoothing length; velocities: c_P; densities: the reference density; stresses: the bulk modulus.
  Eigen::VectorXd variable_scale() const override;

  /// The uniform state: initial positions, v = 0, the initial density and deviator on every particle. At a complete
  /// lattice (fixed layers or periodic) it is an equilibrium: F = 0 to rounding.
  Eigen::VectorXd uniform_state() const;

  /// Offsets into y (-1 where a particle does not carry that variable).
  int position_offset(int particle) const { return m_x_off[particle]; }
  int velocity_offset(int particle) const { return m_x_off[particle] < 0 ? -1 : m_x_off[particle] + Dim; }
  int density_offset(int particle) const { return m_rho_off[particle]; }
  int stress_offset(int particle) const { return m_rho_off[particle] < 0 ? -1 : m_rho_off[particle] + 1; }

  /// Declares driven particles (see the file comment), replacing any earlier declaration; empty vectors: none.
  /// @param particles     free particle indices, distinct
  /// @param accelerations one constant acceleration per entry of `particles`, finite
  /// Throws std::invalid_argument for mismatched sizes, an index out of range, a fixed or repeated particle, or a
  /// non-finite acceleration.
  void set_driven(std::vector<int> particles, std::vector<Eigen::Matrix<double, Dim, 1>> accelerations);
  const std::vector<int>& driven_particles() const { return m_driven; }
  const std::vector<Eigen::Matrix<double, Dim, 1>>& driven_accelerations() const { return m_driven_acc; }
  bool is_driven(int particle) const { return !m_driven_slot.empty() && m_driven_slot[particle] >= 0; }

  /// Declares absorbing boundary particles (forms/absorbing_boundary.hpp), replacing any earlier declaration; an
  /// empty set: none. Their acceleration is the absorbing condition's, Powell (2.62) in 2D and (2.69) in 1D, from the
  /// velocity gradient of their own velocities v (not the GMS XSPH vhat) with the scheme's gradient (plain or NCSPH,
  /// normalised over the neighbours used; upwind: the interior side only); everything else about them is unchanged.
  /// With AbsorbingCondition::ViscousTraction (Powell (2.75)) the momentum equation is kept and the traction's
  /// acceleration added instead. Throws std::invalid_argument for mismatched sizes, an index out of range, a fixed,
  /// driven or repeated particle, a normal that is not of unit length (1e-12; 1D: +-1), the Higdon condition, a
  /// speed scale that is not finite and positive, or a viscous traction without a positive depth or with upwind or
  /// convective set.
  void set_absorbing(AbsorbingParticles<Dim> boundary);
  const AbsorbingParticles<Dim>& absorbing() const { return m_absorbing; }
  bool is_absorbing(int particle) const { return !m_absorbing_slot.empty() && m_absorbing_slot[particle] >= 0; }

  /// The same scheme on a neighbour list built at the positions of state y (free particles; fixed particles keep
  /// their reference positions), for runs with large motion (RateFormRunOptions::neighbour_skin). Keeps the masses
  /// (volumes), initial density, deviator, material, options, driven particles and the state layout; what the
  /// constructor derives from the list is recomputed at the new positions (the C_ij / S-SPH pattern and counts n_i,
  /// pair transposes); volumes, depth, spacing, roles and the periodic box are copied. The new discretisation holds
  /// the positions of y, wrapped into a periodic box (y may keep unwrapped ones: the rate takes the minimum image), so
  /// the result's uniform_state() starts there.
  /// @param y               state (size()), finite positions
  /// @param neighbour_radius list radius >= the kernel support (0: the support)
  /// Throws std::invalid_argument for a state of the wrong size, non-finite positions or a radius below the support.
  RateFormScheme rebuilt(const Eigen::VectorXd& y, double neighbour_radius = 0) const;
  /// Takes over the scratch arrays of `previous` (which is left with none), e.g. of the scheme a rebuilt() one
  /// replaces in a run: its rate evaluations then reuse those buffers instead of allocating and first touching their
  /// own (per build about 20 bytes per listed pair and 200 per particle; at 1e6 particles with a Verlet list, 0.7 GB).
  /// The rates do not change: every scratch entry an evaluation reads is written earlier in the same call.
  void take_scratch(RateFormScheme& previous) { m_work = std::move(previous.m_work); }

  /// Distributed evaluation (distributed/distributed_rate_form.hpp): from here on rate(VectorXd) computes the rates of
  /// particles [first, last) only, with the same operations per particle as the whole evaluation (so the same bits),
  /// and then calls exchange(dydt), which must fill the entries of the other particles (every process holds the whole
  /// state; the rates are divided). The complex rate (Jacobians) stays whole. Copies and rebuilt() keep the partition.
  /// Throws std::invalid_argument for an empty range or one outside [0, particle count], an empty exchange, or a
  /// scheme with absorbing particles (their post-pass reads other particles' rates).
  void set_row_partition(int first, int last, std::function<void(Eigen::VectorXd&)> exchange);
  bool partitioned() const { return static_cast<bool>(m_exchange); }
  /// State indices [begin, end) of particles [first, last): the state is ordered by particle. Throws
  /// std::invalid_argument for a range outside [0, particle count].
  std::pair<int, int> state_range(int first, int last) const;

  /// 1/2 sum over free particles of m_i |v_i|^2.
  double kinetic_energy(const Eigen::VectorXd& y) const;
  /// Sets the velocity of particle i (a free particle) in y.
  void set_velocity(Eigen::VectorXd& y, int particle, const Eigen::Matrix<double, Dim, 1>& v) const;
  /// Smallest density over the particles that carry one (a non-positive density ends a run).
  double min_density(const Eigen::VectorXd& y) const;

  const Discretisation<Dim>& discretisation() const { return *m_disc; }
  const ElasticMaterial& material() const { return m_material; }
  const RateFormOptions& options() const { return m_options; }
  double initial_density() const { return m_density; }
  /// The uniform initial deviator (kStress entries): the stress of fixed particles that do not evolve.
  const Eigen::VectorXd& initial_deviator() const { return m_deviator; }
  const Eigen::VectorXd& mass() const { return m_mass; }

 private:
  template <int, class>
  friend struct rate_form_detail::Evaluation;
  /// Overwrites the accelerations of the absorbing particles in dydt (after evaluate() on the same y); the viscous
  /// traction adds to them.
  template <class Scalar>
  void absorb(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& y, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& dydt) const;
  template <class Scalar>
  void evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& y,
                Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& dydt) const;

  /// evaluate()'s scratch arrays, kept between calls (std::vector::resize reallocates only when the particle or pair
  /// count grows; core/scratch.hpp: a copied scheme starts with empty ones).
  template <class Scalar>
  struct Workspace {
    // Per particle.
    std::vector<Eigen::Matrix<Scalar, Dim, 1>> x, v, vhat, row_mean, col_mean, mean_mean;
    std::vector<Scalar> rho, vol, bulk_q;
    std::vector<Eigen::Matrix<Scalar, kStress, 1>> S;
    std::vector<Eigen::Matrix<Scalar, Dim, Dim>> sigma, sigma_rho2, R;  // sigma, sigma / rho^2, artificial stress
    std::vector<Eigen::Matrix<bool, Dim, 1>> on;
    // Per pair (only the arrays the options need; none for the plain symmetric/antisymmetric forms).
    std::vector<Eigen::Matrix<Scalar, Dim, 1>> rij, grad, gh;
    std::vector<Scalar> w, r2s;
    // The plain symmetric/antisymmetric forms: per pair of one neighbour row r and scalars (r^2, |r|, W, ...); per
    // pair of the rows not yet summed grad W, Pi / rhobar, f^n (a ring); per row the last neighbour and where its
    // pairs start in the ring; the rows summed last.
    std::vector<Eigen::Matrix<Scalar, Dim, 1>> row_r;
    std::vector<Scalar> row;
    std::vector<double> row_mass;
    std::vector<Eigen::Matrix<Scalar, Dim + 2, 1>> ring;
    std::vector<long> ready, ring_start;
    std::vector<int> late;
    // PairLoop::Pairs: per particle the sums and whether it moves with XSPH; the pair loop's own scratch
    // (src/forms/rate_form_pair_loop.hpp), created on first use.
    std::vector<Eigen::Matrix<Scalar, Dim, 1>> acc;
    std::vector<Eigen::Matrix<Scalar, Dim, Dim>> L;
    std::vector<Scalar> drho;
    std::vector<char> xsph_moves;
    std::shared_ptr<void> pair_loop;
  };

  std::shared_ptr<const Discretisation<Dim>> m_disc;
  ElasticMaterial m_material;
  RateFormOptions m_options;
  double m_density = 0;
  double m_w_dp = 1;  // W(dp) of the artificial stress
  Eigen::VectorXd m_mass, m_deviator;
  std::vector<int> m_x_off, m_rho_off;  // per particle: offset of x (free only) and of rho (or -1)
  std::vector<long> m_transpose;        // pair (i, j) -> pair (j, i) (antisymmetric momentum)
  std::vector<long> m_upper;            // PairLoop::Pairs: per row, the first list entry with j > i
  Eigen::VectorXd m_counts;             // n_i of the local means (Cij, StabilisedSph)
  Eigen::VectorXd m_shepard_sum;        // S0_i of (4.18) (first_step_shepard; empty otherwise)
  std::vector<Eigen::Matrix<double, Dim, 1>> m_shepard_grad;  // G0_i of (4.18)
  std::vector<char> m_in_support;            // per list entry: in the local means' pattern (empty: every entry is)
  std::vector<int> m_driven, m_driven_slot;  // driven particles; per particle: index into m_driven_acc or -1
  std::vector<Eigen::Matrix<double, Dim, 1>> m_driven_acc;
  AbsorbingParticles<Dim> m_absorbing;
  std::vector<int> m_absorbing_slot;  // per particle: index into m_absorbing or -1 (empty: none)
  std::vector<bool> m_excluded;       // StabilisedSph: particles that never get the correction
  int m_first = 0, m_last = -1;       // set_row_partition: the particles this process evaluates (-1: all)
  std::function<void(Eigen::VectorXd&)> m_exchange;
  int m_size = 0;
  mutable Scratch<Workspace> m_work;  // rate(VectorXd), rate(VectorXcd) (complex-step Jacobians)
};

}  // namespace sphstab
