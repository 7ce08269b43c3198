#pragma once
// The key numbers of the gms-rings study for summary.md.in [GMS2001, §7.2]: the results table of the full runs (GMS
// units), the cost table of every run, the key numbers of each run (the row-loop runs in full, the pair-loop, fast
// and half-dt variants for the comparison with them, the SI timing runs with the cost of the whole collision), the
// verdicts on GMS's claims, the row loop against the pair loop (loops_table), and the thin-ring ovalling period.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "ring_case.hpp"
#include "ring_measures.hpp"
#include "ring_run.hpp"

namespace grings {

/// The run of `runs` in these units with this eps, pair loop and rates per step, at the full time step.
inline const RingRun& find_run(const std::vector<RingRun>& runs, bool si_units, double eps, PairLoop loop,
                               bool one_rate = false) {
  for (const RingRun& r : runs)
    if (r.c.si == si_units && r.c.eps == eps && r.c.loop == loop && r.c.one_rate == one_rate && r.c.dt_scale == 1)
      return r;
  throw std::logic_error("gms-rings: no run for that case");
}

/// The keys <k>_<measure> of a GMS-unit run's measures; with `full` (the row-loop runs, not the variants compared
/// with them) also the fragments of the scene, the most particles lost, the first contact and the rebound velocities.
inline void summarise_measures(study::Summary& s, const std::string& k, const RingRun& r, const RingMeasures& m,
                               int n_ring, bool full) {
  s.set(k + "_vx_end", r.vx1.back(), 3);
  s.set(k + "_ring_fragments_end", m.frag_ring_end);
  s.set(k + "_ring_fragments_max", m.frag_ring_max);
  s.set(k + "_lost_end", m.lost_end);
  s.set(k + "_ring_break_time", m.ring_break_time, 4);
  s.set(k + "_touch_first", m.touch_first, 3);
  s.set(k + "_touch_last", m.touch_last, 4);
  s.set(k + "_contact_last", m.contact_last, 4);
  s.set(k + "_separated", m.separated ? "yes" : "no");
  s.set(k + "_restitution", m.restitution, 3);
  s.set(k + "_ke_end", m.ke_end_over_ke0, 3);
  s.set(k + "_sxx_max", m.sxx_max, 3);
  s.set(k + "_outcome", outcome(m, n_ring));
  if (!full) return;
  s.set(k + "_fragments_end", m.frag_all_end);
  s.set(k + "_fragments_max", m.frag_all_max);
  s.set(k + "_lost_max", m.lost_max);
  s.set(k + "_contact_first", m.contact_first, 3);
  s.set(k + "_vx0_after", m.vx0_after, 3);
  s.set(k + "_vx1_after", m.vx1_after, 3);
}

/// The keys <k>_<cost> of a run: wall and thread CPU seconds, steps, and the microseconds per particle-step of both.
inline void summarise_cost(study::Summary& s, const std::string& k, const study::RunCost& cost) {
  s.set(k + "_wall", cost.wall, 3);
  s.set(k + "_cpu", cost.cpu, 3);
  s.set(k + "_steps", cost.steps);
  s.set(k + "_us", cost.us_per_particle_step(), 3);
  s.set(k + "_us_cpu", cost.us_cpu(), 3);
}

/// The verdict on GMS's claim for the row-loop GMS-unit run with this eps: eps = 0 the rings break (eps0_verdict),
/// eps = 0.3 they bounce off intact (eps03_verdict).
inline void summarise_verdict(study::Summary& s, double eps, const RingMeasures& m, int n_ring) {
  const std::string limit = "no ring loses more than " + study::sig(100 * kBreakShare) + " % of its particles";
  if (eps > 0)
    s.set("eps03_verdict", !breaks(m, n_ring) && m.separated
                               ? "**Reproduced**: " + limit + " (at most " + std::to_string(m.lost_max) +
                                     " torn off), and the rings separate"
                               : std::string("**Not reproduced**: ") +
                                     (breaks(m, n_ring) ? "a ring breaks" : "the rings do not separate by t_end"));
  else
    s.set("eps0_verdict", breaks(m, n_ring)
                              ? "**Reproduced**: the rings break (" + std::to_string(m.frag_ring_end) +
                                    " fragments in the more broken ring at the end, " + std::to_string(m.lost_end) +
                                    " of its " + std::to_string(n_ring) + " particles outside its largest fragment)"
                              : "**Not reproduced**: " + limit);
}

/// The tables and key numbers of every run (measures[k] of runs[k]; t_end: the GMS-unit run length), and the summed
/// wall and CPU time of the runs.
inline void summarise_runs(study::Summary& s, const std::vector<RingRun>& runs,
                           const std::vector<RingMeasures>& measures, double t_end) {
  std::string table, cost_table;
  double wall_runs = 0, cpu_runs = 0;
  const int n_ring = runs.front().per_ring;
  for (std::size_t q = 0; q < runs.size(); ++q) {
    const RingRun& r = runs[q];
    const RingMeasures& m = measures[q];
    wall_runs += r.cost.wall;
    cpu_runs += r.cost.cpu;
    study::md_row(cost_table, {r.c.tag, r.c.si ? "SI" : "GMS", std::to_string(r.particles),
                               std::to_string(r.cost.steps), study::sig(r.t_run(), 4), study::fixed(r.cost.wall, 1),
                               study::fixed(r.cost.cpu, 1), study::sig(r.cost.us_per_particle_step(), 3),
                               study::sig(r.cost.us_cpu(), 3), std::to_string(r.cost.neighbour_builds)});
    if (r.c.loop == PairLoop::Pairs || r.c.dt_scale != 1) {  // compared with the row loop below
      if (!r.c.si) {
        const std::string k = std::string(r.c.dt_scale != 1 ? "halfdt_"
                                          : r.c.one_rate    ? "fast_"
                                                            : "pairs_") +
                              (r.c.eps > 0 ? "eps03" : "eps0");
        summarise_measures(s, k, r, m, n_ring, false);
      }
      continue;
    }
    if (r.c.steps == 0)  // the full runs
      study::md_row(
          table, {r.c.tag, study::fixed(r.c.eps, 1), study::sig(r.t_run(), 4), std::to_string(m.frag_all_end),
                  std::to_string(m.frag_ring_end) + " / " + std::to_string(m.frag_ring_max), std::to_string(m.lost_end),
                  study::sig(m.ring_break_time, 4), study::sig(m.contact_first, 3), study::sig(m.contact_last, 4),
                  study::sig(m.touch_first, 3), study::sig(m.touch_last, 4), m.separated ? "yes" : "no",
                  study::fixed(m.vx0_after, 4, true) + " / " + study::fixed(m.vx1_after, 4, true),
                  study::fixed(m.restitution, 3), study::sig(m.ke_end_over_ke0, 3)});
    if (r.c.si) {
      const std::string k = r.c.eps > 0 ? "si_eps03" : "si_eps0";
      // The whole collision (t_end in cm/c0) at this run's cost per particle-step.
      const double full_steps = std::ceil(t_end * r.u.time() / r.dt);
      s.set(k + "_full_steps", full_steps, 4);
      s.set(k + "_full_minutes", full_steps * r.particles * r.cost.us_cpu() * 1e-6 / 60, 2);
      summarise_cost(s, k, r.cost);
      continue;
    }
    const std::string k = r.c.eps > 0 ? "eps03" : "eps0";
    summarise_measures(s, k, r, m, n_ring, true);
    summarise_cost(s, k, r.cost);
    s.set(k + "_status", r.status);
    summarise_verdict(s, r.c.eps, m, n_ring);
  }
  s.set("results_table", table);
  s.set("cost_table", cost_table);
  s.set("wall_runs", wall_runs, 3);
  s.set("cpu_runs", cpu_runs, 3);
}

/// loops_table: the row loop against the pair loop (two and one rate evaluations per step), per units and eps: the
/// largest difference of the end positions over dp, and the thread CPU per particle-step (the run's own cost; the
/// runs of a pair need not share the machine's load).
inline void summarise_loops(study::Summary& s, const std::vector<RingRun>& runs) {
  std::string loops_table;
  for (bool si_units : {false, true})
    for (double eps : {0.0, 0.3}) {
      const RingRun &a = find_run(runs, si_units, eps, PairLoop::Rows),
                    &b = find_run(runs, si_units, eps, PairLoop::Pairs),
                    &c = find_run(runs, si_units, eps, PairLoop::Pairs, true);
      // Every particle of the rings is free: x at 8 i in the state.
      const auto largest_difference = [&](const RingRun& q) {
        double d = 0;
        for (int i = 0; i < a.particles; ++i)
          d = std::max(d, (a.y_end.segment<2>(8 * i) - q.y_end.segment<2>(8 * i)).norm());
        return d / a.c.dp;
      };
      study::md_row(loops_table, {si_units ? "SI" : "GMS", study::fixed(eps, 1), std::to_string(a.cost.steps),
                                  study::sig(largest_difference(b), 3), study::sig(largest_difference(c), 3),
                                  study::sig(a.cost.us_cpu(), 3), study::sig(b.cost.us_cpu(), 3),
                                  study::sig(c.cost.us_cpu(), 3), study::fixed(a.cost.us_cpu() / b.cost.us_cpu(), 2),
                                  study::fixed(a.cost.us_cpu() / c.cost.us_cpu(), 2)});
    }
  s.set("loops_table", loops_table);
}

/// The in-plane n = 2 (ovalling) period of a thin ring of mean radius R and thickness t, plane strain:
/// omega^2 = E' I / (rho A R^4) n^2 (n^2 - 1)^2 / (n^2 + 1), E' = E / (1 - nu^2), I / A = t^2 / 12.
inline double ring_ovalling_period(double K, double mu, double R, double t) {
  const double E = 9 * K * mu / (3 * K + mu), nu = (3 * K - 2 * mu) / (2 * (3 * K + mu));
  const double Ep = E / (1 - nu * nu);
  const double w = std::sqrt(Ep * t * t / 12 / std::pow(R, 4) * 4 * 9 / 5);
  return 2 * M_PI / w;
}

}  // namespace grings
