#pragma once
// The key numbers and computed Markdown tables/lists of the Swegle study for summary.md.in (the prose lives there):
// the parameters, the stable/unstable and linear-versus-nonlinear tables of the 2D runs, the lists of disagreements,
// the dominant-wavevector table and the S-SPH equilibria, the energy-conservation orders, the 1D table, and the numbers
// and verdicts of the comparison with [Powell2012, ch. 4 §2.2-2.3, Fig. 4.2].

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "energy_conservation.hpp"
#include "onedim_runs.hpp"
#include "sphstab/problems/swegle.hpp"
#include "swegle_formulations.hpp"
#include "swegle_options.hpp"
#include "swegle_runs.hpp"

namespace swegle_study {

using namespace sphstab;
using study::sig;

inline const Row* find_row(const std::vector<Row>& rows, const std::string& form, double xi) {
  for (const Row& r : rows)
    if (r.form == form && std::abs(r.xi - xi) < 1e-12) return &r;
  return nullptr;
}

/// Header of a Markdown table with one column per label.
inline std::string table_header(const std::string& first, const std::vector<std::string>& labels) {
  std::string s = "| " + first + " |", rule = "|---|";
  for (const std::string& l : labels) s += " " + l + " |", rule += "---|";
  return s + "\n" + rule;
}

inline std::string xi_label(double xi) { return "xi = " + sig(xi, 6); }

/// The parameters of the study (material, pre-stress at the largest xi, time step, detection limit) and the largest
/// commutation error of a Jacobian with the block's reflections.
inline void summarise_parameters(study::Summary& s, const SwegleScene& base, const Config& c, double dt,
                                 const std::vector<Row>& rows) {
  s.set("lambda", base.material.lambda(), 5), s.set("mu", base.material.mu(), 5), s.set("c_P", base.wave_speed, 5);
  std::string xis;
  for (double xi : c.xis) xis += (xis.empty() ? "" : ", ") + sig(xi, 6);
  s.set("xi_list", xis);
  s.set("sigma0_xi_max", make_swegle_scene({.area_ratio = c.xis.back()}).prestrain.stress(base.material)(0, 0), 3);
  s.set("ke0", base.initial_kinetic_energy(), 3);
  s.set("dt", dt, 4), s.set("t_end", c.t_end, 6), s.set("steps", static_cast<long>(std::ceil(c.t_end / dt)));
  s.set("record_every", c.record_every), s.set("onset", c.onset, 6), s.set("detect", c.detect, 3);
  double commutation = 0;
  for (const Row& r : rows) commutation = std::max(commutation, r.lin.commutation);
  s.set("commutation_max", commutation, 2);
}

/// Stable/unstable table, linear-versus-nonlinear table and the ratio range of the 2D runs.
inline void summarise_2d_tables(study::Summary& s, const std::vector<Row>& rows, const std::vector<Formulation>& forms,
                                const Config& c) {
  std::vector<std::string> labels;
  for (double xi : c.xis) labels.push_back(xi_label(xi));
  std::string stable = table_header("formulation", labels), linear = stable;
  for (const Formulation& f : forms) {
    stable += "\n| " + f.name + " |";
    linear += "\n| " + f.name + " |";
    for (double xi : c.xis) {
      const Row* r = find_row(rows, f.name, xi);
      std::string cell, lin;
      if (r) {
        const bool late = r->run_verdict == "late growth";
        // Class, gamma_J / gamma_M, then the run: its measured rate, "late" growth, a blow-up without a fitted
        // window, or "–" (bounded).
        cell = (r->verdict == "S" || r->verdict == "n/a" ? r->verdict : "**" + r->verdict + "**") + " " +
               sig(std::max(r->gamma_j, 0.0), 2) + " / " + sig(std::max(r->gamma_m, 0.0), 2) + " · ";
        if (r->run.fit.grew)
          cell += sig(r->run.fit.gamma, 2);
        else if (late)
          cell += "late " + sig(r->run.fit.gamma_late, 2);
        else if (r->run.blew_up())
          cell += "blow-up";
        else
          cell += "–";
        if (r->run.blew_up()) cell += " (t " + sig(r->run.t_stop) + ")";
        lin = sig(r->gamma_pred) + " / " + sig(late ? r->run.fit.gamma_late : r->run.fit.gamma) +
              (late ? " late" : "") + " (" + sig(r->ratio) + ")";
      }
      stable += " " + cell + " |";
      linear += " " + lin + " |";
    }
  }
  s.set("stability_table", stable);
  s.set("linear_table", linear);
  double rmin = 1e300, rmax = 0;
  int nratio = 0;
  for (const Row& r : rows)
    if (!std::isnan(r.ratio) && r.equilibrium && r.run.fit.grew && !(r.switching && r.sigma0 == 0)) {
      rmin = std::min(rmin, r.ratio);
      rmax = std::max(rmax, r.ratio);
      ++nratio;
    }
  s.set("ratio_count", nratio), s.set("ratio_min", rmin, 4), s.set("ratio_max", rmax, 4);
}

/// Lists of the runs where linear theory and the run disagree, are below detection or are not comparable; the
/// dominant-wavevector table; the equilibrium of the S-SPH runs out of equilibrium.
inline void summarise_2d_lists(study::Summary& s, const std::vector<Row>& rows, const Config& c) {
  auto describe = [&](const Row& r) {
    std::ostringstream o;
    o << r.form << ", xi = " << r.xi << ": gamma_pred " << sig(r.gamma_pred) << " (without XSPH: excited class "
      << sig(r.lin.gamma_exc) << ", all classes " << sig(r.lin.gamma_all) << "); run " << r.run_verdict
      << ", KE max/KE0 " << sig(r.run.fit.max_ratio) << "; dominant wavevector k dx/pi of the run (" << sig(r.k_run.kx)
      << ", " << sig(r.k_run.ky) << "), component " << r.k_run.component() << ", of the linear mode ("
      << sig(r.k_mode.kx) << ", " << sig(r.k_mode.ky) << "); snapshots `modes/" << r.form << "_xi" << std::fixed
      << std::setprecision(2) << r.xi << "_{run,linear}.vtp`";
    return o.str();
  };
  std::string disagree, weak, na, k_rows, eq;
  auto add = [](std::string& list, const std::string& item) { list += (list.empty() ? "- " : "\n- ") + item; };
  for (const Row& r : rows) {
    if (r.agreement == "run grows, linear stable" || r.agreement == "linear unstable, run bounded")
      add(disagree, "[" + r.agreement + "] " + describe(r));
    if (r.agreement == "below detection") add(weak, describe(r));
    if (r.agreement == "n/a")
      add(na, r.form + ", xi = " + sig(r.xi, 6) + ": run " + r.run_verdict +
                  (r.run.fit.grew ? " (gamma " + sig(r.run.fit.gamma) + ")" : std::string()));
    if (r.run_verdict != "bounded" && (r.xi == c.xis.front() || r.xi == c.xis.back()))
      k_rows += "\n| " + r.form + " | " + sig(r.xi, 6) + " | (" + sig(r.k_run.kx) + ", " + sig(r.k_run.ky) + "), " +
                r.k_run.component() + ", " + sig(r.k_run.peak, 2) + " | (" + sig(r.k_mode.kx) + ", " +
                sig(r.k_mode.ky) + "), " + r.k_mode.component() + " |";
    if (!r.equilibrium)
      add(eq, r.form + ", xi = " + sig(r.xi, 6) + ": |a(0)|max = " + sig(r.a0) +
                  " cm/us^2 at the pre-strained lattice; Newton: " + r.newton +
                  (std::isnan(r.ustar) ? std::string()
                                       : ", max |u*| = " + sig(r.ustar) + " dx, gamma at u*: excited " +
                                             sig(r.lin_star.gamma_exc) + ", with XSPH map " +
                                             sig(r.lin_star.gamma_map) + ", all classes " + sig(r.lin_star.gamma_all)) +
                  "; linear at the lattice: excited " + sig(r.lin.gamma_exc));
  }
  s.set("disagreements", disagree.empty() ? "- none" : disagree);
  s.set("below_detection", weak.empty() ? "- none" : weak);
  s.set("not_comparable", na.empty() ? "- none" : na);
  s.set("wavevector_table",
        "| formulation | xi | run (kx, ky), component, peak | linear mode (kx, ky), component |\n"
        "|---|---|---|---|" +
            k_rows);
  s.set("ssph_equilibrium", eq.empty() ? "- none" : eq);
}

/// Energy table and convergence orders; the 1D table.
inline void summarise_energy_1d(study::Summary& s, const std::vector<EnergyRow>& energy,
                                const std::vector<Row1D>& rows1, const Config& c) {
  std::string rows;
  for (const EnergyRow& e : energy)
    rows += (rows.empty() ? "| " : "\n| ") + e.form + " | " + sig(e.dt, 4) + " | " + std::to_string(e.steps) + " | " +
            sig(e.max_dev) + " | " + sig(e.end_drift) + " | " + sig(e.slope_drift) + " |";
  s.set("energy_rows", rows);
  for (std::string name : {"conservative", "tl"}) {
    std::vector<const EnergyRow*> es;
    for (const EnergyRow& e : energy)
      if (e.form == name) es.push_back(&e);  // 2 dt, dt, dt/2
    s.set("energy_" + name + "_ratio_2dt", es[0]->max_dev / es[1]->max_dev, 4);
    s.set("energy_" + name + "_ratio_dt", es[1]->max_dev / es[2]->max_dev, 4);
    s.set("energy_" + name + "_order", std::log2(es[1]->max_dev / es[2]->max_dev), 3);
  }
  double m = 0;
  for (const Row1D& r : rows1)
    if (r.gamma_analytic > 0) m = std::max(m, std::abs(r.gamma_cs / r.gamma_analytic - 1));
  s.set("onedim_cs_vs_analytic", m, 2);
  s.set("t_end_1d", c.t_end_1d, 6);
  std::vector<std::string> labels, names;
  for (double xi : c.xis) labels.push_back("T = " + sig(xi - 1, 2));
  for (const Row1D& r : rows1)
    if (std::find(names.begin(), names.end(), r.form) == names.end()) names.push_back(r.form);
  std::string table = table_header("form", labels);
  for (const std::string& name : names) {
    table += "\n| " + name + " |";
    for (const Row1D& r : rows1)
      if (r.form == name)
        table += std::string(" ") + (r.run_verdict == "bounded" ? "S" : "**U**") + " " + sig(r.run.fit.gamma) + " / " +
                 sig(r.gamma_exc) + " |";
  }
  s.set("onedim_table", table);
}

/// The numbers and verdicts of the comparison with [Powell2012, ch. 4 §2.2-2.3, Fig. 4.2].
inline void summarise_powell(study::Summary& s, const std::vector<Row>& rows, const Config& c) {
  struct Side {  // one formulation over tension (xi > 1) or compression (xi < 1)
    int runs = 0, unstable = 0;
    double gmax = 0;
    std::string list;
  };
  auto side = [&](const std::string& form, bool tension) {
    Side sd;
    for (const Row& r : rows)
      if (r.form == form && (tension ? r.xi > 1 : r.xi < 1)) {
        ++sd.runs;
        if (r.run_verdict != "bounded") {
          ++sd.unstable;
          sd.list += (sd.list.empty() ? "" : ", ") + sig(r.xi, 3);
          if (r.run.fit.grew) sd.gmax = std::max(sd.gmax, r.run.fit.gamma);
        }
      }
    return sd;
  };
  auto grow = [](const Side& sd, bool tension) {
    return std::to_string(sd.unstable) + " of " + std::to_string(sd.runs) + (tension ? " tension" : " compression") +
           " runs grow";
  };
  auto fastest = [](const Side& sd) { return sd.gmax > 0 ? ", fastest gamma " + sig(sd.gmax) + "/us" : ""; };
  // "**agrees**" etc. with Powell's claim that the runs are unstable (claim_unstable) or stable, and the counts.
  auto verdict = [&](const std::string& form, bool tension, bool claim_unstable) -> std::string {
    const Side sd = side(form, tension);
    if (sd.runs == 0) return "not run";
    const bool all = sd.unstable == sd.runs, none = sd.unstable == 0;
    return std::string(claim_unstable ? (all ? "**agrees**" : (none ? "**disagrees**" : "**partly agrees**"))
                                      : (none ? "**agrees**" : (all ? "**disagrees**" : "**partly agrees**"))) +
           " (" + grow(sd, tension) + (sd.list.empty() ? "" : ": xi = " + sd.list) + fastest(sd) + ")";
  };
  auto counts = [&](const std::string& form, bool tension) -> std::string {
    const Side sd = side(form, tension);
    if (sd.runs == 0) return "not run";
    return grow(sd, tension) + (sd.list.empty() ? "" : " (xi = " + sd.list + ")") + fastest(sd);
  };
  auto k_of = [&](const std::string& form, double xi) -> std::string {
    const Row* r = find_row(rows, form, xi);
    if (!r || std::isnan(r->k_run.kx)) return "-";
    return "(" + sig(r->k_run.kx, 2) + ", " + sig(r->k_run.ky, 2) + ") " + r->k_run.component() + "-component";
  };
  auto ratio_of = [&](const std::string& a, const std::string& b, double xi) {
    const Row *ra = find_row(rows, a, xi), *rb = find_row(rows, b, xi);
    return ra && rb && ra->run.fit.grew && rb->run.fit.grew ? ra->run.fit.gamma / rb->run.fit.gamma : kNaN;
  };
  const double lo = c.xis.front(), hi = c.xis.back();
  s.set("xi_min", lo, 6), s.set("xi_max", hi, 6);
  s.set("powell_sph_tension", verdict("sph", true, true)), s.set("powell_sph_compression", counts("sph", false));
  s.set("k_sph_xi_max", k_of("sph", hi)), s.set("k_sph_xi_min", k_of("sph", lo));
  s.set("powell_ncsph_tension", verdict("ncsph", true, true));
  s.set("powell_ncsph_compression", counts("ncsph", false));
  s.set("powell_cij_tension", verdict("cij", true, false)),
      s.set("powell_cij_compression", verdict("cij", false, true));
  s.set("powell_sph-xsph_tension", verdict("sph-xsph", true, true));
  s.set("xsph_over_sph_1.01", ratio_of("sph-xsph", "sph", 1.01)),
      s.set("xsph_over_sph_1.04", ratio_of("sph-xsph", "sph", 1.04));
  s.set("powell_tl_tension", counts("tl", true)), s.set("powell_tl_compression", counts("tl", false));
  s.set("powell_ssph_tension", verdict("ssph", true, false));
  s.set("powell_ssph_compression", verdict("ssph", false, false));
  s.set("powell_ssph-pp_tension", verdict("ssph-pp", true, false));
  s.set("powell_ssph-pp_compression", verdict("ssph-pp", false, false));
  s.set("powell_ssph-printed_tension", counts("ssph-printed", true));
  s.set("powell_ssph-printed_compression", counts("ssph-printed", false));
  s.set("powell_sph-gms_tension", counts("sph-gms", true));
  s.set("gms_over_sph_1.04", ratio_of("sph-gms", "sph", 1.04)), s.set("k_sph-gms_xi_max", k_of("sph-gms", hi));
  const Row* gms1 = find_row(rows, "sph-gms", 1.0);
  s.set("sph-gms_xi1_run", gms1 ? gms1->run_verdict : std::string("-"));
}

}  // namespace swegle_study
