#pragma once
// The key numbers and Markdown tables of the mean-polishing study for summary.md.in (the prose and the comparison
// with [Powell2012] claims 2-4, (3.33), (3.59), (4.11) live there), from the rows of critical_loads.hpp,
// momentum_conservation.hpp, locality.hpp and thin_layers.hpp: the critical loads aggregated per correction | form |
// corrected operator over the N = n sweep, the size check N = n_check against N = n, the momentum, thin-layer and
// locality tables, and the numbers the comparison with Powell quotes.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "correction_cases.hpp"
#include "critical_loads.hpp"
#include "locality.hpp"
#include "momentum_conservation.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "thin_layers.hpp"

namespace mean_polishing {

using namespace sphstab;
using study::md_row;
using study::sig;

/// One correction | form | corrected operator over the N = n sweep, first criterion of each direction.
struct Agg {
  int cases = 0, tension_inf = 0, compression_inf = 0, nonsymmetric = 0;
  double min_tension = INFINITY, max_compression = -INFINITY, max_a1 = 0, max_asym = 0, max_residual = 0;
};

/// The aggregates per "correction | form | target", and the keys in the order of the sweep.
struct Aggregates {
  std::map<std::string, Agg> agg;
  std::vector<std::string> order;
  const Agg& find(const std::string& c, const std::string& f, const std::string& t) const {
    return agg.at(c + " | " + f + " | " + t);
  }
};

/// Per correction|form|target over the N = n sweep, first criterion of each direction.
inline Aggregates aggregate(const std::vector<Row>& rows, int n) {
  std::map<std::string, Agg> agg;
  std::vector<std::string> order;
  for (size_t k = 0; k < rows.size(); ++k) {
    const Row& r = rows[k];
    if (r.n != n) continue;
    if (k > 0 && rows[k - 1].n == r.n && rows[k - 1].kernel == r.kernel && rows[k - 1].h == r.h &&
        rows[k - 1].correction == r.correction && rows[k - 1].form == r.form && rows[k - 1].target == r.target &&
        rows[k - 1].direction == r.direction)
      continue;  // second criterion (symmetric part) of a nonsymmetric case
    const std::string key = r.correction + " | " + r.form + " | " + r.target;
    if (!agg.count(key)) order.push_back(key);
    Agg& a = agg[key];
    if (r.direction == "tension") {
      ++a.cases;
      if (std::isinf(r.tcrit)) ++a.tension_inf;
      if (std::isfinite(r.tcrit)) a.min_tension = std::min(a.min_tension, r.tcrit);
      if (r.criterion != criterion_name(Criterion::Definiteness))
        ++a.nonsymmetric;  // (it compared with "pd", a
                           // name no row carries: all counted)
    } else {
      if (std::isinf(r.tcrit)) ++a.compression_inf;
      if (std::isfinite(r.tcrit)) a.max_compression = std::max(a.max_compression, r.tcrit);
    }
    a.max_a1 = std::max(a.max_a1, r.a1_rel);
    a.max_asym = std::max({a.max_asym, r.asym0, r.asym1});
    a.max_residual = std::max(a.max_residual, r.residual);
  }
  return {std::move(agg), std::move(order)};
}

/// The critical-load table (one line per correction | form | target) and the count of nonsymmetric cases.
inline void summarise_critical_loads(study::Summary& s, const Aggregates& g) {
  std::string lines;
  int nonsym = 0;
  for (const std::string& key : g.order) {
    const Agg& a = g.agg.at(key);
    nonsym += a.nonsymmetric;
    const std::string cases = "/" + std::to_string(a.cases);
    md_row(lines,
           {key, std::to_string(a.tension_inf) + cases, sig(a.min_tension), std::to_string(a.compression_inf) + cases,
            sig(a.max_compression), sig(a.max_a1, 2), sig(a.max_asym, 2), sig(a.max_residual, 2)});
  }
  s.set("table_critical_loads", lines);
  s.set("nonsymmetric_cases", nonsym);
}

/// The size check: N = n_check rows vs the same case at N = n (T_crit = inf agreement, finite values relative change).
inline void summarise_size_check(study::Summary& sum, const std::vector<Row>& rows, int n, int n_check) {
  int check_cases = 0, check_same_class = 0;
  double check_max_rel = 0;
  std::string check_worst;
  std::vector<double> check_rel;
  for (const Row& r : rows) {
    if (r.n != n_check) continue;
    for (const Row& s : rows)
      if (s.n == n && s.kernel == r.kernel && s.h == r.h && s.correction == r.correction && s.form == r.form &&
          s.target == r.target && s.direction == r.direction && s.criterion == r.criterion) {
        ++check_cases;
        if (std::isinf(r.tcrit) == std::isinf(s.tcrit)) ++check_same_class;
        if (std::isfinite(r.tcrit) && std::isfinite(s.tcrit) && s.tcrit != 0) {
          const double rel = std::abs(r.tcrit / s.tcrit - 1);
          check_rel.push_back(rel);
          if (rel > check_max_rel) {
            check_max_rel = rel;
            check_worst = r.correction + " " + r.form + " " + r.kernel + " h = " + sig(r.h) + " " + r.direction + ": " +
                          sig(s.tcrit) + " -> " + sig(r.tcrit);
          }
        }
      }
  }
  double check_median = 0;
  if (!check_rel.empty()) {
    std::nth_element(check_rel.begin(), check_rel.begin() + check_rel.size() / 2, check_rel.end());
    check_median = check_rel[check_rel.size() / 2];
  }
  sum.set("check_same_class", check_same_class);
  sum.set("check_cases", check_cases);
  sum.set("check_finite", static_cast<int>(check_rel.size()));
  sum.set("check_median_percent", 100 * check_median, 2);
  sum.set("check_max_percent", 100 * check_max_rel, 2);
  sum.set("check_worst", check_worst);
}

/// The largest total force |sum V a| / sum V |a| of a correction, form and corrected operator over the kernels.
inline double momentum_of(const std::vector<MomentumRow>& momentum, const std::string& c, const std::string& f,
                          const std::string& t) {
  double m = 0;
  for (const MomentumRow& r : momentum)
    if (r.correction == c && r.form == f && r.target == t) m = std::max(m, r.total);
  return m;
}

/// The momentum table: per correction the row and column sums of Ghat and the total force of each form.
inline void summarise_momentum(study::Summary& s, const std::vector<MomentumRow>& momentum) {
  std::string lines;
  for (const Variant& v : variants()) {
    double rs = 0, cs = 0;
    for (const MomentumRow& r : momentum)
      if (r.correction == v.name) rs = std::max(rs, r.rowsum), cs = std::max(cs, r.colsum);
    const std::string t = v.correction == Correction::None ? "-" : "divergence";
    md_row(lines, {v.name, sig(rs, 2), sig(cs, 2), sig(momentum_of(momentum, v.name, "uncorrected", t), 2),
                   sig(momentum_of(momentum, v.name, "plus", t), 2), sig(momentum_of(momentum, v.name, "minus", t), 2),
                   sig(momentum_of(momentum, v.name, "conservative", t == "-" ? "-" : "strain"), 2)});
  }
  s.set("table_momentum", lines);
}

/// The thin-layer cases that are nonsymmetric or out of equilibrium, and their counts.
inline void summarise_thin_layers(study::Summary& s, const std::vector<ThinRow>& thin) {
  std::string lines;
  int thin_nonsym = 0, thin_noneq = 0;
  for (const ThinRow& r : thin) {
    const bool nonsym_r = r.first != criterion_name(Criterion::Definiteness), noneq = r.residual > 1e-10;
    thin_nonsym += nonsym_r;
    thin_noneq += noneq;
    if (nonsym_r || noneq)
      md_row(lines, {r.correction, r.form + " (" + r.target + ")", sig(r.residual, 2), sig(r.asymmetry, 2),
                     r.first + ": " + sig(r.t_first), sig(r.t_second), sig(r.t_compression)});
  }
  s.set("table_thin_layers", lines);
  s.set("thin_nonsymmetric", thin_nonsym);
  s.set("thin_not_equilibrium", thin_noneq);
  s.set("thin_cases", static_cast<int>(thin.size()));
}

/// The locality table: stored and non-zero entries of Ghat and of the Jacobians, colour counts.
inline void summarise_locality(study::Summary& s, const std::vector<LocalityRow>& locality) {
  std::string lines;
  for (const LocalityRow& r : locality)
    md_row(lines, {r.correction, std::to_string(r.gh_stored), std::to_string(r.gh_nonzero), std::to_string(r.jac_plus),
                   std::to_string(r.colours_plus), std::to_string(r.jac_cons), std::to_string(r.colours_cons)});
  s.set("table_locality", lines);
  s.set("locality_g_stored", locality.front().g_stored);
}

/// The numbers of the comparison with Powell's claims (summary.md.in).
inline void summarise_powell(study::Summary& s, const Aggregates& g, const std::vector<MomentumRow>& momentum,
                             const std::vector<LocalityRow>& locality) {
  auto find = [&](const std::string& c, const std::string& f, const std::string& t) -> const Agg& {
    return g.find(c, f, t);
  };
  auto momentum_of = [&](const std::string& c, const std::string& f, const std::string& t) {
    return mean_polishing::momentum_of(momentum, c, f, t);
  };
  // Comparison with Powell: key "<correction>.<form>.<field>" of the aggregated N = n sweep.
  auto put = [&](const std::string& c, const std::string& f, const std::string& t, const std::string& fields) {
    const Agg& a = find(c, f, t);
    std::string p = c + "." + f + ".";
    std::replace(p.begin(), p.end(), '+', '_');
    std::istringstream is(fields);
    for (std::string w; is >> w;) {
      if (w == "cases") s.set(p + w, a.cases);
      if (w == "tension_inf") s.set(p + w, a.tension_inf);
      if (w == "compression_inf") s.set(p + w, a.compression_inf);
      if (w == "tension_finite") s.set(p + w, a.cases - a.tension_inf);
      if (w == "min_tension") s.set(p + w, a.min_tension);
      if (w == "max_compression") s.set(p + w, a.max_compression);
      if (w == "max_a1") s.set(p + w, a.max_a1, 2);
      if (w == "max_residual") s.set(p + w, a.max_residual, 2);
    }
  };
  put("mean-polish", "conservative", "strain", "cases tension_inf compression_inf max_a1");
  put("shepard-column-polish", "conservative", "strain", "cases tension_inf compression_inf max_a1");
  put("column-shepard", "conservative", "strain", "cases tension_inf compression_inf");
  put("column-shepard", "plus", "divergence", "min_tension");
  put("shepard", "conservative", "strain", "cases tension_finite min_tension");
  put("none", "conservative", "-", "min_tension");
  put("none", "minus", "-", "cases tension_inf");
  put("local-polish", "uncorrected", "divergence", "cases tension_inf compression_inf");
  put("local-polish", "conservative", "strain", "min_tension max_compression");
  put("local-polish+fig4.3", "uncorrected", "divergence", "cases tension_inf");
  put("local-polish+eq4.18", "uncorrected", "divergence", "cases tension_inf min_tension max_a1");
  put("local-polish+eq4.18", "conservative", "strain", "max_residual");
  bool normalised_no_t = true;
  for (const char* c : {"shepard", "ncsph", "local-polish", "mean-polish", "shepard-column-polish"})
    for (const char* f : {"uncorrected", "plus", "minus"}) {
      const Agg& a = find(c, f, "divergence");
      normalised_no_t = normalised_no_t && a.tension_inf == a.cases && a.compression_inf == a.cases;
    }
  s.set("normalised_no_t", normalised_no_t ? "all" : "NOT all");
  s.set("momentum.column-shepard.conservative", momentum_of("column-shepard", "conservative", "strain"), 2);
  s.set(
      "momentum.difference_strain_max",
      std::max({momentum_of("mean-polish", "conservative", "strain"), momentum_of("shepard", "conservative", "strain"),
                momentum_of("shepard-column-polish", "conservative", "strain")}),
      2);
  for (const char* c : {"local-polish", "shepard", "ncsph"})
    s.set(std::string("momentum.") + c + ".uncorrected", momentum_of(c, "uncorrected", "divergence"), 2);
  s.set("nonlocal.ghat_nonzero", locality.back().gh_nonzero);
  s.set("nonlocal.g_nonzero", locality.front().g_nonzero);
  s.set("nonlocal.jacobian_plus_none", locality.front().jac_plus);
  for (const LocalityRow& r : locality)
    if (r.correction == "mean-polish") s.set("nonlocal.jacobian_plus_mean_polish", r.jac_plus);
}

}  // namespace mean_polishing
