#pragma once
// The key numbers of the gms-slab study for summary.md.in [GMS2001, §7.3, Figs. 8-10]: the results table (neck
// onset, break and separation times against GMS's 119 and 542, where the slab broke and how thin the neck was, in dp)
// and the cost table of every run, the key numbers of the finest resolution (the times, places and widths of the
// events, GMS's "strain" at the neck onset and the break), the grid of that run and the summed run times.
#include <algorithm>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "slab_break.hpp"
#include "slab_case.hpp"
#include "slab_run.hpp"
#include "sphstab/core/format.hpp"

namespace gslab {

/// The tables and the key numbers of `runs` (dps: the spacings, finest first).
inline void summarise_runs(study::Summary& s, const std::vector<SlabRun>& runs, const std::vector<double>& dps) {
  std::string table, cost_table;
  double wall_runs = 0, wall_max = 0, cpu_runs = 0;
  for (const SlabRun& r : runs) {
    wall_runs += r.cost.wall;
    cpu_runs += r.cost.cpu;
    wall_max = std::max(wall_max, r.cost.wall);
    const std::string paper_break = r.c.eps > 0 ? "542" : "119";
    study::md_row(table, {study::fixed(r.c.dp, 3), std::to_string(r.columns) + " × " + std::to_string(r.rows),
                          study::fixed(r.c.eps, 1), study::sig(r.t_neck, 4), study::sig(r.x_neck, 3),
                          study::sig(r.t_w95, 4), study::sig(r.t_w10, 4),
                          study::sig(r.brk.t, 4) + " (" + paper_break + ")", study::sig(r.brk_support.t, 4),
                          std::to_string(r.brk.cracks()), crack_x(r.brk), study::fixed(r.brk.junction_distance(), 3),
                          study::sig(r.brk.width_before() / r.c.dp, 3), study::sig(r.t_stop, 4)});
    study::md_row(cost_table, {r.c.tag, std::to_string(r.particles), study::sig(r.dt, 4), std::to_string(r.cost.steps),
                               study::sig(r.t_stop, 4), study::fixed(r.cost.wall, 1), study::fixed(r.cost.cpu, 1),
                               study::sig(r.cost.us_per_particle_step(), 3), study::sig(r.cost.us_cpu(), 3),
                               std::to_string(r.cost.neighbour_builds), r.status});
    if (r.c.dp != dps.front()) continue;  // the key numbers of the prose: the finest resolution run
    const std::string k = r.c.eps > 0 ? "eps03" : "eps0";
    s.set(k + "_t_neck", r.t_neck, 4);
    s.set(k + "_x_neck", r.x_neck, 3);
    s.set(k + "_t_w95", r.t_w95, 4);
    s.set(k + "_t_w10", r.t_w10, 4);
    s.set(k + "_t_break", r.brk.t, 4);
    s.set(k + "_cracks", r.brk.cracks());
    s.set(k + "_x_break", crack_x(r.brk));
    s.set(k + "_break_junction", r.brk.junction_distance(), 3);
    s.set(k + "_width_before", r.brk.width_before() / r.c.dp, 3);
    s.set(k + "_x_narrowest", r.brk.x_narrowest, 3);
    s.set(k + "_width_narrowest", r.brk.width_narrowest / r.c.dp, 3);
    s.set(k + "_t_separation", r.brk_support.t, 4);
    s.set(k + "_t_stop", r.t_stop, 4);
    s.set(k + "_wall", r.cost.wall, 3);
    s.set(k + "_cpu", r.cost.cpu, 3);
    s.set(k + "_end_displacement", end_disp(r.brk.t), 3);
    s.set(k + "_where", where(r.brk, r.c.dp));
    // GMS's "strain": one end's displacement over the length 3 (0.13 at t = 394).
    s.set(k + "_neck_strain", end_disp(r.t_neck) / 3, 3);
    s.set(k + "_break_strain", end_disp(r.brk.t) / 3, 3);
    s.set(k + "_where_separation", where(r.brk_support, r.c.dp));
    s.set("fine_particles", r.particles);
    s.set("fine_grid", std::to_string(r.columns) + " × " + std::to_string(r.rows));
    s.set("fine_dt", r.dt, 4);
  }
  s.set("fine_dp", dps.front(), 3);
  std::string dp_list;
  for (double dp : dps) dp_list += (dp_list.empty() ? "" : ", ") + format_number(dp);
  s.set("dp_list", dp_list);
  s.set("results_table", table);
  s.set("cost_table", cost_table);
  s.set("wall_runs", wall_runs, 3);
  s.set("cpu_runs", cpu_runs, 3);
  s.set("wall_max", wall_max, 3);
}

}  // namespace gslab
