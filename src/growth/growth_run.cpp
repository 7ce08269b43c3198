#include "sphstab/growth/growth_run.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sphstab {

template <int Dim>
GrowthRun run_growth_test(std::shared_ptr<const Discretisation<Dim>> disc, std::shared_ptr<const ForceFunction> force,
                          const Eigen::VectorXd& u0_in, const Eigen::VectorXd& v0, const GrowthRunOptions& o) {
  const char* who = "run_growth_test";
  if (!disc || !force) throw std::invalid_argument(std::string(who) + ": discretisation or force function is null");
  const Discretisation<Dim>& d = *disc;
  if (force->dofs() != d.dofs() || force->dim() != Dim)
    throw std::invalid_argument(std::string(who) + ": force function has " + std::to_string(force->dofs()) +
                                " DOFs, the discretisation " + std::to_string(d.dofs()));
  const Eigen::VectorXd u0 = u0_in.size() ? u0_in : Eigen::VectorXd::Zero(d.dofs());
  if (u0.size() != d.dofs() || v0.size() != d.dofs())
    throw std::invalid_argument(std::string(who) + ": u0 and v0 need " + std::to_string(d.dofs()) + " entries (got " +
                                std::to_string(u0.size()) + ", " + std::to_string(v0.size()) + ")");
  if (!(o.dt > 0) || !(o.t_end > 0) || !(o.displacement_limit > 0) || !(o.linear_limit > 0) || o.record_every < 1 ||
      !(o.reference_time >= 0) || !std::isfinite(o.dt) || !std::isfinite(o.t_end) || !std::isfinite(o.reference_time))
    throw std::invalid_argument(std::string(who) +
                                ": need finite dt, t_end, displacement_limit, linear_limit > 0, reference_time >= 0 "
                                "and record_every >= 1");
  SecondOrderSystem sys;
  sys.acceleration = acceleration_function(force);
  sys.dofs_per_particle = Dim;
  const Eigen::VectorXd dof_mass = force->dof_mass();
  sys.mass.resize(d.free_count());
  for (int f = 0; f < d.free_count(); ++f) sys.mass[f] = dof_mass[f * Dim];
  sys.reference_positions.resize(d.dofs());
  for (int f = 0; f < d.free_count(); ++f)
    for (int a = 0; a < Dim; ++a) sys.reference_positions[f * Dim + a] = d.particles.x(d.free[f], a);
  if (o.xsph) {
    sys.velocity_hook = xsph_hook<Dim>(disc, o.xsph_options);
    sys.hook_mode = o.xsph_mode;
  }
  GrowthRun run;
  bool linear = true;
  auto sample = [&](double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
    const double ke = 0.5 * (dof_mass.array() * v.array().square()).sum();
    const double umax = (u - u0).cwiseAbs().maxCoeff();
    run.t.push_back(t);
    run.kinetic.push_back(ke);
    run.max_displacement.push_back(umax);
    if (linear && umax <= o.linear_limit) {
      run.t_linear_end = t;
      run.u_linear = u - u0;
    } else {
      linear = false;
    }
  };
  LeapfrogOptions lo;
  lo.dt = o.dt;
  lo.t_end = o.t_end;
  lo.record_every = 0;
  lo.keep_history = false;
  lo.observe_every = o.record_every;
  lo.observer = [&](const StepView& s) { sample(s.time, s.u, s.v); };
  // The limit applies to u - u0; u0 is small where it is used (a nearby equilibrium), so shift the bound.
  lo.limits.max_displacement = o.displacement_limit + u0.cwiseAbs().maxCoeff();
  lo.observers = o.observers;
  const LeapfrogResult r = run_leapfrog(sys, u0, v0, lo);
  if (r.status != RunStatus::Completed && r.u.allFinite() && r.v.allFinite() &&
      (run.t.empty() || r.time > run.t.back()))
    sample(r.time, r.u, r.v);
  run.status = r.status;
  run.message = r.message;
  run.steps = r.steps;
  run.t_stop = r.time;
  run.dt = r.dt;
  run.u_end = r.u;
  run.wall_seconds = r.wall_seconds;
  run.initial_energy = 0.5 * (dof_mass.array() * v0.array().square()).sum();
  // The fit window ends with the linear regime, or (out-of-equilibrium start) with the run.
  const double t_fit_end = o.reference_time > 0 ? run.t_stop : run.t_linear_end;
  run.reference_energy = run.initial_energy;
  for (std::size_t k = 0; k < run.t.size() && run.t[k] <= o.reference_time; ++k)
    run.reference_energy = std::max(run.reference_energy, run.kinetic[k]);
  if (run.t.size() >= 2 && run.reference_energy > 0)
    run.fit = fit_exponential_growth(run.t, run.kinetic, run.reference_energy, t_fit_end, o.window);
  return run;
}

template GrowthRun run_growth_test<1>(std::shared_ptr<const Discretisation<1>>, std::shared_ptr<const ForceFunction>,
                                      const Eigen::VectorXd&, const Eigen::VectorXd&, const GrowthRunOptions&);
template GrowthRun run_growth_test<2>(std::shared_ptr<const Discretisation<2>>, std::shared_ptr<const ForceFunction>,
                                      const Eigen::VectorXd&, const Eigen::VectorXd&, const GrowthRunOptions&);

}  // namespace sphstab
