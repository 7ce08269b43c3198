#pragma once
/// \file stabilised_sph.hpp
/// Stabilised SPH (S-SPH) of Powell ch. 4 §2.3-3, eqs (4.13)-(4.18), algorithms 4.1 and 4.2, for 2D elasticity:
/// the basic SPH momentum equation (4.13) plus, per component and only "in tension", the correction g_i of (4.14),
/// whose kernel is the last three terms of the local polish C_ij (4.9).
///
/// Per step (all at the current positions x = x0 + u; S_ij = (sigma_i + sigma_j)/rho, constant density):
///   1. algorithm 4.1: for each axis b the means of the first-step Shepard gradient (4.18)
///        Gt^b_ij = (G^b_ij S0_i - W_ij g0^b_i) / S0_i^2   (S0 = W^0 1, g0^b = G^{b,0} 1 frozen at x0),
///      r^b_i = (1/n_i) sum_k Gt^b_ik, c^b_j = (1/n_j) sum_k Gt^b_kj, m^b_i = (1/n_i) sum_{j in N(i)} c^b_j, with the
///      boundary-level counts n_i of Fig. 4.3 (local_polish.hpp, neighbour_counts);
///   2. algorithm 4.2: f_ij = S_ij . G_ij and g_ij = -S_ij . (r_i + c_j - m_i) (vectors over the axis b);
///      g_ij,alpha = 0 unless the switch of particle i is on for component alpha; particles on the outer layer (BP:
///      depth <= excluded_depth) never get the correction;
///   3. symmetrised pair interactions: a_i += (f_ij + g_ij)/2 and a_j -= (f_ij + g_ij)/2 for every i (free and
///      fixed) and j in N(i), which conserves linear momentum for equal masses.
///
/// Implementation: ElasticForm2D(Plus) supplies sum_j f_ij; StabilisedSphTerm adds the difference to algorithm 4.2,
///   sum over the pairs (i, j) of row i of  -(f_ij)/2 to a_i and to a_j,  +g_ij/2 to a_i and -g_ij/2 to a_j,
/// i.e. a_i(term) = -1/2 sum_j S_ij . (G_ij + G_ji) + 1/2 sum_j (g_ij - g_ji); the first part vanishes for equal
/// volumes (G_ji = -G_ij), where S-SPH is exactly basic SPH plus the antisymmetrised correction.
///
/// Switch (SwitchRule::Tension, the default): component alpha of particle i is corrected iff
/// sum_{j in N(i)} sigma_j,alpha alpha > 0 with sigma tension-positive (Powell 4.15-4.17: the C_ij kernel "in
/// tension", basic SPH "in compression"). \note Algorithm 4.2 as printed zeroes g when sum[alpha] > 0, which under
/// the tension-positive convention applies the correction in COMPRESSION, contradicting (4.15)-(4.17) and the
/// motivation of §2.3 (C_ij is stable in tension, basic SPH in compression); SwitchRule::AsPrinted reproduces the
/// printed test for comparison. (4.17) also prints sigma_j,beta beta in its second case where alpha alpha is meant.
///
/// \note Linearisation: the switch is piecewise constant in u. All branches use real parts, so a complex-step
///       Jacobian at u is the Jacobian of the force with the switch state frozen at u (the state of the real point;
///       exactly on a switching surface, sum = 0, the "off" branch). frozen() makes that state explicit so that a
///       real finite-difference Jacobian can be compared with it.
/// \note With the (4.18) normalisation the correction does not vanish identically near a boundary at x0 (the
///       columns of Gt do not sum to zero there), so the pre-stressed lattice with fixed layers is an exact
///       equilibrium only away from the boundary; see the Swegle study for the size of the imbalance.
///
/// \code{.cpp}
/// auto disc = sphstab::make_discretisation(set, sphstab::Kernel<2>(sphstab::KernelType::CubicSpline), 1.3 * dx);
/// auto force = sphstab::make_stabilised_sph(disc, material, sphstab::PreStrain::from_area_ratio(1.02));
/// Eigen::VectorXd u = Eigen::VectorXd::Zero(force->dofs()), a;
/// force->acceleration(u, a);
/// \endcode
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/elastic_term.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/operators/local_polish.hpp"
#include "sphstab/operators/shepard.hpp"

namespace sphstab {

/// When the S-SPH correction of component alpha is applied (sum_alpha = sum_{j in N(i)} sigma_j,alpha alpha).
enum class SwitchRule {
  Tension,    ///< sum_alpha > 0 (Powell 4.15-4.17, tension positive): the default
  AsPrinted,  ///< sum_alpha <= 0 (algorithm 4.2 as printed, read with tension-positive stress)
  Always,     ///< always (the symmetrised C_ij momentum equation with (4.13)'s symmetric stress term)
  Never       ///< never (basic SPH)
};
std::string switch_rule_name(SwitchRule rule);
/// Parses "tension", "as-printed", "always", "never"; throws std::invalid_argument otherwise.
SwitchRule parse_switch_rule(const std::string& name);

struct StabilisedSphOptions {
  NeighbourCounting counting = NeighbourCounting::BoundaryLevel;  ///< n_i of algorithm 4.1 (Fig. 4.3)
  bool first_step_shepard = true;  ///< means of the first-step Shepard gradient (4.18); false: of G itself
  /// Particles with depth <= excluded_depth (the outer layer BP of algorithm 4.2 for 0) never get the correction;
  /// -1 excludes none.
  int excluded_depth = 0;
  SwitchRule rule = SwitchRule::Tension;
  /// true: symmetrised pair interactions (algorithm 4.2); false: a_i + g_i per particle as in (4.14)-(4.17).
  bool symmetrise = true;
  /// Stress sums with |sum| <= switch_tolerance * (lambda + 2 mu) count as zero (switch "off" for Tension). Exactly
  /// zero stress (xi = 1 at the lattice) then stays on the off branch in complex-step evaluations, whose real parts
  /// carry O(h^2) ~ 1e-60 contamination. >= 0.
  double switch_tolerance = 1e-14;
};

/// Switch state: on[i][alpha] = the correction of component alpha of particle i is applied (N entries).
using SwitchState = std::vector<std::array<bool, 2>>;

/// The S-SPH correction as an ElasticForm2D term (see the file comment). Add it to an ElasticForm2D with
/// MomentumForm::Plus and the plain gradient (make_stabilised_sph does this).
class StabilisedSphTerm final : public ElasticTermT<StabilisedSphTerm> {
 public:
  /// Records the first-step sums S0, g0 and the counts n_i at the reference positions of `discretisation`.
  /// Throws std::invalid_argument for a null discretisation, depth missing (boundary-level counting) or a zero
  /// reference kernel sum.
  StabilisedSphTerm(std::shared_ptr<const Discretisation<2>> discretisation, const StabilisedSphOptions& options = {});

  std::string name() const override;
  OperatorRequest requirements() const override { return {.kernel = true, .gradient = true, .hessian = false}; }
  /// 3 hops: a_i reads g_ji, whose m_j averages c_k over k in N(j), and c_k reads positions in N(k).
  int dependence_radius() const override { return 3; }

  template <class Scalar>
  void add_impl(const ElasticTermContext<Scalar>& context, ParticleAccelerations<Scalar>& acc) const;

  /// r, c, m of algorithm 4.1 per axis for operators (W and G) at the current positions: the means of the first-step
  /// Shepard gradient (4.18) (or of G) with the counts n_i, computed in one fused pass over the pattern.
  template <class Scalar>
  std::array<LocalMeans<Scalar>, 2> local_means_of(const Operators<2, Scalar>& operators) const;

  /// The switch state for the stresses `stress` (N x 3, real parts), excluded particles off (or the frozen state);
  /// sums with |sum| <= zero_tolerance (stress units) count as zero.
  SwitchState switch_state(const Eigen::MatrixX3d& stress, double zero_tolerance = 0) const;
  /// A copy whose switch is fixed to `state` (N entries) regardless of the stresses.
  std::shared_ptr<StabilisedSphTerm> frozen(SwitchState state) const;
  bool is_frozen() const { return !m_frozen.empty(); }

  const StabilisedSphOptions& options() const { return m_options; }
  const Eigen::VectorXd& counts() const { return m_counts; }

 private:
  std::shared_ptr<const Discretisation<2>> m_disc;
  StabilisedSphOptions m_options;
  Eigen::VectorXd m_counts;
  std::array<ShepardReference, 2> m_reference;
  SwitchState m_frozen;
};

/// ElasticForm2D(Plus, plain gradient) + StabilisedSphTerm: the S-SPH force function.
std::shared_ptr<ElasticForm2D> make_stabilised_sph(std::shared_ptr<const Discretisation<2>> discretisation,
                                                   const ElasticMaterial& material, const PreStrain& prestrain,
                                                   const StabilisedSphOptions& options = {});

/// The S-SPH term of a force built by make_stabilised_sph (nullptr if it has none).
const StabilisedSphTerm* find_stabilised_sph_term(const ElasticForm2D& force);

/// A copy of an S-SPH force function with the switch frozen at the state of displacement u (for linearisation
/// and finite-difference checks). Throws std::invalid_argument if `force` has no StabilisedSphTerm.
std::shared_ptr<ElasticForm2D> freeze_switch(const ElasticForm2D& force, const Eigen::VectorXd& u);

}  // namespace sphstab
