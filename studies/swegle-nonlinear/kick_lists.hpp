#pragma once
// The summary's tables and lists of the nonlinear Swegle study, from its (formulation, xi) cases: the measured growth
// per kick and integrator, the dt dependence, the cases by verdict (semi-discrete, integrator-made, stable), the
// growth the verdict does not predict at the largest kick (amplitude-dependent) and the fits of low r².
#include <cmath>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "kick_case.hpp"

namespace swegle_nonlinear {

struct KickLists {
  std::string table, dt_table, semi, integrator, stable, amplitude, low_r2;

  void add(const KickCase& c, const Setup& s) {
    const std::vector<double>& v0s = s.v0s;
    std::vector<std::string> row{"**" + c.form + "**", study::fixed(c.xi, 2), study::sig(c.all.growth_rate, 4),
                                 c.vpc.letter() + " / " + c.vlf.letter()};
    const std::string label = "`" + c.form + "` ξ = " + study::fixed(c.xi, 2);
    for (RateFormIntegrator i : kIntegrators)
      for (double v0 : v0s) {
        const Measured& m = c.runs.at(i).at(v0);
        std::string cell = m.fit.grew ? study::sig(m.fit.gamma, 4) : "S";
        if (m.early.grew && (!m.fit.grew || std::abs(m.early.gamma / m.fit.gamma - 1) > 0.05))
          cell += " [" + study::sig(m.early.gamma, 4) + "]";
        if (m.status != "completed") cell += " (" + m.status + ")";
        row.push_back(cell);
        if (m.fit.grew && m.fit.fit.r2 < 0.5)
          low_r2 += "- " + label + ", " + integrator_name(i) + ", v0 = " + study::sig(v0, 1) + ": γ " +
                    study::sig(m.fit.gamma, 3) + ", r² " + study::sig(m.fit.fit.r2, 2) + "\n";
      }
    study::md_row(table, row);
    const Measured& pc = c.runs.at(RateFormIntegrator::PredictorCorrector).at(v0s.front());
    const Measured& lf = c.runs.at(RateFormIntegrator::Leapfrog).at(v0s.front());
    const auto measured = [](const Measured& m) {
      return m.fit.grew ? study::sig(m.fit.gamma, 3) : "– (KE max " + study::sig(m.ke_max, 2) + " KE0)";
    };
    const StabilityVerdict &vpc = c.vpc, &vlf = c.vlf, &vhalf = c.vhalf;
    study::md_row(dt_table, {"**" + c.form + "**", study::fixed(c.xi, 2), study::sig(c.all.growth_rate, 4),
                             study::sig(pc.fit.gamma, 4), study::sig(c.half.fit.gamma, 4),
                             study::sig(vpc.map_growth, 3) + " " + vpc.letter(),
                             study::sig(vhalf.map_growth, 3) + " " + vhalf.letter()});
    // The verdict lists of the summary, from the classes and the smallest kick's runs.
    const std::string runs_text =
        "measured PC " + measured(pc) + ", LF " + measured(lf) + ", PC at dt/2 " + measured(c.half);
    if (vpc.verdict == VerdictClass::SemiDiscrete || vpc.verdict == VerdictClass::Both)
      semi += "- " + label + ": " + vpc.letter() + " (LF " + vlf.letter() + ", dt/2 " + vhalf.letter() +
              "), γ_J = " + study::sig(vpc.semi_discrete_growth, 4) + "; " + runs_text + "\n";
    else if (vpc.verdict == VerdictClass::Integrator)
      integrator += "- " + label + ": I at dt (γ_M = " + study::sig(vpc.map_growth, 3) + "), " + vhalf.letter() +
                    " at dt/2 (γ_M = " + study::sig(vhalf.map_growth, 3) + "), LF " + vlf.letter() + "; " + runs_text +
                    "\n";
    else
      stable += "- " + label + ": S (LF " + vlf.letter() + "); " + runs_text + "\n";
    // Growth the verdict does not predict at the largest kick: amplitude-dependent.
    for (RateFormIntegrator i : kIntegrators) {
      const Measured& big = c.runs.at(i).at(v0s.back());
      const StabilityVerdict& v = c.verdict(i);
      if (big.fit.grew && !(v.map_growth > s.floor))
        amplitude += "- " + label + ", " + integrator_name(i) + ", v0 = " + study::sig(v0s.back(), 1) + ": grew at " +
                     study::sig(big.fit.gamma, 3) + " /µs (r² " + study::sig(big.fit.fit.r2, 2) +
                     "), the map predicts " + v.letter() + "; " + big.status +
                     " at t = " + study::sig(big.run.time, 3) + " µs\n";
    }
  }

  void summarise(study::Summary& s) const {
    const auto list = [](const std::string& l) { return l.empty() ? std::string("- none\n") : l; };
    s.set("table", table);
    s.set("dt_table", dt_table);
    s.set("semi_list", list(semi));
    s.set("integrator_list", list(integrator));
    s.set("stable_list", list(stable));
    s.set("amplitude_list", list(amplitude));
    s.set("low_r2_list", list(low_r2));
  }
};

}  // namespace swegle_nonlinear
