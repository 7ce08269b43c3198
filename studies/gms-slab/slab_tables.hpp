#pragma once
// The CSV files of the gms-slab study [GMS2001, §7.3] (columns: see README.md "Outputs"): series/<tag>.csv (one row
// per time unit of a run), frames.csv and profiles.csv (the VTK frames and the width profiles logged by the runs), and
// runs.csv (one row per run: grid, cost, and the events: neck onset, break, separation).
#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

#include "common/gms.hpp"
#include "slab_case.hpp"
#include "slab_run.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/io/csv.hpp"

namespace gslab {

/// series/<tag>.csv: the records of one run.
inline void write_series(const std::string& out, const SlabRun& r) {
  const SlabCase& c = r.c;
  std::ofstream csv(out + "/series/" + c.tag + ".csv");
  csv << "t,kinetic,end_displacement,min_width,min_x,median_width,min_width_all,min_x_all,junction_left,"
         "junction_right,fragments,largest,fragments_support,broken,broken_support\n";
  for (const SlabRecord& s : r.records)
    csv << csv_line({format_number(s.t, 8), format_number(s.ke, 8), format_number(s.end_displacement, 8),
                     format_number(s.min_width, 8), format_number(s.min_x, 8), format_number(s.median_width, 8),
                     format_number(s.min_width_all, 8), format_number(s.min_x_all, 8),
                     format_number(s.junction_left, 8), format_number(s.junction_right, 8), std::to_string(s.fragments),
                     std::to_string(s.largest), std::to_string(s.fragments_support), s.broken ? "1" : "0",
                     s.broken_support ? "1" : "0"});
}

/// frames.csv and profiles.csv: the frames and profile rows of every run, in the order of the cases.
inline void write_frames_profiles(const std::string& out, const std::vector<std::vector<FrameInfo>>& frame_logs,
                                  const std::vector<std::vector<std::string>>& profile_logs) {
  std::ofstream frames_csv(out + "/frames.csv"), profiles_csv(out + "/profiles.csv");
  frames_csv << "tag,kind,t,file\n";
  profiles_csv << "tag,t,kind,x,width,count\n";
  for (std::size_t k = 0; k < frame_logs.size(); ++k) {
    for (const FrameInfo& f : frame_logs[k]) frames_csv << csv_line({f.tag, f.kind, format_number(f.t, 8), f.file});
    for (const std::string& line : profile_logs[k]) profiles_csv << line;
  }
}

/// runs.csv: one row per run.
inline void write_runs(const std::string& out, const std::vector<SlabRun>& runs) {
  std::ofstream runs_csv(out + "/runs.csv");
  runs_csv
      << "tag,dp,eps,columns,rows,particles,driven,h,dt,steps,chunks,t_stop,status,wall,cpu,us_per_particle_step,"
         "us_cpu,"
         "neighbour_builds,width0,t_neck,x_neck,width_neck,t_w95,t_w10,t_break,cracks,x_crack_left,y_crack_left,"
         "x_crack_right,y_crack_right,junction_distance_left,junction_distance_right,position_left,position_right,"
         "width_before_left,width_before_right,t_separation,separation_cracks,x_separation_left,x_separation_right,"
         "separation_junction_distance,end_displacement_at_break,x_narrowest_before_break,"
         "width_narrowest_before_break\n";
  for (const SlabRun& r : runs) {
    std::vector<std::string> row{r.c.tag,
                                 format_number(r.c.dp),
                                 format_number(r.c.eps),
                                 std::to_string(r.columns),
                                 std::to_string(r.rows),
                                 std::to_string(r.particles),
                                 std::to_string(r.driven),
                                 format_number(r.h),
                                 format_number(r.dt, 8),
                                 std::to_string(r.cost.steps),
                                 std::to_string(r.chunks),
                                 format_number(r.t_stop),
                                 r.status};
    const std::vector<std::string> cost = study::cost_cells(r.cost);
    row.insert(row.end(), cost.begin(), cost.end());
    row.insert(row.end(), {format_number(r.width0),
                           format_number(r.t_neck),
                           format_number(r.x_neck),
                           format_number(r.width_neck),
                           format_number(r.t_w95),
                           format_number(r.t_w10),
                           format_number(r.brk.t),
                           std::to_string(r.brk.cracks()),
                           format_number(r.brk.left.x),
                           format_number(r.brk.left.y),
                           format_number(r.brk.right.x),
                           format_number(r.brk.right.y),
                           format_number(r.brk.left.junction_distance),
                           format_number(r.brk.right.junction_distance),
                           format_number(r.brk.left.position),
                           format_number(r.brk.right.position),
                           format_number(r.brk.left.width_before),
                           format_number(r.brk.right.width_before),
                           format_number(r.brk_support.t),
                           std::to_string(r.brk_support.cracks()),
                           format_number(r.brk_support.left.x),
                           format_number(r.brk_support.right.x),
                           format_number(r.brk_support.junction_distance()),
                           format_number(end_disp(r.brk.t)),
                           format_number(r.brk.x_narrowest),
                           format_number(r.brk.width_narrowest)});
    runs_csv << csv_line(row);
  }
}

}  // namespace gslab
