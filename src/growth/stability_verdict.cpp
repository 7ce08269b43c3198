#include "sphstab/growth/stability_verdict.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/growth/system_spectrum.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"
#include "sphstab/spectral/dominant_wavenumber.hpp"
#include "sphstab/spectral/dominant_wavevector.hpp"

namespace sphstab {

constexpr NamedValue<VerdictClass> kVerdictLetters[] = {{VerdictClass::Stable, "S"},
                                                        {VerdictClass::SemiDiscrete, "U"},
                                                        {VerdictClass::Integrator, "I"},
                                                        {VerdictClass::Both, "B"}};
constexpr NamedValue<VerdictClass> kVerdictNames[] = {{VerdictClass::Stable, "stable"},
                                                      {VerdictClass::SemiDiscrete, "semi-discrete"},
                                                      {VerdictClass::Integrator, "integrator"},
                                                      {VerdictClass::Both, "both"}};

std::string verdict_letter(VerdictClass c) { return name_of(c, kVerdictLetters); }
std::string verdict_name(VerdictClass c) { return name_of(c, kVerdictNames); }

double detection_floor(double t_end, double energy_ratio) {
  if (!(t_end > 0) || !std::isfinite(t_end))
    throw std::invalid_argument("detection_floor: t_end must be finite and > 0 (got " + format_number(t_end) + ")");
  if (!(energy_ratio > 1) || !std::isfinite(energy_ratio))
    throw std::invalid_argument("detection_floor: energy_ratio must be finite and > 1 (got " +
                                format_number(energy_ratio) + ")");
  return std::log(energy_ratio) / (2 * t_end);  // KE ~ amplitude^2 ~ e^{2 gamma t}
}

namespace {

void check_floor(double floor, const char* who) {
  if (!(floor > 0) || !std::isfinite(floor))
    throw std::invalid_argument(std::string(who) + ": floor must be finite and > 0 (got " + format_number(floor) + ")");
}

}  // namespace

VerdictClass classify_verdict(double semi_discrete_growth, double map_growth, double floor) {
  check_floor(floor, "classify_verdict");
  if (std::isnan(semi_discrete_growth) || std::isnan(map_growth))
    throw std::invalid_argument("classify_verdict: a growth rate is NaN");
  const bool semi = semi_discrete_growth > floor;
  if (!semi) return map_growth > floor ? VerdictClass::Integrator : VerdictClass::Stable;
  const double excess = map_growth - std::max(semi_discrete_growth, 0.0);
  return excess > floor ? VerdictClass::Both : VerdictClass::SemiDiscrete;
}

namespace {

/// The velocity slots of the first layout.size entries of a complex eigenvector, as a real unit shape.
Eigen::VectorXd velocity_shape(const Eigen::VectorXcd& vector, const StateLayout& layout) {
  Eigen::VectorXcd v(static_cast<Eigen::Index>(layout.velocity.size()));
  for (std::size_t k = 0; k < layout.velocity.size(); ++k) v[k] = vector[layout.velocity[k]];
  if (v.size() == 0 || v.norm() == 0) return {};
  return real_mode_shape(v);
}

/// Index of the largest eigenvalue by `key`, with the eigenvalue.
template <class Key>
Eigen::Index argmax(const Eigen::VectorXcd& values, Key key) {
  Eigen::Index best = 0;
  for (Eigen::Index k = 1; k < values.size(); ++k)
    if (key(values[k]) > key(values[best])) best = k;
  return best;
}

/// rho(M), its eigenvalue and (when it grows above the floor) the velocity shape of its eigenvector.
void map_part(StabilityVerdict& v, const Eigen::MatrixXd& M, const StateLayout& layout) {
  v.map_size = static_cast<int>(M.rows());
  if (!M.allFinite()) {
    v.status = Status::NumericalIssue;
    append_reason(v.reason, "the one-step map has non-finite entries");
    return;
  }
  DenseGeneralEigen eig = general_eigen(M, false);
  if (eig.status != Status::Successful) {
    v.status = Status::NumericalIssue;
    append_reason(v.reason, "dgeev failed on the one-step map (info " + std::to_string(eig.lapack_info) + ")");
    return;
  }
  const auto abs = [](std::complex<double> z) { return std::abs(z); };
  Eigen::Index k = argmax(eig.values, abs);
  v.map_eigenvalue = eig.values[k];
  v.map_spectral_radius = std::abs(eig.values[k]);
  v.map_growth = std::log(v.map_spectral_radius) / v.dt;
  if (v.map_growth > v.floor) {  // where the run's growth lives
    eig = general_eigen(M, true);
    if (eig.status == Status::Successful) {
      k = argmax(eig.values, abs);
      v.map_mode.shape = velocity_shape(eig.vectors.col(k), layout);
    }
  }
}

/// The semi-discrete part from a dense J: max Re lambda, its eigenvalue and (above the floor) its velocity shape.
void dense_semi_discrete(StabilityVerdict& v, const Eigen::MatrixXd& J, const StateLayout& layout) {
  DenseGeneralEigen eig = general_eigen(J, false);
  if (eig.status != Status::Successful) {
    v.status = Status::NumericalIssue;
    append_reason(v.reason, "dgeev failed on J (info " + std::to_string(eig.lapack_info) + ")");
    return;
  }
  const auto re = [](std::complex<double> z) { return z.real(); };
  Eigen::Index k = argmax(eig.values, re);
  v.lambda = eig.values[k];
  v.semi_discrete_growth = eig.values[k].real();
  v.lambda_max = eig.values.cwiseAbs().maxCoeff();
  if (v.semi_discrete_growth > v.floor) {
    eig = general_eigen(J, true);
    if (eig.status == Status::Successful) {
      k = argmax(eig.values, re);
      v.semi_discrete_mode.shape = velocity_shape(eig.vectors.col(k), layout);
    }
  }
}

/// Resolution, class, excess and the reason, once both rates are known.
void finish(StabilityVerdict& v) {
  if (v.status == Status::NumericalIssue) return;
  v.resolution = 1e-7 * std::max(v.lambda_max, 1 / v.dt);
  v.integrator_excess = v.map_growth - std::max(v.semi_discrete_growth, 0.0);
  v.verdict = classify_verdict(v.semi_discrete_growth, v.map_growth, v.floor);
  v.status = Status::Successful;
  if (!(v.floor > v.resolution)) {
    v.status = Status::NumericalIssue;
    append_reason(v.reason, "floor " + format_number(v.floor) + " is not above the rates' rounding resolution " +
                                format_number(v.resolution));
  }
  if (v.verdict == VerdictClass::SemiDiscrete && !(v.map_growth > v.floor))
    append_reason(v.reason, "the integrator damps the semi-discrete growth below the floor at this dt");
}

/// Particle and share of the largest |v| of a shape over free particles (DOF f Dim + a), and with `x` (free positions
/// in DOF order) the dominant wavevector.
template <int Dim>
void locate(VerdictMode& m, const Discretisation<Dim>& d, const std::optional<BravaisLattice2D>& lattice) {
  if (m.shape.size() != d.dofs()) return;
  double total = m.shape.squaredNorm(), best = -1;
  for (int f = 0; f < d.free_count(); ++f) {
    const double e = m.shape.template segment<Dim>(f * Dim).squaredNorm();
    if (e > best) best = e, m.particle = d.free[f];
  }
  m.particle_share = total > 0 ? best / total : NAN;
  double along_x = 0;
  for (int f = 0; f < d.free_count(); ++f) along_x += m.shape[f * Dim] * m.shape[f * Dim];
  m.x_share = total > 0 ? along_x / total : NAN;
  const Eigen::MatrixXd x = d.free_positions();
  if constexpr (Dim == 1) {
    m.kx_over_pi = dominant_wavenumber(m.shape, x.col(0), d.particles.periodic[0]).k_projection;
  } else {
    if (lattice) {
      const WavevectorEstimate k = dominant_wavevector(m.shape, Eigen::MatrixX2d(x), *lattice);
      m.kx_over_pi = k.kx_over_pi;
      m.ky_over_pi = k.ky_over_pi;
    }
  }
}

}  // namespace

StabilityVerdict stability_verdict(const Eigen::MatrixXd& J, const StateLayout& layout, const RateFormRunOptions& run,
                                   double floor) {
  check_floor(floor, "stability_verdict");
  const Eigen::MatrixXd M = linear_step_map(J, layout, run);  // validates J, the layout and the options
  StabilityVerdict v;
  v.integrator = rate_form_integrator_name(run);
  v.dt = run.dt;
  v.floor = floor;
  v.map_route = "closed-form";
  dense_semi_discrete(v, J, layout);
  if (v.status != Status::NumericalIssue) map_part(v, M, layout);
  finish(v);
  // Without particles: the largest velocity DOF of each shape.
  for (VerdictMode* m : {&v.semi_discrete_mode, &v.map_mode})
    if (m->shape.size() > 0) {
      Eigen::Index k = 0;
      m->shape.cwiseAbs().maxCoeff(&k);
      m->particle = static_cast<int>(k);
      m->particle_share = m->shape[k] * m->shape[k] / m->shape.squaredNorm();
    }
  return v;
}

template <int Dim>
StabilityVerdict stability_verdict(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y,
                                   const RateFormRunOptions& run, const StabilityVerdictOptions& options) {
  const std::string who = "stability_verdict";
  check_floor(options.floor, who.c_str());
  if (y.size() != scheme.size())
    throw std::invalid_argument(who + ": state has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(scheme.size()));
  if (std::isfinite(run.yield_stress) || run.neighbour_skin > 0)
    throw std::invalid_argument(who + ": needs an elastic run on the scheme's own list (no yield stress, no skin)");
  const StateLayout layout = state_layout(scheme);
  if (!(run.dt > 0) || !std::isfinite(run.dt))
    throw std::invalid_argument(who + ": dt must be finite and > 0 (got " + format_number(run.dt) + ")");
  bool at_rest = true;
  for (int k : layout.velocity) at_rest = at_rest && y[k] == 0;
  // Powell's XSPH acts outside F: its map is reduced at rest (rate_form_spectrum), else only the stepper has it.
  const bool stepper = options.stepper_map || (run.leapfrog_xsph > 0 && !at_rest) || run.absorbing_half_step;
  const bool reduced = at_rest && !stepper && !run.reuse_corrector_rate;
  const std::string needs =
      ": a class basis needs the reduced route (a state at rest, the two-rate "
      "predictor-corrector or the leap-frog, no stepper-only option)";
  if (options.basis.size() && !reduced) throw std::invalid_argument(who + needs);
  RateFormSpectrum s;
  if (reduced)
    s = rate_form_spectrum(scheme, y,
                           {.want_mode = true,
                            .basis = options.basis,
                            .map_dt = run.dt,
                            .map_positions = run.positions,
                            .map_integrator = run.integrator,
                            .map_leapfrog_xsph = run.leapfrog_xsph});
  if (!s.map_reason.empty() && options.basis.size())
    throw std::invalid_argument(who + needs + " (" + s.map_reason + ")");
  if (reduced && s.map_reason.empty()) {
    StabilityVerdict v;
    v.integrator = rate_form_integrator_name(run);
    v.dt = run.dt;
    v.floor = options.floor;
    v.map_route = "reduced";
    if (s.status != Status::Successful) {
      v.status = Status::NumericalIssue;
      append_reason(v.reason, "rate_form_spectrum: " + s.reason);
      return v;
    }
    v.semi_discrete_growth = s.growth_rate;
    v.lambda = s.lambda;
    v.lambda_max = s.eigenvalues.size() ? s.eigenvalues.cwiseAbs().maxCoeff() : 0.0;
    if (s.growth_rate > v.floor) v.semi_discrete_mode.shape = s.mode;
    v.map_spectral_radius = s.map_spectral_radius;
    v.map_eigenvalue = s.map_eigenvalue;
    v.map_growth = s.map_growth;
    v.map_size = s.map_reduced;
    if (v.map_growth > v.floor) v.map_mode.shape = s.map_mode;
    finish(v);
    const Discretisation<Dim>& d = scheme.discretisation();
    locate(v.semi_discrete_mode, d, options.lattice);
    locate(v.map_mode, d, options.lattice);
    return v;
  }
  const Eigen::Index nv = static_cast<Eigen::Index>(layout.velocity.size());
  const Eigen::Index nmap = run.integrator == RateFormIntegrator::Leapfrog ? y.size() + 2 * nv
                            : run.reuse_corrector_rate                     ? 2 * y.size()
                                                                           : y.size();
  require_dense_memory(static_cast<long>(nmap), 6, who + ": the one-step map");

  StabilityVerdict v;
  v.integrator = rate_form_integrator_name(run);
  v.dt = run.dt;
  v.floor = options.floor;
  v.map_route = stepper ? "stepper" : "closed-form";
  Eigen::MatrixXd M;
  ComplexStepJacobian jac(scheme);
  const Eigen::MatrixXd J(jac.compute(y));
  if (jac.info() != Status::Successful) {
    v.status = Status::NumericalIssue;
    v.reason = "J = dF/dy is not finite at the state";
    return v;
  }
  M = stepper ? rate_form_step_matrix(scheme, y, run.dt, run, options.delta) : linear_step_map(J, layout, run);

  if (at_rest) {  // the exact reduction: no Jordan blocks of the slaved density and stress (rate_form_spectrum.hpp)
    const RateFormSpectrum r = reduced ? s : rate_form_spectrum(scheme, y, {.want_mode = true});
    if (r.status != Status::Successful) {
      v.status = Status::NumericalIssue;
      append_reason(v.reason, "rate_form_spectrum: " + r.reason);
    } else {
      v.semi_discrete_growth = r.growth_rate;
      v.lambda = r.lambda;
      v.lambda_max = r.eigenvalues.size() ? r.eigenvalues.cwiseAbs().maxCoeff() : 0.0;
      if (r.growth_rate > v.floor) v.semi_discrete_mode.shape = r.mode;
    }
  } else {
    dense_semi_discrete(v, J, layout);
  }
  if (v.status != Status::NumericalIssue) map_part(v, M, layout);
  finish(v);
  const Discretisation<Dim>& d = scheme.discretisation();
  locate(v.semi_discrete_mode, d, options.lattice);
  locate(v.map_mode, d, options.lattice);
  return v;
}

template StabilityVerdict stability_verdict<1>(const RateFormScheme<1>&, const Eigen::VectorXd&,
                                               const RateFormRunOptions&, const StabilityVerdictOptions&);
template StabilityVerdict stability_verdict<2>(const RateFormScheme<2>&, const Eigen::VectorXd&,
                                               const RateFormRunOptions&, const StabilityVerdictOptions&);

}  // namespace sphstab
