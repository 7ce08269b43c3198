#pragma once
// The critical loads of the four 1D SPH momentum forms (uncorrected, plus, minus, conservative) in tension AND
// compression [Powell2012, ch. 3 §3-4, (3.27), (3.28), (3.38), (3.40)]:
// - T_crit per kernel, h/dx, form and direction by the analytic route (critical_tension_1d), with the wavenumber of
//   the unstable mode (tcrit.csv);
// - the cross-check by the general affine route from the force functions' complex-step Jacobians (crosscheck.csv);
// - the summary numbers built on them: the ratios 4 (uncorrected) and 2 (plus) to the conservative T_crit, the minus
//   form's critical loads, and per kernel the conservative form's h/dx ranges stable in compression.
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace forms_study {

using namespace sphstab;
using study::sig;

struct TcritRow {
  std::string kernel;
  double h;
  std::string form, direction;
  double tcrit, mode_k;
  std::string status, reason;
};

/// The T_crit rows, and the conservative T_crit^- per (kernel, h) that the compression conditions compare with.
struct TcritTable {
  std::vector<TcritRow> rows;
  std::map<std::pair<std::string, double>, double> cons_minus;  // conservative T_crit^- per (kernel, h)
};

/// T_crit in tension and compression, analytic route: every kernel, h/dx in `hs`, form, on n free particles.
inline TcritTable critical_loads_1d(const std::vector<double>& hs, int n, const std::vector<MomentumForm>& forms) {
  TcritTable table;
  for (KernelType type : all_kernel_types()) {
    Kernel<1> kernel(type);
    for (double h : hs) {
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, n);
      CriticalLoadOptions with_mode = CriticalLoadOptions::tension_1d();
      with_mode.want_mode = true;
      for (MomentumForm form : forms)
        for (int dir = 0; dir < 2; ++dir) {
          const LoadDirection d = dir == 0 ? LoadDirection::Tension : LoadDirection::Compression;
          const CriticalLoad r = critical_tension_1d(set, kernel, h, form, with_mode, d);
          const double t = r.load;
          table.rows.push_back({kernel_name(type), h, momentum_form_name(form), load_direction_name(d), t,
                                std::isfinite(r.load) ? r.mode_wavenumber.k_projection : NAN, status_name(r.status),
                                r.reason});
          if (dir == 1 && form == MomentumForm::Conservative) table.cons_minus[{kernel_name(type), h}] = t;
        }
    }
    std::cout << "tcrit " << kernel_name(type) << std::endl;
  }
  return table;
}

inline void write_tcrit(const std::string& path, const std::vector<TcritRow>& rows) {
  std::ofstream csv(path);
  csv << "kernel,h_over_dx,form,direction,tcrit,mode_k_over_pi,status,reason\n";
  for (const TcritRow& r : rows)
    csv << r.kernel << "," << format_number(r.h, 10) << "," << r.form << "," << r.direction << ","
        << format_number(r.tcrit, 10) << "," << format_number(r.mode_k, 10) << "," << r.status << ",\"" << r.reason
        << "\"\n";
}

struct CrossCheck {
  double max = 0;  ///< largest relative difference where both routes are finite
  int cases = 0, class_mismatch = 0;
};

/// Cross-check: general affine route from the force functions' complex-step Jacobians against the analytic route,
/// every kernel, h/dx in `hs`, form and direction; writes one row per case to `path` (crosscheck.csv).
inline CrossCheck crosscheck_affine(const std::string& path, const std::vector<double>& hs, int n,
                                    const std::vector<MomentumForm>& forms) {
  CrossCheck c;
  std::ofstream csv(path);
  csv << "kernel,h_over_dx,form,direction,tcrit_analytic,tcrit_affine,relative_difference\n";
  for (KernelType type : all_kernel_types()) {
    Kernel<1> kernel(type);
    for (double h : hs) {
      auto disc = make_discretisation(tension_lattice_1d(kernel, h, n), kernel, h);
      for (MomentumForm form : forms) {
        Linearisation split = affine_jacobian(WaveForm1D(disc, form, 0.0), Eigen::VectorXd::Zero(disc->dofs()));
        split.x = disc->free_positions();
        for (LoadDirection dir : {LoadDirection::Tension, LoadDirection::Compression}) {
          const double affine = critical_loads(split, dir).front().load;
          const double analytic =
              critical_tension_1d(disc->particles, kernel, h, form, CriticalLoadOptions::tension_1d(), dir).load;
          double rel = 0;
          if (std::isinf(analytic) != std::isinf(affine)) {
            rel = INFINITY;
            ++c.class_mismatch;
          } else if (std::isfinite(analytic)) {
            rel = std::abs(affine / analytic - 1);
          }
          if (std::isfinite(rel)) c.max = std::max(c.max, rel);  // both infinite: rel = 0
          ++c.cases;
          csv << kernel_name(type) << "," << format_number(h, 10) << "," << momentum_form_name(form) << ","
              << load_direction_name(dir) << "," << format_number(analytic, 10) << "," << format_number(affine, 10)
              << "," << format_number(rel, 10) << "\n";
        }
      }
    }
  }
  return c;
}

/// T_crit of one case (kernel, h/dx, form and direction by name); NaN if absent.
inline double tcrit_of(const std::vector<TcritRow>& rows, const std::string& kernel, double h, const std::string& form,
                       const std::string& dir) {
  for (const TcritRow& r : rows)
    if (r.kernel == kernel && std::abs(r.h - h) < 1e-9 && r.form == form && r.direction == dir) return r.tcrit;
  return std::numeric_limits<double>::quiet_NaN();
}

/// Key numbers of the T_crit table: ratio_dev, minus_critical_load and tension_compression_table (ft_min: the
/// relative minimum of each kernel's Fourier transform, a column of that table).
inline void summarise_critical_loads(study::Summary& sum, const std::vector<TcritRow>& tcrit,
                                     const std::vector<double>& hs, const std::map<std::string, double>& ft_min) {
  auto tc = [&](const std::string& kernel, double h, const std::string& form, const std::string& dir) {
    return tcrit_of(tcrit, kernel, h, form, dir);
  };
  double ratio_dev = 0;
  bool minus_inf = true;
  for (const TcritRow& r : tcrit) {
    if (r.form == "minus") minus_inf = minus_inf && std::isinf(r.tcrit);
    if (r.form != "conservative" || !std::isfinite(r.tcrit)) continue;
    ratio_dev = std::max(ratio_dev, std::abs(tc(r.kernel, r.h, "uncorrected", r.direction) / r.tcrit - 4));
    ratio_dev = std::max(ratio_dev, std::abs(tc(r.kernel, r.h, "plus", r.direction) / r.tcrit - 2));
  }
  sum.set("ratio_dev", ratio_dev, 2);
  sum.set("minus_critical_load", minus_inf ? "no" : "SOME");

  // Conservative form per kernel: h/dx ranges stable in compression, T_crit^- and T_crit at h/dx = 1.2, 1.5, 2.
  std::string table;
  for (KernelType type : all_kernel_types()) {
    const std::string k = kernel_name(type);
    int stable = 0;
    std::string ranges;
    double run_start = NAN, prev = NAN;
    auto close_run = [&] {
      if (std::isnan(run_start)) return;
      ranges += (ranges.empty() ? "" : ", ") + sig(run_start) + (prev > run_start ? "-" + sig(prev) : "");
      run_start = NAN;
    };
    for (double h : hs) {
      if (std::isinf(tc(k, h, "conservative", "compression"))) {
        ++stable;
        if (std::isnan(run_start)) run_start = h;
        prev = h;
      } else {
        close_run();
      }
    }
    close_run();
    auto at = [&](const std::string& dir) {
      return sig(tc(k, 1.2, "conservative", dir)) + " / " + sig(tc(k, 1.5, "conservative", dir)) + " / " +
             sig(tc(k, 2.0, "conservative", dir));
    };
    study::md_row(table, {k, sig(ft_min.at(k), 2),
                          (ranges.empty() ? "none" : ranges) + " (" + std::to_string(stable) + "/" +
                              std::to_string(hs.size()) + ")",
                          at("compression"), at("tension")});
  }
  sum.set("tension_compression_table", table);
}

}  // namespace forms_study
