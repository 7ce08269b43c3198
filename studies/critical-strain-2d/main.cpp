// Study critical-strain-2d: critical pre-strain of 2D SPH lattices (square, hexagonal; elastic forms, plane strain),
// GitHub issue 3; comparison with [GMS2001, §5]. What the study asks: README.md; the prose of the summary:
// summary.md.in (rendered from summary.json by scripts/render_summary.py).
//
// Writes to --out DIR:
//   sweep.csv         n = 16 free particles per side, fixed layers; 4 kernels x h/dx = 1.0..2.5 (0.1); isotropic and
//                     uniaxial pre-strain; tension and compression; forms conservative, plus, uncorrected (isotropic:
//                     definiteness; uniaxial plus/uncorrected: symmetric-part criterion, labelled), minus; e_crit by
//                     bisection and eigen routes, mechanism, critical-mode wavevector, infinite-lattice limit
//   nonsymmetric.csv  uniaxial plus form with the stability criterion proper (all eigenvalues real and positive,
//                     dense dgeev): n = 12 for every kernel, h/dx = 1.0..2.5 (0.3)
//   versus_n.csv      e_crit(n), n = 10..80 per side, conservative isotropic, with the periodic (exact symbol) value
//                     at the same n and the infinite-lattice limit
//   infinite.csv      infinite-lattice e_crit (Fourier symbols) for square, hex, face-centred, every kernel and h
//   gms.csv           Gray, Monaghan & Swift (2001) lattice sums at k = (pi/dp, 0) (cubic spline) and the stability
//                     of that single mode against the whole Brillouin zone
//   summary.json      key numbers and tables for summary.md.in
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace {

using namespace sphstab;
using study::Clock;
using study::seconds_since;

// Plane strain, E = 2.1, nu = 0.3, rho = 7.8 (Powell's Swegle test); e_crit depends on nu only.
const double kE = 2.1, kNu = 0.3, kRho = 7.8;
const ElasticMaterial kMaterial{
    .lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), .mu = kE / (2 * (1 + kNu)), .rho = kRho};
const std::vector<KernelType> kKernels{KernelType::CubicSpline, KernelType::QuinticSpline, KernelType::WendlandC2,
                                       KernelType::WendlandC4};
const std::vector<LatticeType> kLattices{LatticeType::Square, LatticeType::Hexagonal};

std::string num(double v) { return format_number(v, 12); }
// Not study::sig: NaN is printed "nan" here (gms.csv infinite_k_* columns, and the GMS table of the summary).
std::string sig(double v, int digits = 3) { return format_number(v, digits); }
std::string csv_field(const std::string& s) { return s.find(',') == std::string::npos ? s : "\"" + s + "\""; }
std::string kind_name(PreStrainKind k) { return k == PreStrainKind::Isotropic ? "isotropic" : "uniaxial"; }

std::vector<double> h_grid(double step_tenths) {
  std::vector<double> hs;
  for (int i = 10; i <= 25; i += static_cast<int>(step_tenths)) hs.push_back(i / 10.0);
  return hs;
}

struct SweepRow {
  LatticeType lattice;
  KernelType kernel;
  double h;
  MomentumForm form;
  PreStrainKind kind;
  LoadDirection sign;
  int n;
  CriticalLoad r;
  SymbolCriticalStrain inf;
  double seconds;
};

std::string sweep_header() {
  return "lattice,kernel,h_over_dx,form,prestrain,direction,n,criterion,ecrit,ecrit_eig,ecrit_bisect,rel_diff,"
         "mechanism,mode_kx_over_pi,mode_ky_over_pi,mode_peak_fraction,ecrit_infinite,infinite_kx_over_pi,"
         "infinite_ky_over_pi,infinite_mechanism,status,reason,seconds\n";
}
std::string sweep_line(const SweepRow& s) {
  std::ostringstream o;
  o << lattice_name(s.lattice) << "," << kernel_name(s.kernel) << "," << num(s.h) << "," << momentum_form_name(s.form)
    << "," << kind_name(s.kind) << "," << load_direction_name(s.sign) << "," << s.n << ","
    << criterion_name(s.r.criterion) << "," << num(s.r.load) << "," << num(s.r.load_eigen) << ","
    << num(s.r.load_bisection) << "," << num(s.r.relative_difference) << "," << mechanism_name(s.r.mechanism) << ","
    << num(s.r.mode_wavevector.kx_over_pi) << "," << num(s.r.mode_wavevector.ky_over_pi) << ","
    << num(s.r.mode_wavevector.peak_fraction) << "," << num(s.inf.e) << "," << num(s.inf.kx_over_pi) << ","
    << num(s.inf.ky_over_pi) << "," << mechanism_name(s.inf.mechanism) << "," << status_name(s.r.status) << ","
    << csv_field(s.r.reason) << "," << sig(s.seconds, 4) << "\n";
  return o.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Critical pre-strain of 2D SPH lattices (issue 3)"};
  std::string out_dir = "results/critical-strain-2d";
  bool quick = false;
  app.add_option("--out", out_dir, "Output directory");
  app.add_flag("--quick", quick, "Small smoke run (n = 8, few h, n up to 20)");
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(out_dir);
  const auto t_start = Clock::now();
  const int n_main = quick ? 8 : 16, n_nonsym = quick ? 6 : 12;
  const std::vector<double> hs = quick ? std::vector<double>{1.0, 1.3, 2.0} : h_grid(1);

  // ---------------- A. main sweep, n = n_main ----------------
  std::vector<SweepRow> sweep;
  std::ofstream sweep_csv(out_dir + "/sweep.csv");
  sweep_csv << sweep_header();
  double t_sweep = 0;
  {
    const auto t0 = Clock::now();
    int done = 0;
    const int total = static_cast<int>(kLattices.size() * kKernels.size() * hs.size());
    for (LatticeType lt : kLattices)
      for (KernelType kt : kKernels) {
        const Kernel<2> kernel(kt);
        for (double h : hs) {
          auto disc = make_discretisation(strain_lattice_2d(lt, kernel, h, n_main), kernel, h);
          const Operators<2> ops = assemble_operators<2>(disc->particles, disc->neighbours, kernel, h,
                                                         {.kernel = false, .gradient = true, .hessian = true});
          // The shared 2-core machine limits the budget: every h with the eigen route (conservative,
          // isotropic); on the subset h in {1.0, 1.6, 2.2} also the bisection route, uniaxial pre-strain and the
          // other forms (eigen route).
          const bool subset = std::abs(std::round((h - 1.0) / 0.6) * 0.6 - (h - 1.0)) < 1e-9;
          for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX})
            for (MomentumForm form : all_momentum_forms()) {
              if (!subset && (form != MomentumForm::Conservative || kind != PreStrainKind::Isotropic)) continue;
              const Linearisation jac = analytic_jacobian_2d(*disc, ops, kMaterial, form, kind);
              const ElasticSymbol2D symbol(lt, kernel, h, 1.0, kMaterial, form, kind);
              for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
                const auto tc = Clock::now();
                CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
                if (!jac.symmetric) opt.criterion = Criterion::SymmetricPart;  // dense spectrum: nonsymmetric.csv
                opt.method =
                    subset && form == MomentumForm::Conservative ? CriticalLoadMethod::Both : CriticalLoadMethod::Eigen;
                SweepRow row{lt, kt, h, form, kind, sign, n_main, critical_load(jac, sign, opt), {}, 0};
                row.inf = critical_strain_infinite_2d(symbol, sign, 128);
                row.seconds = seconds_since(tc);
                sweep_csv << sweep_line(row);
                sweep.push_back(std::move(row));
              }
            }
          ++done;
          if (done % 8 == 0 || done == total)
            std::cout << "critical-strain-2d: sweep " << done << "/" << total << " (" << sig(seconds_since(t0), 3)
                      << " s)" << std::endl;
        }
      }
    t_sweep = seconds_since(t0);
  }
  sweep_csv.close();

  // ---------------- B. non-symmetric (uniaxial plus), spectrum criterion ----------------
  std::vector<SweepRow> nonsym;
  double t_nonsym = 0;
  {
    const auto t0 = Clock::now();
    std::ofstream csv(out_dir + "/nonsymmetric.csv");
    csv << sweep_header();
    const std::vector<double> hs_ns = quick ? std::vector<double>{1.3} : h_grid(3);
    const std::size_t total = kLattices.size() * kKernels.size() * hs_ns.size();
    int done = 0;
    for (LatticeType lt : kLattices)
      for (KernelType kt : kKernels)
        for (double h : hs_ns) {
          const Kernel<2> kernel(kt);
          auto disc = make_discretisation(strain_lattice_2d(lt, kernel, h, n_nonsym), kernel, h);
          const Linearisation jac =
              analytic_jacobian_2d(*disc, kMaterial, MomentumForm::Plus, PreStrainKind::UniaxialX);
          const ElasticSymbol2D symbol(lt, kernel, h, 1.0, kMaterial, MomentumForm::Plus, PreStrainKind::UniaxialX);
          for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
            const auto tc = Clock::now();
            CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
            opt.criterion = Criterion::Spectrum;
            SweepRow row{lt, kt, h, MomentumForm::Plus, PreStrainKind::UniaxialX, sign, n_nonsym, {}, {}, 0};
            row.r = critical_load(jac, sign, opt);
            row.inf = critical_strain_infinite_2d(symbol, sign, 128);
            row.seconds = seconds_since(tc);
            csv << sweep_line(row);
            nonsym.push_back(std::move(row));
          }
          if (++done % 8 == 0 || done == static_cast<int>(total))
            std::cout << "critical-strain-2d: non-symmetric " << done << "/" << total << " ("
                      << sig(seconds_since(t0), 3) << " s)" << std::endl;
        }
    t_nonsym = seconds_since(t0);
  }

  // ---------------- C. e_crit versus n ----------------
  struct NRow {
    LatticeType lt;
    KernelType kt;
    double h;
    LoadDirection sign;
    int n;
    CriticalLoad r;
    SymbolCriticalStrain periodic, inf;
    double seconds;
    std::string method;
  };
  std::vector<NRow> nrows;
  double t_versus_n = 0;
  {
    const auto t0 = Clock::now();
    std::ofstream csv(out_dir + "/versus_n.csv");
    csv << "lattice,kernel,h_over_dx,form,prestrain,direction,n,method,ecrit,ecrit_eig,ecrit_bisect,rel_diff,"
           "mode_kx_over_pi,mode_ky_over_pi,ecrit_periodic,periodic_kx_over_pi,periodic_ky_over_pi,ecrit_infinite,"
           "status,reason,seconds\n";
    const std::vector<int> sizes = quick ? std::vector<int>{10, 20} : std::vector<int>{10, 20, 40, 80};
    for (LatticeType lt : kLattices)
      for (KernelType kt : {KernelType::CubicSpline})
        for (double h : {1.3}) {
          const Kernel<2> kernel(kt);
          const ElasticSymbol2D symbol(lt, kernel, h, 1.0, kMaterial, MomentumForm::Conservative,
                                       PreStrainKind::Isotropic);
          for (int n : sizes) {
            auto disc = make_discretisation(strain_lattice_2d(lt, kernel, h, n), kernel, h);
            const Linearisation jac =
                analytic_jacobian_2d(*disc, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
            for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
              const auto tc = Clock::now();
              CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
              // Bisection (~40 factorisations) up to n = 20; the eigen route alone above (benchmark.md: timing).
              opt.method = n <= 20 ? CriticalLoadMethod::Both : CriticalLoadMethod::Eigen;
              NRow row{lt, kt, h, sign, n, critical_load(jac, sign, opt), {}, {}, 0, n <= 20 ? "both" : "eig"};
              row.periodic = critical_strain_periodic_symbol_2d(symbol, n, sign);
              row.inf = critical_strain_infinite_2d(symbol, sign);
              row.seconds = seconds_since(tc);
              csv << lattice_name(lt) << "," << kernel_name(kt) << "," << num(h) << ",conservative,isotropic,"
                  << load_direction_name(sign) << "," << n << "," << row.method << "," << num(row.r.load) << ","
                  << num(row.r.load_eigen) << "," << num(row.r.load_bisection) << "," << num(row.r.relative_difference)
                  << "," << num(row.r.mode_wavevector.kx_over_pi) << "," << num(row.r.mode_wavevector.ky_over_pi) << ","
                  << num(row.periodic.e) << "," << num(row.periodic.kx_over_pi) << "," << num(row.periodic.ky_over_pi)
                  << "," << num(row.inf.e) << "," << status_name(row.r.status) << "," << csv_field(row.r.reason) << ","
                  << sig(row.seconds, 4) << "\n";
              nrows.push_back(std::move(row));
            }
          }
          std::cout << "critical-strain-2d: versus n " << lattice_name(lt) << " " << kernel_name(kt) << " h " << h
                    << " (" << sig(seconds_since(t0), 3) << " s)" << std::endl;
        }
    t_versus_n = seconds_since(t0);
  }

  // ---------------- D. infinite lattice ----------------
  struct InfRow {
    LatticeType lt;
    KernelType kt;
    double h;
    MomentumForm form;
    PreStrainKind kind;
    LoadDirection sign;
    SymbolCriticalStrain s;
  };
  std::vector<InfRow> infrows;
  {
    std::ofstream csv(out_dir + "/infinite.csv");
    csv << "lattice,kernel,h_over_dx,form,prestrain,direction,ecrit_infinite,kx_over_pi,ky_over_pi,mechanism,"
           "neutral_points,reason\n";
    for (LatticeType lt : {LatticeType::Square, LatticeType::Hexagonal, LatticeType::FaceCentred})
      for (KernelType kt : kKernels)
        for (double h : h_grid(1))
          for (MomentumForm form : {MomentumForm::Conservative, MomentumForm::Plus})
            for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
              const ElasticSymbol2D symbol(lt, Kernel<2>(kt), h, 1.0, kMaterial, form, kind);
              for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
                InfRow row{lt, kt, h, form, kind, sign, critical_strain_infinite_2d(symbol, sign, 128)};
                csv << lattice_name(lt) << "," << kernel_name(kt) << "," << num(h) << "," << momentum_form_name(form)
                    << "," << kind_name(kind) << "," << load_direction_name(sign) << "," << num(row.s.e) << ","
                    << num(row.s.kx_over_pi) << "," << num(row.s.ky_over_pi) << "," << mechanism_name(row.s.mechanism)
                    << "," << row.s.neutral_points << "," << csv_field(row.s.reason) << "\n";
                infrows.push_back(row);
              }
            }
  }

  // ---------------- E. Gray, Monaghan & Swift (2001) §5 ----------------
  struct GmsRow {
    LatticeType lt;
    double h, bx, by, ax, ek_t, ek_c, einf_t, einf_c, en_t, en_c;
    std::string kinf_t, kinf_c;
  };
  std::vector<GmsRow> gms;
  {
    std::ofstream csv(out_dir + "/gms.csv");
    csv << "lattice,h_over_dp,B_x,B_y,A_x,ecrit_k_pi0_tension,ecrit_k_pi0_compression,ecrit_infinite_tension,"
           "ecrit_infinite_compression,infinite_k_tension,infinite_k_compression,ecrit_n20_tension,"
           "ecrit_n20_compression\n";
    const Kernel<2> cubic(KernelType::CubicSpline);
    for (LatticeType lt : {LatticeType::Square, LatticeType::FaceCentred})
      for (int i = 0; i <= 14; ++i) {
        const double h = 1.0 + 0.05 * i;
        const bool finite_n = i % 2 == 0;  // n = 20 lattice at h/dp = 1.0, 1.1, ..., 1.7
        // GMS's momentum equation sum_b m_b (sigma_a/rho_a^2 + sigma_b/rho_b^2) grad W is the plus form;
        // a uniform pressure is the isotropic pre-stress (tension = -P).
        const ElasticSymbol2D sym(lt, cubic, h, 1.0, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic);
        const auto v = sym({M_PI, 0});
        GmsRow g{lt, h, v.l(0, 0), v.l(1, 1), -v.s[0], 0, 0, 0, 0, std::nan(""), std::nan(""), "", ""};
        g.ek_t = critical_strain_2x2(v.a0, v.a1, LoadDirection::Tension, 1e-12 * v.a1.cwiseAbs().maxCoeff()).e;
        g.ek_c = critical_strain_2x2(v.a0, v.a1, LoadDirection::Compression, 1e-12 * v.a1.cwiseAbs().maxCoeff()).e;
        const auto it = critical_strain_infinite_2d(sym, LoadDirection::Tension);
        const auto ic = critical_strain_infinite_2d(sym, LoadDirection::Compression);
        g.einf_t = it.e;
        g.einf_c = ic.e;
        g.kinf_t = "(" + sig(it.kx_over_pi) + " " + sig(it.ky_over_pi) + ")";
        g.kinf_c = "(" + sig(ic.kx_over_pi) + " " + sig(ic.ky_over_pi) + ")";
        if (!quick && finite_n) {
          auto disc = make_discretisation(strain_lattice_2d(lt, cubic, h, 20), cubic, h);
          const auto jac = analytic_jacobian_2d(*disc, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic);
          CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
          opt.method = CriticalLoadMethod::Eigen;
          opt.want_mode = false;
          g.en_t = critical_load(jac, LoadDirection::Tension, opt).load;
          g.en_c = critical_load(jac, LoadDirection::Compression, opt).load;
        }
        csv << lattice_name(lt) << "," << num(h) << "," << num(g.bx) << "," << num(g.by) << "," << num(g.ax) << ","
            << num(g.ek_t) << "," << num(g.ek_c) << "," << num(g.einf_t) << "," << num(g.einf_c) << "," << g.kinf_t
            << "," << g.kinf_c << "," << num(g.en_t) << "," << num(g.en_c) << "\n";
        gms.push_back(g);
      }
  }
  const double t_total = seconds_since(t_start);

  // ---------------- key numbers and tables for summary.md.in ----------------
  study::Summary sum;
  auto table = [](const std::vector<std::string>& rows) {  // Markdown rows, without the final newline
    std::string t;
    for (const std::string& r : rows) t += (t.empty() ? "" : "\n") + r;
    return t;
  };
  auto cells = [](const std::vector<std::string>& v) {  // one Markdown row "| a | b |"
    std::string r = "|";
    for (const std::string& c : v) r += " " + c + " |";
    return r;
  };
  auto find = [&](const std::vector<SweepRow>& rows, LatticeType lt, KernelType kt, double h, MomentumForm f,
                  PreStrainKind kind, LoadDirection s) -> const SweepRow* {
    for (const auto& r : rows)
      if (r.lattice == lt && r.kernel == kt && std::abs(r.h - h) < 1e-9 && r.form == f && r.kind == kind && r.sign == s)
        return &r;
    return nullptr;
  };
  sum.set("lambda", kMaterial.lambda, 6);
  sum.set("mu", kMaterial.mu, 6);
  sum.set("n_main", n_main);
  sum.set("n_nonsymmetric", n_nonsym);
  sum.set("sweep_rows", static_cast<int>(sweep.size()));
  sum.set("sweep_seconds", t_sweep);
  sum.set("nonsymmetric_rows", static_cast<int>(nonsym.size()));
  sum.set("nonsymmetric_seconds", t_nonsym);
  sum.set("versus_n_rows", static_cast<int>(nrows.size()));
  sum.set("versus_n_seconds", t_versus_n);
  sum.set("total_seconds", t_total);

  // Route agreement, status, ratios.
  double max_rd = 0, max_ratio_dev_plus = 0, max_ratio_dev_unc = 0;
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
    if (r.form == MomentumForm::Conservative && r.kind == PreStrainKind::Isotropic && std::isfinite(r.r.load)) {
      const auto* p = find(sweep, r.lattice, r.kernel, r.h, MomentumForm::Plus, r.kind, r.sign);
      const auto* u = find(sweep, r.lattice, r.kernel, r.h, MomentumForm::Uncorrected, r.kind, r.sign);
      if (p) max_ratio_dev_plus = std::max(max_ratio_dev_plus, std::abs(p->r.load / r.r.load / 2 - 1));
      if (u) max_ratio_dev_unc = std::max(max_ratio_dev_unc, std::abs(u->r.load / r.r.load / 4 - 1));
    }
  }
  sum.set("route_max_rel_diff", sig(max_rd, 2));
  sum.set("route_worst", worst_rd);
  sum.set("route_over_1e-8", n_over);
  sum.set("route_rows", n_rows_both);
  sum.set("rows_not_successful", n_bad_status);
  sum.set("ratio_dev_plus", sig(max_ratio_dev_plus, 2));
  sum.set("ratio_dev_uncorrected", sig(max_ratio_dev_unc, 2));

  // Conservative form, isotropic: e_crit at a few h per lattice and kernel.
  std::vector<std::string> lines;
  for (LatticeType lt : kLattices)
    for (KernelType kt : kKernels)
      for (double h : {1.0, 1.3, 1.6, 2.0, 2.5}) {
        const auto* t =
            find(sweep, lt, kt, h, MomentumForm::Conservative, PreStrainKind::Isotropic, LoadDirection::Tension);
        const auto* c =
            find(sweep, lt, kt, h, MomentumForm::Conservative, PreStrainKind::Isotropic, LoadDirection::Compression);
        if (!t || !c) continue;
        auto k = [](const SweepRow* r) {
          return std::isfinite(r->r.load) ? "(" + sig(r->r.mode_wavevector.kx_over_pi, 2) + ", " +
                                                sig(r->r.mode_wavevector.ky_over_pi, 2) + ")"
                                          : std::string("-");
        };
        lines.push_back(cells({lattice_name(lt), kernel_name(kt), sig(h), sig(t->r.load), k(t), sig(t->inf.e),
                               sig(c->r.load), k(c), sig(c->inf.e)}));
      }
  sum.set("table_conservative", table(lines));

  // Infinite-lattice classification (conservative form, square and hex).
  int inf_zero_t = 0, inf_zero_c = 0, inf_tiny_t = 0, inf_pos_t = 0, inf_stable_c = 0, inf_fin_c = 0, inf_tiny_c = 0,
      nt = 0, nc = 0;
  for (const auto& r : infrows) {
    if (r.lt == LatticeType::FaceCentred || r.form != MomentumForm::Conservative) continue;
    if (r.sign == LoadDirection::Tension) {
      ++nt;
      if (r.s.e == 0)
        ++inf_zero_t;
      else if (std::abs(r.s.e) < 1e-6)
        ++inf_tiny_t;
      else if (std::isfinite(r.s.e))
        ++inf_pos_t;
    } else {
      ++nc;
      if (r.s.e == 0)
        ++inf_zero_c;
      else if (std::isinf(r.s.e))
        ++inf_stable_c;
      else if (std::abs(r.s.e) < 1e-6)
        ++inf_tiny_c;
      else
        ++inf_fin_c;
    }
  }
  sum.set("infinite_tension_cases", nt);
  sum.set("infinite_tension_zero", inf_zero_t);
  sum.set("infinite_tension_tiny", inf_tiny_t);
  sum.set("infinite_tension_positive", inf_pos_t);
  sum.set("infinite_compression_cases", nc);
  sum.set("infinite_compression_zero", inf_zero_c);
  sum.set("infinite_compression_tiny", inf_tiny_c);
  sum.set("infinite_compression_finite", inf_fin_c);
  sum.set("infinite_compression_stable", inf_stable_c);

  // e_crit versus n: the observed exponent p of |e_crit| ~ n^-p over n >= 40.
  lines.clear();
  std::map<std::tuple<int, int, double, int>, std::vector<const NRow*>> groups;
  for (const auto& r : nrows)
    groups[{static_cast<int>(r.lt), static_cast<int>(r.kt), r.h, static_cast<int>(r.sign)}].push_back(&r);
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
    lines.push_back(cells(row));
  }
  sum.set("table_versus_n", table(lines));

  // Non-symmetric forms: flutter (complex pair) versus real crossing.
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
  lines.clear();
  for (const auto& r : nonsym)
    if (std::abs(r.h - 1.3) < 1e-9 && (r.kernel == KernelType::CubicSpline || r.kernel == KernelType::WendlandC2)) {
      const auto* sp = find(sweep, r.lattice, r.kernel, r.h, MomentumForm::Plus, PreStrainKind::UniaxialX, r.sign);
      lines.push_back(
          cells({lattice_name(r.lattice), kernel_name(r.kernel), load_direction_name(r.sign), std::to_string(r.n),
                 sig(r.r.load), mechanism_name(r.r.mechanism), sig(r.r.load_eigen), sp ? sig(sp->r.load) : "-"}));
    }
  sum.set("table_nonsymmetric", table(lines));

  // Gray, Monaghan & Swift (2001) §5.
  auto gms_at = [&](LatticeType lt, double h) -> const GmsRow* {
    for (const auto& g : gms)
      if (g.lt == lt && std::abs(g.h - h) < 1e-9) return &g;
    return nullptr;
  };
  lines.clear();
  for (LatticeType lt : {LatticeType::Square, LatticeType::FaceCentred})
    for (double h : {1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7})
      if (const GmsRow* g = gms_at(lt, h))
        lines.push_back(cells({lattice_name(lt), sig(h), sig(g->bx, 4), sig(g->by, 3), sig(g->ax, 3),
                               sig(g->ek_t) + " / " + sig(g->ek_c),
                               sig(g->einf_t) + " " + g->kinf_t + " / " + sig(g->einf_c) + " " + g->kinf_c,
                               sig(g->en_t) + " / " + sig(g->en_c)}));
  sum.set("table_gms", table(lines));
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
  const GmsRow* sq1 = gms_at(LatticeType::Square, 1.0);
  const GmsRow* fc1 = gms_at(LatticeType::FaceCentred, 1.0);
  sum.set("gms_square_bx", sig(sq1 ? sq1->bx : std::nan(""), 5));
  sum.set("gms_square_by", sig(sq1 ? sq1->by : std::nan(""), 3));
  sum.set("gms_square_by_positive_h", h_range(LatticeType::Square, [](const GmsRow& g) { return g.by > 0; }));
  sum.set("gms_fc_compression_stable_h",
          h_range(LatticeType::FaceCentred, [](const GmsRow& g) { return std::isinf(g.ek_c); }));
  sum.set("gms_fc_bx", sig(fc1 ? fc1->bx : std::nan(""), 4));
  sum.set("gms_fc_by", sig(fc1 ? fc1->by : std::nan(""), 3));
  sum.set("gms_fc_ax", sig(fc1 ? fc1->ax : std::nan(""), 3));
  sum.write(out_dir);
  std::cout << "critical-strain-2d: wrote " << out_dir << " in " << sig(seconds_since(t_start), 3) << " s\n";
  return 0;
}
