#pragma once
// One run of a bar case (bar_problem.hpp) to t_to by Powell's leap-frog [Powell2012, algorithm 1.1]: its status
// (unstable X when the kinetic energy grows 100-fold, a state is non-finite or the NCSPH moment matrix is singular),
// the mean relative velocity error (2.72) at particle 80 against the exact solution, and optionally the series of v at
// particle 80; and the runs of a list of cases in parallel.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "bar_problem.hpp"
#include "common/study.hpp"

namespace nrbc1d {

struct BarRun {
  BarCase c;
  std::string status;
  bool stable = false;
  double error = NAN;  ///< mean of (2.72) over the steps with t_from < t <= t_to
  long steps = 0;
  std::vector<double> t, v;
};

inline BarRun run_bar(const BarCase& c) {
  const BarScene scene = make_bar(c);
  const RateFormScheme<1>& scheme = *scene.scheme;
  BarRun r{.c = c};
  const double x80 = scene.x80;
  double sum = 0;
  long count = 0;
  RateFormRunOptions o = run_options(c);
  o.observer = [&](long, double t, const Eigen::VectorXd& y) {
    const double v = y[scheme.velocity_offset(scene.probe)];
    if (c.keep_series) r.t.push_back(t), r.v.push_back(v);
    if (t > c.t_from + 1e-12) {
      const double exact = exact_velocity(x80, t);
      sum += std::abs(exact - v) / std::abs(exact);  // (2.72); exact = -V for t > 2.21
      ++count;
    }
  };
  try {
    const RateFormRunResult res = run_rate_form(scheme, scene.y0, o);
    r.steps = res.steps;
    r.stable = res.completed();
    r.status = run_status_name(res.status);
  } catch (const std::domain_error&) {  // the NCSPH moment matrix of a particle that lost its neighbours: unstable
    r.status = "singular-ncsph";
    return r;
  }
  if (r.stable && count > 0) r.error = sum / count;
  return r;
}

inline std::vector<BarRun> run_all(const std::vector<BarCase>& cases, int threads) {
  std::vector<BarRun> runs(cases.size());
  study::parallel_for(cases.size(), threads, [&](std::size_t k) { runs[k] = run_bar(cases[k]); });
  return runs;
}

}  // namespace nrbc1d
