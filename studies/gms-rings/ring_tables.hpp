#pragma once
// The CSV files of the gms-rings study [GMS2001, §7.2] (columns: see README.md): series/<tag>.csv (one row per record
// of a run) and runs.csv (one row per run: units, scheme variant, grid, cost, and what it measured).
#include <fstream>
#include <string>
#include <vector>

#include "common/gms.hpp"
#include "ring_measures.hpp"
#include "ring_run.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/io/csv.hpp"

namespace grings {

/// series/<tag>.csv: the records of one run.
inline void write_series(const std::string& out, const RingRun& r) {
  std::ofstream csv(out + "/series/" + r.c.tag + ".csv");
  csv << "t,kinetic,ring_distance,body_distance,com_vx0,com_vx1,sigma_xx_max,fragments,fragments_ring0,"
         "fragments_ring1,lost_ring0,lost_ring1\n";
  for (std::size_t k = 0; k < r.t.size(); ++k)
    csv << csv_line({format_number(r.t[k], 8), format_number(r.ke[k], 8), format_number(r.dmin[k], 8),
                     format_number(r.dbody[k], 8), format_number(r.vx0[k], 8), format_number(r.vx1[k], 8),
                     format_number(r.sxx_max[k], 8), std::to_string(r.frag_all[k]), std::to_string(r.frag0[k]),
                     std::to_string(r.frag1[k]), std::to_string(r.lost0[k]), std::to_string(r.lost1[k])});
}

/// runs.csv: one row per run with its measures (measures[k] of runs[k]).
inline void write_runs(const std::string& out, const std::vector<RingRun>& runs,
                       const std::vector<RingMeasures>& measures) {
  std::ofstream runs_csv(out + "/runs.csv");
  runs_csv << "tag,units,eps,loop,rates_per_step,dp,gap,particles,per_ring,h,dt,steps,t_end,status,wall,cpu,us_per_"
              "particle_step,us_cpu,"
              "neighbour_builds,contact_first,contact_last,touch_first,touch_last,separated,com_vx0_after,"
              "com_vx1_after,restitution,fragments_end,fragments_max,ring_fragments_end,ring_fragments_max,"
              "ring_break_time,lost_end,lost_max,ke_end_over_ke0,sigma_xx_max\n";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const RingRun& r = runs[k];
    const RingMeasures& m = measures[k];
    std::vector<std::string> row{r.c.tag,
                                 r.c.si ? "SI" : "GMS",
                                 format_number(r.c.eps),
                                 r.c.loop == PairLoop::Pairs ? "pairs" : "rows",
                                 r.c.one_rate ? "1" : "2",
                                 format_number(r.c.dp),
                                 format_number(r.c.gap),
                                 std::to_string(r.particles),
                                 std::to_string(r.per_ring),
                                 format_number(r.h),
                                 format_number(r.dt, 8),
                                 std::to_string(r.cost.steps),
                                 format_number(r.t_run()),
                                 r.status};
    const std::vector<std::string> cost = study::cost_cells(r.cost);
    row.insert(row.end(), cost.begin(), cost.end());
    row.insert(row.end(),
               {format_number(m.contact_first), format_number(m.contact_last), format_number(m.touch_first),
                format_number(m.touch_last), m.separated ? "1" : "0", format_number(m.vx0_after),
                format_number(m.vx1_after), format_number(m.restitution), std::to_string(m.frag_all_end),
                std::to_string(m.frag_all_max), std::to_string(m.frag_ring_end), std::to_string(m.frag_ring_max),
                format_number(m.ring_break_time), std::to_string(m.lost_end), std::to_string(m.lost_max),
                format_number(m.ke_end_over_ke0), format_number(m.sxx_max)});
    runs_csv << csv_line(row);
  }
}

}  // namespace grings
