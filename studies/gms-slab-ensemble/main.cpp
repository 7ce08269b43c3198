// Which findings of the gms-slab study survive changes far below anything physical? GMS's slab [GMS2001, §7.3] necks
// and breaks through a symmetry-breaking instability, so one trajectory may not be the outcome: with the pair loop,
// whose rates equal the row loop's to rounding, the eps = 0.3 crack moved and two of gms-slab's claims failed
// (studies/gms-slab/slab_case.hpp). Here each eps is run as an ensemble at one spacing: gms-slab's own run (row loop),
// the pair loop, and row-loop runs whose free particles start displaced by up to `perturbation` x dp (seeded). The
// runs are gms-slab's (studies/gms-slab/slab_run.hpp: the same scene, scheme, steps, break and crack detection).
// Writes to --out DIR: runs.csv (gms-slab's columns, one row per member; tag dp<dp>_eps<eps>_<member>), summary.json.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/cli.hpp"
#include "common/driver.hpp"
#include "common/study.hpp"
#include "gms-slab/slab_case.hpp"
#include "gms-slab/slab_run.hpp"
#include "gms-slab/slab_tables.hpp"

using namespace gslab;

namespace {

struct Member {
  SlabCase c;
  std::string member;  ///< rows | pairs | p<seed>
};

std::vector<Member> ensemble(double dp, double eps, double t_max, int perturbed, double perturbation) {
  const std::string tag = "dp" + format_number(dp) + "_eps" + format_number(eps) + "_";
  const SlabCase base{.dp = dp, .eps = eps, .t_max = t_max, .frames = 0};
  std::vector<Member> members = {{base, "rows"}, {base, "pairs"}};
  members[1].c.pair_loop = true;
  for (int s = 1; s <= perturbed; ++s) {
    Member m{base, "p" + std::to_string(s)};
    m.c.perturbation = perturbation;
    m.c.seed = static_cast<unsigned>(s);
    members.push_back(m);
  }
  for (Member& m : members) m.c.tag = tag + m.member;
  return members;
}

/// The smallest and largest of a measure over the runs of one eps (NaN skipped).
study::Range range_of(const std::vector<SlabRun>& runs, double eps, double (*value)(const SlabRun&)) {
  study::Range r;
  for (const SlabRun& run : runs)
    if (run.c.eps == eps) r.add(value(run));
  return r;
}

}  // namespace

int main(int argc, char** argv) try {
  study::DriverCli cli{"GMS 2001 §7.3: which of the plastic slab's findings survive rounding-level changes",
                       "results/gms-slab-ensemble", "pipeline check: dp 0.08, two perturbed members, runs to t = 60"};
  double dp = 0.04, perturbation = 1e-9, t_max0 = 200, t_max3 = 650;
  int perturbed = 6, threads = 2;
  cli.app.add_option("--dp", dp, "particle spacing (gms-slab's finer: 0.04)")->check(CLI::Range(0.01, 0.2));
  cli.app.add_option("--members", perturbed, "perturbed members per eps")->check(CLI::Range(0, 100));
  cli.app.add_option("--perturbation", perturbation, "largest initial displacement of a free particle, in dp")
      ->check(CLI::Range(0.0, 0.1));
  cli.add_threads(threads, "runs side by side");
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  for (const auto& [name, v] : {std::pair{"--dp", dp}, std::pair{"--perturbation", perturbation}})
    if (!std::isfinite(v))
      throw std::invalid_argument(std::string(name) + " must be a finite number");  // NaN passes Range
  if (cli.quick) dp = 0.08, perturbed = 2, t_max0 = t_max3 = 60;
  const auto t0 = study::Clock::now();

  // ---- 1. The members: per eps, gms-slab's run, the pair loop and the perturbed runs. ----
  std::vector<Member> members;
  for (double eps : {0.3, 0.0})
    for (Member& m : ensemble(dp, eps, eps > 0 ? t_max3 : t_max0, perturbed, perturbation)) members.push_back(m);
  const std::vector<SlabRun> runs = study::run_costliest_first(
      members, threads, [](const Member& m) { return m.c.t_max; },
      [&](const Member& m) {
        std::vector<FrameInfo> frames;
        std::vector<std::string> profiles;
        SlabRun r = run_slab(m.c, cli.out, frames, profiles);
        std::fprintf(stderr, "%s: break %.4g, %d crack(s), crack x %.4g\n", m.c.tag.c_str(), r.brk.t, r.brk.cracks(),
                     r.brk.left.x);
        return r;
      });
  write_runs(cli.out, runs);

  // ---- 2. Key numbers: per eps the spread of every finding, and how many members share the reference's. ----
  study::Summary s;
  std::string table;
  for (double eps : {0.3, 0.0}) {
    const std::string k = eps > 0 ? "eps03_" : "eps0_";
    const SlabRun* ref = nullptr;
    int count = 0, same_cracks = 0, necked = 0, middle = 0;
    for (std::size_t i = 0; i < runs.size(); ++i)
      if (runs[i].c.eps == eps && members[i].member == "rows") ref = &runs[i];
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const SlabRun& r = runs[i];
      if (r.c.eps != eps) continue;
      ++count;
      same_cracks += r.brk.cracks() == ref->brk.cracks();
      necked += !std::isnan(r.t_neck) && !std::isnan(r.brk.t) && r.t_neck < r.brk.t;
      // a crack in the middle third between the junctions (position 1/3..2/3 of the free length)
      middle += std::abs(r.brk.left.position - 0.5) < 1.0 / 6 && std::abs(r.brk.right.position - 0.5) < 1.0 / 6;
      study::md_row(table, {format_number(eps), members[i].member, study::sig(r.t_neck, 4), study::sig(r.brk.t, 4),
                            std::to_string(r.brk.cracks()), study::sig(r.brk.left.x, 3), study::sig(r.brk.right.x, 3),
                            study::sig(r.brk.junction_distance(), 4), r.status});
    }
    s.set(k + "members", count);
    s.set(k + "ref_t_break", ref->brk.t, 4);
    s.set(k + "ref_cracks", ref->brk.cracks());
    s.set(k + "same_cracks", same_cracks);
    s.set(k + "necked_before_break", necked);
    s.set(k + "middle_cracks", middle);
    s.set(k + "t_break_range", range_of(runs, eps, [](const SlabRun& r) { return r.brk.t; }).text(0));
    s.set(k + "t_neck_range", range_of(runs, eps, [](const SlabRun& r) { return r.t_neck; }).text(0));
    s.set(k + "junction_range",
          range_of(runs, eps, [](const SlabRun& r) { return r.brk.junction_distance(); }).text(3));
    s.set(k + "crack_x_range", range_of(runs, eps, [](const SlabRun& r) { return r.brk.left.x; }).text(3));
  }
  s.set("members_table", table);
  s.set("dp", dp, 3);
  s.set("perturbation", perturbation, 3);
  s.set("perturbed", perturbed);
  study::write_summary(s, cli.out, t0, {.load = true, .threads = threads});
  return 0;
} catch (const std::exception& e) {
  return study::exit_on_error("gms-slab-ensemble", e);
}
