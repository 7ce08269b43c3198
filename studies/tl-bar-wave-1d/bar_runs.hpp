#pragma once
// The runs of the tl-bar-wave-1d study [Ismail2009, §4.6.3, §5.3.1] and the time-stepped system of one run:
// - the case table: Hooke 1D stress (Ismail's algorithm 4.1, T11 = E eps), Neo-Hookean 1D strain (algorithm 5.1) and
//   Neo-Hookean 1D stress with the clamped end, and Hooke 1D stress with the mirror, eta and modified-matrix fixed
//   ends (fixed_end.hpp);
// - BarRun: the finite-strain TL form (forms/finite_strain_total_lagrangian.hpp) on the bar of common/ismail_bar.hpp
//   with its ghost closure (left: the exact incoming wave; right: the run's fixed end), recomputed from the free
//   displacements at every force evaluation, the leap-frog system and its time step.
#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "common/ismail_bar.hpp"
#include "fixed_end.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace bar_wave {

struct Run {
  std::string name;
  std::shared_ptr<const HyperelasticModel<1>> material;
  double c = 0;  ///< small-strain speed of the material's 1D state
  FixedEnd fixed_end = FixedEnd::Clamped;
  /// The Hooke runs (every fixed end): with Hooke's law the TL form is linear in u, so the closed loop is exact.
  bool fixed_end_run() const { return name.rfind("hooke", 0) == 0; }
};

/// The case table; cb = sqrt(E / rho) (1D stress), cl = sqrt((lambda + 2 mu) / rho) (1D strain).
inline std::vector<Run> bar_runs(const ElasticMaterial& lame, double cb, double cl) {
  return {
      {"hooke-1d-stress", std::make_shared<Hooke<1>>(lame, UniaxialState::Stress), cb},
      {"neo-hookean-1d-strain", std::make_shared<NeoHookean<1>>(lame, UniaxialState::Strain), cl},
      {"neo-hookean-1d-stress", std::make_shared<NeoHookean<1>>(lame, UniaxialState::Stress), cb},
      {"hooke-1d-stress-mirror", std::make_shared<Hooke<1>>(lame, UniaxialState::Stress), cb, FixedEnd::Mirror},
      {"hooke-1d-stress-eta", std::make_shared<Hooke<1>>(lame, UniaxialState::Stress), cb, FixedEnd::Eta},
      {"hooke-1d-stress-modified", std::make_shared<Hooke<1>>(lame, UniaxialState::Stress), cb, FixedEnd::Modified}};
}

/// One run on one resolution: the TL form, its ghost closure, the leap-frog system and the time step. The system's
/// closures refer to this object: it is neither copied nor moved.
class BarRun {
 public:
  BarRun(const Bar& bar, const FixedEndOperators& ends, const Run& run_case)
      : run(run_case),
        tl(bar.disc, run_case.material, kRho),
        c(run_case.c),
        v0(source_velocity(c)),  // particle velocity of the incoming compressive wave
        modified_op(&ends.modified),
        m_bar(bar),
        m_ends(ends),
        m_d(bar.x_fixed.size()),
        m_u_all(Eigen::VectorXd::Zero(bar.disc->size())) {
    // time step: half the leap-frog limit 2 / sqrt(lambda_max(M^-1 K)) at rest (clamped ghosts)
    set_fixed(Eigen::VectorXd::Zero(tl.dofs()));
    dt = 0.5 * stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs())).dt;
    t_end = 1.9 * kLength / c;  // before the fixed-end reflection reaches the source
    sys.acceleration = [this](const Eigen::VectorXd& u, Eigen::VectorXd& a) {
      set_fixed(u);
      tl.acceleration(u, a);
    };
    sys.set_time = [this](double t) { set_time(t); };
    sys.mass = tl.dof_mass();
  }
  BarRun(const BarRun&) = delete;
  BarRun& operator=(const BarRun&) = delete;

  /// The fixed displacements at t_now for the free displacements u: left, the incoming wave; right, the fixed end.
  void set_fixed(const Eigen::VectorXd& u) {
    const auto& disc = m_bar.disc;
    const std::vector<double>& x_fixed = m_bar.x_fixed;
    const RightGhosts& g = m_ends.ghosts;
    for (std::size_t k = 0; k < x_fixed.size(); ++k) m_d[k] = source_displacement(x_fixed[k], t_now, c, v0);
    if (run.fixed_end == FixedEnd::Mirror) {
      for (std::size_t k = 0; k < x_fixed.size(); ++k)
        if (g.mirror_free[k] >= 0) m_d[k] = -u[g.mirror_free[k]];
    } else if (run.fixed_end != FixedEnd::Clamped) {
      for (int f = 0; f < disc->free_count(); ++f) m_u_all[disc->free[f]] = u[f];
      for (std::size_t k = 0; k < x_fixed.size(); ++k) m_u_all[g.fixed_index[k]] = m_d[k];  // right ghosts start at 0
      if (run.fixed_end == FixedEnd::Eta)
        m_ends.eta.apply(m_u_all, 0.0);  // Ismail (2.42): <u>(L) = 0
      else
        modified_op->apply(m_u_all,
                           Eigen::VectorXd::Zero(static_cast<Eigen::Index>(modified_op->constrained().size())));
      for (std::size_t k = 0; k < x_fixed.size(); ++k)
        if (x_fixed[k] > kLength) m_d[k] = m_u_all[g.fixed_index[k]];
    }
    tl.set_fixed_displacement(m_d);
  }
  void set_time(double t) { t_now = t; }

  const Run& run;
  FiniteStrainTotalLagrangian<1> tl;
  const double c, v0;
  double t_now = 0;  ///< the time of the left source
  double dt = 0, t_end = 0;
  SecondOrderSystem sys;
  /// The closure of the modified runs (the layer sweep of closed_loop.hpp points it elsewhere while probing).
  const ModifiedMatrixDirichlet* modified_op;

 private:
  const Bar& m_bar;
  const FixedEndOperators& m_ends;
  Eigen::VectorXd m_d, m_u_all;
};

}  // namespace bar_wave
