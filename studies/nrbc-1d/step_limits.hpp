#pragma once
// The time-step limits that explain the X entries of [Powell2012, Table 2.1], two independent ways: the largest CFL at
// which a case runs stably to t_to (bisection on whole runs), and the largest CFL at which the spectral radius of the
// leap-frog's one-step map linearised at rest stays <= 1 + 1e-6 (integrate/rate_form_run.hpp, leapfrog_step_matrix;
// dense LAPACK eigenvalues), undamped and damped; with the radius at the table's CFL.
#include <cmath>
#include <stdexcept>
#include <vector>

#include "bar_problem.hpp"
#include "bar_run.hpp"
#include "common/study.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"

namespace nrbc1d {

/// Largest CFL in [lo, hi] for which stable(cfl) holds, by geometric bisection to relative resolution 1e-2 (stability
/// assumed monotone in dt: sampling, not proof). Returns hi when hi is stable, 0 when lo is not.
template <class Stable>
inline double largest_stable_cfl(double lo, double hi, Stable&& stable) {
  if (stable(hi)) return hi;
  if (!stable(lo)) return 0;
  while (hi / lo - 1 > 1e-2) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

/// Largest CFL at which the case runs stably to t_to.
inline double stable_cfl_limit(BarCase c, double lo, double hi) {
  c.keep_series = false;
  return largest_stable_cfl(lo, hi, [&](double cfl) {
    c.cfl = cfl;
    return run_bar(c).stable;
  });
}

/// Spectral radius of the leap-frog's linearised step at rest (integrate/rate_form_run.hpp, leapfrog_step_matrix):
/// > 1 + 1e-6 means small perturbations grow at this dt (the threshold sits far above the central differences' noise,
/// ~1e-8, and far below the growth of the unstable cases, >= 1e-4 per step).
/// The compression switch of the viscosity is not differentiable at rest (v_ij . r_ij = 0), so the scheme as run lies
/// between two linearisations: undamped (viscosity off) and damped (the linear term on every pair, Always).
inline double step_radius(BarCase c, ViscositySwitch viscosity) {
  c.viscosity = viscosity;
  if (c.mirror) c.particles /= 2;  // the same 1 cm in all: a 600 x 600 step matrix
  const BarScene scene = make_bar(c);
  const RateFormScheme<1>& s = *scene.scheme;
  const RateFormRunOptions o = run_options(c);
  const DenseGeneralEigen e = general_eigen(leapfrog_step_matrix(s, s.uniform_state(), o.dt, o));
  if (e.lapack_info != 0) throw std::runtime_error("nrbc-1d: dgeev did not converge for " + tag_of(c));
  return e.values.cwiseAbs().maxCoeff();
}
constexpr double kRadiusTolerance = 1e-6;

/// Largest CFL with step radius <= 1 + kRadiusTolerance.
inline double linear_cfl_limit(BarCase c, ViscositySwitch viscosity, double lo, double hi) {
  return largest_stable_cfl(lo, hi, [&](double cfl) {
    c.cfl = cfl;
    return step_radius(c, viscosity) <= 1 + kRadiusTolerance;
  });
}

/// The limits of every case of the limit phase, index by index.
struct StepLimits {
  std::vector<BarCase> cases;
  std::vector<double> limits, linear_off, linear_on, radius_off, radius_on;
};

/// Both from runs (bisection on whole runs to 20 us) and from the linearised step (spectral radius at rest; not for
/// the 800-particle reference, whose dense step matrix would be 4800 x 4800).
/// Linearisations undamped (viscosity off) and damped (linear viscosity on every pair).
inline StepLimits step_limits(const std::vector<BarCase>& limit_cases, double cfl, int threads) {
  const std::size_t nl = limit_cases.size();
  std::vector<double> limits(nl), linear_off(nl, NAN), linear_on(nl, NAN), radius_off(nl, NAN), radius_on(nl, NAN);
  study::parallel_for(nl, threads, [&](std::size_t k) {
    limits[k] = stable_cfl_limit(limit_cases[k], 0.05, 2.0);
    if (limit_cases[k].particles == 800) return;
    linear_off[k] = linear_cfl_limit(limit_cases[k], ViscositySwitch::Off, 0.05, 2.0);
    linear_on[k] = linear_cfl_limit(limit_cases[k], ViscositySwitch::Always, 0.05, 2.0);
    BarCase at = limit_cases[k];
    at.cfl = cfl;
    radius_off[k] = step_radius(at, ViscositySwitch::Off);
    radius_on[k] = step_radius(at, ViscositySwitch::Always);
  });
  return {limit_cases, limits, linear_off, linear_on, radius_off, radius_on};
}

}  // namespace nrbc1d
