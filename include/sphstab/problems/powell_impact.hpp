#pragma once
/// \file powell_impact.hpp
/// Powell's three impact problems [Powell2012, ch. 4 §4, Figs. 4.5-4.18] as Scenes (problems/scene.hpp): a
/// rectangular block of steel (g-cm-us: rho0 7.8, E 2.1, nu 0.3; linear elasticity; plane strain), h = 1.3 dx, on the
/// rate-form scheme with MCM's configuration per formulation (powell_formulation_options), and TL-SPH on the same
/// particles (impact_total_lagrangian).
///
///   symmetric  (§4.1, Fig. 4.5) one block whose top half starts with v_y = -v0 and bottom half with +v0: v0 > 0 the
///              halves approach (initial compression, §4.1.1), v0 < 0 they separate (initial expansion, §4.1.2)
///   bar        (§4.2, Fig. 4.10) a bar along x whose part left of x = split * length starts with v_x = +v0 and the
///              rest with -v0 ("identical to the previous case save the dimensions": an impact plane off the middle)
///   beam       (§4.3, Fig. 4.13) a block with its first and last `clamp_layers` (5) vertical layers fixed; the section
///              of width `split` * length centred at mid-span starts with v_y = -v0 (Powell: 0.3 cm/us)
///
/// The figures' dimensions are drawings, not text. Taken from the text: material, h / dx, the speeds, the five clamped
/// layers. Taken from the MCM input deck [Powell2012, appendix B]: the spacing dx = 0.02 cm (its nodes 0.01 ... 0.99)
/// and INITIALH 0.026 = 1.3 dx. Chosen here (each an option, each a study parameter): the block sizes, the bar's
/// impact plane, the beam's loaded section, particle A and the run lengths; problem_defaults() returns them.
///
/// Particles sit at ((i + 1/2) dx, (j + 1/2) dx), i < nx, j < ny (the block spans [0, length] x [0, height]), free
/// particles first (the beam's clamped ones last), depth = the boundary level of Fig. 4.3 (0 on the outer layer).
/// A particle whose initial velocity region is ambiguous (on the split plane) cannot occur: the planes lie between
/// particle rows (sizes whole multiples of dx, the symmetric block's height of 2 dx, the bar's split and the beam's
/// section edges between particle columns; checked).
///
/// Measures: "pressure_A" p = K (rho / rho0 - 1) at particle A, "speed_A" |v_A|, "length" (max - min x of the free
/// particles: the bar's length, Fig. 4.11), "deflection" (y displacement of the bottom particle nearest mid-span:
/// the beam's midline bottom-surface displacement, Fig. 4.14). Particle A: symmetric, the particle nearest the
/// centre of the top half (length / 2, 3 height / 4); bar, the particle nearest the impact plane at mid-height on its
/// left; beam, the bottom mid-span particle.
///
/// \code{.cpp}
/// sphstab::Scene<2> s = sphstab::powell_impact_scene({.problem = sphstab::ImpactProblem::Symmetric,
///                                                     .scheme = sphstab::powell_formulation_options("ssph")});
/// const auto r = sphstab::run_rate_form(*s.scheme, s.y0, {.dt = s.time_step(0.8), .t_end = s.t_end,
///     .integrator = sphstab::RateFormIntegrator::Leapfrog, .leapfrog_xsph = 0.1});
/// \endcode
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/total_lagrangian.hpp"
#include "sphstab/problems/scene.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

enum class ImpactProblem { Symmetric, Bar, Beam };

/// "symmetric" | "bar" | "beam"; throws std::invalid_argument naming the valid choices.
ImpactProblem parse_impact_problem(const std::string& name);
std::string impact_problem_name(ImpactProblem problem);

struct PowellImpactOptions {
  ImpactProblem problem = ImpactProblem::Symmetric;
  double spacing = 0.02;  ///< dx (cm), the MCM deck's
  /// NaN: the problem's default (problem_defaults). length and height: the block (cm), whole multiples of dx (the
  /// symmetric impact's height of 2 dx).
  double length = std::numeric_limits<double>::quiet_NaN();
  double height = std::numeric_limits<double>::quiet_NaN();
  /// v0 (cm/us). symmetric and bar: > 0 the parts approach, < 0 they separate; beam: the section's downward speed.
  double speed = std::numeric_limits<double>::quiet_NaN();
  /// bar: impact plane at split * length; beam: loaded section width split * length. In (0, 1).
  double split = std::numeric_limits<double>::quiet_NaN();
  double t_end = std::numeric_limits<double>::quiet_NaN();  ///< run length (us)
  int clamp_layers = 5;                                     ///< beam: fixed vertical layers at each end [§4.3]
  double h_over_dx = 1.3;
  ElasticMaterial material = ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8);
  RateFormOptions scheme;
};

/// The problem's defaults for the NaN fields (the choices listed above):
///   symmetric: 1 x 1 cm, v0 0.06, t_end 6 us;  bar: 4 x 0.4 cm, split 0.25, v0 0.06, t_end 40 us;
///   beam: 4 x 0.4 cm ("the physical dimensions and discretisation are as in figure 4.10": the bar's, Fig. 4.13),
///   section 0.1 (0.4 cm), v0 0.3, t_end 20 us.
PowellImpactOptions problem_defaults(PowellImpactOptions options);

/// MCM's rate form for a formulation name [Powell2012, ch. 4]: "sph" (plain gradient, symmetric momentum (1.36)),
/// "ncsph" (NCSPH gradient (1.19)), "ssph" (S-SPH momentum, algorithm 4.2 with Fig. 4.3's boundary-level counts and the
/// row mean normalised on the first step, (4.18));
/// each with MCM's continuity -rho tr L (1.32) and the material card's bulk viscosity (QBVC 1.5, LBVC 0.06). The
/// velocity smoothing (2.71) is the leap-frog's (RateFormRunOptions::leapfrog_xsph), not part of the scheme. Throws
/// std::invalid_argument naming the valid names ("tl" is not a rate form: impact_total_lagrangian).
RateFormOptions powell_formulation_options(const std::string& formulation);

/// The scene (name "symmetric-impact", "bar-impact" or "clamped-beam"). Throws std::invalid_argument for a spacing or
/// size outside check_length's range, sizes that are not whole multiples of dx (2 dx: the symmetric height),
/// MemoryLimitError for a block whose estimated memory exceeds the limit (before allocating), a split outside (0, 1) or
/// off the particle rows, a non-finite speed or t_end <= 0, clamp layers < 1 or leaving no free particle, and as the
/// scheme.
Scene<2> powell_impact_scene(const PowellImpactOptions& options);

/// The beam's clamp of width `clamp` (cm) as whole vertical layers of dx (PowellImpactOptions::clamp_layers). Throws
/// std::invalid_argument("... does not divide ...") unless dx divides the width into at least one layer (1e-9).
int impact_clamp_layers(double clamp, double spacing);

/// Particle A of the scene powell_impact_scene(options) builds (its index; throws as the scene).
int impact_particle_a(const PowellImpactOptions& options);

/// Material model of TL-SPH on an impact scene.
///   Linear            Powell's TL-SPH: small-strain linear elasticity, the kernel frozen at the initial positions
///                     (forms/total_lagrangian.hpp); a rigid rotation strains it
///   StVenantKirchhoff the same operators with finite strain, S = lambda tr(E) I + 2 mu E, P = F S
///                     (forms/finite_strain_total_lagrangian.hpp: difference strain sum, Plus divergence; with Hooke's
///                     law it is the linear form exactly): for the clamped beam's large deflection, where rotations
///                     are not small
enum class ImpactTLModel { Linear, StVenantKirchhoff };

/// "linear" | "svk"; throws std::invalid_argument naming the valid choices.
ImpactTLModel parse_impact_tl_model(const std::string& name);

/// TL-SPH [Powell2012, ch. 4 §2.2] on a scene's particles: a total-Lagrangian form on the scheme's discretisation
/// (`model`), with the scene's material (lambda = K - 2 mu / 3, plane strain) and initial velocities. The run is
/// run_leapfrog(system, 0, v0, ...); positions are x0 + u (fixed particles stay at x0). Throws std::invalid_argument
/// for a scene whose fixed particles do not come last.
struct ImpactTotalLagrangian {
  std::shared_ptr<const ForceFunction> form;
  SecondOrderSystem system;
  Eigen::VectorXd v0;  ///< free-particle velocities in DOF order
  /// Pressure of particle i with the TL gradient (Grad u)_i = sum_j (u_j - u_i) V_j grad W(x0_i - x0_j), F = I + Grad
  /// u: Linear, p = -K tr(Grad u) (the linear pressure, comparable with the rate form's K (rho / rho0 - 1) to first
  /// order in the strain); StVenantKirchhoff, p = K (1 / det F - 1), the rate form's K (rho / rho0 - 1) with rho / rho0
  /// = 1 / det F.
  std::function<double(const Eigen::VectorXd& u, int particle)> pressure;
};
ImpactTotalLagrangian impact_total_lagrangian(const Scene<2>& scene, ImpactTLModel model = ImpactTLModel::Linear);

}  // namespace sphstab
