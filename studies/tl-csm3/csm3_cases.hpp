#pragma once
// The runs of the Turek & Hron (2006) CSM3 study and the computation of one: the chosen form at every resolution
// --across, the two other forms and the --clamp-sensitivity clamp at the coarsest one; per run the beam
// (problems/turek_hron_csm3.hpp), the form (common/csm3.hpp: make_form), the eigenvalues of the linearisation at rest
// (growth rate, lowest eigenfrequency; coarse runs only) and the leap-frog run under gravity with the mean, amplitude
// and frequency of u(A) (common/csm3.hpp: gravity_run), the snapshot of the finest run (deflection_snapshot.hpp).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "common/csm3.hpp"
#include "common/study.hpp"
#include "deflection_snapshot.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

namespace csm3_study {

using namespace sphstab;
using C = TurekHronCsm3;
using study::csm3::Measure;

struct RunSpec {
  int across;
  std::string gradient;  ///< "ncsph" or "plain"
  int clamp_layers;
  std::string name() const {
    return "n" + std::to_string(across) + "-" + gradient + "-clamp" + std::to_string(clamp_layers);
  }
};

struct CaseResult {
  RunSpec spec;
  int particles = 0, free = 0, clamp = 0;
  double dx = 0, dt = 0, dt_limit = 0, wall = 0, energy_drift = 0;
  double f_linear = NAN;  ///< lowest eigenfrequency of the linearisation at rest (Hz); NaN when not computed
  double growth = NAN;    ///< max Re sqrt(-mu), mu in eig(A), A = -da/du at rest (1/s); NaN when not computed
  long steps = 0;
  std::string status = "completed";
  Measure ux, uy;
};

/// The two forms other than `gradient`, in the order plain, ncsph, ncsph-variational.
inline std::vector<std::string> other_gradients(const std::string& gradient) {
  std::vector<std::string> others;
  for (const std::string g : {"plain", "ncsph", "ncsph-variational"})
    if (g != gradient) others.push_back(g);
  return others;
}

/// The runs: `gradient` at every resolution of `across`, the other forms and the wide_clamp clamp at the coarsest.
inline std::vector<RunSpec> case_specs(const std::vector<int>& across, const std::string& gradient, int clamp_layers,
                                       int wide_clamp) {
  std::vector<RunSpec> specs;
  for (int n : across) specs.push_back({n, gradient, clamp_layers});
  for (const std::string& g : other_gradients(gradient)) specs.push_back({across.front(), g, clamp_layers});
  specs.push_back({across.front(), gradient, wide_clamp});
  return specs;
}

/// What every run shares: the output directory, the stress divergence, h / dx (Wendland C2) and the time settings.
struct CaseSettings {
  std::string out, divergence;
  double h_over_dx = 1.5, t_end = 6, t_measure = 2, cfl = 0.8;
};

/// One run (tip history into tip_<run>.csv); snapshot: the state at the largest deflection of the last reference
/// period goes there (the finest run of the chosen form), nullptr for the other runs.
inline CaseResult run_case(const RunSpec& spec, const CaseSettings& s, const Kernel<2>& kernel,
                           const std::shared_ptr<const HyperelasticModel<2>>& svk, DeflectionSnapshot* snapshot) {
  const auto tr = study::Clock::now();
  const TurekHronBeam beam = turek_hron_beam({.across = spec.across, .clamp_layers = spec.clamp_layers});
  const double h = s.h_over_dx * beam.dx;
  const auto disc = make_discretisation(beam.particles, kernel, h);
  // the form: FiniteStrainTotalLagrangian (plain or NCSPH strain, divergence of the plain G) or the variational
  // form with the NCSPH strain and its transpose as divergence ("ncsph-variational"): common/csm3.hpp
  const study::csm3::Form form = study::csm3::make_form(spec.gradient, s.divergence, disc, svk);
  const std::shared_ptr<const ForceFunction> tl = form.force;
  CaseResult r;
  r.spec = spec;
  r.particles = beam.particles.size();
  r.free = beam.free_count;
  r.clamp = beam.clamp_count;
  r.dx = beam.dx;
  if (tl->dofs() <= 1200) {  // dense nonsymmetric eigenvalues of the linearisation at rest (coarse runs only)
    const Eigen::EigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(jacobian(*tl, Eigen::VectorXd::Zero(tl->dofs()))),
                                                 false);
    r.growth = 0;
    for (const auto& mu : es.eigenvalues()) r.growth = std::max(r.growth, std::sqrt(-mu).real());
  }
  if (tl->dofs() <= 2500 && tl->conservative()) {  // M A symmetric, equal masses: A symmetric; lowest mode
    const Eigen::MatrixXd A = Eigen::MatrixXd(jacobian(*tl, Eigen::VectorXd::Zero(tl->dofs())));
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()), Eigen::EigenvaluesOnly);
    r.f_linear = std::sqrt(es.eigenvalues()[0]) / (2 * std::numbers::pi);
  }
  // snapshot (finest run): x + u and the Cauchy stress at the largest deflection of the last reference period
  auto on_sample = [&](double t, const Eigen::VectorXd& u, double uy) {
    if (!(snapshot && t >= s.t_end - 1 / C::frequency && uy < snapshot->uy)) return;
    snapshot->record(t, u, uy, form, *disc);
  };
  const study::csm3::Run run = study::csm3::gravity_run(tl, beam,
                                                        {.name = spec.name(),
                                                         .csv_path = s.out + "/tip_" + spec.name() + ".csv",
                                                         .t_end = s.t_end,
                                                         .t_measure = s.t_measure,
                                                         .cfl = s.cfl},
                                                        on_sample);
  r.dt = run.dt;
  r.dt_limit = run.dt_limit;
  r.steps = run.steps;
  r.energy_drift = run.energy_drift;
  r.status = run.status;
  r.ux = run.ux;
  r.uy = run.uy;
  r.wall = study::seconds_since(tr);
  std::cout << spec.name() << ": " << r.particles << " particles (" << r.free << " free), dt = " << r.dt << " s ("
            << r.dt / r.dt_limit << " of the limit), growth at rest " << r.growth << " 1/s, f_linear " << r.f_linear
            << " Hz, " << r.steps << " steps, " << r.wall << " s wall, " << r.status << "; ux " << r.ux.mean << " +- "
            << r.ux.amplitude << " [" << r.ux.frequency << "], uy " << r.uy.mean << " +- " << r.uy.amplitude << " ["
            << r.uy.frequency << "]\n";
  return r;
}

}  // namespace csm3_study
