#pragma once
// The key numbers and Markdown tables of the critical-strain-2d study for summary.md.in, from the rows of its phases:
// agreement of the bisection and eigen routes and the form ratios (sweep), the conservative e_crit table, the
// classification of the infinite-lattice limits, the exponent of e_crit(n), flutter in the non-symmetric form, and
// the GMS lattice sums.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "common/study.hpp"
#include "gms_lattice_sums.hpp"
#include "infinite_lattice.hpp"
#include "strain_setup.hpp"
#include "sweep_row.hpp"
#include "versus_n.hpp"

namespace cstrain {

/// Route agreement (the sweep's rows with a finite e_crit by both routes: the largest relative difference and where,
/// the rows above 1e-8) and the rows whose status is not successful.
inline void summarise_routes(study::Summary& sum, const std::vector<SweepRow>& sweep) {
  double max_rd = 0;
  int n_rows_both = 0, n_bad_status = 0, n_over = 0;
  std::string worst_rd;
  for (const auto& r : sweep) {
    if (r.r.status != Status::Successful) ++n_bad_status;
    if (!std::isnan(r.r.relative_difference) && std::isfinite(r.r.load)) {
      ++n_rows_both;
      if (r.r.relative_difference > 1e-8) ++n_over;
      if (r.r.relative_difference > max_rd) {
        max_rd = r.r.relative_difference;
        worst_rd = lattice_name(r.lattice) + " " + kernel_name(r.kernel) + " h/dx = " + sig(r.h) + " " +
                   momentum_form_name(r.form) + " " + kind_name(r.kind) + " " + load_direction_name(r.sign) +
                   " (e = " + sig(r.r.load) + ")";
      }
    }
  }
  sum.set("route_max_rel_diff", sig(max_rd, 2));
  sum.set("route_worst", worst_rd);
  sum.set("route_over_1e-8", n_over);
  sum.set("route_rows", n_rows_both);
  sum.set("rows_not_successful", n_bad_status);
}

/// The form ratios under isotropic pre-strain (one A0 for every form, A1 in the ratio 4 : 2 : 1): the largest
/// relative deviations of e_crit(plus) / e_crit(conservative) from 2 and of e_crit(uncorrected) / e_crit(conservative)
/// from 4.
inline void summarise_form_ratios(study::Summary& sum, const std::vector<SweepRow>& sweep) {
  double max_ratio_dev_plus = 0, max_ratio_dev_unc = 0;
  for (const auto& r : sweep)
    if (r.form == MomentumForm::Conservative && r.kind == PreStrainKind::Isotropic && std::isfinite(r.r.load)) {
      const auto* p = find_row(sweep, r.lattice, r.kernel, r.h, MomentumForm::Plus, r.kind, r.sign);
      const auto* u = find_row(sweep, r.lattice, r.kernel, r.h, MomentumForm::Uncorrected, r.kind, r.sign);
      if (p) max_ratio_dev_plus = std::max(max_ratio_dev_plus, std::abs(p->r.load / r.r.load / 2 - 1));
      if (u) max_ratio_dev_unc = std::max(max_ratio_dev_unc, std::abs(u->r.load / r.r.load / 4 - 1));
    }
  sum.set("ratio_dev_plus", sig(max_ratio_dev_plus, 2));
  sum.set("ratio_dev_uncorrected", sig(max_ratio_dev_unc, 2));
}

/// table_conservative: the conservative form under isotropic pre-strain at a few h per lattice and kernel, e_crit
/// with its mode and the infinite-lattice limit in tension and compression.
inline void summarise_conservative(study::Summary& sum, const std::vector<SweepRow>& sweep) {
  const auto k = [](const SweepRow* r) {
    return std::isfinite(r->r.load)
               ? "(" + sig(r->r.mode_wavevector.kx_over_pi, 2) + ", " + sig(r->r.mode_wavevector.ky_over_pi, 2) + ")"
               : std::string("-");
  };
  std::string table;
  for (LatticeType lt : kLattices)
    for (KernelType kt : kKernels)
      for (double h : {1.0, 1.3, 1.6, 2.0, 2.5}) {
        const auto* t =
            find_row(sweep, lt, kt, h, MomentumForm::Conservative, PreStrainKind::Isotropic, LoadDirection::Tension);
        const auto* c = find_row(sweep, lt, kt, h, MomentumForm::Conservative, PreStrainKind::Isotropic,
                                 LoadDirection::Compression);
        if (!t || !c) continue;
        study::md_row(table, {lattice_name(lt), kernel_name(kt), sig(h), sig(t->r.load), k(t), sig(t->inf.e),
                              sig(c->r.load), k(c), sig(c->inf.e)});
      }
  sum.set("table_conservative", table);
}

/// infinite_<direction>_<class>: the infinite-lattice limits of the conservative form on the square and hexagonal
/// lattices, counted by class (zero, tiny below 1e-6, positive / finite, stable).
inline void summarise_infinite(study::Summary& sum, const std::vector<InfRow>& infrows) {
  std::map<std::string, int> count;
  for (const char* key : {"tension_cases", "tension_zero", "tension_tiny", "tension_positive", "compression_cases",
                          "compression_zero", "compression_tiny", "compression_finite", "compression_stable"})
    count[key] = 0;
  for (const auto& r : infrows) {
    if (r.lt == LatticeType::FaceCentred || r.form != MomentumForm::Conservative) continue;
    const double e = r.s.e;
    if (r.sign == LoadDirection::Tension) {
      ++count["tension_cases"];
      const char* c = e == 0 ? "zero" : std::abs(e) < 1e-6 ? "tiny" : std::isfinite(e) ? "positive" : nullptr;
      if (c) ++count[std::string("tension_") + c];
    } else {
      ++count["compression_cases"];
      ++count[std::string("compression_") + (e == 0               ? "zero"
                                             : std::isinf(e)      ? "stable"
                                             : std::abs(e) < 1e-6 ? "tiny"
                                                                  : "finite")];
    }
  }
  for (const auto& [key, n] : count) sum.set("infinite_" + key, n);
}

/// table_versus_n: e_crit(n) per lattice and direction, the observed exponent p of |e_crit| ~ n^-p over n >= 40, the
/// periodic and infinite-lattice values and the mode at the largest n.
inline void summarise_versus_n(study::Summary& sum, const std::vector<NRow>& nrows) {
  std::map<std::tuple<int, int, double, int>, std::vector<const NRow*>> groups;
  for (const auto& r : nrows)
    groups[{static_cast<int>(r.lt), static_cast<int>(r.kt), r.h, static_cast<int>(r.sign)}].push_back(&r);
  std::string table;
  for (const auto& [key, rows] : groups) {
    std::vector<double> x, y;
    for (const NRow* r : rows)
      if (r->n >= 40 && std::isfinite(r->r.load) && r->r.load != 0) x.push_back(r->n), y.push_back(r->r.load);
    const NRow* last = rows.back();
    std::vector<std::string> row{lattice_name(last->lt), kernel_name(last->kt), sig(last->h),
                                 load_direction_name(last->sign)};
    for (int n : {10, 20, 40, 80}) {
      const NRow* f = nullptr;
      for (const NRow* r : rows)
        if (r->n == n) f = r;
      row.push_back(f ? sig(f->r.load) : "-");
    }
    row.push_back(study::sig(-study::loglog_slope(x, y), 3));  // "-" with fewer than two points (NaN slope)
    row.push_back(sig(last->periodic.e));
    row.push_back(sig(last->inf.e));
    row.push_back("(" + sig(last->r.mode_wavevector.kx_over_pi, 2) + ", " + sig(last->r.mode_wavevector.ky_over_pi, 2) +
                  ")");
    study::md_row(table, row);
  }
  sum.set("table_versus_n", table);
}

/// Flutter (complex pair) against a real crossing in the non-symmetric form, and table_nonsymmetric (h = 1.3, cubic
/// and Wendland C2) with the symmetric-part value of the sweep beside it.
inline void summarise_nonsymmetric(study::Summary& sum, const std::vector<SweepRow>& nonsym,
                                   const std::vector<SweepRow>& sweep) {
  int ns_total = 0, ns_flutter = 0;
  double ns_ratio_min = 1e300, ns_ratio_max = 0;
  for (const auto& r : nonsym) {
    if (!std::isfinite(r.r.load)) continue;
    ++ns_total;
    if (r.r.mechanism == InstabilityMechanism::ComplexPair) {
      ++ns_flutter;
      if (std::isfinite(r.r.load_eigen)) {
        const double q = r.r.load / r.r.load_eigen;
        ns_ratio_min = std::min(ns_ratio_min, q), ns_ratio_max = std::max(ns_ratio_max, q);
      }
    }
  }
  sum.set("flutter_cases", ns_flutter);
  sum.set("nonsymmetric_finite_cases", ns_total);
  sum.set("flutter_ratio_min", sig(ns_ratio_min, 3));
  sum.set("flutter_ratio_max", sig(ns_ratio_max, 3));
  std::string table;
  for (const auto& r : nonsym)
    if (std::abs(r.h - 1.3) < 1e-9 && (r.kernel == KernelType::CubicSpline || r.kernel == KernelType::WendlandC2)) {
      const auto* sp = find_row(sweep, r.lattice, r.kernel, r.h, MomentumForm::Plus, PreStrainKind::UniaxialX, r.sign);
      study::md_row(table,
                    {lattice_name(r.lattice), kernel_name(r.kernel), load_direction_name(r.sign), std::to_string(r.n),
                     sig(r.r.load), mechanism_name(r.r.mechanism), sig(r.r.load_eigen), sp ? sig(sp->r.load) : "-"});
    }
  sum.set("table_nonsymmetric", table);
}

/// table_gms and the GMS claims: the lattice sums at h/dp = 1 and the h/dp ranges where B_y > 0 (square) and where
/// the mode k = (pi/dp, 0) is stable in compression (face-centred).
inline void summarise_gms(study::Summary& sum, const std::vector<GmsRow>& gms) {
  std::string table;
  for (LatticeType lt : {LatticeType::Square, LatticeType::FaceCentred})
    for (double h : {1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7})
      if (const GmsRow* g = gms_at(gms, lt, h))
        study::md_row(table, {lattice_name(lt), sig(h), sig(g->bx, 4), sig(g->by, 3), sig(g->ax, 3),
                              sig(g->ek_t) + " / " + sig(g->ek_c),
                              sig(g->einf_t) + " " + g->kinf_t + " / " + sig(g->einf_c) + " " + g->kinf_c,
                              sig(g->en_t) + " / " + sig(g->en_c)});
  sum.set("table_gms", table);
  // The h/dp range (first to last value on the 0.05 grid) where a GMS row satisfies `pred`, or "none".
  auto h_range = [&](LatticeType lt, auto pred) {
    double lo = 0, hi = 0;
    for (const auto& g : gms)
      if (g.lt == lt && pred(g)) {
        if (lo == 0) lo = g.h;
        hi = g.h;
      }
    return lo > 0 ? sig(lo) + "-" + sig(hi) : std::string("none");
  };
  const GmsRow* sq1 = gms_at(gms, LatticeType::Square, 1.0);
  const GmsRow* fc1 = gms_at(gms, LatticeType::FaceCentred, 1.0);
  sum.set("gms_square_bx", sig(sq1 ? sq1->bx : std::nan(""), 5));
  sum.set("gms_square_by", sig(sq1 ? sq1->by : std::nan(""), 3));
  sum.set("gms_square_by_positive_h", h_range(LatticeType::Square, [](const GmsRow& g) { return g.by > 0; }));
  sum.set("gms_fc_compression_stable_h",
          h_range(LatticeType::FaceCentred, [](const GmsRow& g) { return std::isinf(g.ek_c); }));
  sum.set("gms_fc_bx", sig(fc1 ? fc1->bx : std::nan(""), 4));
  sum.set("gms_fc_by", sig(fc1 ? fc1->by : std::nan(""), 3));
  sum.set("gms_fc_ax", sig(fc1 ? fc1->ax : std::nan(""), 3));
}

}  // namespace cstrain
