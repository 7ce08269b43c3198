// Study mean-polishing: kernel corrections in the 1D momentum forms ([Powell2012, ch. 3 §4-4.1.1, ch. 4 §2]).
// What the study asks and what the sources claim: README.md; the prose of the summary: summary.md.in.
//
// For every correction x momentum form (x corrected operator) on the 1D pre-tensioned bar at u = 0: the exact
// A(T) = A0 + T A1 (complex step through the correction) and its critical loads in tension and compression
// (critical_load.hpp); momentum conservation and locality at displaced states.
//
// Writes to --out DIR:
//   tcrit.csv        N = n sweep (kernels cubic, wendland-c2, quintic; h/dx = 1.0..2.5) and the N = n_check check
//   momentum.csv     periodic lattice, displaced state: total force sum_i V_i a_i / sum_i V_i |a_i|, row and column
//                    sums of Ghat
//   locality.csv     stored/non-zero entries of G and Ghat, and of the Jacobian, per correction
//   thin_layers.csv  the same critical loads with fixed layers only one support thick (boundary sensitivity)
//   summary.json     key numbers and tables for summary.md.in (scripts/render_summary.py)
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace {

using namespace sphstab;
using study::Clock;
using study::random_vector;
using study::seconds_since;
using study::sig;

constexpr int kLayerSupports = 3;  // fixed layers: see tension_lattice_1d

std::string num(double v) { return format_number(v, 10); }

struct Variant {
  std::string name;
  Correction correction;
  CorrectionGradientOptions options;
};

const std::vector<Variant>& variants() {
  static const std::vector<Variant> v{
      {"none", Correction::None, {}},
      {"minus", Correction::Minus, {}},
      {"shepard", Correction::Shepard, {}},
      {"column-shepard", Correction::ColumnShepard, {}},
      {"ncsph", Correction::Ncsph, {}},
      {"local-polish", Correction::LocalPolish, {}},
      {"local-polish+fig4.3", Correction::LocalPolish, {.counting = NeighbourCounting::BoundaryLevel}},
      {"local-polish+eq4.18", Correction::LocalPolish, {.first_step_shepard = true}},
      {"mean-polish", Correction::MeanPolish, {}},
      {"shepard-column-polish", Correction::ShepardColumnPolish, {}},
  };
  return v;
}

struct FormCase {
  MomentumForm form;
  CorrectedOperator target;
};

/// Forms x corrected operator: the divergence (Powell 3.28) and both operators for the non-conservative forms, the
/// strain (3.55) for the conservative one. For "none" only the first of each form is run.
const std::vector<FormCase>& form_cases() {
  static const std::vector<FormCase> v{
      {MomentumForm::Uncorrected, CorrectedOperator::Divergence}, {MomentumForm::Uncorrected, CorrectedOperator::Both},
      {MomentumForm::Plus, CorrectedOperator::Divergence},        {MomentumForm::Plus, CorrectedOperator::Both},
      {MomentumForm::Minus, CorrectedOperator::Divergence},       {MomentumForm::Minus, CorrectedOperator::Both},
      {MomentumForm::Conservative, CorrectedOperator::Strain},
  };
  return v;
}

struct Row {
  int n;
  std::string kernel;
  double h;
  std::string correction, form, target, strain_sum, direction, criterion;
  double tcrit, growth, mode_k, a1_rel, asym0, asym1, residual;
  std::string status, reason;
  double seconds;
};

std::shared_ptr<const GradientProvider<1>> provider(const Variant& v) {
  return make_gradient_provider<1>(v.correction, v.options);
}

void run_case(int n, KernelType type, double h, const Variant& v, const FormCase& fc, std::vector<Row>& rows) {
  Kernel<1> kernel(type);
  auto disc = make_discretisation(tension_lattice_1d(kernel, h, n, false, kLayerSupports), kernel, h);
  const auto t0 = Clock::now();
  WaveForm1D force(disc, fc.form, 0.0, provider(v), {.corrected = fc.target});
  const ForceCriticalLoad tension = force_critical_loads(force, LoadDirection::Tension, disc->free_positions());
  const std::vector<CriticalLoad> compression = critical_loads(tension.jacobian, LoadDirection::Compression);
  const double seconds = seconds_since(t0);
  const std::string target = v.correction == Correction::None                           ? "-"
                             : force.strain_corrected() && force.divergence_corrected() ? "both"
                             : force.strain_corrected()                                 ? "strain"
                                                                                        : "divergence";
  const std::string strain_sum =
      force.strain_corrected() ? (force.strain_sum() == StrainSum::Direct ? "direct" : "difference") : "plain";
  for (const auto* list : {&tension.results, &compression})
    for (const CriticalLoad& r : *list)
      rows.push_back({n, kernel_name(type), h, v.name, momentum_form_name(fc.form), target, strain_sum,
                      load_direction_name(r.direction), criterion_name(r.criterion), r.load, r.growth_rate,
                      r.reported_wavenumber().k_projection, r.a1_relative, r.asymmetry0, r.asymmetry1,
                      tension.residual_relative, status_name(r.status), r.reason, seconds});
}

/// Ghat of a provider at the displaced positions x0 + u (u on the free particles).
Eigen::MatrixXd corrected_gradient_at(const Discretisation<1>& d, const GradientProvider<1>& p,
                                      const Eigen::VectorXd& u) {
  Positions<1> x = d.particles.x;
  for (int f = 0; f < d.free_count(); ++f) x(d.free[f], 0) += u[f];
  const Operators<1> ops =
      assemble_operators<1, double>(d.particles, d.neighbours, d.kernel, d.h, p.requirements(), &x);
  std::array<SparseMatrix<>, 1> g{ops.G[0]};
  p.correct(GradientContext<1, double>{d, x, ops}, g);
  return Eigen::MatrixXd(g[0]);
}

long count_nonzero(const Eigen::MatrixXd& m, double relative) {
  const double tol = relative * m.cwiseAbs().maxCoeff();
  return (m.array().abs() > tol).count();
}

/// A CSV cell: a number with 10 significant digits (num), an integer or text as it is.
template <class T>
std::string cell(const T& v) {
  if constexpr (std::is_floating_point_v<T>)
    return num(v);
  else if constexpr (std::is_integral_v<T>)
    return std::to_string(v);
  else
    return std::string(v);
}

template <class... T>
void csv_line(std::ostream& o, const T&... v) {
  const char* sep = "";
  ((o << sep << cell(v), sep = ","), ...);
  o << "\n";
}

/// A Markdown table row "| a | b |" of texts and integers (numbers are formatted by the caller with sig()).
template <class... T>
std::string md_row(const T&... v) {
  static_assert(!(std::is_floating_point_v<T> || ...), "format numbers with sig()");
  std::string r = "|";
  ((r += " " + cell(v) + " |"), ...);
  return r;
}

/// The rows of a Markdown table, without the final newline (the template holds the header).
std::string table(const std::vector<std::string>& rows) {
  std::string t;
  for (const std::string& r : rows) t += (t.empty() ? "" : "\n") + r;
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Kernel corrections in the 1D SPH momentum forms: critical loads, momentum, locality (Powell ch. 3-4)"};
  std::string out = "results/mean-polishing";
  int n = 30, n_check = 120;
  bool quick = false;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles of the main sweep");
  app.add_option("--n-check", n_check, "free particles of the size check");
  app.add_flag("--quick", quick, "h/dx in steps of 0.5 only (smoke run)");
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(out);
  const auto start = Clock::now();
  const std::vector<KernelType> kernels{KernelType::CubicSpline, KernelType::WendlandC2, KernelType::QuinticSpline};
  std::vector<double> hs;
  for (int k = 0; k <= 15; k += quick ? 5 : 1) hs.push_back(1.0 + 0.1 * k);

  // 1. Critical loads, N = n sweep and N = n_check check.
  std::vector<Row> rows;
  double dense_conservative_seconds = 0;
  for (const auto& [size, h_list] : {std::pair{n, hs}, std::pair{n_check, std::vector<double>{1.3, 2.0}}})
    for (KernelType type : kernels)
      for (double h : h_list) {
        const auto t0 = Clock::now();
        for (const Variant& v : variants())
          for (const FormCase& fc : form_cases()) {
            if (v.correction == Correction::None && fc.target == CorrectedOperator::Both) continue;
            // The dense corrected conservative forms cost O(N^4) through the nested derivatives (dual passes inside
            // complex steps): about 10-30 s each at N = 120.
            const bool dense_cons = correction_is_dense(v.correction) && fc.form == MomentumForm::Conservative;
            const auto tc = Clock::now();
            run_case(size, type, h, v, fc, rows);
            if (size == n_check && dense_cons) dense_conservative_seconds += seconds_since(tc);
          }
        std::cout << "N=" << size << " " << kernel_name(type) << " h=" << h << " (" << sig(seconds_since(t0), 2)
                  << " s)" << std::endl;
      }
  std::ofstream csv(out + "/tcrit.csv");
  csv << "N,kernel,h_over_dx,correction,form,corrected_operator,strain_sum,direction,criterion,tcrit,growth_2tcrit,"
         "mode_k_over_pi,a1_relative,asymmetry_T0,asymmetry_T1,equilibrium_residual,status,seconds,reason\n";
  for (const Row& r : rows)
    csv_line(csv, r.n, r.kernel, r.h, r.correction, r.form, r.target, r.strain_sum, r.direction, r.criterion, r.tcrit,
             r.growth, r.mode_k, r.a1_rel, r.asym0, r.asym1, r.residual, r.status, r.seconds, "\"" + r.reason + "\"");
  csv.close();

  // 2. Momentum conservation on a periodic displaced lattice, row and column sums of Ghat there.
  struct MomentumRow {
    std::string kernel, correction, form, target;
    double total, rowsum, colsum;
  };
  std::vector<MomentumRow> momentum;
  for (KernelType type : kernels) {
    Kernel<1> kernel(type);
    const double h = 1.3;
    auto disc = make_discretisation(tension_lattice_1d(kernel, h, 31, true), kernel, h);
    const Eigen::VectorXd u = random_vector(disc->dofs(), 0.1, 7);
    const Eigen::VectorXd mass = WaveForm1D(disc, MomentumForm::Plus, 0.0).dof_mass();
    for (const Variant& v : variants()) {
      const auto p = provider(v);
      const Eigen::MatrixXd gh = corrected_gradient_at(*disc, *p, u);
      const double scale = gh.cwiseAbs().maxCoeff();
      const double rowsum = gh.rowwise().sum().cwiseAbs().maxCoeff() / scale;
      const double colsum = gh.colwise().sum().cwiseAbs().maxCoeff() / scale;
      for (const FormCase& fc : form_cases()) {
        if (v.correction == Correction::None && fc.target == CorrectedOperator::Both) continue;
        WaveForm1D force(disc, fc.form, 0.1, p, {.corrected = fc.target});
        Eigen::VectorXd a;
        force.acceleration(u, a);
        const double total = std::abs(mass.dot(a)) / mass.dot(a.cwiseAbs());
        momentum.push_back({kernel_name(type), v.name, momentum_form_name(fc.form),
                            v.correction == Correction::None ? "-" : corrected_operator_name(fc.target), total, rowsum,
                            colsum});
      }
    }
  }
  csv.open(out + "/momentum.csv");
  csv << "kernel,correction,form,corrected_operator,total_force_relative,max_row_sum_relative,"
         "max_column_sum_relative\n";
  for (const MomentumRow& r : momentum)
    csv_line(csv, r.kernel, r.correction, r.form, r.target, r.total, r.rowsum, r.colsum);
  csv.close();
  std::cout << "momentum done" << std::endl;

  // 3. Locality: entries of Ghat and of the Jacobian at a displaced state (N = n, cubic, h = 1.3).
  struct LocalityRow {
    std::string correction;
    long g_stored, g_nonzero, gh_stored, gh_nonzero, pattern_plus, jac_plus, pattern_cons, jac_cons;
    int colours_plus, colours_cons;
  };
  std::vector<LocalityRow> locality;
  {
    Kernel<1> kernel(KernelType::CubicSpline);
    const double h = 1.3;
    auto disc = make_discretisation(tension_lattice_1d(kernel, h, n, false, kLayerSupports), kernel, h);
    const Eigen::VectorXd u = random_vector(disc->dofs(), 0.05, 3);
    const Eigen::MatrixXd g = corrected_gradient_at(*disc, PlainGradient<1>(), u);
    for (const Variant& v : variants()) {
      const auto p = provider(v);
      WaveForm1D plus(disc, MomentumForm::Plus, 0.1, p);
      WaveForm1D cons(disc, MomentumForm::Conservative, 0.1, p);
      const Eigen::MatrixXd gh = corrected_gradient_at(*disc, *p, u);
      Positions<1> x = disc->particles.x;
      const Operators<1> ops =
          assemble_operators<1, double>(disc->particles, disc->neighbours, disc->kernel, h, p->requirements(), &x);
      std::array<SparseMatrix<>, 1> stored{ops.G[0]};
      p->correct(GradientContext<1, double>{*disc, x, ops}, stored);
      const ComplexStepJacobian jp(plus), jc(cons);
      locality.push_back({v.name, disc->neighbours.nonzeros(), count_nonzero(g, 1e-14), stored[0].nonZeros(),
                          count_nonzero(gh, 1e-14), jp.pattern().nonzeros(),
                          count_nonzero(Eigen::MatrixXd(jp.compute(u)), 1e-14), jc.pattern().nonzeros(),
                          count_nonzero(Eigen::MatrixXd(jc.compute(u)), 1e-14), jp.colours(), jc.colours()});
    }
  }
  csv.open(out + "/locality.csv");
  csv << "correction,G_stored,G_nonzero,Ghat_stored,Ghat_nonzero,jacobian_pattern_plus,jacobian_nonzero_plus,"
         "colours_plus,jacobian_pattern_conservative,jacobian_nonzero_conservative,colours_conservative\n";
  for (const LocalityRow& r : locality)
    csv_line(csv, r.correction, r.g_stored, r.g_nonzero, r.gh_stored, r.gh_nonzero, r.pattern_plus, r.jac_plus,
             r.colours_plus, r.pattern_cons, r.jac_cons, r.colours_cons);
  csv.close();

  // 4. Boundary sensitivity: the same at N = n, cubic, h = 1.3, with fixed layers only ONE support thick.
  struct ThinRow {
    std::string correction, form, target;
    double residual, asymmetry, t_first, t_second, t_compression;
    std::string first, second;
  };
  std::vector<ThinRow> thin;
  {
    Kernel<1> kernel(KernelType::CubicSpline);
    const double h = 1.3;
    auto disc = make_discretisation(tension_lattice_1d(kernel, h, n), kernel, h);
    const Eigen::MatrixXd x = disc->free_positions();
    for (const Variant& v : variants())
      for (const FormCase& fc : form_cases()) {
        if (fc.target == CorrectedOperator::Both) continue;
        WaveForm1D force(disc, fc.form, 0.0, provider(v), {.corrected = fc.target});
        const ForceCriticalLoad t = force_critical_loads(force, LoadDirection::Tension, x);
        const auto c = critical_loads(t.jacobian, LoadDirection::Compression);
        const CriticalLoad& r0 = t.results.front();
        thin.push_back({v.name, momentum_form_name(fc.form),
                        v.correction == Correction::None ? "-" : corrected_operator_name(fc.target),
                        t.residual_relative, std::max(r0.asymmetry0, r0.asymmetry1), r0.load,
                        t.results.size() > 1 ? t.results[1].load : NAN, c.front().load, criterion_name(r0.criterion),
                        t.results.size() > 1 ? criterion_name(t.results[1].criterion) : "-"});
      }
  }
  csv.open(out + "/thin_layers.csv");
  csv << "correction,form,corrected_operator,equilibrium_residual,asymmetry,criterion,tcrit,second_criterion,"
         "tcrit_second,tcrit_compression\n";
  for (const ThinRow& r : thin)
    csv_line(csv, r.correction, r.form, r.target, r.residual, r.asymmetry, r.first, r.t_first, r.second, r.t_second,
             r.t_compression);
  csv.close();
  const double seconds = seconds_since(start);

  // 5. Key numbers. Per correction|form|target over the N = n sweep, first criterion of each direction.
  struct Agg {
    int cases = 0, tension_inf = 0, compression_inf = 0, nonsymmetric = 0;
    double min_tension = INFINITY, max_compression = -INFINITY, max_a1 = 0, max_asym = 0, max_residual = 0;
  };
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
      if (r.criterion != criterion_name(Criterion::Definiteness)) ++a.nonsymmetric;  // (it compared with "pd", a
                                                                                    // name no row carries: all counted)
    } else {
      if (std::isinf(r.tcrit)) ++a.compression_inf;
      if (std::isfinite(r.tcrit)) a.max_compression = std::max(a.max_compression, r.tcrit);
    }
    a.max_a1 = std::max(a.max_a1, r.a1_rel);
    a.max_asym = std::max({a.max_asym, r.asym0, r.asym1});
    a.max_residual = std::max(a.max_residual, r.residual);
  }
  auto find = [&](const std::string& c, const std::string& f, const std::string& t) -> const Agg& {
    return agg.at(c + " | " + f + " | " + t);
  };
  // N = n_check rows vs the same case at N = n (T_crit = inf agreement, finite values relative change)
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
  auto momentum_of = [&](const std::string& c, const std::string& f, const std::string& t) {
    double m = 0;
    for (const MomentumRow& r : momentum)
      if (r.correction == c && r.form == f && r.target == t) m = std::max(m, r.total);
    return m;
  };

  study::Summary s;
  s.set("n", n);
  s.set("n_check", n_check);
  s.set("layer_supports", kLayerSupports);
  s.set("h_first", hs.front(), 6);
  s.set("h_last", hs.back(), 6);
  s.set("h_step", quick ? "0.5" : "0.1");
  s.set("dense_conservative_seconds", dense_conservative_seconds);
  s.set("wall_seconds", seconds);
  s.set("cases_per_row", static_cast<int>(kernels.size() * hs.size()));
  std::vector<std::string> lines;
  int nonsym = 0;
  for (const std::string& key : order) {
    const Agg& a = agg[key];
    nonsym += a.nonsymmetric;
    const std::string cases = "/" + std::to_string(a.cases);
    lines.push_back(md_row(key, std::to_string(a.tension_inf) + cases, sig(a.min_tension),
                           std::to_string(a.compression_inf) + cases, sig(a.max_compression), sig(a.max_a1, 2),
                           sig(a.max_asym, 2), sig(a.max_residual, 2)));
  }
  s.set("table_critical_loads", table(lines));
  s.set("nonsymmetric_cases", nonsym);
  s.set("check_same_class", check_same_class);
  s.set("check_cases", check_cases);
  s.set("check_finite", static_cast<int>(check_rel.size()));
  s.set("check_median_percent", 100 * check_median, 2);
  s.set("check_max_percent", 100 * check_max_rel, 2);
  s.set("check_worst", check_worst);
  lines.clear();
  for (const Variant& v : variants()) {
    double rs = 0, cs = 0;
    for (const MomentumRow& r : momentum)
      if (r.correction == v.name) rs = std::max(rs, r.rowsum), cs = std::max(cs, r.colsum);
    const std::string t = v.correction == Correction::None ? "-" : "divergence";
    lines.push_back(md_row(v.name, sig(rs, 2), sig(cs, 2), sig(momentum_of(v.name, "uncorrected", t), 2),
                           sig(momentum_of(v.name, "plus", t), 2), sig(momentum_of(v.name, "minus", t), 2),
                           sig(momentum_of(v.name, "conservative", t == "-" ? "-" : "strain"), 2)));
  }
  s.set("table_momentum", table(lines));
  lines.clear();
  int thin_nonsym = 0, thin_noneq = 0;
  for (const ThinRow& r : thin) {
    const bool nonsym_r = r.first != criterion_name(Criterion::Definiteness), noneq = r.residual > 1e-10;
    thin_nonsym += nonsym_r;
    thin_noneq += noneq;
    if (nonsym_r || noneq)
      lines.push_back(md_row(r.correction, r.form + " (" + r.target + ")", sig(r.residual, 2), sig(r.asymmetry, 2),
                             r.first + ": " + sig(r.t_first), sig(r.t_second), sig(r.t_compression)));
  }
  s.set("table_thin_layers", table(lines));
  s.set("thin_nonsymmetric", thin_nonsym);
  s.set("thin_not_equilibrium", thin_noneq);
  s.set("thin_cases", static_cast<int>(thin.size()));
  lines.clear();
  for (const LocalityRow& r : locality)
    lines.push_back(
        md_row(r.correction, r.gh_stored, r.gh_nonzero, r.jac_plus, r.colours_plus, r.jac_cons, r.colours_cons));
  s.set("table_locality", table(lines));
  s.set("locality_g_stored", locality.front().g_stored);
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
  s.write(out);
  std::cout << "wrote " << out << "/tcrit.csv, momentum.csv, locality.csv, thin_layers.csv, summary.json ("
            << sig(seconds, 3) << " s)\n";
  return 0;
}
