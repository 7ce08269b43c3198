#include "sphstab/problems/powell_impact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

constexpr NamedValue<ImpactProblem> kImpactProblemNames[] = {
    {ImpactProblem::Symmetric, "symmetric"}, {ImpactProblem::Bar, "bar"}, {ImpactProblem::Beam, "beam"}};
constexpr NamedValue<ImpactTLModel> kImpactTLModelNames[] = {{ImpactTLModel::Linear, "linear"},
                                                             {ImpactTLModel::StVenantKirchhoff, "svk"}};

ImpactProblem parse_impact_problem(const std::string& name) {
  return parse_named(name, kImpactProblemNames, "impact problem");
}
std::string impact_problem_name(ImpactProblem problem) { return name_of(problem, kImpactProblemNames); }

PowellImpactOptions problem_defaults(PowellImpactOptions o) {
  struct Defaults {
    double length, height, speed, split, t_end;
  };
  const Defaults d = o.problem == ImpactProblem::Symmetric ? Defaults{1.0, 1.0, 0.06, 0.5, 6.0}
                     : o.problem == ImpactProblem::Bar     ? Defaults{4.0, 0.4, 0.06, 0.25, 40.0}
                                                           : Defaults{4.0, 0.4, 0.3, 0.1, 20.0};
  if (std::isnan(o.length)) o.length = d.length;
  if (std::isnan(o.height)) o.height = d.height;
  if (std::isnan(o.speed)) o.speed = d.speed;
  if (std::isnan(o.split)) o.split = d.split;
  if (std::isnan(o.t_end)) o.t_end = d.t_end;
  return o;
}

int impact_clamp_layers(double clamp, double spacing) {
  const double layers = clamp / spacing;
  if (!(std::abs(layers - std::round(layers)) <= 1e-9 * layers) || !(std::round(layers) >= 1))
    throw std::invalid_argument("impact_clamp_layers: dx = " + format_number(spacing) + " does not divide the " +
                                format_number(clamp) + " cm clamp into whole layers");
  return static_cast<int>(std::lround(layers));
}

RateFormOptions powell_formulation_options(const std::string& formulation) {
  RateFormOptions o{.continuity = ContinuityForm::Divergence,  // MCM (1.32)
                    .bulk_viscosity_quadratic = 1.5,           // MCM deck: QBVC
                    .bulk_viscosity_linear = 0.06};            // LBVC
  if (formulation == "sph") return o;
  if (formulation == "ncsph") {
    o.gradient = RateFormGradient::Ncsph;  // (1.19)
    return o;
  }
  if (formulation == "ssph") {
    o.momentum = RateFormMomentum::StabilisedSph;   // algorithm 4.2
    o.counting = NeighbourCounting::BoundaryLevel;  // Fig. 4.3
    o.first_step_shepard = true;                    // (4.18): the means of the first-step Shepard gradient
    return o;
  }
  throw std::invalid_argument("unknown rate-form formulation '" + formulation + "' (valid: sph, ncsph, ssph)");
}

namespace {

/// Whole number of spacings in `value`, or a one-line error.
int whole_spacings(double value, double dx, int multiple, const std::string& what) {
  check_length(value, "powell_impact_scene: " + what);
  const double n = value / dx;
  if (!(n <= 1e6))
    throw std::invalid_argument("powell_impact_scene: " + what + " " + format_number(value) + " is " +
                                format_number(n, 3) + " spacings of dx = " + format_number(dx) +
                                ", more than 1e6 along one side");
  const long k = std::lround(n / multiple) * multiple;
  if (k < multiple || std::abs(n - static_cast<double>(k)) > 1e-9 * n)
    throw std::invalid_argument("powell_impact_scene: " + what + " " + format_number(value) +
                                " must be a whole multiple of " + std::to_string(multiple) +
                                " dx = " + format_number(multiple * dx));
  return static_cast<int>(k);
}

/// The particle nearest the problem's point A (lowest index on ties).
int particle_a(const ParticleSet<2>& q, const PowellImpactOptions& o) {
  const double dx = o.spacing, length = o.length, height = o.height;
  const double split = std::round(o.split * length / dx) * dx;
  Eigen::Vector2d target = Eigen::Vector2d::Zero();
  switch (o.problem) {
    case ImpactProblem::Symmetric:
      target = {0.5 * length, 0.75 * height};
      break;
    case ImpactProblem::Bar:
      target = {split - 0.5 * dx, 0.5 * height};
      break;
    case ImpactProblem::Beam:
      target = {0.5 * length - 0.5 * dx, 0.5 * dx};
      break;
  }
  int a = -1;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < q.size(); ++k) {
    const double d = (q.x.row(k).transpose() - target).norm();
    if (q.role[k] == Role::Free && d < best - 1e-12 * dx) best = d, a = k;
  }
  return a;
}

/// The block's particles (free first, clamped columns last), after checking every option; o has its defaults.
ParticleSet<2> impact_particles(const PowellImpactOptions& o) {
  const char* who = "powell_impact_scene";
  check_length(o.spacing, std::string(who) + ": spacing");
  const double dx = o.spacing;
  // The symmetric impact's plane lies between two particle rows: an even row count.
  const int nx = whole_spacings(o.length, dx, 1, "length");
  const int ny = whole_spacings(o.height, dx, o.problem == ImpactProblem::Symmetric ? 2 : 1, "height");
  if (!std::isfinite(o.speed))
    throw std::invalid_argument(std::string(who) + ": speed must be finite (got " + format_number(o.speed) + ")");
  if (!(o.t_end > 0) || !std::isfinite(o.t_end))
    throw std::invalid_argument(std::string(who) + ": t_end must be finite and > 0 (got " + format_number(o.t_end) +
                                ")");
  if (!(o.split > 0 && o.split < 1))
    throw std::invalid_argument(std::string(who) + ": split must be in (0, 1) (got " + format_number(o.split) + ")");
  // The split plane (bar) or the section's edges (beam) between particle columns.
  const double columns = o.split * nx;
  if (o.problem != ImpactProblem::Symmetric && std::abs(columns - std::round(columns)) > 1e-9 * nx)
    throw std::invalid_argument(std::string(who) + ": split * length / dx = " + format_number(columns) +
                                " must be a whole number of particle columns");
  const int split_columns = static_cast<int>(std::lround(columns));
  if (o.problem == ImpactProblem::Beam && (nx - split_columns) % 2 != 0)
    throw std::invalid_argument(std::string(who) + ": the beam's section (" + std::to_string(split_columns) +
                                " columns) must leave an even number of columns to centre it in " + std::to_string(nx));
  const int clamp = o.problem == ImpactProblem::Beam ? o.clamp_layers : 0;
  if (o.problem == ImpactProblem::Beam && (clamp < 1 || 2 * clamp + split_columns > nx))
    throw std::invalid_argument(std::string(who) + ": clamp_layers " + std::to_string(o.clamp_layers) +
                                " must be >= 1 and leave the section free (" + std::to_string(nx) + " columns)");

  // Free particles first, clamped columns last (the TL form and the DOF order want free first).
  ParticleSet<2> p;
  const long total = static_cast<long>(nx) * ny;
  // Before allocating: the particle set (positions, volume, role, depth, order) and the rate-form state and its
  // neighbour list (about 13 neighbours within 2h = 2.6 dx, 8 state values per particle), a lower bound.
  require_memory(static_cast<double>(total) * (8 * 3 + 4 * 3 + 8 * 8 + 4 * 25), std::string(who) + " particles");
  p.x.resize(total, 2);
  p.volume = Eigen::VectorXd::Constant(total, dx * dx);
  p.role.resize(total);
  p.depth.resize(total);
  p.spacing = dx;
  std::vector<std::pair<int, int>> order;  // (column, row)
  for (int pass = 0; pass < 2; ++pass)
    for (int r = 0; r < ny; ++r)
      for (int c = 0; c < nx; ++c)
        if ((c < clamp || c >= nx - clamp) == (pass == 1)) order.emplace_back(c, r);
  for (long k = 0; k < total; ++k) {
    const auto [c, r] = order[k];
    p.x(k, 0) = (c + 0.5) * dx;
    p.x(k, 1) = (r + 0.5) * dx;
    p.role[k] = (c < clamp || c >= nx - clamp) ? Role::Fixed : Role::Free;
    p.depth[k] = std::min({c, nx - 1 - c, r, ny - 1 - r});
  }
  return p;
}

}  // namespace

int impact_particle_a(const PowellImpactOptions& options) {
  const PowellImpactOptions o = problem_defaults(options);
  return particle_a(impact_particles(o), o);
}

Scene<2> powell_impact_scene(const PowellImpactOptions& options) {
  const PowellImpactOptions o = problem_defaults(options);
  ParticleSet<2> p = impact_particles(o);
  const double dx = o.spacing;
  Scene<2> s;
  s.name = o.problem == ImpactProblem::Symmetric ? "symmetric-impact"
           : o.problem == ImpactProblem::Bar     ? "bar-impact"
                                                 : "clamped-beam";
  s.spacing = dx;
  s.t_end = o.t_end;
  // as the MCM deck runs them: Powell's leap-frog [Powell2012, algorithm 1.1] with XSPH (2.71) 0.1, TSSFAC 0.8
  s.integrator = "leapfrog";
  s.leapfrog_xsph = 0.1;
  s.cfl = 0.8;
  const Kernel<2> kernel(KernelType::CubicSpline);
  s.scheme = std::make_shared<RateFormScheme<2>>(make_discretisation(std::move(p), kernel, o.h_over_dx * dx),
                                                 o.material, o.scheme);
  s.y0 = s.scheme->uniform_state();
  const ParticleSet<2>& q = s.scheme->discretisation().particles;
  const double length = o.length, height = o.height;
  const int split_columns = static_cast<int>(std::lround(o.split * length / dx));
  for (int k = 0; k < q.size(); ++k) {
    if (q.role[k] != Role::Free) continue;
    const double x = q.x(k, 0), y = q.x(k, 1);
    Eigen::Vector2d v = Eigen::Vector2d::Zero();
    switch (o.problem) {
      case ImpactProblem::Symmetric:
        v.y() = y > 0.5 * height ? -o.speed : o.speed;
        break;  // Fig. 4.5
      case ImpactProblem::Bar:
        v.x() = x < split_columns * dx ? o.speed : -o.speed;
        break;
      case ImpactProblem::Beam:
        if (std::abs(x - 0.5 * length) < 0.5 * split_columns * dx) v.y() = -o.speed;
        break;
    }
    s.scheme->set_velocity(s.y0, k, v);
  }
  const int a = particle_a(q, o);
  const RateFormScheme<2>& scheme = *s.scheme;
  const int rho_a = scheme.density_offset(a), v_a = scheme.velocity_offset(a);
  const double y_a = q.x(a, 1), K = o.material.bulk_modulus(), rho0 = o.material.density();
  s.measures.push_back({"pressure_A", [rho_a, K, rho0](const Eigen::Matrix2Xd&, const Eigen::VectorXd& y) {
                          return K * (y[rho_a] / rho0 - 1);  // GMS (2.7)
                        }});
  s.measures.push_back(
      {"speed_A", [v_a](const Eigen::Matrix2Xd&, const Eigen::VectorXd& y) { return y.segment<2>(v_a).norm(); }});
  std::vector<int> free = s.scheme->discretisation().free;
  s.measures.push_back({"length", [free](const Eigen::Matrix2Xd& x, const Eigen::VectorXd&) {
                          double lo = std::numeric_limits<double>::infinity(), hi = -lo;
                          for (int k : free) lo = std::min(lo, x(0, k)), hi = std::max(hi, x(0, k));
                          return hi - lo;
                        }});
  s.measures.push_back(
      {"deflection", [a, y_a](const Eigen::Matrix2Xd& x, const Eigen::VectorXd&) { return x(1, a) - y_a; }});
  if (o.problem == ImpactProblem::Bar) std::swap(s.measures[0], s.measures[2]);   // headline: the bar's length
  if (o.problem == ImpactProblem::Beam) std::swap(s.measures[0], s.measures[3]);  // the beam's deflection
  s.neighbour_skin = 0.5 * dx;  // fracturing runs move particles by many h
  return s;
}

ImpactTLModel parse_impact_tl_model(const std::string& name) {
  return parse_named(name, kImpactTLModelNames, "TL-SPH model");
}

ImpactTotalLagrangian impact_total_lagrangian(const Scene<2>& scene, ImpactTLModel model) {
  if (!scene.scheme) throw std::invalid_argument("impact_total_lagrangian: scene without a scheme");
  const RateFormScheme<2>& scheme = *scene.scheme;
  // Aliasing: the discretisation lives as long as the scheme that owns it.
  const std::shared_ptr<const Discretisation<2>> disc(scene.scheme, &scheme.discretisation());
  const ElasticMaterial& m = scheme.material();
  // lambda = K - 2 mu / 3 from the scheme's K (not the E, nu lambda of from_young_poisson): the TL runs have always
  // used this derived value, and a last-bit change would show in the impact studies' long runs.
  const ElasticMaterial material = ElasticMaterial::from_bulk_shear(m.bulk_modulus(), m.mu(), m.density());
  ImpactTotalLagrangian tl;
  if (model == ImpactTLModel::Linear) {
    auto form = std::make_shared<const TotalLagrangianForm2D>(disc, material);
    tl.form = form;
    tl.system.strain_energy = [form](const Eigen::VectorXd& u) { return form->strain_energy(u); };
  } else {
    const auto svk = std::make_shared<const StVenantKirchhoff<2>>(material);
    auto form = std::make_shared<const FiniteStrainTotalLagrangian<2>>(disc, svk, m.density());
    tl.form = form;
    // Not thread-safe (scratch arrays): one form per run, as here.
    tl.system.strain_energy = [form](const Eigen::VectorXd& u) { return form->strain_energy(u); };
  }
  tl.system.acceleration = acceleration_function(tl.form);
  tl.system.dofs_per_particle = 2;
  tl.system.mass = m.density() * disc->particles.volume(disc->free);
  tl.system.reference_positions = disc->free_positions().transpose().reshaped();
  const Eigen::Matrix2Xd v = rate_form_velocities(scheme, scene.y0);
  const double K = m.bulk_modulus();
  const bool finite = model == ImpactTLModel::StVenantKirchhoff;
  tl.pressure = [disc, K, finite](const Eigen::VectorXd& u, int i) {
    if (i < 0 || i >= disc->size())
      throw std::invalid_argument("impact_total_lagrangian: particle " + std::to_string(i) + " out of range");
    const auto at = [&](int j) -> Eigen::Vector2d {
      const int f = disc->free_slot[j];
      return f < 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(u.segment<2>(2 * f));
    };
    Eigen::Matrix2d grad = Eigen::Matrix2d::Zero();
    double div = 0;  // summed pair by pair, as tr(grad) in another order
    const Eigen::Vector2d ui = at(i);
    for (long k = disc->neighbours.offsets[i]; k < disc->neighbours.offsets[i + 1]; ++k) {
      const int j = disc->neighbours.indices[k];
      const Eigen::Vector2d r = (disc->particles.x.row(i) - disc->particles.x.row(j)).transpose();
      const double d = r.norm();
      if (j == i || d == 0) continue;
      const Eigen::Vector2d g = disc->kernel.d1(d, disc->h) / d * r;  // grad_i W(x0_i - x0_j)
      div += disc->particles.volume[j] * (at(j) - ui).dot(g);
      if (finite) grad += disc->particles.volume[j] * (at(j) - ui) * g.transpose();
    }
    if (!finite) return -K * div;
    return K * (1 / (Eigen::Matrix2d::Identity() + grad).determinant() - 1);
  };
  tl.v0.resize(disc->dofs());
  for (int f = 0; f < disc->free_count(); ++f) tl.v0.segment<2>(2 * f) = v.col(disc->free[f]);
  return tl;
}

}  // namespace sphstab
