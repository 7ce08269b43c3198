#pragma once
// The summary's numbers of the rate-form Swegle study's cases: the verdict classes, the agreement of the one-step
// map with the runs (and the disagreements), the measured / linear growth ratios, the largest residual of
// equilibrium, and per formulation the classes on either side of xi = 1 and the cut of basic SPH's rate.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "common/study.hpp"
#include "rate_form_case.hpp"

namespace swegle_rate_form {

/// One (formulation, xi) of the table: its verdict and its run.
struct Cell {
  std::string letter;
  double gamma_j = NAN, gamma_m = NAN, measured = NAN;
  bool grew = false;
};

struct Tally {
  int agree = 0, cases = 0, comparable = 0;
  double ratio_min = 1e300, ratio_max = -1e300, smooth_min = 1e300, smooth_max = -1e300;
  std::map<std::string, int> classes;                   // verdict letter -> count
  std::map<std::string, std::map<double, Cell>> cells;  // formulation -> xi -> verdict and run
  std::string disagreements;                            // runs whose growth the map does not predict (or the reverse)
  double eq_res_max = 0;  // largest equilibrium residual over the kick's acceleration scale

  void add(const Formulation& form, const CaseResult& c) {
    const StabilityVerdict& v = c.v;
    const ExponentialGrowthFit& fit = c.fit;
    eq_res_max = std::max(eq_res_max, c.equilibrium);
    ++classes[v.letter()];
    ++cases;
    agree += c.map_unstable == fit.grew;
    cells[form.name][c.xi] = {v.letter(), v.semi_discrete_growth, v.map_growth, fit.gamma, fit.grew};
    if (c.map_unstable != fit.grew)
      disagreements += "- `" + form.name + "`, ξ = " + study::sig(c.xi) + ": " + v.letter() + ", γ_J " +
                       study::sig(v.semi_discrete_growth, 3) + ", γ_M " + study::sig(v.map_growth, 3) + " /µs; run " +
                       (fit.grew ? "grew at " + study::sig(fit.gamma, 3) + " /µs" : "stayed below the window") + "\n";
    if (std::isfinite(c.ratio)) {
      ++comparable;
      ratio_min = std::min(ratio_min, c.ratio);
      ratio_max = std::max(ratio_max, c.ratio);
      if (form.options.viscosity == ViscositySwitch::Off) {  // smooth terms: the linear theory applies
        smooth_min = std::min(smooth_min, c.ratio);
        smooth_max = std::max(smooth_max, c.ratio);
      }
    }
  }

  /// Per formulation, the class at each xi of one side of 1 (the rows of the statement table of the summary); "–"
  /// for a formulation not run (--quick).
  std::string classes_of(const std::string& name, int side) const {
    if (!cells.count(name)) return "–";
    std::string t;
    for (const auto& [xi, c] : cells.at(name))
      if ((side > 0 && xi > 1) || (side < 0 && xi < 1))
        t += (t.empty() ? "" : ", ") + study::sig(xi) + " " + c.letter;
      else if (side == 0 && xi == 1)
        t = c.letter;
    return t;
  }

  /// "lo–hi" at 2 significant digits, one value when both round alike, "–" for none.
  static std::string range(double lo, double hi) {
    if (lo > hi) return std::string("–");
    return study::sig(lo, 2) == study::sig(hi, 2) ? study::sig(lo, 2) : study::sig(lo, 2) + "–" + study::sig(hi, 2);
  }

  /// The ratio of basic SPH's rate to the formulation's over the xi where both grow on one side of 1: gamma_J of
  /// both (linear), or the runs' measured rates (for the viscosity, whose switch the linearisation takes as off).
  std::string cut(const std::string& name, int side, bool measured, double detect) const {
    double lo = 1e300, hi = -1e300;
    if (!cells.count(name) || !cells.count("sph")) return range(lo, hi);  // not run (--quick)
    for (const auto& [xi, c] : cells.at(name)) {
      const Cell& b = cells.at("sph").at(xi);
      if ((side > 0) != (xi > 1) || xi == 1) continue;
      const bool both = measured ? c.grew && b.grew : c.gamma_j > detect && b.gamma_j > detect;
      if (!both) continue;
      const double r = measured ? b.measured / c.measured : b.gamma_j / c.gamma_j;
      lo = std::min(lo, r), hi = std::max(hi, r);
    }
    return range(lo, hi);
  }

  void summarise(study::Summary& s, double detect) const {
    s.set("cases", cases);
    s.set("disagreements", disagreements.empty() ? "- none" : disagreements);
    for (const char* name : {"sph", "ncsph", "ncsph-xsph", "ncsph-anti", "cij", "ssph", "ssph-printed", "sph-xsph"}) {
      s.set(std::string("tension_") + name, classes_of(name, 1));
      s.set(std::string("compression_") + name, classes_of(name, -1));
    }
    for (const char* name : {"sph", "ncsph", "cij", "ssph", "sph-as", "sph-all"})
      s.set(std::string("neutral_") + name, classes_of(name, 0));
    s.set("ssph_tension_cut", cut("ssph", 1, false, detect));
    s.set("xsph_tension_cut", cut("sph-xsph", 1, false, detect));
    s.set("xsph_compression_cut", cut("sph-xsph", -1, false, detect));
    s.set("visc_compression_cut", cut("sph-visc", -1, true, detect));
    double map_lo = 1e300, map_hi = -1e300;  // the integrator's rate where it alone grows
    for (const auto& [name, row] : cells)
      for (const auto& [xi, c] : row)
        if (c.letter == "I") map_lo = std::min(map_lo, c.gamma_m), map_hi = std::max(map_hi, c.gamma_m);
    s.set("integrator_rate_range", range(map_lo, map_hi));
    for (const char* c : {"S", "U", "I", "B"}) s.set(std::string("class_") + c, classes.count(c) ? classes.at(c) : 0);
    s.set("agree", agree);
    s.set("comparable", comparable);
    s.set("ratio_min", comparable ? ratio_min : NAN, 3);
    s.set("ratio_max", comparable ? ratio_max : NAN, 3);
    s.set("smooth_ratio_min", smooth_min, 3);
    s.set("smooth_ratio_max", smooth_max, 3);
    s.set("equilibrium_residual", eq_res_max, 2);
  }
};

}  // namespace swegle_rate_form
