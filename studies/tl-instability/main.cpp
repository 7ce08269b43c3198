// Why the NCSPH strain with the plain plus divergence (FiniteStrainTotalLagrangian, the "ncsph" run of tl-csm3) is
// unstable at rest while the variational NCSPH form is not: the linearisation A = -da/du at u = 0 (coloured complex
// step) of three TL forms (St Venant-Kirchhoff, plane strain, the CSM3 material; Wendland C2, h = 1.5 dx) on four
// particle sets:
//   beam      the CSM3 beam at --across particles through the thickness, clamped (problems/turek_hron_csm3.hpp);
//   free-beam the same particles, every one free (no clamp);
//   block     a free square block of --block x --block particles (no fixed layers);
//   periodic  a periodic square lattice of --block x --block particles (the NCSPH correction matrix is the same at
//             every particle there).
// Forms: ncsph (K = NCSPH reference gradient, divergence of the plain G, plus), ncsph-variational (the divergence is
// K's transpose: M a = -dU/du), plain (K = G, plus: the plain variational pair).
// Per case: the asymmetry ||A - A^T||_F / ||A||_F (equal masses: the asymmetry of M A), the growth rate
// gamma = max Re sqrt(-mu) (growth/growth_rate.hpp, dense dgeev), the fastest mode's eigenvalue (real negative or a
// complex pair), the number of unstable modes above the tolerance 1e-6 sqrt(||A||_F), where the fastest mode lives
// (share of |mode|^2 on the boundary-deficient particles, those within the support 2h of a free surface or of the
// clamp's end, and on the rest), and the spread of the NCSPH correction matrix L_i over the particles.
// Writes to --out DIR: cases.csv, modes.csv (fastest mode of each unstable case: x, y, mode_x, mode_y),
// spectrum.csv (all mu of the ncsph and ncsph-variational beam cases), summary.json.
#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/forms/variational_total_lagrangian.hpp"
#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

using namespace sphstab;
namespace fs = std::filesystem;
using C = TurekHronCsm3;

namespace {

std::shared_ptr<const ForceFunction> make_form(const std::string& form, std::shared_ptr<const Discretisation<2>> disc,
                                               std::shared_ptr<const HyperelasticModel<2>> material) {
  if (form == "ncsph-variational")
    return std::make_shared<VariationalTotalLagrangian<2>>(disc, material, C::density,
                                                           make_gradient_provider<2>(Correction::Ncsph));
  FiniteStrainOptions<2> opt;  // plus divergence of the plain G, difference strain
  if (form == "ncsph") opt.gradient = make_gradient_provider<2>(Correction::Ncsph);
  return std::make_shared<FiniteStrainTotalLagrangian<2>>(disc, material, C::density, opt);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"TL instabilities: the non-variational NCSPH form at rest, beam / free block / periodic lattice"};
  std::string out = "results/tl-instability";
  int across = 4, block = 12;
  double h_over_dx = 1.5;
  app.add_option("--out", out, "output directory");
  app.add_option("--across", across, "CSM3 beam: particles through the thickness")->check(CLI::Range(2, 8));
  app.add_option("--block", block, "free block / periodic lattice: particles per side")->check(CLI::Range(6, 30));
  app.add_option("--h", h_over_dx, "h / dx (Wendland C2, support 2h)")->check(CLI::Range(1.0, 3.0));
  bool quick = false;
  app.add_flag("--quick", quick, "pipeline check: beam of 2 particles across, block and periodic lattice of 8 x 8");
  CLI11_PARSE(app, argc, argv);
  if (quick) across = 2, block = 8;
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  const ElasticMaterial lame =
      ElasticMaterial::from_lame(2 * C::shear_modulus * C::poisson / (1 - 2 * C::poisson), C::shear_modulus, 1.0);
  auto svk = std::make_shared<StVenantKirchhoff<2>>(lame);
  const double cp = std::sqrt((lame.lambda() + 2 * lame.mu()) / C::density);  // P-wave speed: the rate unit c / dx
  const Kernel<2> kernel(KernelType::WendlandC2);

  const TurekHronBeam beam = turek_hron_beam({.across = across, .clamp_layers = 4});
  const double dx = beam.dx, h = h_over_dx * dx, support = kernel.support_radius(h);
  struct Set {
    std::string name;
    ParticleSet<2> particles;
  };
  std::vector<Set> sets;
  sets.push_back({"beam", beam.particles});
  {
    ParticleSet<2> free_beam = beam.particles;
    for (auto& r : free_beam.role) r = Role::Free;
    sets.push_back({"free-beam", free_beam});
  }
  sets.push_back({"block", make_lattice<2>(LatticeType::Square, block, {.spacing = dx, .fixed_layers = 0})});
  sets.push_back({"periodic", make_lattice<2>(LatticeType::Square, block, {.spacing = dx, .periodic = true})});

  CsvWriter ccsv(out + "/cases.csv", {"set",
                                      "form",
                                      "particles",
                                      "dofs",
                                      "asymmetry",
                                      "gamma",
                                      "gamma_dx_over_c",
                                      "mu_re",
                                      "mu_im",
                                      "unstable_modes",
                                      "gamma_real",
                                      "gamma_complex",
                                      "tolerance",
                                      "share_surface",
                                      "share_corner",
                                      "share_clamp",
                                      "particles_surface",
                                      "particles_corner",
                                      "particles_clamp",
                                      "correction_spread"});
  CsvWriter mcsv(out + "/modes.csv", {"set", "form", "x", "y", "role", "depth", "corner", "mode_x", "mode_y"});
  CsvWriter scsv(out + "/spectrum.csv", {"set", "form", "mu_re", "mu_im"});
  study::Summary summary;
  std::string md;
  for (const Set& set : sets) {
    const auto disc = make_discretisation(set.particles, kernel, h);
    const int n = disc->size();
    // where a mode lives: the depth of a free particle below the outer layer of the free particles' bounding box, in
    // layers (0 = the outermost row or column; the side of a clamp does not count as a surface), per axis; corner =
    // within the support of two surfaces; clamp = within the support of a fixed particle
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = Eigen::Vector2d::Constant(-1e300);
    for (int f : disc->free) {
      lo = lo.cwiseMin(disc->particles.x.row(f).transpose());
      hi = hi.cwiseMax(disc->particles.x.row(f).transpose());
    }
    const bool periodic = disc->particles.periodic[0];
    std::vector<int> depth(n, 1 << 20);
    std::vector<char> corner(n, 0), near_clamp(n, 0);
    for (int i = 0; i < n; ++i) {
      if (disc->free_slot[i] < 0 || periodic) continue;
      bool clamp_side = false;
      for (long k = disc->neighbours.offsets[i]; k < disc->neighbours.offsets[i + 1]; ++k)
        if (disc->free_slot[disc->neighbours.indices[k]] < 0) near_clamp[i] = 1, clamp_side = true;
      int surfaces = 0;
      for (int a = 0; a < 2; ++a) {
        const double x = disc->particles.x(i, a);
        // the low-x side of a clamped beam is the clamp, not a surface
        const double dlo = (a == 0 && set.name == "beam") ? 1e300 : (x - lo[a]) / dx,
                     d = std::min(dlo, (hi[a] - x) / dx);
        depth[i] = std::min(depth[i], static_cast<int>(std::lround(d)));
        if (d < support / dx) ++surfaces;
      }
      corner[i] = surfaces >= 2 || (clamp_side && surfaces >= 1);
    }
    // spread of the first-order moment matrix S_i^{ab} = sum_j (x_j^a - x_i^a) G^b_ij of the plain gradient (the
    // matrix NCSPH inverts, Powell (1.19), up to its Shepard step) over the free particles:
    // max_i ||S_i - S_mean||_F / ||S_mean||_F; 0 where the correction is one constant matrix
    double spread = 0;
    {
      const std::array<SparseMatrix<>, 2> G{gradient_matrix(disc->particles, disc->neighbours, kernel, h, 0),
                                            gradient_matrix(disc->particles, disc->neighbours, kernel, h, 1)};
      std::vector<Eigen::Matrix2d> S(disc->free.size(), Eigen::Matrix2d::Zero());
      Eigen::Matrix2d mean = Eigen::Matrix2d::Zero();
      for (std::size_t f = 0; f < disc->free.size(); ++f) {
        const int i = disc->free[f];
        for (int b = 0; b < 2; ++b)
          for (SparseMatrix<>::InnerIterator it(G[b], i); it; ++it) {
            const auto d = disc->particles.separation(static_cast<int>(it.col()), i);  // x_j - x_i, min. image
            for (int a = 0; a < 2; ++a) S[f](a, b) += d[a] * it.value();
          }
        mean += S[f];
      }
      mean /= static_cast<double>(S.size());
      for (const auto& Si : S) spread = std::max(spread, (Si - mean).norm() / mean.norm());
    }
    for (const std::string form : {"ncsph", "ncsph-variational", "plain"}) {
      const auto tl = make_form(form, disc, svk);
      const Eigen::MatrixXd A(jacobian(*tl, Eigen::VectorXd::Zero(tl->dofs())));
      const double asym = (A - A.transpose()).norm() / A.norm();
      Eigen::VectorXd x_dof(tl->dofs());  // positions for growth_rate's wavenumber estimate (x component)
      for (int f = 0; f < disc->free_count(); ++f)
        x_dof[2 * f] = x_dof[2 * f + 1] = disc->particles.x(disc->free[f], 0);
      const GrowthAnalysis g = growth_rate(A, x_dof);
      const bool unstable = !g.unstable.empty();
      const std::complex<double> mu = unstable ? g.unstable.front().mu : std::complex<double>(NAN, NAN);
      double share_surface = NAN, share_corner = NAN, share_clamp = NAN;
      if (unstable) {
        const Eigen::VectorXd& m = g.unstable.front().shape;
        share_surface = share_corner = share_clamp = 0;
        for (int f = 0; f < disc->free_count(); ++f) {
          const int i = disc->free[f];
          const double e = m[2 * f] * m[2 * f] + m[2 * f + 1] * m[2 * f + 1];
          share_surface += depth[i] == 0 ? e : 0;
          share_corner += corner[i] ? e : 0;
          share_clamp += near_clamp[i] ? e : 0;
          mcsv.row({set.name, form, disc->particles.x(i, 0), disc->particles.x(i, 1), "free", depth[i],
                    static_cast<int>(corner[i]), m[2 * f], m[2 * f + 1]});
        }
        for (int i = 0; i < n; ++i)
          if (disc->free_slot[i] < 0)
            mcsv.row({set.name, form, disc->particles.x(i, 0), disc->particles.x(i, 1), "fixed", -1, 0, 0.0, 0.0});
      }
      // reference shares: the fraction of free particles in each region (a mode spread evenly would have these)
      int in_surface = 0, in_corner = 0, in_clamp = 0;
      for (int i : disc->free) in_surface += depth[i] == 0, in_corner += corner[i], in_clamp += near_clamp[i];
      const double nf = disc->free_count();
      if (set.name == "beam" && form != "plain")
        for (const auto& e : g.eigenvalues) scsv.row({set.name, form, e.real(), e.imag()});
      // the two kinds of growing eigenvalue: real negative mu (divergence, e^{sqrt(-mu) t}) and complex pairs (flutter)
      double gamma_real = 0, gamma_complex = 0;
      for (const auto& e : g.eigenvalues) {
        const double r = mode_growth(e);
        if (r <= g.tolerance) continue;
        (std::abs(e.imag()) <= 1e-9 * std::abs(e) ? gamma_real : gamma_complex) =
            std::max(std::abs(e.imag()) <= 1e-9 * std::abs(e) ? gamma_real : gamma_complex, r);
      }
      const double growth = unstable ? g.growth_rate : 0.0;  // below the tolerance: round-off, not a mode
      ccsv.row({set.name,
                form,
                n,
                tl->dofs(),
                asym,
                g.growth_rate,
                g.growth_rate * dx / cp,
                mu.real(),
                mu.imag(),
                static_cast<int>(g.unstable.size()),
                gamma_real,
                gamma_complex,
                g.tolerance,
                share_surface,
                share_corner,
                share_clamp,
                in_surface / nf,
                in_corner / nf,
                in_clamp / nf,
                spread});
      std::string kind = "-";
      if (unstable) kind = std::abs(mu.imag()) <= 1e-9 * std::abs(mu) ? "real, negative" : "complex pair";
      study::md_row(
          md,
          {set.name, form, std::to_string(n), std::to_string(tl->dofs()), study::sig(asym, 3), study::sig(spread, 3),
           study::sig(growth, 4), study::sig(growth * dx / cp, 3), kind,
           unstable
               ? study::sig(mu.real(), 4) + (mu.imag() < 0 ? " − " : " + ") + study::sig(std::abs(mu.imag()), 4) + "i"
               : "-",
           std::to_string(g.unstable.size()), study::sig(gamma_real, 4), study::sig(gamma_complex, 4),
           unstable ? study::fixed(100 * share_surface, 0) + " (" + study::fixed(100 * in_surface / nf, 0) + ")" : "-",
           unstable ? study::fixed(100 * share_corner, 0) + " (" + study::fixed(100 * in_corner / nf, 0) + ")" : "-",
           unstable ? study::fixed(100 * share_clamp, 0) + " (" + study::fixed(100 * in_clamp / nf, 0) + ")" : "-"});
      std::cout << set.name << " " << form << ": asymmetry " << asym << ", gamma " << g.growth_rate << " 1/s, "
                << g.unstable.size() << " unstable modes\n";
    }
  }
  summary.set("cases", md);
  summary.set("across", across);
  summary.set("block", block);
  summary.set("h_over_dx", h_over_dx, 3);
  summary.set("dx_mm", dx * 1e3, 4);
  summary.set("support_dx", support / dx, 3);
  summary.set("c_p", cp, 4);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
