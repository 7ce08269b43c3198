#include "sphstab/growth/state_stability.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/forms/discretisation.hpp"
#include "sphstab/particles/bravais_lattice.hpp"

namespace sphstab {

namespace {

[[noreturn]] void refuse(const std::string& what) { throw std::invalid_argument("state: " + what); }

std::string shape(Eigen::Index rows, Eigen::Index cols) {
  return std::to_string(rows) + " x " + std::to_string(cols);
}

void require_shape(const Eigen::MatrixXd& m, Eigen::Index rows, Eigen::Index cols, const char* name, bool optional) {
  if (optional && m.size() == 0) return;
  if (m.rows() != rows || m.cols() != cols)
    refuse(std::string(name) + " must be " + shape(rows, cols) + (optional ? " or empty" : "") + " (got " +
           shape(m.rows(), m.cols()) + ")");
}

/// The first non-finite entry of an N x c array (row = particle), named.
void require_finite(const Eigen::MatrixXd& m, const char* name) {
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      if (!std::isfinite(m(i, c)))
        refuse(std::string(name) + " of particle " + std::to_string(i) + " is not finite (" + format_number(m(i, c)) +
               ")");
}

void require_positive(const Eigen::VectorXd& v, const char* name) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!(v[i] > 0) || !std::isfinite(v[i]))
      refuse(std::string(name) + " of particle " + std::to_string(i) + " must be finite and > 0 (got " +
             format_number(v[i]) + ")");
}

}  // namespace

template <int Dim>
RateFormAtState<Dim> rate_form_at_state(const ParticleState<Dim>& s, KernelType kernel_type,
                                        const ElasticMaterial& material, const RateFormOptions& options) {
  constexpr int kStress = RateFormScheme<Dim>::kStress;
  const Eigen::Index n = s.x.rows();
  if (n == 0) refuse("no particles (x has 0 rows)");
  require_shape(s.x, n, Dim, "x", false);
  require_shape(s.v, n, Dim, "v", true);
  require_shape(s.density, n, 1, "density", false);
  require_shape(s.deviator, n, kStress, "deviator", true);
  require_shape(s.mass, n, 1, "mass", false);
  if (!s.fixed.empty() && static_cast<Eigen::Index>(s.fixed.size()) != n)
    refuse("fixed must have " + std::to_string(n) + " entries or none (got " + std::to_string(s.fixed.size()) + ")");
  require_finite(s.x, "the position");
  require_finite(s.v, "the velocity");
  require_finite(s.deviator, "the deviator");
  require_positive(s.density, "the density");
  require_positive(s.mass, "the mass");
  if (!(s.h > 0) || !std::isfinite(s.h)) refuse("h must be finite and > 0 (got " + format_number(s.h) + ")");
  check_length(s.h, "state: h");
  if (!(s.spacing >= 0) || !std::isfinite(s.spacing))
    refuse("spacing must be finite and >= 0 (got " + format_number(s.spacing) + ")");
  if (s.spacing > 0) check_length(s.spacing, "state: spacing");
  material.validate("state", ShearModulusRule::NonNegative);
  const auto is_fixed = [&](Eigen::Index i) { return !s.fixed.empty() && s.fixed[i]; };
  bool any_free = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!is_fixed(i)) {
      any_free = true;
    } else if (s.v.size() && s.v.row(i).squaredNorm() > 0) {
      refuse("fixed particle " + std::to_string(i) + " has a velocity (" + format_number(s.v.row(i).norm()) +
             "); fixed particles are at rest in the rate-form scheme");
    }
  }
  if (!any_free) refuse("every particle is fixed: the state has no unknowns");

  // The masses are rho_ref V_i. Fixed particles that do not evolve keep the scheme's uniform initial density and
  // deviator, so then rho_ref and the deviator are theirs and must be uniform; otherwise rho_ref = rho0.
  double rho_ref = material.density();
  Eigen::VectorXd frozen_deviator = Eigen::VectorXd::Zero(kStress);
  if (!options.evolve_fixed) {
    Eigen::Index first = -1;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!is_fixed(i)) continue;
      const Eigen::VectorXd S =
          s.deviator.size() ? Eigen::VectorXd(s.deviator.row(i).transpose()) : Eigen::VectorXd::Zero(kStress);
      if (first < 0) {
        first = i;
        rho_ref = s.density[i];
        frozen_deviator = S;
      } else if (s.density[i] != rho_ref || S != frozen_deviator) {
        refuse("fixed particles " + std::to_string(first) + " and " + std::to_string(i) +
               " differ in density or deviator: with evolve_fixed off the scheme holds one uniform frozen state");
      }
    }
  }

  ParticleSet<Dim> set;
  set.x = s.x;
  set.volume = s.mass / rho_ref;
  set.role.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) set.role[i] = is_fixed(i) ? Role::Fixed : Role::Free;
  set.spacing = s.spacing;
  const Kernel<Dim> kernel(kernel_type);
  const auto disc = make_discretisation(std::move(set), kernel, s.h);
  const double too_close = 1e-9 * s.h;
  for (int i = 0; i < disc->size(); ++i)
    for (long k = disc->neighbours.offsets[i]; k < disc->neighbours.offsets[i + 1]; ++k) {
      const int j = disc->neighbours.indices[k];
      if (j > i && disc->particles.separation(i, j).norm() < too_close)
        refuse("particles " + std::to_string(i) + " and " + std::to_string(j) + " coincide (closer than 1e-9 h)");
    }

  RateFormAtState<Dim> out;
  auto scheme = std::make_shared<RateFormScheme<Dim>>(disc, material, options, rho_ref, frozen_deviator);
  out.y = scheme->uniform_state();
  for (int i = 0; i < disc->size(); ++i) {
    if (scheme->velocity_offset(i) >= 0 && s.v.size())
      out.y.template segment<Dim>(scheme->velocity_offset(i)) = s.v.row(i).transpose();
    if (scheme->density_offset(i) >= 0) {
      out.y[scheme->density_offset(i)] = s.density[i];
      if (s.deviator.size()) out.y.template segment<kStress>(scheme->stress_offset(i)) = s.deviator.row(i).transpose();
    }
  }
  out.scheme = std::move(scheme);
  return out;
}

template <int Dim>
StateStability state_stability(const ParticleState<Dim>& s, const StateStabilityOptions& o) {
  if (!(o.dt > 0) || !std::isfinite(o.dt)) refuse("dt must be finite and > 0 (got " + format_number(o.dt) + ")");
  if (!(o.floor > 0) || !std::isfinite(o.floor))
    refuse("the detection floor must be finite and > 0 (got " + format_number(o.floor) + ")");
  const RateFormAtState<Dim> at = rate_form_at_state(s, o.kernel, o.material, o.scheme);
  const RateFormScheme<Dim>& scheme = *at.scheme;
  StateStability r;
  r.particles = static_cast<int>(s.x.rows());
  r.states = scheme.size();
  r.at_rest = s.v.size() == 0 || s.v.cwiseAbs().maxCoeff() == 0;
  r.rate_scale = o.material.p_wave_speed() / s.h;
  Eigen::VectorXd f;
  scheme.rate(at.y, f);
  for (int i = 0; i < r.particles; ++i) {
    if (scheme.velocity_offset(i) < 0) continue;
    ++r.free;
    r.acceleration_max = std::max(r.acceleration_max, f.template segment<Dim>(scheme.velocity_offset(i)).norm());
  }

  RateFormRunOptions run = o.run;
  run.dt = o.dt;
  if (!(run.t_end > 0)) run.t_end = o.dt;
  StabilityVerdictOptions vo{.floor = o.floor};
  if constexpr (Dim == 2) {
    if (s.spacing > 0)
      vo.lattice = o.lattice ? bravais_lattice_2d(*o.lattice, s.spacing)
                             : detect_bravais_lattice_2d(Eigen::MatrixX2d(s.x), s.spacing);
  }
  r.verdict = stability_verdict(scheme, at.y, run, vo);
  if (r.at_rest) {
    r.time_step = rate_form_time_step(scheme, at.y);
  } else {
    r.time_step.reason = "the step limits need a state at rest (rate_form_time_step.hpp)";
  }
  return r;
}

template RateFormAtState<1> rate_form_at_state<1>(const ParticleState<1>&, KernelType, const ElasticMaterial&,
                                                  const RateFormOptions&);
template RateFormAtState<2> rate_form_at_state<2>(const ParticleState<2>&, KernelType, const ElasticMaterial&,
                                                  const RateFormOptions&);
template StateStability state_stability<1>(const ParticleState<1>&, const StateStabilityOptions&);
template StateStability state_stability<2>(const ParticleState<2>&, const StateStabilityOptions&);

}  // namespace sphstab
