// Study: the Swegle test as Powell ran it [Powell2012, ch. 4 §2.2, Figs. 4.1, 4.2] — MCM's configuration: the rate
// form with MCM's continuity -rho tr L (1.32), the staggered leap-frog (algorithm 1.1), XSPH as (2.71) on the velocity
// with eps = 0.1, the material card's bulk viscosity (QBVC 1.5, LBVC 0.06: RateFormOptions::bulk_viscosity_*) and
// TSSFAC 0.8. Sweeps h / dx, the block size and the volume strain xi; every case gets its verdict
// (growth/stability_verdict.hpp: gamma_J of the semi-discrete scheme, gamma_M of the leap-frog's one-step map with
// Powell's XSPH, both in the mirror class the kick excites, against the run's detection floor) and a nonlinear run
// whose kinetic-energy growth is fitted. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, ke.csv, summary.json. Units g, cm, us (stress in Mbar).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/growth/growth_fit.hpp"
#include "sphstab/growth/mirror_symmetry.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/powell_impact.hpp"
#include "sphstab/problems/swegle.hpp"

using namespace sphstab;

namespace {

constexpr double kTssfac = 0.8;      // MCM deck, card 2: dt = TSSFAC h / c_P (the DYNA rule at rest)
constexpr double kXsph = 0.1;        // Powell (2.71)
constexpr double kOnset = 100;       // the fit window opens at 100 KE0
constexpr double kStopGrowth = 1e10;  // a run stops at 1e10 KE0 (still linear: amplitude 1e-5 dx)

struct Formulation {
  std::string name, label;
  RateFormOptions options;
  double xsph = 0;         // Powell's XSPH eps on the leap-frog velocity
  int layer_supports = 1;  // fixed layers (in supports) the formulation needs for an exact equilibrium
};

/// Fig. 4.2's formulations in MCM's form: every one with MCM's continuity (1.32) and the bulk viscosity.
std::vector<Formulation> formulations() {
  // MCM's rate forms as the impact problems run them (problems/powell_impact.hpp): continuity (1.32), the deck's
  // bulk viscosity; NCSPH (1.19) in L and in the row momentum (1.36); S-SPH with Fig. 4.3's counts and (4.18).
  const RateFormOptions mcm = powell_formulation_options("sph"), ncsph = powell_formulation_options("ncsph"),
                        ssph = powell_formulation_options("ssph");
  RateFormOptions cij = mcm;
  cij.momentum = RateFormMomentum::Cij;  // (4.10), local polish (4.9), actual counts
  return {{"sph", "basic SPH", mcm},
          {"xsph", "SPH + XSPH (2.71)", mcm, kXsph},
          {"ncsph", "NCSPH (1.19), row momentum (1.36)", ncsph, 0, 2},
          {"ncxsph", "NCSPH + XSPH (2.71)", ncsph, kXsph, 2},
          {"cij", "C_ij momentum (4.10)", cij, 0, 2},
          // (4.18)'s sums differ from the interior's within one support of the outer edge, and r_i, c_j, m_i carry
          // them three supports in (c_j over N(j), m_i over N(i), the pair (i, f)): four supports of fixed layers
          // leave the free particles in exact equilibrium (three left a residual 225 times the kick's scale).
          {"ssph", "S-SPH (algorithm 4.2, Fig. 4.3 counts, first-step Shepard (4.18)) + XSPH (2.71)", ssph, kXsph, 4}};
}

/// A block (h / dx, n, fixed layers) and the mirror class (px, py) = (-1, +1) its kick excites.
struct Block {
  SwegleScene scene;
  Eigen::MatrixXd excited;
};

Block make_block(double h_over_dx, int n, int layers) {
  SwegleOptions so;
  so.n = n;
  so.h_over_dx = h_over_dx;
  so.layer_supports = layers;
  Block b{make_swegle_scene(so), {}};
  const auto& d = b.scene.discretisation;
  Eigen::VectorXd pos(2 * d->free_count());
  for (int f = 0; f < d->free_count(); ++f) pos.segment<2>(2 * f) = d->particles.x.row(d->free[f]).transpose();
  const Eigen::Vector2d centre = d->particles.x.row(b.scene.centre).transpose();
  b.excited = symmetry_basis(mirror_symmetry(pos, centre, 1e-9 * so.spacing), -1, 1);
  return b;
}

/// One case: a set of the study ("main": the h sweep at the main block size; "size": other block sizes;
/// "no-bulk": without the bulk viscosity; "half-dt": TSSFAC 0.4), a formulation, h / dx, n and xi.
struct Case {
  std::string set;
  int form = 0;
  double h_over_dx = 1.3, xi = 1, tssfac = kTssfac;
  int n = 21;
  bool bulk = true;
};

struct Outcome {
  StabilityVerdict verdict;
  ExponentialGrowthFit fit;
  RunStatus status = RunStatus::Completed;
  long steps = 0;
  double t_stop = 0, dt = 0, ke_max = 0, equilibrium = 0, wall_linear = 0, wall_run = 0;
  int particles = 0;
  std::string gamma_method;  // "fit" (the growth fit) or "mean" (energy limit reached before a fit window)
  std::vector<double> times, kinetic;
};

Outcome run_case(const Case& c, const Formulation& form, const Block& block, double t_end, double floor) {
  Outcome out;
  const SwegleScene& scene = block.scene;
  const auto& disc = scene.discretisation;
  const SwegleOptions& so = scene.options;
  const RateFormMaterial steel = RateFormMaterial::from_youngs(so.youngs_modulus, so.poisson_ratio, so.density);
  RateFormOptions o = form.options;
  if (!c.bulk) o.bulk_viscosity_quadratic = o.bulk_viscosity_linear = 0;
  const RateFormScheme<2> scheme(disc, steel, o, so.density / c.xi);
  const RateFormRunOptions run{.dt = c.tssfac * scene.h / steel.p_wave_speed(),
                               .t_end = t_end,
                               .record_every = 2,
                               .energy_growth = kStopGrowth,
                               .integrator = RateFormIntegrator::Leapfrog,
                               .leapfrog_xsph = form.xsph};
  Eigen::VectorXd y = scheme.uniform_state();
  // The unkicked block's largest acceleration over the kick's acceleration scale v0 c_P / h.
  Eigen::VectorXd f;
  scheme.rate(y, f);
  for (int i = 0; i < disc->size(); ++i)
    if (scheme.velocity_offset(i) >= 0)
      out.equilibrium = std::max(out.equilibrium, f.segment<2>(scheme.velocity_offset(i)).cwiseAbs().maxCoeff());
  const Eigen::Vector2d kick = scene.v0.segment<2>(2 * disc->free_slot[scene.centre]);
  out.equilibrium /= kick.norm() * steel.p_wave_speed() / disc->h;
  scheme.set_velocity(y, scene.centre, kick);
  auto t0 = study::Clock::now();
  const RateFormRunResult r = run_rate_form(scheme, y, run);
  out.wall_run = study::seconds_since(t0);
  out.status = r.status;
  out.steps = r.steps;
  out.t_stop = r.time;
  out.dt = r.dt;
  out.times = r.times;
  out.kinetic = r.kinetic_energy;
  const double ke0 = r.kinetic_energy.front();
  for (double e : r.kinetic_energy) out.ke_max = std::max(out.ke_max, e / ke0);
  out.fit = fit_exponential_growth(r.times, r.kinetic_energy, ke0, r.times.back(), {.onset_factor = kOnset});
  // A run that reached the energy limit grew, even when too few records lie in the window for a fit (the fastest
  // cases stop within a few dozen steps): its rate is then the mean ln(KE_max / KE0) / (2 t_stop), a lower bound.
  out.gamma_method = "fit";
  if (!out.fit.grew && r.status == RunStatus::EnergyGrowth) {
    out.fit.grew = true;
    out.fit.gamma = std::log(out.ke_max) / (2 * r.time);
    out.gamma_method = "mean";
  }
  // The verdict at the run's dt (run_rate_form rounds dt to t_end / steps), in the excited class, at rest.
  RateFormRunOptions at = run;
  at.dt = r.dt;
  t0 = study::Clock::now();
  out.verdict = stability_verdict(scheme, scheme.uniform_state(), at, {.floor = floor, .basis = block.excited});
  out.wall_linear = study::seconds_since(t0);
  if (out.verdict.status != Status::Successful)
    throw std::runtime_error(form.name + ": verdict: " + out.verdict.reason);
  out.particles = disc->size();
  return out;
}

/// "lo–hi" of a set of numbers at 2 digits ("–" for none).
std::string range(const std::vector<double>& v) {
  if (v.empty()) return "–";
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return study::sig(*lo, 2) == study::sig(*hi, 2) ? study::sig(*lo, 2) : study::sig(*lo, 2) + "–" + study::sig(*hi, 2);
}

/// "1.1, 1.3" of the h values in a set ("none" for none).
std::string h_list(const std::set<double>& hs) {
  std::string s;
  for (double h : hs) s += (s.empty() ? "" : ", ") + study::sig(h);
  return s.empty() ? "none" : s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The Swegle test in Powell's MCM configuration: h, block size and xi sweeps with verdicts"};
  std::string out = "results/swegle-powell";
  int n = 21, threads = 2;
  double t_end = 45;
  bool quick = false;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles per side of the main block (odd)")->check(CLI::Range(5, 61));
  app.add_option("--t-end", t_end, "run length (us)")->check(CLI::PositiveNumber);
  app.add_option("--threads", threads, "concurrent cases")->check(CLI::Range(1, 64));
  app.add_flag("--quick", quick, "h = 1.3 only, an 11 x 11 block, 20 us, no size or sensitivity sets");
  CLI11_PARSE(app, argc, argv);
  const auto t0 = study::Clock::now();
  std::filesystem::create_directories(out);
  set_threads(1);  // cases run side by side (parallel_for); each scheme on one thread
  if (quick) n = 11, t_end = std::min(t_end, 20.0);

  const std::vector<Formulation> forms = formulations();
  const std::vector<double> xis = {0.96, 0.98, 0.99, 1.0, 1.01, 1.02, 1.04};
  const std::vector<double> hs = quick ? std::vector<double>{1.3} : std::vector<double>{1.1, 1.2, 1.3, 1.4, 1.5};
  const std::vector<int> sizes = quick ? std::vector<int>{} : std::vector<int>{11, 31};
  const double floor = detection_floor(t_end, kOnset);  // ln(100) / (2 t_end)

  std::vector<Case> cases;
  for (double h : hs)
    for (std::size_t f = 0; f < forms.size(); ++f)
      for (double xi : xis) cases.push_back({"main", static_cast<int>(f), h, xi, kTssfac, n, true});
  for (int size : sizes)
    for (std::size_t f = 0; f < forms.size(); ++f)
      for (double xi : {0.98, 1.02}) cases.push_back({"size", static_cast<int>(f), 1.3, xi, kTssfac, size, true});
  if (!quick)
    for (std::size_t f = 0; f < forms.size(); ++f)
      for (double xi : {0.98, 1.0, 1.02}) {
        cases.push_back({"no-bulk", static_cast<int>(f), 1.3, xi, kTssfac, n, false});
        cases.push_back({"half-dt", static_cast<int>(f), 1.3, xi, kTssfac / 2, n, true});
      }

  // The blocks (h, n, layers) the cases need, built once.
  std::map<std::tuple<double, int, int>, Block> blocks;
  for (const Case& c : cases) {
    const auto key = std::make_tuple(c.h_over_dx, c.n, forms[c.form].layer_supports);
    if (!blocks.count(key)) blocks.emplace(key, make_block(c.h_over_dx, c.n, forms[c.form].layer_supports));
  }
  std::vector<Outcome> outcomes(cases.size());
  study::parallel_for(cases.size(), threads, [&](std::size_t k) {
    const Case& c = cases[k];
    const Formulation& form = forms[c.form];
    outcomes[k] = run_case(c, form, blocks.at({c.h_over_dx, c.n, form.layer_supports}), t_end, floor);
    const Outcome& o = outcomes[k];
    std::printf("%-8s h %.1f n %d %-7s xi %.2f: %s (J %.4g, map %.4g), measured %.4g (%s), %s (%.1f + %.1f s)\n",
                c.set.c_str(), c.h_over_dx, c.n, form.name.c_str(), c.xi, o.verdict.letter().c_str(),
                o.verdict.semi_discrete_growth, o.verdict.map_growth, o.fit.gamma, o.fit.grew ? "grew" : "bounded",
                run_status_name(o.status).c_str(), o.wall_linear, o.wall_run);
    std::fflush(stdout);
  });

  std::ofstream runs_csv(out + "/runs.csv"), ke_csv(out + "/ke.csv");
  runs_csv << "set,formulation,h_over_dx,n,xi,bulk_viscosity,tssfac,dt,gamma_linear_class,gamma_map_class,floor,verdict,"
              "gamma_measured,gamma_method,grew,fit_t_begin,fit_t_end,fit_r2,map_predicts_growth,status,steps,t_stop,"
              "ke_max_over_ke0,equilibrium_residual,layer_supports,particles,wall_linear,wall_run\n";
  ke_csv << "set,formulation,h_over_dx,n,xi,t,kinetic\n";
  std::map<std::string, int> classes;
  int agree = 0, main_cases = 0;
  double eq_max = 0, wall_linear = 0, wall_runs = 0;
  std::string disagreements;
  // (formulation, h) -> xi -> outcome, for the main set.
  std::map<std::pair<std::string, double>, std::map<double, const Outcome*>> cell;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const Formulation& form = forms[c.form];
    const Outcome& o = outcomes[k];
    const StabilityVerdict& v = o.verdict;
    const bool predicts = v.map_growth > floor;
    wall_linear += o.wall_linear;
    wall_runs += o.wall_run;
    runs_csv << csv_line({c.set, form.name, format_number(c.h_over_dx), std::to_string(c.n), format_number(c.xi),
                          c.bulk ? "1" : "0", format_number(c.tssfac), format_number(o.dt, 8),
                          format_number(v.semi_discrete_growth, 8), format_number(v.map_growth, 8),
                          format_number(floor, 6), v.letter(), format_number(o.fit.gamma, 8), o.gamma_method, o.fit.grew ? "1" : "0",
                          format_number(o.fit.fit.t_begin, 6), format_number(o.fit.fit.t_end, 6),
                          format_number(o.fit.fit.r2, 8), predicts ? "1" : "0", run_status_name(o.status),
                          std::to_string(o.steps), format_number(o.t_stop, 6), format_number(o.ke_max, 6),
                          format_number(o.equilibrium, 3), std::to_string(form.layer_supports),
                          std::to_string(o.particles), format_number(o.wall_linear, 3), format_number(o.wall_run, 3)});
    for (std::size_t s = 0; s < o.times.size(); ++s)  // every 10th record (of every 2nd step) and the last
      if (s % 10 == 0 || s + 1 == o.times.size())
        ke_csv << csv_line({c.set, form.name, format_number(c.h_over_dx), std::to_string(c.n), format_number(c.xi),
                            format_number(o.times[s], 8), format_number(o.kinetic[s], 8)});
    if (c.set != "main") continue;
    ++main_cases;
    ++classes[v.letter()];
    agree += predicts == o.fit.grew;
    eq_max = std::max(eq_max, o.equilibrium);
    if (predicts != o.fit.grew)
      disagreements += "- `" + form.name + "`, h = " + study::sig(c.h_over_dx) + " dx, ξ = " + study::sig(c.xi) +
                       ": " + v.letter() + ", γ_J " + study::sig(v.semi_discrete_growth, 3) + ", γ_M " +
                       study::sig(v.map_growth, 3) + " /µs; run " +
                       (o.fit.grew ? "grew at " + study::sig(o.fit.gamma, 3) + " /µs" : "stayed below the window") +
                       "\n";
    cell[{form.name, c.h_over_dx}][c.xi] = &o;
  }

  // Verdict tables per h: class, gamma_J / gamma_M, then the run's measured rate ("–": below the window).
  study::Summary s;
  std::string tables;
  for (double h : hs) {
    std::string t = "| formulation |";
    std::string sep = "|---|";
    for (double xi : xis) t += " " + study::sig(xi) + " |", sep += "---|";
    t += "\n" + sep;
    for (const Formulation& form : forms) {
      std::vector<std::string> row{"**" + form.name + "**"};
      for (double xi : xis) {
        const Outcome& o = *cell.at({form.name, h}).at(xi);
        const StabilityVerdict& v = o.verdict;
        const std::string letter = v.verdict == VerdictClass::Stable ? "S" : "**" + v.letter() + "**";
        row.push_back(letter + " " + study::sig(std::max(v.semi_discrete_growth, 0.0), 2) + " / " +
                      study::sig(std::max(v.map_growth, 0.0), 2) + " · " + (o.fit.grew ? study::sig(o.fit.gamma, 2) : "–"));
      }
      study::md_row(t, row);
    }
    tables += "\n### h = " + study::sig(h) + " Δx\n\n" + t + "\n";
  }
  s.set("verdict_tables", tables);

  // Powell's statements, per h: where the runs show them (grew / stayed below the window) and the classes.
  const auto side = [](double xi, int sgn) { return sgn > 0 ? xi > 1 : sgn < 0 ? xi < 1 : xi == 1; };
  const auto grows_on = [&](const std::string& name, double h, int sgn) {  // some xi of that side grew
    bool any = false;
    for (const auto& [xi, o] : cell.at({name, h}))
      if (side(xi, sgn)) any = any || o->fit.grew;
    return any;
  };
  const auto bounded_on = [&](const std::string& name, double h, int sgn) {  // no xi of that side grew
    bool none = true;
    for (const auto& [xi, o] : cell.at({name, h}))
      if (side(xi, sgn)) none = none && !o->fit.grew;
    return none;
  };
  // The classes on that side and how many of its runs grew, e.g. "SU, 2/3 grew".
  const auto classes_on = [&](const std::string& name, double h, int sgn) {
    std::set<std::string> letters;
    int grew = 0, count = 0;
    for (const auto& [xi, o] : cell.at({name, h}))
      if (side(xi, sgn)) letters.insert(o->verdict.letter()), grew += o->fit.grew, ++count;
    std::string t;
    for (const std::string& l : letters) t += l;
    return t + ", " + std::to_string(grew) + "/" + std::to_string(count) + " grew";
  };
  // Measured rate of a formulation over that of its unsmoothed partner where both grew (tension).
  const auto mitigation = [&](const std::string& smooth, const std::string& base) {
    std::vector<double> r;
    for (double h : hs)
      for (double xi : xis)
        if (xi > 1) {
          const Outcome &a = *cell.at({smooth, h}).at(xi), &b = *cell.at({base, h}).at(xi);
          if (a.fit.grew && b.fit.grew) r.push_back(a.fit.gamma / b.fit.gamma);
        }
    return range(r);
  };
  struct Statement {
    std::string key, text, form;
    int sgn;
    bool unstable;  // the statement says "grows" (true) or "stable" (false)
  };
  const std::vector<Statement> statements = {
      {"sph_tension", "SPH unstable in tension", "sph", +1, true},
      {"ncsph_tension", "NCSPH unstable in tension", "ncsph", +1, true},
      {"sph_compression", "SPH stable in compression (§2.3)", "sph", -1, false},
      {"cij_tension", "C_ij stable in tension", "cij", +1, false},
      {"cij_compression", "C_ij unstable in compression", "cij", -1, true},
      {"ssph_tension", "S-SPH stable in tension", "ssph", +1, false},
      {"ssph_compression", "S-SPH stable in compression", "ssph", -1, false}};
  std::string stable_table;
  for (const Statement& st : statements) {
    std::set<double> yes, no;
    std::string cls;
    for (double h : hs) {
      const bool holds = st.unstable ? grows_on(st.form, h, st.sgn) : bounded_on(st.form, h, st.sgn);
      (holds ? yes : no).insert(h);
      cls += (cls.empty() ? "" : "; ") + study::sig(h) + ": " + classes_on(st.form, h, st.sgn);
    }
    s.set(st.key + "_reproduced", h_list(yes));
    s.set(st.key + "_not", h_list(no));
    study::md_row(stable_table, {st.text, h_list(yes), h_list(no), cls});
  }
  s.set("statements_table", stable_table);
  s.set("xsph_mitigation", mitigation("xsph", "sph"));
  s.set("ncxsph_mitigation", mitigation("ncxsph", "ncsph"));

  // Block size and sensitivity sets: one row per case.
  const auto set_table = [&](const std::string& set) {
    std::string t;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const Case& c = cases[k];
      if (c.set != set) continue;
      const Outcome& o = outcomes[k];
      // The same formulation and xi in the main set at h = 1.3 (the reference of the sensitivity).
      const Outcome* ref = cell.count({forms[c.form].name, 1.3}) ? cell.at({forms[c.form].name, 1.3}).at(c.xi) : nullptr;
      study::md_row(t, {forms[c.form].name, std::to_string(c.n), study::sig(c.xi), study::sig(c.tssfac),
                        c.bulk ? "on" : "off", o.verdict.letter(), study::sig(o.verdict.semi_discrete_growth, 3),
                        study::sig(o.verdict.map_growth, 3), o.fit.grew ? study::sig(o.fit.gamma, 3) : "–",
                        ref ? (ref->fit.grew ? study::sig(ref->fit.gamma, 3) : "–") : "-"});
    }
    return t.empty() ? std::string("(not run)") : t;
  };
  s.set("size_table", set_table("size"));
  s.set("no_bulk_table", set_table("no-bulk"));
  s.set("half_dt_table", set_table("half-dt"));

  const SwegleScene& ref = blocks.begin()->second.scene;
  const RateFormMaterial steel = RateFormMaterial::from_youngs(ref.options.youngs_modulus, ref.options.poisson_ratio,
                                                               ref.options.density);
  s.set("n", n);
  s.set("sizes", sizes.empty() ? std::string("none") : std::to_string(sizes[0]) + ", " + std::to_string(sizes[1]));
  s.set("h_list", h_list(std::set<double>(hs.begin(), hs.end())));
  s.set("xi_list", "0.96, 0.98, 0.99, 1, 1.01, 1.02, 1.04");
  s.set("tssfac", kTssfac, 3);
  s.set("xsph", kXsph, 3);
  s.set("qbvc", powell_formulation_options("sph").bulk_viscosity_quadratic, 3);
  s.set("lbvc", powell_formulation_options("sph").bulk_viscosity_linear, 3);
  s.set("c_P", steel.p_wave_speed(), 4);
  s.set("c0", steel.sound_speed(), 4);
  s.set("t_end", t_end, 4);
  s.set("onset", kOnset, 3);
  s.set("stop_growth", kStopGrowth, 3);
  s.set("detect", floor, 3);
  s.set("cases", main_cases);
  s.set("all_cases", static_cast<int>(cases.size()));
  for (const char* c : {"S", "U", "I", "B"}) s.set(std::string("class_") + c, classes[c]);
  s.set("agree", agree);
  s.set("disagreements", disagreements.empty() ? "- none" : disagreements);
  s.set("equilibrium_residual", eq_max, 2);
  s.set("wall_linear", wall_linear, 3);
  s.set("wall_runs", wall_runs, 3);
  s.set("wall_total", study::seconds_since(t0), 3);
  s.set("quick", quick ? "yes" : "no");
  s.write(out);
  std::printf("%d main cases: S %d U %d I %d B %d; map predicts the run in %d\n", main_cases, classes["S"],
              classes["U"], classes["I"], classes["B"], agree);
  return 0;
}
