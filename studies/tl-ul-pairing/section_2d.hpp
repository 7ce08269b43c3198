#pragma once
// The 2D section of the TL-vs-UL pairing study (Ismail 2009 §4.7 in 2D): a block of nx x ny free particles inside
// fixed layers on every side (Ismail's bar "constrained in the transverse direction"; see README), pre-stretched
// uniaxially (F = diag(1 + e, 1)) or isotropically (F = (1 + e) I), one particle at the centre perturbed by 5 % of its
// displacement.
// TL: FiniteStrainTotalLagrangian<2> (Hooke, plane strain; plain reference gradient, difference strain, plus
//     divergence: the variational pair), the fixed layers following the affine pre-stretch.
// UL: ElasticForm2D (kernel at the CURRENT positions, the same Hooke law, Powell's additive pre-stress sigma0(e) on the
//     stretched lattice) in the plus and the conservative momentum forms.
// 1. critical pre-strain: UL by the engine (stability/critical_load.hpp) on the analytic Jacobian, cross-checked by a
//    Cholesky sweep of A0 + e A1 from the complex-step Jacobian of the force itself; TL by the same engine on
//    A0 + e A1 from the complex-step Jacobian at the pre-stretched states (Hooke: A1 = 0), and a Cholesky sweep of the
//    Neo-Hookean TL stiffness along each stretch path.
// 2. runs from the perturbed pre-stretched state: bond ratios |x_i - x_j| / |x_i - x_j|_eq over the nearest-neighbour
//    bonds, pairing time, particle snapshots.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/growth/growth_fit.hpp"
#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/cholmod_definiteness.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/particles/block_lattice.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace pairing2d {

using namespace sphstab;

struct Options {
  std::string kernel = "cubic";
  double h = 1.3;  ///< h / dx
  int nx = 41, ny = 5;
  double strain = 0.05;  ///< run pre-strain e (E = 1)
  double t_end = 100;
  double dt = 0.05;
  double perturbation = 0.05;
  double nu = 0.3;
};

/// The stretch per unit pre-strain: (1, 0) uniaxial (x stretched, y held), (1, 1) isotropic.
inline Eigen::Vector2d direction(PreStrainKind kind) {
  return kind == PreStrainKind::Isotropic ? Eigen::Vector2d(1, 1) : Eigen::Vector2d(1, 0);
}

/// The block: nx x ny free particles, fixed layers two supports deep (the TL strain of a fixed particle that is a
/// neighbour of a free one needs a complete neighbourhood of its own, as in 1D), neighbour list with a margin of dx
/// for the UL motion.
inline std::shared_ptr<const Discretisation<2>> make_block(int nx, int ny, const Kernel<2>& kernel, double h) {
  const double s = kernel.support_radius(h);
  return make_discretisation(make_block_lattice_2d(nx, ny, {.spacing = 1.0, .support_radius = 2 * s}), kernel, h,
                             s + 1.0);
}

/// The affine pre-stretch u = e d (.) X (d = direction(kind)), held at the block's lower-left corner X = 0 (between
/// the free and the fixed particles), of the free particles (interleaved) or of the fixed ones (as
/// set_fixed_displacement wants).
inline Eigen::VectorXd affine_u(const Discretisation<2>& disc, PreStrainKind kind, double e, bool fixed) {
  const Eigen::Vector2d d = e * direction(kind);
  Eigen::VectorXd u(2 * (fixed ? disc.size() - disc.free_count() : disc.free_count()));
  for (int i = 0, k = 0; i < disc.size(); ++i)
    if ((disc.free_slot[i] < 0) == fixed) {
      u[2 * k] = d[0] * disc.particles.x(i, 0);
      u[2 * k + 1] = d[1] * disc.particles.x(i, 1);
      ++k;
    }
  return u;
}

/// Positive definiteness of the symmetric part by CHOLMOD (the complex-step Jacobian is symmetric to round-off).
inline bool positive_definite_2d(const SparseMatrix<>& a) {
  return is_positive_definite(ColSparseMatrix(SparseMatrix<>(0.5 * (a + SparseMatrix<>(a.transpose())))));
}

/// Cholesky sweep over e_k = 10^(-7 + k / per_decade) up to 1: the last positive-definite and the first not
/// positive-definite pre-strain (NaN if none).
struct SweepBracket {
  double lo = std::nan(""), hi = std::nan("");
};
inline SweepBracket cholesky_sweep(const Linearisation& lin, int per_decade) {
  SweepBracket b;
  for (int k = 0; k <= 7 * per_decade; ++k) {
    const double e = std::pow(10.0, -7.0 + static_cast<double>(k) / per_decade);
    if (positive_definite_2d(lin.at(e))) {
      b.lo = e;
    } else {
      b.hi = e;
      break;
    }
  }
  return b;
}

/// Nearest-neighbour bonds (i, j) of the square lattice (|X_i - X_j| = dx) with at least one free end, each once.
inline std::vector<std::pair<int, int>> lattice_bonds(const Discretisation<2>& disc) {
  std::vector<std::pair<int, int>> bonds;
  const NeighbourList& nl = disc.neighbours;
  for (int i : disc.free)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (j == i || (disc.free_slot[j] >= 0 && j < i)) continue;
      const double r = (disc.particles.x.row(i) - disc.particles.x.row(j)).norm();
      if (std::abs(r - disc.particles.spacing) < 1e-9) bonds.emplace_back(i, j);
    }
  return bonds;
}

/// Current positions of every particle: X + u (free), X + u_fixed (fixed).
inline Eigen::MatrixX2d current_positions(const Discretisation<2>& disc, const Eigen::VectorXd& u,
                                          const Eigen::VectorXd& u_fixed) {
  Eigen::MatrixX2d x = disc.particles.x;
  for (int i = 0, k = 0; i < disc.size(); ++i) {
    const int f = disc.free_slot[i];
    const double ux = f >= 0 ? u[2 * f] : u_fixed[2 * k], uy = f >= 0 ? u[2 * f + 1] : u_fixed[2 * k + 1];
    if (f < 0) ++k;
    x(i, 0) += ux;
    x(i, 1) += uy;
  }
  return x;
}

struct CriticalRow {
  std::string kernel, form, kind;
  double h = 0;
  CriticalLoad r;
  SweepBracket sweep;
  std::string sweep_jacobian = "-";  ///< the linearisation the sweep factorised
};

/// Critical pre-strains of the UL forms (engine + Cholesky sweep) and of the TL Hooke form (engine on the
/// complex-step A0 + e A1) on one block; appends to rows. complex_step: the sweep factorises A0 + e A1 from the
/// complex-step Jacobian of the force (independent of the engine's analytic Jacobian; tens of seconds for the
/// mollifier's 5.5 dx support), else the engine's own linearisation (a check of its search only, as in 1D).
inline void critical_2d(const Options& o, const Kernel<2>& kernel, double h, bool complex_step,
                        std::vector<CriticalRow>& rows, std::vector<double>* tl_a1_relative = nullptr) {
  const auto disc = make_block(o.nx, o.ny, kernel, h);
  const ElasticMaterial lame = ElasticMaterial::from_young_poisson(1.0, o.nu, 1.0);
  const ElasticMaterial& material = lame;  // the small-strain forms and the finite-strain models: one material
  CriticalLoadOptions copt = CriticalLoadOptions::strain_2d();
  copt.want_mode = true;
  for (PreStrainKind kind : {PreStrainKind::UniaxialX, PreStrainKind::Isotropic}) {
    for (MomentumForm form : {MomentumForm::Conservative, MomentumForm::Plus}) {
      CriticalRow row{kernel_name(kernel.type()), momentum_form_name(form), prestrain_kind_name(kind), h, {}, {}};
      const Linearisation lin = analytic_jacobian_2d(*disc, material, form, kind);
      row.r = critical_load(lin, LoadDirection::Tension, copt);
      // the sweep needs a symmetric A(e): the conservative form, the plus form under isotropic pre-strain
      if (form == MomentumForm::Conservative || kind == PreStrainKind::Isotropic) {
        row.sweep_jacobian = complex_step ? "complex-step" : "analytic";
        row.sweep =
            cholesky_sweep(complex_step ? affine_jacobian(ElasticForm2D(disc, material, form, PreStrain{kind, 0}),
                                                          Eigen::VectorXd::Zero(2 * disc->free_count()))
                                        : lin,
                           200);
      }
      rows.push_back(row);
    }
    // TL, Hooke plane strain: A(e) from the complex-step Jacobian at the pre-stretched states e = 0 and e1
    auto hooke = std::make_shared<Hooke<2>>(lame);
    FiniteStrainTotalLagrangian<2> tl(disc, hooke, 1.0);
    Linearisation lin;
    tl.set_fixed_displacement(affine_u(*disc, kind, 0, true));
    lin.A0 = jacobian(tl, Eigen::VectorXd::Zero(tl.dofs()));
    const double e1 = 0.5;
    tl.set_fixed_displacement(affine_u(*disc, kind, e1, true));
    lin.A1 = SparseMatrix<>((jacobian(tl, affine_u(*disc, kind, e1, false)) - lin.A0) / e1);
    lin.symmetric = true;
    lin.dofs_per_particle = 2;
    CriticalRow row{kernel_name(kernel.type()), "tl-hooke", prestrain_kind_name(kind), h, {}, {}};
    row.r = critical_load(lin, LoadDirection::Tension, copt);
    if (tl_a1_relative) tl_a1_relative->push_back(lin.A1.norm() / lin.A0.norm());
    rows.push_back(row);
  }
}

/// Bond-ratio state of a run: min and max of |x_i - x_j| / |x_i - x_j|_eq over the lattice bonds.
struct BondState {
  double min = 1e300, max = 0;
  double deviation() const { return std::max(1 - min, max - 1); }
};
inline BondState bond_state(const std::vector<std::pair<int, int>>& bonds, const Eigen::MatrixX2d& x,
                            const Eigen::MatrixX2d& x_eq) {
  BondState s;
  for (const auto& [i, j] : bonds) {
    const double ratio = (x.row(i) - x.row(j)).norm() / (x_eq.row(i) - x_eq.row(j)).norm();
    s.min = std::min(s.min, ratio);
    s.max = std::max(s.max, ratio);
  }
  return s;
}

/// The whole 2D section: writes critical_2d.csv, sweep_2d.csv, pairing_2d.csv, snapshots_2d.csv, vtk_2d/ and the
/// summary keys ending in _2d.
inline void run(const Options& o, const std::string& out, study::Summary& summary) {
  const auto t0 = study::Clock::now();
  if (o.nx % 2 == 0 || o.ny % 2 == 0)
    throw std::invalid_argument("tl-ul-pairing: --nx-2d and --ny-2d must be odd (a centre particle)");
  const Kernel<2> kernel(parse_kernel_type(o.kernel));
  const double h = o.h;
  const auto disc = make_block(o.nx, o.ny, kernel, h);
  const int nfree = disc->free_count();
  const ElasticMaterial lame = ElasticMaterial::from_young_poisson(1.0, o.nu, 1.0);
  const ElasticMaterial& material = lame;  // the small-strain forms and the finite-strain models: one material
  summary.set("kernel_2d", kernel_name(kernel.type()));
  summary.set("h_over_dx_2d", h, 4);
  summary.set("nx_2d", o.nx);
  summary.set("ny_2d", o.ny);
  summary.set("particles_2d", disc->size());
  summary.set("nu_2d", o.nu, 3);

  // 1. critical pre-strains: the run's kernel and h, and the 1D study's kernel and h (modified mollifier, 2.75 dx)
  std::vector<CriticalRow> rows;
  std::vector<double> a1_rel;
  critical_2d(o, kernel, h, true, rows, &a1_rel);
  const Kernel<2> mollifier(KernelType::ModifiedMollifier);
  if (kernel.type() != KernelType::ModifiedMollifier || h != 2.75) critical_2d(o, mollifier, 2.75, false, rows);
  // the 1D UL critical tension of the same kernels (T = E eps, E = 1: a critical strain)
  auto one_d = [&](KernelType type, double hh, MomentumForm form) {
    const Kernel<1> k1(type);
    const auto set =
        make_lattice<1>(LatticeType::Line, o.nx, {.spacing = 1.0, .support_radius = k1.support_radius(hh)});
    return critical_tension_1d(set, k1, hh, form).load;
  };
  CsvWriter ccsv(out + "/critical_2d.csv",
                 {"kernel", "h_over_dx", "form", "prestrain", "criterion", "e_crit", "e_crit_eigen", "e_crit_bisection",
                  "routes_relative_difference", "sweep_jacobian", "sweep_last_pd", "sweep_first_not_pd",
                  "mode_kx_over_pi", "mode_ky_over_pi", "a1_relative", "status", "reason"});
  std::string md;
  auto key = [](const CriticalRow& r) {
    std::string k = (r.form == "tl-hooke" ? std::string("tl") : "ul_" + r.form) + "_" + r.kind;
    for (char& c : k)
      if (c == '-') c = '_';
    return k;
  };
  for (const CriticalRow& r : rows) {
    const bool main_kernel = r.kernel == kernel_name(kernel.type()) && r.h == h;
    ccsv.row({r.kernel, r.h, r.form, r.kind, criterion_name(r.r.criterion), r.r.load, r.r.load_eigen,
              r.r.load_bisection, r.r.relative_difference, r.sweep_jacobian, r.sweep.lo, r.sweep.hi,
              r.r.mode_wavevector.kx_over_pi, r.r.mode_wavevector.ky_over_pi, r.r.a1_relative, status_name(r.r.status),
              r.r.reason});
    const std::string load = std::isinf(r.r.load) ? std::string("∞") : study::sig(r.r.load, 6);
    const bool in_bracket = !std::isnan(r.sweep.hi) && r.sweep.lo < r.r.load && r.r.load <= r.sweep.hi;
    study::md_row(
        md,
        {r.kernel + ", " + study::sig(r.h, 3) + " Δx", r.form == "tl-hooke" ? "TL (Hooke)" : "UL " + r.form, r.kind,
         criterion_name(r.r.criterion), load, study::sig(r.r.relative_difference, 2),
         std::isnan(r.sweep.hi) ? "-"
                                : "(" + study::sig(r.sweep.lo, 4) + ", " + study::sig(r.sweep.hi, 4) + "] (" +
                                      r.sweep_jacobian + "): " + (in_bracket ? "contains it" : "DOES NOT contain it"),
         std::isfinite(r.r.load) ? "(" + study::sig(r.r.mode_wavevector.kx_over_pi, 3) + ", " +
                                       study::sig(r.r.mode_wavevector.ky_over_pi, 3) + ")"
                                 : "-",
         status_name(r.r.status)});
    if (main_kernel) {
      summary.set("e_crit_" + key(r) + "_2d", load);
      if (!std::isnan(r.sweep.hi)) summary.set("sweep_" + key(r) + "_2d", in_bracket ? "yes" : "no");
    } else if (r.form != "tl-hooke" && r.kind == "uniaxial") {
      summary.set("e_crit_" + key(r) + "_mollifier_2d", load);
    }
  }
  summary.set("critical_2d", md);
  for (const CriticalRow& r : rows)
    if (r.kernel == kernel_name(kernel.type()) && r.h == h && r.form == "plus" && r.kind == "uniaxial")
      summary.set("strain_over_e_crit_2d", o.strain / r.r.load, 3);
  summary.set("tl_a1_relative_uniaxial_2d", a1_rel.at(0), 2);
  summary.set("tl_a1_relative_isotropic_2d", a1_rel.at(1), 2);
  summary.set("t_crit_1d_plus_same_kernel_2d", one_d(kernel.type(), h, MomentumForm::Plus), 6);
  summary.set("t_crit_1d_conservative_same_kernel_2d", one_d(kernel.type(), h, MomentumForm::Conservative), 6);
  summary.set("t_crit_1d_conservative_mollifier_2d",
              one_d(KernelType::ModifiedMollifier, 2.75, MomentumForm::Conservative), 6);

  // TL, Neo-Hookean (plane strain, Ismail's Psi): Cholesky sweep of the stiffness along each stretch path, stretch
  // 1.001 .. 3 (uniaxial: x only), with the Cauchy stress sigma_xx / E at each state
  auto nh = std::make_shared<NeoHookean<2>>(lame);
  FiniteStrainTotalLagrangian<2> tl_nh(disc, nh, 1.0);
  CsvWriter scsv(out + "/sweep_2d.csv", {"prestrain", "stretch", "cauchy_xx", "tl_neo_hookean_pd"});
  for (PreStrainKind kind : {PreStrainKind::UniaxialX, PreStrainKind::Isotropic}) {
    bool all_pd = true;
    double max_stress = 0;
    for (int k = 0; k <= 30; ++k) {
      const double stretch = std::pow(3.0, k / 30.0) + (k == 0 ? 1e-3 : 0.0);
      Deformation<double, 2> F = Deformation<double, 2>::Identity();
      F(0, 0) = stretch;
      if (kind == PreStrainKind::Isotropic) F(1, 1) = stretch;
      const double sxx = nh->cauchy_stress(F)(0, 0);
      tl_nh.set_fixed_displacement(affine_u(*disc, kind, stretch - 1, true));
      const bool pd = positive_definite_2d(jacobian(tl_nh, affine_u(*disc, kind, stretch - 1, false)));
      scsv.row({prestrain_kind_name(kind), stretch, sxx, pd ? 1 : 0});
      all_pd = all_pd && pd;
      if (pd) max_stress = std::max(max_stress, sxx);
    }
    summary.set("tl_nh_all_pd_" + prestrain_kind_name(kind) + "_2d", all_pd ? "yes" : "no");
    summary.set("tl_nh_max_stress_" + prestrain_kind_name(kind) + "_2d", max_stress, 4);
  }
  std::cout << "2D critical pre-strains written; TL A1/A0 = " << a1_rel.at(0) << ", " << a1_rel.at(1) << "\n";

  // 2. runs at e = o.strain from the perturbed pre-stretched state
  const double e = o.strain;
  const double c_l = std::sqrt(lame.uniaxial_modulus(UniaxialState::Strain));  // plane-strain P-wave speed (rho = 1)
  int centre = -1;
  for (int f = 0; f < nfree; ++f) {
    const auto p = disc->particles.x.row(disc->free[f]);
    if (std::abs(p[0] - 0.5 * o.nx) < 1e-9 && std::abs(p[1] - 0.5 * o.ny) < 1e-9) centre = f;
  }
  const Eigen::Vector2d x_centre = disc->particles.x.row(disc->free[centre]).transpose();
  const double t_arrival = x_centre[0] / c_l;  // the perturbation's P wave reaches the held ends
  summary.set("strain_2d", e, 4);
  summary.set("t_end_2d", o.t_end, 3);
  summary.set("dt_2d", o.dt, 3);
  summary.set("t_arrival_2d", t_arrival, 3);
  const auto bonds = lattice_bonds(*disc);
  summary.set("bonds_2d", static_cast<long>(bonds.size()));
  CsvWriter pcsv(out + "/pairing_2d.csv",
                 {"prestrain", "run", "t", "min_bond_ratio", "max_bond_ratio", "deviation_over_initial"}, false);
  CsvWriter ncsv(out + "/snapshots_2d.csv",
                 {"prestrain", "run", "snapshot", "t", "particle", "free", "x", "y", "dx_from_eq", "dy_from_eq"},
                 false);
  std::filesystem::create_directories(out + "/vtk_2d");
  // snapshots at t = 0, 5, 10 dx/c (the UL growth under way) and at the end of each run; the free particles and the
  // first fixed layer
  const std::vector<double> snap_times{0, 5, 10};
  std::vector<int> shown;
  for (int i = 0; i < disc->size(); ++i) {
    const auto p = disc->particles.x.row(i);
    if (p[0] > -1 && p[0] < o.nx + 1 && p[1] > -1 && p[1] < o.ny + 1) shown.push_back(i);
  }
  std::string md_runs;
  double gamma_ratio_lo = 1e300, gamma_ratio_hi = 0;
  auto hooke = std::make_shared<Hooke<2>>(lame);
  for (PreStrainKind kind : {PreStrainKind::UniaxialX, PreStrainKind::Isotropic}) {
    const std::string kname = prestrain_kind_name(kind);
    const Eigen::Vector2d delta = o.perturbation * e * direction(kind).cwiseProduct(x_centre);
    if (kind == PreStrainKind::UniaxialX) summary.set("delta_over_dx_2d", delta.norm(), 4);
    for (const std::string run : {"TL", "UL plus", "UL conservative"}) {
      std::shared_ptr<ForceFunction> force;
      Eigen::VectorXd u_eq = Eigen::VectorXd::Zero(2 * nfree),
                      u_fixed = Eigen::VectorXd::Zero(2 * (disc->size() - nfree));
      if (run == "TL") {
        auto f = std::make_shared<FiniteStrainTotalLagrangian<2>>(disc, hooke, 1.0);
        u_fixed = affine_u(*disc, kind, e, true);
        f->set_fixed_displacement(u_fixed);
        u_eq = affine_u(*disc, kind, e, false);
        force = f;
      } else {
        force = std::make_shared<ElasticForm2D>(
            disc, material, run == "UL plus" ? MomentumForm::Plus : MomentumForm::Conservative, PreStrain{kind, e});
      }
      Eigen::VectorXd a_eq;
      force->acceleration(u_eq, a_eq);
      // linear growth rate gamma = max Re sqrt(-mu) of A at the pre-stretched state (dense): TL its Jacobian there,
      // UL the engine's analytic A(e)
      Eigen::VectorXd x_dof(2 * nfree);
      for (int f = 0; f < nfree; ++f) x_dof[2 * f] = x_dof[2 * f + 1] = disc->particles.x(disc->free[f], 0);
      const SparseMatrix<> a_lin =
          run == "TL" ? jacobian(*force, u_eq)
                      : analytic_jacobian_2d(*disc, material,
                                             run == "UL plus" ? MomentumForm::Plus : MomentumForm::Conservative, kind)
                            .at(e);
      const double gamma_lin = growth_rate(Eigen::MatrixXd(a_lin), x_dof).growth_rate;
      std::vector<double> ts, devs;
      const Eigen::MatrixX2d x_eq = current_positions(*disc, u_eq, u_fixed);
      Eigen::VectorXd u0 = u_eq;
      u0.segment<2>(2 * centre) += delta;
      SecondOrderSystem sys;
      sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { force->acceleration(u, a); };
      sys.dofs_per_particle = 2;
      sys.mass.resize(nfree);
      const Eigen::VectorXd dm = force->dof_mass();
      for (int f = 0; f < nfree; ++f) sys.mass[f] = dm[2 * f];
      LeapfrogStepper stepper(sys, u0, Eigen::VectorXd::Zero(2 * nfree));
      const double dev0 = bond_state(bonds, current_positions(*disc, u0, u_fixed), x_eq).deviation();
      double t_pair = std::nan(""), min_all = 1e300, dev_max = 0, dev_arrival = std::nan("");
      std::string status = "completed";
      std::size_t next_snap = 0;
      std::string tag = kname + "_" + run;
      for (char& c : tag)
        if (c == ' ') c = '_';
      auto snapshot = [&](const Eigen::MatrixX2d& x, const std::string& label) {
        for (int i : shown)
          ncsv.row({kname, run, label, stepper.time(), i, disc->free_slot[i] >= 0 ? 1 : 0, x(i, 0), x(i, 1),
                    x(i, 0) - x_eq(i, 0), x(i, 1) - x_eq(i, 1)});
      };
      SnapshotFunction bond_probe([&](const StepView& view) {
        const double t = view.time;
        const Eigen::MatrixX2d x = current_positions(*disc, view.u, u_fixed);
        const BondState s = bond_state(bonds, x, x_eq);
        const double dev = s.deviation() / dev0;
        min_all = std::min(min_all, s.min);
        dev_max = std::max(dev_max, dev);
        if (std::isnan(dev_arrival) && t >= t_arrival) dev_arrival = dev;
        if (std::isnan(t_pair) && s.min < 0.5) t_pair = t;
        if (view.step % 4 == 0) pcsv.row({kname, run, t, s.min, s.max, dev});
        ts.push_back(t);
        devs.push_back(dev);
        const bool stop = s.min < 0.05 || t >= o.t_end - 1e-12;
        if (next_snap < snap_times.size() && t >= snap_times[next_snap] - 1e-9 && !stop)
          snapshot(x, study::sig(snap_times[next_snap++], 3));
        if (stop) snapshot(x, "end");
        if (stop) {
          if (s.min < 0.05) status = "particles within 0.05 spacing (stopped)";
          Eigen::VectorXd d(2 * disc->size());
          for (int i = 0; i < disc->size(); ++i) d.segment<2>(2 * i) = (x.row(i) - x_eq.row(i)).transpose();
          Eigen::VectorXd fr(disc->size());
          for (int i = 0; i < disc->size(); ++i) fr[i] = disc->free_slot[i] >= 0 ? 1 : 0;
          write_vtp(out + "/vtk_2d/" + tag + "_end.vtp", x, {{"displacement_from_equilibrium", 2, d}, {"free", 1, fr}});
          if (s.min < 0.05) bond_probe.stop(status);
        }
      });
      // steps of o.dt while t < t_end - 1e-12; the probe stops the run at a pair closer than 0.05 spacing
      sphstab::RunOptions ro{.dt = o.dt, .t_end = o.t_end - 1e-12, .land_on_t_end = false, .snapshot_every = 1};
      ro.observers = {&bond_probe};
      const RunResult result = sphstab::run(stepper, ro);
      if (result.status == RunStatus::Exception)  // TL: det F <= 0 at an active particle
        status = "stopped: " + result.reason;
      else if (result.status == RunStatus::NonFinite)
        status = "non-finite";
      // measured growth: log-linear fit of the bond deviation while it grows from 2 to 6 times its initial value
      // (bond changes of about 0.1 to 0.3 dx: the growing mode dominates, the motion is still nearly linear)
      double gamma_fit = std::nan(""), t2 = std::nan(""), t6 = std::nan("");
      for (std::size_t k = 0; k < ts.size(); ++k) {
        if (std::isnan(t2) && devs[k] >= 2 && ts[k] > 1) t2 = ts[k];
        if (!std::isnan(t2) && std::isnan(t6) && devs[k] >= 6) t6 = ts[k];
      }
      if (!std::isnan(t6)) gamma_fit = fit_log_linear(ts, devs, t2, t6).slope;
      std::string tkey = kname + "_" + (run == "TL" ? "tl" : run == "UL plus" ? "ul_plus" : "ul_conservative");
      if (run == "TL") {
        summary.set("dev_max_" + tkey + "_2d", dev_max, 3);
        summary.set("min_bond_" + tkey + "_2d", min_all, 4);
        summary.set("t_pair_" + tkey + "_2d", std::isnan(t_pair) ? std::string("never") : study::sig(t_pair, 4));
      } else {
        summary.set("t_pair_" + tkey + "_2d", std::isnan(t_pair) ? std::string("never") : study::sig(t_pair, 4));
        summary.set("gamma_lin_" + tkey + "_2d", gamma_lin, 3);
        summary.set("gamma_fit_" + tkey + "_2d", gamma_fit, 3);
        gamma_ratio_lo = std::min(gamma_ratio_lo, gamma_fit / gamma_lin);
        gamma_ratio_hi = std::max(gamma_ratio_hi, gamma_fit / gamma_lin);
      }
      study::md_row(
          md_runs,
          {kname, run, force->name(), study::sig(a_eq.cwiseAbs().maxCoeff(), 2), study::sig(gamma_lin, 3),
           study::sig(gamma_fit, 3), study::sig(dev_arrival, 3), study::sig(dev_max, 3), study::sig(min_all, 4),
           std::isnan(t_pair) ? "never" : study::sig(t_pair, 4), study::sig(stepper.time(), 4), status});
      std::cout << "2D " << kname << " " << run << ": min bond ratio " << min_all << ", t_pair " << t_pair << ", "
                << status << "\n";
    }
  }
  summary.set("runs_2d", md_runs);
  summary.set("gamma_ratio_lo_2d", gamma_ratio_lo, 2);
  summary.set("gamma_ratio_hi_2d", gamma_ratio_hi, 2);
  summary.set("wall_seconds_2d", study::seconds_since(t0), 3);
}

}  // namespace pairing2d
