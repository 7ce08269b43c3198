#pragma once
// The key numbers of summary.md.in: the tally of the main set (classes, where the one-step map predicts the run), the
// verdict tables per h, Powell's Fig. 4.2 statements per h, the block-size and sensitivity tables, and the setup.
#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "powell_cases.hpp"
#include "powell_run.hpp"

namespace swegle_powell {

/// "lo–hi" of a set of numbers at 2 digits ("–" for none).
inline std::string range(const std::vector<double>& v) {
  if (v.empty()) return "–";
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return study::sig(*lo, 2) == study::sig(*hi, 2) ? study::sig(*lo, 2) : study::sig(*lo, 2) + "–" + study::sig(*hi, 2);
}

/// "1.1, 1.3" of the h values in a set ("none" for none).
inline std::string h_list(const std::set<double>& hs) {
  std::string s;
  for (double h : hs) s += (s.empty() ? "" : ", ") + study::sig(h);
  return s.empty() ? "none" : s;
}

/// The main set (the h sweep) tallied, and the wall times of every case.
struct MainSet {
  std::map<std::string, int> classes;  ///< cases per verdict class
  int agree = 0, cases = 0;            ///< the map's growth above the floor predicts the run's
  double equilibrium = 0, wall_linear = 0, wall_runs = 0;
  std::string disagreements;  ///< Markdown list of the cases where it does not
  /// (formulation, h) -> xi -> outcome.
  std::map<std::pair<std::string, double>, std::map<double, const Outcome*>> cell;

  int count(const std::string& letter) const {
    const auto it = classes.find(letter);
    return it == classes.end() ? 0 : it->second;
  }
};

inline MainSet tally(const std::vector<Case>& cases, const std::vector<Formulation>& forms,
                     const std::vector<Outcome>& outcomes, double floor) {
  MainSet m;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const Formulation& form = forms[c.form];
    const Outcome& o = outcomes[k];
    const StabilityVerdict& v = o.verdict;
    const bool predicts = v.map_growth > floor;
    m.wall_linear += o.wall_linear;
    m.wall_runs += o.wall_run;
    if (c.set != "main") continue;
    ++m.cases;
    ++m.classes[v.letter()];
    m.agree += predicts == o.fit.grew;
    m.equilibrium = std::max(m.equilibrium, o.equilibrium);
    if (predicts != o.fit.grew)
      m.disagreements +=
          "- `" + form.name + "`, h = " + study::sig(c.h_over_dx) + " dx, ξ = " + study::sig(c.xi) + ": " + v.letter() +
          ", γ_J " + study::sig(v.semi_discrete_growth, 3) + ", γ_M " + study::sig(v.map_growth, 3) + " /µs; run " +
          (o.fit.grew ? "grew at " + study::sig(o.fit.gamma, 3) + " /µs" : "stayed below the window") + "\n";
    m.cell[{form.name, c.h_over_dx}][c.xi] = &o;
  }
  return m;
}

/// Verdict tables per h: class, gamma_J / gamma_M, then the run's measured rate ("–": below the window).
inline std::string verdict_tables(const MainSet& m, const std::vector<Formulation>& forms,
                                  const std::vector<double>& hs) {
  std::string tables;
  for (double h : hs) {
    std::string t = "| formulation |";
    std::string sep = "|---|";
    for (double xi : kXis) t += " " + study::sig(xi) + " |", sep += "---|";
    t += "\n" + sep;
    for (const Formulation& form : forms) {
      std::vector<std::string> row{"**" + form.name + "**"};
      for (double xi : kXis) {
        const Outcome& o = *m.cell.at({form.name, h}).at(xi);
        const StabilityVerdict& v = o.verdict;
        const std::string letter = v.verdict == VerdictClass::Stable ? "S" : "**" + v.letter() + "**";
        row.push_back(letter + " " + study::sig(std::max(v.semi_discrete_growth, 0.0), 2) + " / " +
                      study::sig(std::max(v.map_growth, 0.0), 2) + " · " +
                      (o.fit.grew ? study::sig(o.fit.gamma, 2) : "–"));
      }
      study::md_row(t, row);
    }
    tables += "\n### h = " + study::sig(h) + " Δx\n\n" + t + "\n";
  }
  return tables;
}

/// Powell's statements, per h: where the runs show them (grew / stayed below the window) and the classes
/// (statements_table, <key>_reproduced, <key>_not); and what XSPH does to the measured rate in tension.
inline void summarise_statements(study::Summary& s, const MainSet& m, const std::vector<double>& hs) {
  const auto side = [](double xi, int sgn) { return sgn > 0 ? xi > 1 : sgn < 0 ? xi < 1 : xi == 1; };
  const auto grows_on = [&](const std::string& name, double h, int sgn) {  // some xi of that side grew
    bool any = false;
    for (const auto& [xi, o] : m.cell.at({name, h}))
      if (side(xi, sgn)) any = any || o->fit.grew;
    return any;
  };
  const auto bounded_on = [&](const std::string& name, double h, int sgn) {  // no xi of that side grew
    bool none = true;
    for (const auto& [xi, o] : m.cell.at({name, h}))
      if (side(xi, sgn)) none = none && !o->fit.grew;
    return none;
  };
  // The classes on that side and how many of its runs grew, e.g. "SU, 2/3 grew".
  const auto classes_on = [&](const std::string& name, double h, int sgn) {
    std::set<std::string> letters;
    int grew = 0, count = 0;
    for (const auto& [xi, o] : m.cell.at({name, h}))
      if (side(xi, sgn)) letters.insert(o->verdict.letter()), grew += o->fit.grew, ++count;
    std::string t;
    for (const std::string& l : letters) t += l;
    return t + ", " + std::to_string(grew) + "/" + std::to_string(count) + " grew";
  };
  // Measured rate of a formulation over that of its unsmoothed partner where both grew (tension).
  const auto mitigation = [&](const std::string& smooth, const std::string& base) {
    std::vector<double> r;
    for (double h : hs)
      for (double xi : kXis)
        if (xi > 1) {
          const Outcome &a = *m.cell.at({smooth, h}).at(xi), &b = *m.cell.at({base, h}).at(xi);
          if (a.fit.grew && b.fit.grew) r.push_back(a.fit.gamma / b.fit.gamma);
        }
    return range(r);
  };
  struct Statement {
    std::string key, text, form;
    int sgn;
    bool unstable;  // the statement says "grows" (true) or "stable" (false)
  };
  const std::vector<Statement> statements = {{"sph_tension", "SPH unstable in tension", "sph", +1, true},
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
}

/// A block-size or sensitivity set: one row per case, with the measured rate of the same formulation and xi in the
/// main set at h = 1.3 (the reference of the sensitivity); "(not run)" for an empty set.
inline std::string set_table(const std::string& set, const MainSet& m, const std::vector<Case>& cases,
                             const std::vector<Formulation>& forms, const std::vector<Outcome>& outcomes) {
  std::string t;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    if (c.set != set) continue;
    const Outcome& o = outcomes[k];
    const std::string& name = forms[c.form].name;
    const Outcome* ref = m.cell.count({name, 1.3}) ? m.cell.at({name, 1.3}).at(c.xi) : nullptr;
    study::md_row(t, {name, std::to_string(c.n), study::sig(c.xi), study::sig(c.tssfac), c.bulk ? "on" : "off",
                      o.verdict.letter(), study::sig(o.verdict.semi_discrete_growth, 3),
                      study::sig(o.verdict.map_growth, 3), o.fit.grew ? study::sig(o.fit.gamma, 3) : "–",
                      ref ? (ref->fit.grew ? study::sig(ref->fit.gamma, 3) : "–") : "-"});
  }
  return t.empty() ? std::string("(not run)") : t;
}

/// The setup: block, sweeps, MCM's constants, the steel's wave speeds, run length and detection floor.
inline void summarise_setup(study::Summary& s, const Sweeps& sw, const SwegleScene& scene, double t_end, double floor) {
  const ElasticMaterial steel = rfs::steel(scene.options);
  s.set("n", sw.n);
  s.set("sizes",
        sw.sizes.empty() ? std::string("none") : std::to_string(sw.sizes[0]) + ", " + std::to_string(sw.sizes[1]));
  s.set("h_list", h_list(std::set<double>(sw.hs.begin(), sw.hs.end())));
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
  s.set("quick", sw.quick ? "yes" : "no");
}

/// The main set's tally and the wall times.
inline void summarise_tally(study::Summary& s, const MainSet& m, std::size_t all_cases) {
  s.set("cases", m.cases);
  s.set("all_cases", static_cast<int>(all_cases));
  for (const char* c : {"S", "U", "I", "B"}) s.set(std::string("class_") + c, m.count(c));
  s.set("agree", m.agree);
  s.set("disagreements", m.disagreements.empty() ? "- none" : m.disagreements);
  s.set("equilibrium_residual", m.equilibrium, 2);
  s.set("wall_linear", m.wall_linear, 3);
  s.set("wall_runs", m.wall_runs, 3);
}

}  // namespace swegle_powell
