#pragma once
// The rate-form scheme's template definitions (RateFormScheme<Dim>, its term helpers and both pair loops), included by
// rate_form.cpp (Dim = 1 and the non-template functions) and rate_form_2d.cpp (Dim = 2): one dimension per translation
// unit, so the two halves of the library's longest file compile side by side (docs/ci.md). Private to src/forms/.
#include "sphstab/forms/rate_form.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <complex>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "kernel_rows.hpp"
#include "rate_form_pair_loop.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/models/artificial_stress.hpp"
#include "sphstab/numerics/real_part.hpp"

namespace sphstab {

using rate_form_detail::PairFactor;
using rate_form_detail::with_kernel_functions;

namespace {

bool uses_local_means(RateFormMomentum m) { return m == RateFormMomentum::Cij || m == RateFormMomentum::StabilisedSph; }

/// Calls body(viscosity_tag, stress_tag) with the viscosity switch and whether the artificial stress acts as
/// compile-time tags, so that the pair loops are compiled for the active terms only.
template <class Body>
void with_term_tags(ViscositySwitch viscosity, bool stress, Body&& body) {
  const auto with_stress = [&](auto viscosity_tag) {
    if (stress)
      body(viscosity_tag, std::true_type{});
    else
      body(viscosity_tag, std::false_type{});
  };
  switch (viscosity) {
    case ViscositySwitch::Off:
      with_stress(std::integral_constant<ViscositySwitch, ViscositySwitch::Off>{});
      break;
    case ViscositySwitch::Compression:
      with_stress(std::integral_constant<ViscositySwitch, ViscositySwitch::Compression>{});
      break;
    case ViscositySwitch::Always:
      with_stress(std::integral_constant<ViscositySwitch, ViscositySwitch::Always>{});
      break;
  }
}

// The helpers below repeat operations of other files exactly (the same expressions on the same types, in the same
// order), so that evaluate() gives bitwise the results it gave when it called those functions; they only drop work
// whose result evaluate() does not read. Change them together with the originals.

/// principal_frame() of models/artificial_stress.cpp without the angle theta (an atan2 that artificial_stress() does
/// not read), and c^2, s^2, sc only where artificial_stress() reads them (one tensile principal stress).
template <class Scalar>
PrincipalFrame<Scalar> principal_frame_without_angle(const SymmetricTensor2<Scalar>& sigma) {
  using detail::re;
  using std::sqrt;
  PrincipalFrame<Scalar> f;
  const Scalar mean = 0.5 * (sigma.xx + sigma.yy);
  const Scalar half_diff = 0.5 * (sigma.xx - sigma.yy);
  const double scale = std::max(std::abs(re(half_diff)), std::abs(re(sigma.xy)));
  if (!(scale > 0)) {
    f.major = mean;
    f.minor = mean;
    return f;
  }
  const Scalar a = half_diff / scale, b = sigma.xy / scale;
  const Scalar rho = sqrt(a * a + b * b);
  const Scalar radius = scale * rho;
  f.major = mean + radius;
  f.minor = mean - radius;
  if (re(f.minor) > 0 || !(re(f.major) > 0)) return f;  // artificial_stress() reads no rotation
  if (re(a) >= 0) {
    f.cc = (rho + a) / (2.0 * rho);
    f.ss = b * b / (2.0 * rho * (rho + a));
  } else {
    f.ss = (rho - a) / (2.0 * rho);
    f.cc = b * b / (2.0 * rho * (rho - a));
  }
  f.sc = b / (2.0 * rho);
  return f;
}

/// artificial_stress(sigma, density, epsilon) of models/artificial_stress.cpp (GMS (6.1)-(6.7)) on
/// principal_frame_without_angle(); epsilon >= 0 is checked by the constructor, the density here as there.
template <class Scalar>
SymmetricTensor2<Scalar> particle_artificial_stress(const SymmetricTensor2<Scalar>& sigma, const Scalar& density,
                                                    double epsilon) {
  using detail::re;
  if (!(re(density) > 0) || !std::isfinite(re(density)))
    throw std::invalid_argument("artificial_stress: density must be finite and > 0 (got " +
                                std::to_string(re(density)) + ")");
  const PrincipalFrame<Scalar> f = principal_frame_without_angle(sigma);
  const bool major_tensile = re(f.major) > 0, minor_tensile = re(f.minor) > 0;
  const Scalar k = -epsilon / (density * density);
  if (minor_tensile) return {k * sigma.xx, k * sigma.yy, k * sigma.xy};
  if (!major_tensile) return {};
  return rotate_from_frame(f, Scalar(k * f.major), Scalar(0));
}

}  // namespace

template <int Dim>
RateFormScheme<Dim>::RateFormScheme(std::shared_ptr<const Discretisation<Dim>> disc, const RateFormMaterial& material,
                                    const RateFormOptions& options, double density, const Eigen::VectorXd& deviator)
    : m_disc(std::move(disc)), m_material(material), m_options(options) {
  const char* who = "RateFormScheme";
  if (!m_disc) throw std::invalid_argument("RateFormScheme: null discretisation");
  m_material.validate(who);
  m_density = std::isnan(density) ? material.density : density;
  if (!(m_density > 0) || !std::isfinite(m_density))
    throw std::invalid_argument("RateFormScheme: density must be finite and > 0 (got " + format_number(m_density) +
                                ")");
  const auto nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
  if (!nonneg(options.xsph) || !nonneg(options.viscosity_alpha) || !nonneg(options.viscosity_beta) ||
      !nonneg(options.artificial_stress) || !nonneg(options.artificial_stress_exponent))
    throw std::invalid_argument(
        "RateFormScheme: xsph, viscosity_alpha, viscosity_beta, artificial_stress and its exponent must be finite and "
        ">= 0");
  if (!nonneg(options.bulk_viscosity_quadratic) || !nonneg(options.bulk_viscosity_linear))
    throw std::invalid_argument("RateFormScheme: bulk_viscosity_quadratic and bulk_viscosity_linear must be finite and "
                                ">= 0 (got " + format_number(options.bulk_viscosity_quadratic) + ", " +
                                format_number(options.bulk_viscosity_linear) + ")");
  if (deviator.size() != 0 && deviator.size() != kStress)
    throw std::invalid_argument("RateFormScheme: deviator must have " + std::to_string(kStress) + " entries (got " +
                                std::to_string(deviator.size()) + ")");
  m_deviator = deviator.size() ? deviator : Eigen::VectorXd::Zero(kStress);
  if (!m_deviator.allFinite()) throw std::invalid_argument("RateFormScheme: deviator must be finite");
  const ParticleSet<Dim>& p = m_disc->particles;
  if (options.artificial_stress > 0) {
    if (!(p.spacing > 0))
      throw std::invalid_argument("RateFormScheme: artificial stress needs a lattice spacing dp (f = W / W(dp))");
    const double w = m_disc->kernel.value(p.spacing, m_disc->h);
    if (!(w > 0))
      throw std::invalid_argument("RateFormScheme: W(dp) = 0: the lattice spacing lies outside the kernel support");
    m_w_dp = w;
  }
  const int n = p.size();
  const NeighbourList& nl = m_disc->neighbours;
  if (uses_local_means(options.momentum)) {
    if (options.gradient != RateFormGradient::Plain)
      throw std::invalid_argument("RateFormScheme: the C_ij and S-SPH momentum forms use the plain gradient");
    // The pattern of the local means: the list's pairs within the kernel support at these positions, by the neighbour
    // search's own test, so that a list with a margin gives the same scheme (rate_form.hpp). A list of radius
    // support passes every entry: m_in_support stays empty.
    const double support = m_disc->kernel.support_radius(m_disc->h), s2 = support * support;
    std::vector<char> in(nl.nonzeros(), 1);
    NeighbourList pattern;
    pattern.radius = support;
    pattern.offsets.assign(n + 1, 0);
    bool all = true;
    for (int i = 0; i < n; ++i) {
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        in[k] = j == i || p.separation(i, j).squaredNorm() < s2;
        all = all && in[k];
        if (in[k]) pattern.indices.push_back(j);
      }
      pattern.offsets[i + 1] = static_cast<long>(pattern.indices.size());
    }
    m_counts = neighbour_counts(p, all ? nl : pattern, options.counting);
    if (!all) m_in_support = std::move(in);
  }
  if (options.first_step_shepard) {
    if (options.momentum != RateFormMomentum::StabilisedSph)
      throw std::invalid_argument("RateFormScheme: first_step_shepard (Powell (4.18)) needs the S-SPH momentum form");
    // Powell (4.18): the first step's Shepard sums, kernel sums over the whole list (W = 0 beyond the support).
    const Kernel<Dim>& kernel = m_disc->kernel;
    const double h = m_disc->h;
    m_shepard_sum = Eigen::VectorXd::Zero(n);
    m_shepard_grad.assign(n, Eigen::Matrix<double, Dim, 1>::Zero());
    for (int i = 0; i < n; ++i)
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        const Eigen::Matrix<double, Dim, 1> r = p.separation(i, j).transpose();
        const double rr = r.norm();
        m_shepard_sum[i] += p.volume[j] * kernel.value(rr, h);
        if (j != i) m_shepard_grad[i] += (p.volume[j] * kernel.d1(rr, h) / rr) * r;
      }
  }
  if (options.momentum == RateFormMomentum::StabilisedSph) {
    if (options.excluded_depth < -1)
      throw std::invalid_argument("RateFormScheme: excluded_depth must be >= -1 (got " +
                                  std::to_string(options.excluded_depth) + ")");
    if (options.excluded_depth >= 0 && static_cast<int>(p.depth.size()) != n)
      throw std::invalid_argument("RateFormScheme: S-SPH's outer-layer exclusion needs a depth per particle");
    m_excluded.assign(n, false);
    for (int i = 0; i < n; ++i) m_excluded[i] = options.excluded_depth >= 0 && p.depth[i] <= options.excluded_depth;
  }
  if (options.momentum == RateFormMomentum::Antisymmetric) {
    m_transpose.assign(nl.nonzeros(), -1);
    for (int i = 0; i < n; ++i)
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        const auto first = nl.indices.begin() + nl.offsets[j], last = nl.indices.begin() + nl.offsets[j + 1];
        const auto it = std::lower_bound(first, last, i);
        if (it == last || *it != i)
          throw std::invalid_argument("RateFormScheme: the neighbour list is not symmetric (pair " + std::to_string(i) +
                                      ", " + std::to_string(j) + ")");
        m_transpose[k] = it - nl.indices.begin();
      }
  }
  if (options.pair_loop == PairLoop::Pairs) {
    if (options.gradient != RateFormGradient::Plain || uses_local_means(options.momentum))
      throw std::invalid_argument(
          "RateFormScheme: the pair loop needs the plain gradient with symmetric or antisymmetric momentum");
    // Rows are sorted and hold i itself (neighbour_list.hpp).
    m_upper.resize(n);
    for (int i = 0; i < n; ++i)
      m_upper[i] = std::upper_bound(nl.indices.begin() + nl.offsets[i], nl.indices.begin() + nl.offsets[i + 1], i) -
                   nl.indices.begin();
  }
  m_mass = m_density * p.volume;
  m_x_off.assign(n, -1);
  m_rho_off.assign(n, -1);
  int next = 0;
  for (int i = 0; i < n; ++i) {
    if (p.role[i] == Role::Free) {
      m_x_off[i] = next;
      next += 2 * Dim;
    } else if (!options.evolve_fixed) {
      continue;
    }
    m_rho_off[i] = next;
    next += 1 + kStress;
  }
  m_size = next;
}

template <int Dim>
void RateFormScheme<Dim>::set_driven(std::vector<int> particles,
                                     std::vector<Eigen::Matrix<double, Dim, 1>> accelerations) {
  if (particles.size() != accelerations.size())
    throw std::invalid_argument("RateFormScheme::set_driven: " + std::to_string(particles.size()) + " particles but " +
                                std::to_string(accelerations.size()) + " accelerations (one per particle)");
  const int n = m_disc->size();
  std::vector<int> slot(n, -1);
  for (std::size_t q = 0; q < particles.size(); ++q) {
    const int i = particles[q];
    const std::string who = "RateFormScheme::set_driven: particle " + std::to_string(i);
    if (i < 0 || i >= n) throw std::invalid_argument(who + " is out of range [0, " + std::to_string(n) + ")");
    if (m_x_off[i] < 0) throw std::invalid_argument(who + " is fixed (only free particles can be driven)");
    if (is_absorbing(i)) throw std::invalid_argument(who + " is absorbing");
    if (slot[i] >= 0) throw std::invalid_argument(who + " is listed twice");
    if (!accelerations[q].allFinite()) throw std::invalid_argument(who + " has a non-finite acceleration");
    slot[i] = static_cast<int>(q);
  }
  if (particles.empty()) slot.clear();
  m_driven = std::move(particles);
  m_driven_acc = std::move(accelerations);
  m_driven_slot = std::move(slot);
}

template <int Dim>
void RateFormScheme<Dim>::set_absorbing(AbsorbingParticles<Dim> boundary) {
  if (m_exchange && !boundary.particles.empty())
    throw std::invalid_argument(
        "RateFormScheme::set_absorbing: a partitioned scheme (set_row_partition) cannot have "
        "absorbing particles");
  const std::size_t count = boundary.particles.size();
  if (boundary.normals.size() != count)
    throw std::invalid_argument("RateFormScheme::set_absorbing: " + std::to_string(count) + " particles but " +
                                std::to_string(boundary.normals.size()) + " normals (one per particle)");
  if (count > 0 && boundary.condition == AbsorbingCondition::Higdon)
    throw std::invalid_argument(
        "RateFormScheme::set_absorbing: Higdon's condition is second order in time (no velocity form)");
  if (!boundary.speed_scale.empty() && boundary.speed_scale.size() != count)
    throw std::invalid_argument("RateFormScheme::set_absorbing: " + std::to_string(count) + " particles but " +
                                std::to_string(boundary.speed_scale.size()) +
                                " speed scales (one per particle or none)");
  for (double s : boundary.speed_scale)
    if (!(s > 0) || !std::isfinite(s))
      throw std::invalid_argument("RateFormScheme::set_absorbing: speed scale " + format_number(s) +
                                  " (need finite and > 0)");
  const bool traction = boundary.condition == AbsorbingCondition::ViscousTraction;
  if (count > 0 && traction && (!(boundary.traction_depth > 0) || !std::isfinite(boundary.traction_depth)))
    throw std::invalid_argument(
        "RateFormScheme::set_absorbing: the viscous traction needs a finite traction_depth > 0 "
        "(got " +
        format_number(boundary.traction_depth) + ")");
  if (count > 0 && traction && (boundary.upwind || boundary.convective))
    throw std::invalid_argument(
        "RateFormScheme::set_absorbing: upwind and convective do not apply to the viscous traction");
  const int n = m_disc->size();
  std::vector<int> slot(n, -1);
  for (std::size_t q = 0; q < count; ++q) {
    const int i = boundary.particles[q];
    const std::string who = "RateFormScheme::set_absorbing: particle " + std::to_string(i);
    if (i < 0 || i >= n) throw std::invalid_argument(who + " is out of range [0, " + std::to_string(n) + ")");
    if (m_x_off[i] < 0) throw std::invalid_argument(who + " is fixed (only free particles can absorb)");
    if (is_driven(i)) throw std::invalid_argument(who + " is driven");
    if (slot[i] >= 0) throw std::invalid_argument(who + " is listed twice");
    const double len = boundary.normals[q].norm();
    if (!(std::abs(len - 1) <= 1e-12))
      throw std::invalid_argument(who + " has a normal of length " + format_number(len) + " (need a unit normal)");
    slot[i] = static_cast<int>(q);
  }
  if (count == 0) slot.clear();
  m_absorbing = std::move(boundary);
  m_absorbing_slot = std::move(slot);
}

template <int Dim>
template <class Scalar>
void RateFormScheme<Dim>::absorb(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& y,
                                 Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& dydt) const {
  using Vec = Eigen::Matrix<Scalar, Dim, 1>;
  using Mat = Eigen::Matrix<Scalar, Dim, Dim>;
  using std::sqrt;
  const Discretisation<Dim>& d = *m_disc;
  const ParticleSet<Dim>& p = d.particles;
  const NeighbourList& nl = d.neighbours;
  const Kernel<Dim>& kernel = d.kernel;
  const double h = d.h;
  const bool ncsph = m_options.gradient == RateFormGradient::Ncsph || m_absorbing.normalised;
  const double c_p = m_material.p_wave_speed(), c_s = std::sqrt(m_material.shear_modulus / m_material.density);
  const auto position = [&](int j) -> Vec {
    return m_x_off[j] >= 0 ? Vec(y.template segment<Dim>(m_x_off[j]))
                           : Vec(p.x.row(j).transpose().template cast<Scalar>());
  };
  const auto velocity = [&](int j) -> Vec {
    return m_x_off[j] >= 0 ? Vec(y.template segment<Dim>(m_x_off[j] + Dim)) : Vec::Zero();
  };
  const auto volume = [&](int j) -> Scalar {
    return m_mass[j] / (m_rho_off[j] >= 0 ? y[m_rho_off[j]] : Scalar(m_density));
  };
  std::vector<int> js;
  std::vector<Vec> rs, gs;
  std::vector<Scalar> ws;
  for (std::size_t q = 0; q < m_absorbing.particles.size(); ++q) {
    const int i = m_absorbing.particles[q];
    const Eigen::Matrix<double, Dim, 1>& normal = m_absorbing.normals[q];
    const double scale = m_absorbing.speed_scale.empty() ? 1.0 : m_absorbing.speed_scale[q];
    const Vec xi = position(i), vi = velocity(i);
    if (m_absorbing.condition == AbsorbingCondition::ViscousTraction) {  // (2.75): adds to the momentum equation
      dydt.template segment<Dim>(m_x_off[i] + Dim) +=
          viscous_traction_acceleration<Scalar, Dim>(scale * c_p, scale * c_s, normal, vi, m_absorbing.traction_depth);
      continue;
    }
    // The neighbours used, r = x_i - x_j (minimum image), V_j grad_i W_ij and V_j W_ij.
    js.clear(), rs.clear(), gs.clear(), ws.clear();
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      Vec r = xi - position(j);
      for (int a = 0; a < Dim; ++a) {
        if (!p.periodic[a]) continue;
        const double L = p.box_hi[a] - p.box_lo[a], dr = detail::re(r[a]);
        if (dr > 0.5 * L) r[a] -= L;
        if (dr < -0.5 * L) r[a] += L;
      }
      // Upwind (2.67): only the interior side, (x_j - x_i) . n <= 0.
      Scalar along(0);
      for (int a = 0; a < Dim; ++a) along -= r[a] * normal[a];
      if (m_absorbing.upwind && j != i && detail::re(along) > 1e-9 * h) continue;
      const Scalar r2 = (r.array() * r.array()).sum(), rr = sqrt(r2), vj = volume(j);  // not squaredNorm: |r_a|^2
      js.push_back(j);
      rs.push_back(r);
      gs.push_back(j == i ? Vec(Vec::Zero()) : Vec((vj * kernel.d1(rr, h) / rr) * r));
      ws.push_back(vj * (j == i ? Scalar(kernel.value(0.0, h)) : kernel.value(rr, h)));
    }
    if (ncsph) {
      // Powell (1.19) over the neighbours used: Shepard gradient, then the inverse moment matrix.
      Scalar shep(0);
      Vec g = Vec::Zero();
      for (std::size_t t = 0; t < js.size(); ++t) shep += ws[t], g += gs[t];
      Mat M = Mat::Zero();
      for (std::size_t t = 0; t < js.size(); ++t) {
        gs[t] = (gs[t] * shep - ws[t] * g) / (shep * shep);
        M -= rs[t] * gs[t].transpose();
      }
      const Eigen::Matrix<double, Dim, Dim> Mr = M.unaryExpr([](const Scalar& z) { return detail::re(z); });
      const Eigen::JacobiSVD<Eigen::Matrix<double, Dim, Dim>> svd(Mr);
      if (!Mr.allFinite() || !(svd.singularValues()(Dim - 1) > 1e-12 * svd.singularValues()(0)))
        throw std::domain_error("RateFormScheme: NCSPH moment matrix of absorbing particle " + std::to_string(i) +
                                " is singular or not finite" + (m_absorbing.upwind ? " (upwind neighbours)" : ""));
      const Mat Minv_t = M.inverse().transpose();
      for (Vec& gt : gs) gt = Minv_t * gt;
    }
    Mat L = Mat::Zero();  // Powell (1.33) with the sign of rate_form.hpp: L^ab = sum_j (v_j^a - v_i^a) Ghat_ij^b
    for (std::size_t t = 0; t < js.size(); ++t) L += (velocity(js[t]) - vi) * gs[t].transpose();
    Vec a;
    if constexpr (Dim == 1) {
      a[0] = absorbing_acceleration_1d(scale * c_p, normal[0], L(0, 0), vi[0], m_absorbing.convective);
    } else {
      a = absorbing_acceleration<Scalar>(m_absorbing.condition, scale * c_p, scale * c_s, normal, L, vi,
                                         m_absorbing.convective);
    }
    dydt.template segment<Dim>(m_x_off[i] + Dim) = a;
  }
}

template <int Dim>
RateFormScheme<Dim> RateFormScheme<Dim>::rebuilt(const Eigen::VectorXd& y, double neighbour_radius) const {
  if (y.size() != m_size)
    throw std::invalid_argument("RateFormScheme::rebuilt: state has " + std::to_string(y.size()) +
                                " entries, expected " + std::to_string(m_size));
  if (!std::isfinite(neighbour_radius))
    throw std::invalid_argument("RateFormScheme::rebuilt: neighbour radius must be finite (got " +
                                format_number(neighbour_radius) + ")");
  const Discretisation<Dim>& d = *m_disc;
  ParticleSet<Dim> p = d.particles;
  for (int i = 0; i < p.size(); ++i) {
    if (m_x_off[i] < 0) continue;  // fixed particles stay at their reference positions
    for (int a = 0; a < Dim; ++a) {
      double x = y[m_x_off[i] + a];
      if (!std::isfinite(x))
        throw std::invalid_argument("RateFormScheme::rebuilt: particle " + std::to_string(i) +
                                    " has a non-finite position");
      const double lo = p.box_lo[a], hi = p.box_hi[a];
      if (p.periodic[a] && (x < lo || x > hi)) {  // the search needs the box; the state keeps its unwrapped x
        x = lo + std::fmod(x - lo, hi - lo);
        if (x < lo) x += hi - lo;
        x = std::clamp(x, lo, hi);
      }
      p.x(i, a) = x;
    }
  }
  RateFormScheme s(make_discretisation(std::move(p), d.kernel, d.h, neighbour_radius), m_material, m_options, m_density,
                   m_deviator);
  s.m_driven = m_driven;
  s.m_driven_acc = m_driven_acc;
  s.m_driven_slot = m_driven_slot;
  s.m_absorbing = m_absorbing;
  s.m_absorbing_slot = m_absorbing_slot;
  s.m_first = m_first;
  s.m_last = m_last;
  s.m_exchange = m_exchange;
  s.m_shepard_sum = m_shepard_sum;  // (4.18): the first step's sums
  s.m_shepard_grad = m_shepard_grad;
  return s;
}

template <int Dim>
std::string RateFormScheme<Dim>::name() const {
  std::string s = "rate-form-" + std::to_string(Dim) + "d(" +
                  (m_options.continuity == ContinuityForm::Summation ? "summation" : "divergence");
  if (m_options.xsph > 0) s += ", xsph " + format_number(m_options.xsph);
  if (m_options.viscosity != ViscositySwitch::Off)
    s += std::string(", viscosity ") +
         (m_options.viscosity == ViscositySwitch::Compression ? "compression" : "always") + " " +
         format_number(m_options.viscosity_alpha) + "/" + format_number(m_options.viscosity_beta);
  if (m_options.bulk_viscosity_quadratic > 0 || m_options.bulk_viscosity_linear > 0)
    s += ", bulk viscosity " + format_number(m_options.bulk_viscosity_quadratic) + "/" +
         format_number(m_options.bulk_viscosity_linear);
  if (m_options.artificial_stress > 0) s += ", artificial stress " + format_number(m_options.artificial_stress);
  if (m_options.gradient == RateFormGradient::Ncsph) s += ", ncsph";
  switch (m_options.momentum) {
    case RateFormMomentum::Symmetric:
      break;
    case RateFormMomentum::Antisymmetric:
      s += ", antisymmetric momentum";
      break;
    case RateFormMomentum::Cij:
      s += ", C_ij momentum";
      break;
    case RateFormMomentum::StabilisedSph:
      s += ", S-SPH " + switch_rule_name(m_options.switch_rule);
      break;
  }
  if (!m_driven.empty()) s += ", " + std::to_string(m_driven.size()) + " driven";
  if (!m_absorbing.empty())
    s += ", " + std::to_string(m_absorbing.particles.size()) + " absorbing" + (m_absorbing.upwind ? " upwind" : "");
  return s + ")";
}

template <int Dim>
Eigen::VectorXd RateFormScheme<Dim>::uniform_state() const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(m_size);
  const ParticleSet<Dim>& p = m_disc->particles;
  for (int i = 0; i < p.size(); ++i) {
    if (m_x_off[i] >= 0)
      for (int a = 0; a < Dim; ++a) y[m_x_off[i] + a] = p.x(i, a);
    if (m_rho_off[i] >= 0) {
      y[m_rho_off[i]] = m_density;
      y.segment(m_rho_off[i] + 1, kStress) = m_deviator;
    }
  }
  return y;
}

template <int Dim>
Eigen::VectorXd RateFormScheme<Dim>::variable_scale() const {
  Eigen::VectorXd s = Eigen::VectorXd::Ones(m_size);
  for (int i = 0; i < m_disc->size(); ++i) {
    if (m_x_off[i] >= 0) {
      s.segment(m_x_off[i], Dim).setConstant(m_disc->h);
      s.segment(m_x_off[i] + Dim, Dim).setConstant(m_material.p_wave_speed());
    }
    if (m_rho_off[i] >= 0) {
      s[m_rho_off[i]] = m_material.density;
      s.segment(m_rho_off[i] + 1, kStress).setConstant(m_material.bulk_modulus);
    }
  }
  return s;
}

template <int Dim>
double RateFormScheme<Dim>::kinetic_energy(const Eigen::VectorXd& y) const {
  if (y.size() != m_size) throw std::invalid_argument("RateFormScheme::kinetic_energy: state has the wrong size");
  double e = 0;
  for (int i = 0; i < m_disc->size(); ++i)
    if (m_x_off[i] >= 0) e += 0.5 * m_mass[i] * y.segment(m_x_off[i] + Dim, Dim).squaredNorm();
  return e;
}

template <int Dim>
void RateFormScheme<Dim>::set_velocity(Eigen::VectorXd& y, int particle, const Eigen::Matrix<double, Dim, 1>& v) const {
  if (y.size() != m_size || particle < 0 || particle >= m_disc->size() || m_x_off[particle] < 0)
    throw std::invalid_argument("RateFormScheme::set_velocity: particle " + std::to_string(particle) +
                                " is not a free particle of this state");
  y.segment(m_x_off[particle] + Dim, Dim) = v;
}

template <int Dim>
double RateFormScheme<Dim>::min_density(const Eigen::VectorXd& y) const {
  double m = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m_disc->size(); ++i)
    if (m_rho_off[i] >= 0) m = std::min(m, y[m_rho_off[i]]);
  return m;
}

template <int Dim>
void RateFormScheme<Dim>::rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) const {
  evaluate(y, dydt);
  if (!m_absorbing.empty()) absorb(y, dydt);
  if (m_exchange) m_exchange(dydt);
}

template <int Dim>
std::pair<int, int> RateFormScheme<Dim>::state_range(int first, int last) const {
  const int n = m_disc->size();
  if (first < 0 || last > n || first > last)
    throw std::invalid_argument("RateFormScheme::state_range: particles [" + std::to_string(first) + ", " +
                                std::to_string(last) + ") outside [0, " + std::to_string(n) + ")");
  // The first state index at or after particle i (m_size past the last).
  const auto begin = [&](int i) {
    for (; i < n; ++i) {
      if (m_x_off[i] >= 0) return m_x_off[i];
      if (m_rho_off[i] >= 0) return m_rho_off[i];
    }
    return m_size;
  };
  return {begin(first), begin(last)};
}

template <int Dim>
void RateFormScheme<Dim>::set_row_partition(int first, int last, std::function<void(Eigen::VectorXd&)> exchange) {
  const int n = m_disc->size();
  if (first < 0 || last > n || first >= last)
    throw std::invalid_argument("RateFormScheme::set_row_partition: particles [" + std::to_string(first) + ", " +
                                std::to_string(last) + ") is empty or outside [0, " + std::to_string(n) + ")");
  if (!exchange) throw std::invalid_argument("RateFormScheme::set_row_partition: empty exchange function");
  if (!m_absorbing.empty())
    throw std::invalid_argument("RateFormScheme::set_row_partition: absorbing particles are not supported");
  m_first = first;
  m_last = last;
  m_exchange = std::move(exchange);
}

template <int Dim>
void RateFormScheme<Dim>::rate(const Eigen::VectorXcd& y, Eigen::VectorXcd& dydt) const {
  evaluate(y, dydt);
  if (!m_absorbing.empty()) absorb(y, dydt);
}

template <int Dim>
template <class Scalar>
void RateFormScheme<Dim>::evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& y,
                                   Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& dydt) const {
  using Vec = Eigen::Matrix<Scalar, Dim, 1>;
  using Mat = Eigen::Matrix<Scalar, Dim, Dim>;
  using std::sqrt;
  if (y.size() != m_size)
    throw std::invalid_argument("RateFormScheme::rate: state has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(m_size));
  const Discretisation<Dim>& d = *m_disc;
  const ParticleSet<Dim>& p = d.particles;
  const NeighbourList& nl = d.neighbours;
  const Kernel<Dim>& kernel = d.kernel;
  const int n = p.size();
  const double h = d.h, rho0 = m_material.density, K = m_material.bulk_modulus, mu = m_material.shear_modulus;
  const RateFormOptions& o = m_options;
  // Threads own whole rows and sum them in the serial order: the same bits for any count (core/threads.hpp).
  const int threads = threads_for(n);
  // The particles whose rates are computed: a partition's, for real states (set_row_partition).
  const bool partial = std::is_same_v<Scalar, double> && m_exchange;
  const int first = partial ? m_first : 0, last = partial ? m_last : n;

  // Scratch kept between calls (rate_form.hpp: one scheme object is not evaluated from two threads at once).
  Workspace<Scalar>& ws = [this]() -> Workspace<Scalar>& {
    if constexpr (std::is_same_v<Scalar, double>)
      return m_work_real;
    else
      return m_work_complex;
  }();

  // Unpack: fixed particles sit at their initial positions at rest; frozen ones keep the initial rho and S.
  std::vector<Vec>&x = ws.x, &v = ws.v, &vhat = ws.vhat;
  std::vector<Scalar>& rho = ws.rho;
  std::vector<Eigen::Matrix<Scalar, kStress, 1>>& S = ws.S;
  x.resize(n);
  v.resize(n);
  vhat.resize(n);
  rho.resize(n);
  S.resize(n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int i = 0; i < n; ++i) {
    if (m_x_off[i] >= 0) {
      x[i] = y.template segment<Dim>(m_x_off[i]);
      v[i] = y.template segment<Dim>(m_x_off[i] + Dim);
    } else {
      x[i] = p.x.row(i).transpose().template cast<Scalar>();
      v[i].setZero();
    }
    if (m_rho_off[i] >= 0) {
      rho[i] = y[m_rho_off[i]];
      S[i] = y.template segment<kStress>(m_rho_off[i] + 1);
    } else {
      rho[i] = Scalar(m_density);
      S[i] = m_deviator.template cast<Scalar>();
    }
  }

  // Pair geometry: r_ij (minimum image decided on the real part) and |r_ij|^2; |r_ij| = sqrt(|r_ij|^2).
  Vec box;
  std::array<double, Dim> half_box;  // +-L/2 of a periodic axis; +inf otherwise (never crossed)
  for (int a = 0; a < Dim; ++a) {
    const double L = p.box_hi[a] - p.box_lo[a];
    box[a] = Scalar(L);
    half_box[a] = p.periodic[a] ? 0.5 * L : std::numeric_limits<double>::infinity();
  }
  const auto separation = [xs = x.data(), box, half_box](int i, int j, Vec& r, Scalar& r2) SPHSTAB_ALWAYS_INLINE {
    r = xs[i] - xs[j];
    for (int a = 0; a < Dim; ++a) {
      const double dr = detail::re(r[a]);
      if (dr > half_box[a])
        r[a] -= box[a];
      else if (dr < -half_box[a])
        r[a] += box[a];
    }
    r2 = Scalar(0);
    for (int a = 0; a < Dim; ++a) r2 += r[a] * r[a];
  };

  const bool plain = o.gradient == RateFormGradient::Plain;
  const bool viscous = o.viscosity != ViscositySwitch::Off;
  const double c0 = m_material.sound_speed(), eta2 = 0.01 * h * h;
  const PairFactor pair_factor(m_w_dp, o.artificial_stress_exponent);
  std::vector<Scalar>& vol = ws.vol;
  vol.resize(n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int i = 0; i < n; ++i) vol[i] = m_mass[i] / rho[i];

  // MCM's bulk viscosity (RateFormOptions::bulk_viscosity_*): q_i = rho_i h (Q1 h d_i^2 - Q2 c0 d_i) where the
  // divergence d_i of v is negative. d_i = sum_j (v_j - v_i) . Ghat_ij with the corrected gradient when one is given
  // (gh, V_j included), else the plain V_j grad W_ij computed here; the self pair contributes nothing.
  const bool bulk = o.bulk_viscosity_quadratic > 0 || o.bulk_viscosity_linear > 0;
  std::vector<Scalar>& bulk_q = ws.bulk_q;
  const auto bulk_pressure = [&](const std::vector<Vec>* corrected) {
    bulk_q.assign(n, Scalar(0));
    const double q1 = o.bulk_viscosity_quadratic * h, q2 = o.bulk_viscosity_linear * c0;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; ++i) {
      Scalar div(0);
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        if (j == i) continue;
        const Vec dv = v[j] - v[i];
        if (corrected) {
          div += dv.cwiseProduct((*corrected)[k]).sum();
        } else {
          Vec r;
          Scalar r2;
          separation(i, j, r, r2);
          const Scalar rr = sqrt(r2);
          div += (vol[j] * kernel.d1(rr, h) / rr) * dv.cwiseProduct(r).sum();
        }
      }
      if (detail::re(div) < 0) bulk_q[i] = rho[i] * h * (q1 * div * div - q2 * div);
    }
  };

  // Stress sigma = S - (p + q) I, sigma / rho^2 and the artificial stress R per particle.
  std::vector<Mat>&sigma = ws.sigma, &sigma_rho2 = ws.sigma_rho2, &R = ws.R;
  const auto stresses = [&] {
    sigma.resize(n);
    sigma_rho2.resize(n);
    R.resize(n);
    FirstException first;  // the artificial stress refuses rho <= 0: a run's result, not an abort in the region
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; ++i) first.run([&] {
      const Scalar pressure = K * (rho[i] / rho0 - 1.0) + (bulk ? bulk_q[i] : Scalar(0));
      Mat s;
      if constexpr (Dim == 1) {
        s(0, 0) = S[i][0];
      } else {
        s << S[i][0], S[i][2], S[i][2], S[i][1];
      }
      sigma[i] = s - pressure * Mat::Identity();
      sigma_rho2[i] = sigma[i] / (rho[i] * rho[i]);
      R[i].setZero();
      if (o.artificial_stress > 0) {
        if constexpr (Dim == 1) {
          if (detail::re(sigma[i](0, 0)) > 0) R[i](0, 0) = -o.artificial_stress * sigma[i](0, 0) / (rho[i] * rho[i]);
        } else {
          const SymmetricTensor2<Scalar> t{sigma[i](0, 0), sigma[i](1, 1), sigma[i](0, 1)};
          const SymmetricTensor2<Scalar> r = particle_artificial_stress(t, rho[i], o.artificial_stress);
          R[i] << r.xx, r.xy, r.xy, r.yy;
        }
      }
    });
    first.rethrow();
  };

  // Rates of particle i from its L, drho (summation) and acceleration: every entry of dydt is written here.
  const auto finish = [&](int i, bool free, const Mat& L, Scalar drho, const Vec& acc) {
    if (o.continuity == ContinuityForm::Divergence) drho = -rho[i] * L.trace();
    if (free) {
      dydt.template segment<Dim>(m_x_off[i]) = vhat[i];
      if (is_driven(i))  // the prescribed acceleration replaces the SPH force
        dydt.template segment<Dim>(m_x_off[i] + Dim) = m_driven_acc[m_driven_slot[i]].template cast<Scalar>();
      else
        dydt.template segment<Dim>(m_x_off[i] + Dim) = acc;
    }
    if (m_rho_off[i] < 0) return;
    dydt[m_rho_off[i]] = drho;
    if constexpr (Dim == 1) {
      dydt[m_rho_off[i] + 1] = (4.0 * mu / 3.0) * L(0, 0);
    } else {
      // Jaumann rate in 3 x 3 with D_zz = 0 and Omega in-plane; S_zz = -(S_xx + S_yy) is carried implicitly.
      const Mat D = 0.5 * (L + L.transpose()), W = 0.5 * (L - L.transpose());
      Mat s;
      s << S[i][0], S[i][2], S[i][2], S[i][1];
      const Scalar tr = D.trace();
      const Mat ds = 2.0 * mu * (D - (tr / 3.0) * Mat::Identity()) + W * s - s * W;
      dydt[m_rho_off[i] + 1] = ds(0, 0);
      dydt[m_rho_off[i] + 2] = ds(1, 1);
      dydt[m_rho_off[i] + 3] = ds(0, 1);
    }
  };

  if constexpr (std::is_same_v<Scalar, double>) {
    if (o.pair_loop == PairLoop::Pairs && !partial) {  // each pair once (rate_form_pair_loop.hpp)
      if (bulk) bulk_pressure(nullptr);
      stresses();
      dydt.resize(m_size);
      ws.acc.resize(n);
      ws.L.resize(n);
      ws.drho.resize(n);
      ws.xsph_moves.resize(n);
      for (int i = 0; i < n; ++i) ws.xsph_moves[i] = m_x_off[i] >= 0 && !is_driven(i);
      const double support = kernel.support_radius(h);
      rate_form_detail::PairLoopArrays<Dim> A{.n = n,
                                              .offsets = nl.offsets.data(),
                                              .upper = m_upper.data(),
                                              .indices = nl.indices.data(),
                                              .x = x.data(),
                                              .v = v.data(),
                                              .rho = rho.data(),
                                              .vol = vol.data(),
                                              .mass = m_mass.data(),
                                              .sigma_rho2 = sigma_rho2.data(),
                                              .R = R.data(),
                                              .xsph_moves = ws.xsph_moves.data(),
                                              .half_box = half_box,
                                              .support2 = support * support,
                                              .h = h,
                                              .eta2 = eta2,
                                              .alpha_c0 = -o.viscosity_alpha * c0,
                                              .beta = o.viscosity_beta,
                                              .xsph = o.xsph,
                                              .summation = o.continuity == ContinuityForm::Summation,
                                              .vhat = vhat.data(),
                                              .acc = ws.acc.data(),
                                              .L = ws.L.data(),
                                              .drho = ws.drho.data()};
      for (int a = 0; a < Dim; ++a) A.box[a] = p.box_hi[a] - p.box_lo[a];
      if (!ws.pair_loop) ws.pair_loop = std::make_shared<rate_form_detail::PairLoopScratch<Dim>>();
      auto& scratch = *static_cast<rate_form_detail::PairLoopScratch<Dim>*>(ws.pair_loop.get());
      with_kernel_functions(kernel, h, [&](const auto& kf) {
        const auto with_xsph = [&](auto viscosity_tag, auto stress_tag) {
          constexpr ViscositySwitch kV = decltype(viscosity_tag)::value;
          constexpr bool kS = decltype(stress_tag)::value;
          if (o.xsph > 0)
            rate_form_detail::pair_loop<Dim, kV, kS, true>(A, kf, pair_factor, scratch);
          else
            rate_form_detail::pair_loop<Dim, kV, kS, false>(A, kf, pair_factor, scratch);
        };
        with_term_tags(o.viscosity, o.artificial_stress > 0, with_xsph);
      });
      for (int i = 0; i < n; ++i)
        if (m_x_off[i] >= 0 || m_rho_off[i] >= 0) finish(i, m_x_off[i] >= 0, ws.L[i], ws.drho[i], ws.acc[i]);
      return;
    }
  }

  if (plain && !uses_local_means(o.momentum)) {
    // Plain gradient, symmetric or antisymmetric momentum (the same for the plain gradient): no per-pair arrays over
    // the whole list. Each pair's r, |r|, W, grad W and pair terms are computed once (rows summed at the end: twice),
    // by the same operations as before; the row loops are compiled for the active viscosity and artificial-stress
    // terms.
    if (bulk) bulk_pressure(nullptr);
    stresses();
    dydt.resize(m_size);
    with_kernel_functions(kernel, h, [&](const auto& kf) {
      // Each neighbour row in two steps. Pair functions: gather r_ij and |r_ij|^2 (and what the pair terms read),
      // then the pairs' scalar functions (|r|, W, dW/dr / r, f^n, the viscosity's Pi / rhobar) as whole-row array
      // loops (vectorised for real states), the row particle's XSPH velocity (it reads v only), and grad W,
      // Pi / rhobar, f^n kept per pair. Sums: L, the continuity and the momentum over the row in neighbour order,
      // which read the neighbours' XSPH velocities. So with XSPH the sums of a row wait until the pair functions of
      // its last neighbour have run, and its kept pair results wait in a ring buffer that holds the pairs of the rows
      // in between (a lattice ordered by rows needs a few lattice rows); the rows whose neighbours lie farther (across
      // a periodic boundary) are summed at the end, their pair functions run again. Without XSPH each row is summed
      // right after its pair functions.
      const bool xsph = o.xsph > 0;
      const auto summed = [&](int i) { return m_x_off[i] >= 0 || m_rho_off[i] >= 0; };
      std::size_t longest = 0;
      for (int i = 0; i < n; ++i)
        longest = std::max(longest, static_cast<std::size_t>(nl.offsets[i + 1] - nl.offsets[i]));
      // Ring: the rows' kept pair results one after the other (a row that would cross the end starts again at 0).
      // Row i is summed after the pair functions of row ready[i]; in between the ring takes the pairs of rows i ..
      // ready[i] (plus at most one row's length left unused at the end). Its size holds that for about 9 rows in 10
      // (and for all rows without XSPH); rows that need more are summed at the end.
      std::vector<long>& ready = ws.ready;  // the row's last neighbour (XSPH) or the row itself
      ready.resize(n);
      std::size_t ring = 2 * longest;
      if (xsph && threads == 1) {  // threads: two passes, no ring
        // The size from every 8th row (an estimate suffices: kept() decides per row).
        std::vector<long>& need = ws.ring_start;  // borrowed: the pairs of rows i .. ready[i]
        need.clear();
        for (int i = 0; i < n; ++i) {
          const long k0 = nl.offsets[i], k1 = nl.offsets[i + 1];
          int last = i;
          for (long k = k0; k < k1; ++k) last = std::max(last, nl.indices[k]);
          ready[i] = last;
          if (i % 8 == 0 && summed(i)) need.push_back(nl.offsets[last + 1] - k0);
        }
        if (!need.empty()) {
          const auto q90 = need.begin() + std::min(need.size() - 1, (9 * need.size()) / 10);
          std::nth_element(need.begin(), q90, need.end());
          ring = std::max(ring, static_cast<std::size_t>(*q90) + 2 * longest);
        }
      } else {
        for (int i = 0; i < n; ++i) ready[i] = i;
      }
      const auto kept = [&](int i) {
        return static_cast<std::size_t>(nl.offsets[ready[i] + 1] - nl.offsets[i]) + longest <= ring;
      };
      std::vector<long>& ring_start = ws.ring_start;  // where row i's kept pair results start
      ring_start.resize(n);
      // grad W (Dim), Pi / rhobar, f^n per pair.
      using Kept = Eigen::Matrix<Scalar, Dim + 2, 1>;
      if (xsph && ws.ring.size() < ring) ws.ring.resize(ring);
      Kept* const kept_pairs = ws.ring.data();
      constexpr int kRowArrays = 8;
      const std::size_t slots = static_cast<std::size_t>(threads);  // one set of row arrays per thread
      if (ws.row_r.size() < slots * longest) ws.row_r.resize(slots * longest);
      if (ws.row.size() < slots * kRowArrays * longest) ws.row.resize(slots * kRowArrays * longest);
      if (ws.row_mass.size() < slots * longest) ws.row_mass.resize(slots * longest);
      const auto row_sqrt = [](const Scalar* r2b, Scalar* rrb, std::size_t len) SPHSTAB_ALWAYS_INLINE {
        if constexpr (std::is_same_v<Scalar, double>)
          Eigen::Map<Eigen::ArrayXd>(rrb, len) = Eigen::Map<const Eigen::ArrayXd>(r2b, len).sqrt();
        else
          for (std::size_t q = 0; q < len; ++q) rrb[q] = sqrt(r2b[q]);
      };

      const auto rows = [&](auto viscosity_tag, auto stress_tag) {
        constexpr ViscositySwitch kViscosity = decltype(viscosity_tag)::value;
        constexpr bool kViscous = kViscosity != ViscositySwitch::Off;
        constexpr bool kStressTerm = decltype(stress_tag)::value;
        const bool summation = o.continuity == ContinuityForm::Summation;
        const double alpha_c0 = -o.viscosity_alpha * c0;
        // The arrays the row loops read and write, as plain pointers copied into the loops (the vector stores of the
        // row arrays may alias anything, which would otherwise reload every vector's data pointer after each).
        struct Arrays {
          const long* off;
          const int* idx;
          const Vec *v, *vhat;
          Vec* vhat_out;
          const Scalar *rho, *vol;
          const double* mass;
          const Mat *sigma_rho2, *R;
          Kept* kept;
          Vec* r;                                         // row arrays: r_ij
          Scalar *r2, *rr, *w, *gf, *f, *rho_j, *vr, *c;  // |r|^2, |r|, W, dW/dr / r, f^n, rho_j, v_ij . r_ij, weights
          double* m;                                      // m_j
        };
        // Thread t's arrays: the shared per-particle arrays and its own row arrays.
        const auto arrays = [&](int t) {
          double* const mb = ws.row_mass.data() + t * longest;           // m_j
          Vec* const rb = ws.row_r.data() + t * longest;                 // r_ij
          Scalar* const r2b = ws.row.data() + t * kRowArrays * longest;  // |r|^2
          Scalar* const rrb = r2b + longest;                             // |r|
          Scalar* const wb = rrb + longest;                              // W
          Scalar* const gfb = wb + longest;                              // dW/dr / r
          Scalar* const fb = gfb + longest;                              // f_ij^n
          Scalar* const rhob = fb + longest;                             // rho_j
          Scalar* const vrb = rhob + longest;                            // v_ij . r_ij
          Scalar* const cb = vrb + longest;                              // XSPH weight; Pi_ij / rhobar_ij
          return Arrays{.off = nl.offsets.data(),
                        .idx = nl.indices.data(),
                        .v = v.data(),
                        .vhat = vhat.data(),
                        .vhat_out = vhat.data(),
                        .rho = rho.data(),
                        .vol = vol.data(),
                        .mass = m_mass.data(),
                        .sigma_rho2 = sigma_rho2.data(),
                        .R = R.data(),
                        .kept = kept_pairs,
                        .r = rb,
                        .r2 = r2b,
                        .rr = rrb,
                        .w = wb,
                        .gf = gfb,
                        .f = fb,
                        .rho_j = rhob,
                        .vr = vrb,
                        .c = cb,
                        .m = mb};
        };
        const Arrays A = arrays(0);

        // Pair functions of row i: the XSPH velocity (with_xsph) and the pair results for the sums (keep), copied to
        // the ring from slot `base` on unless `base` is `now` (summed right away, from the row arrays).
        constexpr std::size_t now = ~std::size_t(0);
        const auto pair_functions_of = [&](const Arrays A) {
          return [&, A](int i, auto xsph_tag, bool keep, std::size_t base) SPHSTAB_ALWAYS_INLINE {
            constexpr bool with_xsph = decltype(xsph_tag)::value;
            const bool free = m_x_off[i] >= 0, terms = keep && free;
            const long k0 = A.off[i];
            const std::size_t len = A.off[i + 1] - k0;
            for (std::size_t q = 0; q < len; ++q) {
              const int j = A.idx[k0 + q];
              separation(i, j, A.r[q], A.r2[q]);
              if constexpr (with_xsph) A.m[q] = A.mass[j];
              if (with_xsph || (kViscous && terms)) A.rho_j[q] = A.rho[j];
              if (kViscous && terms) {
                const Vec vij = A.v[i] - A.v[j];
                A.vr[q] = vij.cwiseProduct(A.r[q]).sum();
              }
            }
            row_sqrt(A.r2, A.rr, len);
            if (!keep)
              kf.row_values(len, A.rr, A.w);
            else if (with_xsph || (kStressTerm && free))
              kf.template row_slopes<true>(len, A.rr, A.w, A.gf);
            else
              kf.template row_slopes<false>(len, A.rr, A.w, A.gf);
            const Scalar rho_i = A.rho[i];
            if constexpr (with_xsph) {  // XSPH velocity [GMS2001, (3.6)]
              for (std::size_t q = 0; q < len; ++q) A.c[q] = o.xsph * A.m[q] * A.w[q] / (0.5 * (rho_i + A.rho_j[q]));
              Vec vh = A.v[i];
              for (std::size_t q = 0; q < len; ++q) {
                const int j = A.idx[k0 + q];
                if (j == i) continue;
                vh += A.c[q] * (A.v[j] - A.v[i]);
              }
              A.vhat_out[i] = vh;
            }
            if (!keep) return;
            if (kStressTerm && free) pair_factor.row(len, A.w, A.f);
            if (kViscous && free)
              for (std::size_t q = 0; q < len; ++q) {
                const Scalar mu_ij = h * A.vr[q] / (A.r2[q] + eta2), rho_bar = 0.5 * (rho_i + A.rho_j[q]);
                Scalar pi = alpha_c0 * mu_ij;
                if constexpr (kViscosity == ViscositySwitch::Compression) pi += o.viscosity_beta * mu_ij * mu_ij;
                const Scalar c = pi / rho_bar;
                // Compression: 0 for a receding pair, selected here rather than branched on in the sums (the sign of
                // v_ij . r_ij is random); 0 - 0 I leaves the zero pair matrix as it is.
                if constexpr (kViscosity != ViscositySwitch::Compression) {
                  A.c[q] = c;
                } else if constexpr (std::is_same_v<Scalar, double>) {  // as below, by a mask (the loop vectorises)
                  const std::uint64_t approaching = -static_cast<std::uint64_t>(A.vr[q] < 0);
                  A.c[q] = std::bit_cast<double>(std::bit_cast<std::uint64_t>(c) & approaching);
                } else {
                  A.c[q] = detail::re(A.vr[q]) < 0 ? c : Scalar(0);
                }
              }
            if (base == now) return;
            Kept* const out = A.kept + base;
            for (std::size_t q = 0; q < len; ++q) {
              out[q].template head<Dim>() = A.gf[q] * A.r[q];  // grad_i W_ij
              if (kViscous && free) out[q][Dim] = A.c[q];
              if (kStressTerm && free) out[q][Dim + 1] = A.f[q];
            }
          };
        };
        const auto pair_functions = pair_functions_of(A);

        // Sums of row i from its pair results (the ring from slot `base` on, or the row arrays: `now`) and the XSPH
        // velocities.
        const auto sums_of = [&](const Arrays A) {
          return [&, A](int i, std::size_t base, auto from_ring) SPHSTAB_ALWAYS_INLINE {
            constexpr bool kRing = decltype(from_ring)::value;
            const bool free = m_x_off[i] >= 0;
            const long k0 = A.off[i];
            const std::size_t len = A.off[i + 1] - k0;
            Mat L = Mat::Zero();
            Scalar drho(0);
            Vec acc = Vec::Zero();
            const Mat& si = A.sigma_rho2[i];
            const Kept* const in = kRing ? A.kept + base : nullptr;
            for (std::size_t q = 0; q < len; ++q) {
              const int j = A.idx[k0 + q];
              if (j == i) continue;
              Vec gk;  // grad_i W_ij
              if constexpr (kRing)
                gk = in[q].template head<Dim>();
              else
                gk = A.gf[q] * A.r[q];
              const Vec dv = A.vhat[j] - A.vhat[i];
              // L^ab = dv^a/dx^b [GMS2001, (3.10)]; continuity [GMS2001, (3.8)] (not dot(): it conjugates complex
              // steps).
              L += (A.vol[j] * dv) * gk.transpose();
              if (summation) drho -= A.mass[j] * dv.cwiseProduct(gk).sum();
              if (!free) continue;
              if constexpr (!kViscous && !kStressTerm) {
                // Powell (1.36): m_j grad W_ij = rho_j Ghat_ij. (Adding the zero pair matrix would change no result:
                // acc starts at +0, so a zero's sign cannot reach it.)
                acc += A.mass[j] * ((si + A.sigma_rho2[j]) * gk);
              } else {
                // Pair terms: viscosity and artificial stress.
                Mat pair = Mat::Zero();
                if constexpr (kViscous) pair -= (kRing ? in[q][Dim] : A.c[q]) * Mat::Identity();
                if constexpr (kStressTerm) pair += (kRing ? in[q][Dim + 1] : A.f[q]) * (A.R[i] + A.R[j]);
                acc += A.mass[j] * ((si + A.sigma_rho2[j] + pair) * gk);
              }
            }
            finish(i, free, L, drho, acc);
          };
        };
        const auto sums = sums_of(A);

        if (threads > 1 || partial) {
          // Two passes over rows split between the threads: the XSPH velocities, then each row's pair functions
          // and sums (as the rows summed late below: the same operations, so the same bits as one thread). A
          // failure is kept, not thrown, so that every thread reaches both loops' barriers. A partition sums its
          // rows and needs the XSPH velocities of their neighbours, rows [lo, hi).
          int lo = first, hi = last;
          if (partial)
            for (long k = nl.offsets[first]; k < nl.offsets[last]; ++k) {
              lo = std::min(lo, nl.indices[k]);
              hi = std::max(hi, nl.indices[k] + 1);
            }
          std::exception_ptr error;
#pragma omp parallel num_threads(threads)
          {
            const Arrays At = arrays(thread_index());
            const auto pf = pair_functions_of(At);
            const auto sm = sums_of(At);
#pragma omp for schedule(static)
            for (int t = lo; t < hi; ++t) try {
                if (xsph && m_x_off[t] >= 0 && !is_driven(t))
                  pf(t, std::true_type{}, false, 0);
                else
                  vhat[t] = v[t];
              } catch (...) {
#pragma omp critical(sphstab_rate_form_error)
                if (!error) error = std::current_exception();
              }
#pragma omp for schedule(static)
            for (int t = first; t < last; ++t) try {
                if (!summed(t)) continue;
                pf(t, std::false_type{}, true, now);
                sm(t, now, std::false_type{});
              } catch (...) {
#pragma omp critical(sphstab_rate_form_error)
                if (!error) error = std::current_exception();
              }
          }
          if (error) std::rethrow_exception(error);
          return;
        }

        std::vector<int>& late = ws.late;  // rows summed at the end
        late.clear();
        int next = 0;  // the next row to sum, in index order
        const auto sum_ready = [&](int t) {
          for (; next <= t; ++next) {
            if (!summed(next)) continue;
            if (!kept(next)) {
              late.push_back(next);
              continue;
            }
            if (ready[next] > t) break;
            sums(next, ring_start[next], std::true_type{});
          }
        };
        if (!xsph) {  // vhat = v: each row summed right after its pair functions
          for (int t = 0; t < n; ++t) vhat[t] = v[t];
          for (int t = 0; t < n; ++t)
            if (summed(t)) {
              pair_functions(t, std::false_type{}, true, now);
              sums(t, now, std::false_type{});
            }
          return;
        }
        std::size_t position = 0;
        for (int t = 0; t < n; ++t) {
          // Fixed particles do not move; driven ones move with v.
          const bool with_xsph = m_x_off[t] >= 0 && !is_driven(t), keep = summed(t) && kept(t);
          if (!with_xsph) vhat[t] = v[t];
          if (keep) {
            const std::size_t len = nl.offsets[t + 1] - nl.offsets[t];
            if (position + len > ring) position = 0;
            ring_start[t] = position;
            position += len;
          }
          if (with_xsph)
            pair_functions(t, std::true_type{}, keep, keep ? ring_start[t] : 0);
          else if (keep)
            pair_functions(t, std::false_type{}, true, ring_start[t]);
          sum_ready(t);
        }
        sum_ready(n - 1);
        for (int i : late) {
          pair_functions(i, std::false_type{}, true, now);
          sums(i, now, std::false_type{});
        }
      };
      with_term_tags(o.viscosity, o.artificial_stress > 0, rows);
    });
  } else {
    // The corrected gradient (NCSPH) and the local means of C_ij / S-SPH: per-pair arrays, as later passes read them:
    // grad W (always), r (NCSPH or viscosity), r^2 (viscosity), W (NCSPH, XSPH or artificial stress).
    const bool keep_r = !plain || viscous, keep_r2 = viscous;
    const bool keep_w = !plain || o.xsph > 0 || o.artificial_stress > 0 || o.first_step_shepard;
    const long nnz = nl.nonzeros();
    std::vector<Vec>&rij = ws.rij, &grad = ws.grad, &gh = ws.gh;
    std::vector<Scalar>&w = ws.w, &r2s = ws.r2s;
    grad.resize(nnz);
    if (keep_r) rij.resize(nnz);
    if (keep_r2) r2s.resize(nnz);
    if (keep_w) w.resize(nnz);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; ++i)
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        if (j == i) {
          if (keep_r) rij[k].setZero();
          grad[k].setZero();
          if (keep_w) w[k] = Scalar(kernel.value(0.0, h));
          if (keep_r2) r2s[k] = Scalar(0);
          continue;
        }
        Vec r;
        Scalar r2;
        separation(i, j, r, r2);
        const Scalar rr = sqrt(r2);
        if (keep_r) rij[k] = r;
        if (keep_r2) r2s[k] = r2;
        if (keep_w) w[k] = kernel.value(rr, h);
        grad[k] = (kernel.d1(rr, h) / rr) * r;
      }

    // The gradient Ghat_ij with V_j included (plain or NCSPH).
    gh.resize(nnz);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; ++i)
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) gh[k] = vol[nl.indices[k]] * grad[k];
    if (o.gradient == RateFormGradient::Ncsph) {
      // A singular moment matrix is reported for its lowest particle (as one thread would), after the loop.
      int bad = n;
      std::string bad_reason;
#pragma omp parallel for schedule(static) num_threads(threads)
      for (int i = 0; i < n; ++i) {
        // Powell (1.19): Shepard gradient (S_i grad W_ij V_j - W_ij V_j g_i) / S_i^2, then times M_i^-1 with
        // M_i^ab = sum_j (x_j^a - x_i^a) gradW~^b_ij, so that sum_j (x_j - x_i) Ghat_ij^T = I.
        Scalar shep(0);
        Vec g = Vec::Zero();
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
          shep += vol[nl.indices[k]] * w[k];
          g += gh[k];
        }
        Mat M = Mat::Zero();
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
          gh[k] = (gh[k] * shep - (vol[nl.indices[k]] * w[k]) * g) / (shep * shep);
          M -= rij[k] * gh[k].transpose();
        }
        const Eigen::Matrix<double, Dim, Dim> Mr = M.unaryExpr([](const Scalar& z) { return detail::re(z); });
        // JacobiSVD stops early on a non-finite matrix and leaves its singular values unset: refuse first.
        std::string reason;
        if (!Mr.allFinite()) {
          reason = "is not finite (non-finite positions or densities in the state)";
        } else {
          const Eigen::JacobiSVD<Eigen::Matrix<double, Dim, Dim>> svd(Mr);
          const double smax = svd.singularValues()(0), smin = svd.singularValues()(Dim - 1);
          if (!(smin > 1e-12 * smax))
            reason = "is singular (rcond " + format_number(smax > 0 ? smin / smax : 0.0) + ")";
        }
        if (!reason.empty()) {
#pragma omp critical(sphstab_rate_form_error)
          if (i < bad) {
            bad = i;
            bad_reason = reason;
          }
          continue;
        }
        const Mat Minv_t = M.inverse().transpose();
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) gh[k] = Minv_t * gh[k];
      }
      if (bad < n)
        throw std::domain_error("RateFormScheme: NCSPH moment matrix of particle " + std::to_string(bad) + " " +
                                bad_reason);
    }

    // XSPH velocity [GMS2001, (3.6)].
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; ++i) {
      vhat[i] = v[i];
      if (o.xsph > 0 && m_x_off[i] >= 0 && !is_driven(i))  // fixed particles do not move; driven ones move with v
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
          const int j = nl.indices[k];
          if (j == i) continue;
          vhat[i] += (o.xsph * m_mass[j] * w[k] / (0.5 * (rho[i] + rho[j]))) * (v[j] - v[i]);
        }
    }

    if (bulk) bulk_pressure(&gh);
    stresses();

    // Local means of algorithm 4.1 of P_ij = V_j grad W_ij (C_ij, S-SPH): row mean r_i, column mean c_j =
    // (1/n_j) sum_k P_kj = -(V_j / n_j) sum_k grad W_jk, mean of column means m_i; and the S-SPH switch.
    // The means' pattern is the list's pairs within the support at the discretisation's positions (rate_form.hpp):
    // m_i and the C_ij / S-SPH terms skip the other entries; r_i and c_j are kernel sums over the whole list.
    const char* in_support = m_in_support.empty() ? nullptr : m_in_support.data();
    const auto in_pattern = [in_support](long k) { return !in_support || in_support[k]; };
    std::vector<Vec>&row_mean = ws.row_mean, &col_mean = ws.col_mean, &mean_mean = ws.mean_mean;
    std::vector<Eigen::Matrix<bool, Dim, 1>>& on = ws.on;
    if (uses_local_means(o.momentum)) {
      row_mean.assign(n, Vec::Zero());
      col_mean.assign(n, Vec::Zero());
      mean_mean.assign(n, Vec::Zero());
#pragma omp parallel for schedule(static) num_threads(threads)
      for (int i = 0; i < n; ++i) {
        Vec gs = Vec::Zero();
        if (!o.first_step_shepard) {
          for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
            row_mean[i] += gh[k];
            gs += grad[k];
          }
          row_mean[i] /= m_counts[i];
          col_mean[i] = (-vol[i] / m_counts[i]) * gs;
          continue;
        }
        // Powell (4.18): P~_ij = V_j (grad W_ij S0_i - W_ij G0_i) / S0_i^2. Row mean: sum_j P~_ij = (sum_j V_j grad
        // W_ij S0_i - sum_j V_j W_ij G0_i) / S0_i^2; column mean of column i: sum_j P~_ji with grad W_ji = -grad W_ij.
        Scalar wsum(0);
        const double s0 = m_shepard_sum[i];
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
          const int j = nl.indices[k];
          row_mean[i] += gh[k];
          wsum += vol[j] * w[k];
          const double sj = m_shepard_sum[j];
          gs -= (grad[k] * sj + w[k] * m_shepard_grad[j].template cast<Scalar>()) / (sj * sj);
        }
        row_mean[i] = (row_mean[i] * s0 - wsum * m_shepard_grad[i].template cast<Scalar>()) / (s0 * s0 * m_counts[i]);
        col_mean[i] = (vol[i] / m_counts[i]) * gs;
      }
#pragma omp parallel for schedule(static) num_threads(threads)
      for (int i = 0; i < n; ++i) {
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
          if (in_pattern(k)) mean_mean[i] += col_mean[nl.indices[k]];
        mean_mean[i] /= m_counts[i];
      }
    }
    if (o.momentum == RateFormMomentum::StabilisedSph) {
      // Switch per component, on the real parts (frozen under a complex step); |sum| below a relative tolerance
      // counts as zero so that the unstressed lattice sits on the "off" branch of the tension rule.
      const double tol = 1e-14 * (K + 4.0 * mu / 3.0);
      on.assign(n, Eigen::Matrix<bool, Dim, 1>::Constant(false));
#pragma omp parallel for schedule(static) num_threads(threads)
      for (int i = 0; i < n; ++i) {
        if (m_excluded[i]) continue;
        for (int a = 0; a < Dim; ++a) {
          double sum = 0;
          for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
            if (in_pattern(k)) sum += detail::re(sigma[nl.indices[k]](a, a));
          if (std::abs(sum) <= tol) sum = 0;
          switch (o.switch_rule) {
            case SwitchRule::Tension:
              on[i][a] = sum > 0;
              break;
            case SwitchRule::AsPrinted:
              on[i][a] = sum <= 0;
              break;
            case SwitchRule::Always:
              on[i][a] = true;
              break;
            case SwitchRule::Never:
              on[i][a] = false;
              break;
          }
        }
      }
    }

    dydt.resize(m_size);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = first; i < last; ++i) {
      const bool free = m_x_off[i] >= 0;
      if (!free && m_rho_off[i] < 0) continue;
      Mat L = Mat::Zero();
      Scalar drho(0);
      Vec acc = Vec::Zero();
      const Mat& si = sigma_rho2[i];
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        if (j == i) {  // only a corrected gradient has a self term (it makes the rows sum to zero)
          if (free && o.momentum == RateFormMomentum::Symmetric && !plain) acc += (2.0 / rho[i]) * (sigma[i] * gh[k]);
          if (free && o.momentum == RateFormMomentum::Cij)
            acc += (sigma[i] / rho[i]) * (gh[k] - row_mean[i] - col_mean[i] + mean_mean[i]);
          continue;
        }
        const Vec& gk = grad[k];
        const Vec dv = vhat[j] - vhat[i];
        // L^ab = dv^a/dx^b [GMS2001, (3.10)]; continuity [GMS2001, (3.8)] (not dot(): it conjugates complex steps).
        if (plain) {
          L += (vol[j] * dv) * gk.transpose();
          if (o.continuity == ContinuityForm::Summation) drho -= m_mass[j] * dv.cwiseProduct(gk).sum();
        } else {
          L += dv * gh[k].transpose();
          if (o.continuity == ContinuityForm::Summation) drho -= rho[j] * dv.cwiseProduct(gh[k]).sum();
        }
        if (!free) continue;
        // Pair terms on the plain gradient: viscosity and artificial stress (every momentum form).
        Mat pair = Mat::Zero();
        if (viscous) {
          const Vec vij = v[i] - v[j];
          const Scalar vr = vij.cwiseProduct(rij[k]).sum();
          if (o.viscosity == ViscositySwitch::Always || detail::re(vr) < 0) {
            const Scalar mu_ij = h * vr / (r2s[k] + eta2), rho_bar = 0.5 * (rho[i] + rho[j]);
            Scalar pi = -o.viscosity_alpha * c0 * mu_ij;
            if (o.viscosity == ViscositySwitch::Compression) pi += o.viscosity_beta * mu_ij * mu_ij;
            pair -= (pi / rho_bar) * Mat::Identity();
          }
        }
        if (o.artificial_stress > 0) pair += pair_factor(w[k]) * (R[i] + R[j]);
        const Mat& sj = sigma_rho2[j];
        switch (o.momentum) {
          case RateFormMomentum::Symmetric:  // Powell (1.36): m_j grad W_ij = rho_j Ghat_ij
            if (plain) {
              acc += m_mass[j] * ((si + sj + pair) * gk);
            } else {
              acc += rho[j] * ((si + sj) * gh[k]) + m_mass[j] * (pair * gk);
            }
            break;
          case RateFormMomentum::Antisymmetric: {
            if (plain) {  // grad W_ji = -grad W_ij: the symmetric form
              acc += m_mass[j] * ((si + sj + pair) * gk);
            } else {
              const Vec ga = 0.5 * (gh[k] / vol[j] - gh[m_transpose[k]] / vol[i]);
              acc += m_mass[j] * ((si + sj) * ga + pair * gk);
            }
            break;
          }
          case RateFormMomentum::Cij:  // Powell (4.10), C_ij of (4.9); C_ij = P_ij outside the pattern
            if (in_pattern(k))
              acc += (sigma[j] / rho[j]) * (gh[k] - row_mean[i] - col_mean[j] + mean_mean[i]) + m_mass[j] * (pair * gk);
            else
              acc += (sigma[j] / rho[j]) * gh[k] + m_mass[j] * (pair * gk);
            break;
          case RateFormMomentum::StabilisedSph: {  // Powell algorithm 4.2: a_i += (f_ij + g_ij - f_ji - g_ji) / 2
            const Mat Sij = sigma[i] / rho[i] + sigma[j] / rho[j];
            Vec gij = -(Sij * (row_mean[i] + col_mean[j] - mean_mean[i]));
            Vec gji = -(Sij * (row_mean[j] + col_mean[i] - mean_mean[j]));
            for (int a = 0; a < Dim; ++a) {
              if (!on[i][a] || !in_pattern(k)) gij[a] = Scalar(0);
              if (!on[j][a] || !in_pattern(k)) gji[a] = Scalar(0);
            }
            acc += 0.5 * ((vol[i] + vol[j]) * (Sij * gk) + gij - gji) + m_mass[j] * (pair * gk);
            break;
          }
        }
      }
      finish(i, free, L, drho, acc);
    }
  }
}

template <int Dim>
SparsityPattern RateFormScheme<Dim>::pattern() const {
  // Rows of particle i read the particles within `hops` of i: 1 (own neighbours), 2 with XSPH (vhat_j reads v_k).
  const NeighbourList& nl = m_disc->neighbours;
  // Momentum reach: Ghat_ji reads N(j) (antisymmetric), c_j reads N(j) (C_ij), g_ji reads m_j, i.e. c of N(j)
  // (S-SPH); XSPH's vhat_j reads N(j) in L_i and the continuity.
  const RateFormMomentum m = m_options.momentum;
  const int momentum_reach = m == RateFormMomentum::Symmetric ? 1 : m == RateFormMomentum::StabilisedSph ? 3 : 2;
  const int n = m_disc->size(), hops = std::max(momentum_reach, m_options.xsph > 0 ? 2 : 1);
  auto block = [&](int i, std::vector<int>& cols) {
    if (m_x_off[i] >= 0)
      for (int c = 0; c < 2 * Dim; ++c) cols.push_back(m_x_off[i] + c);
    if (m_rho_off[i] >= 0)
      for (int c = 0; c < 1 + kStress; ++c) cols.push_back(m_rho_off[i] + c);
  };
  SparsityPattern pat;
  pat.rows = pat.cols = m_size;
  pat.offsets.assign(m_size + 1, 0);
  std::vector<int> mark(n, -1), reach, cols;
  for (int i = 0; i < n; ++i) {
    reach.assign(1, i);
    mark[i] = i;
    for (std::size_t start = 0, level = 0; level < static_cast<std::size_t>(hops); ++level) {
      const std::size_t end = reach.size();
      for (std::size_t q = start; q < end; ++q)
        for (long k = nl.offsets[reach[q]]; k < nl.offsets[reach[q] + 1]; ++k)
          if (mark[nl.indices[k]] != i) {
            mark[nl.indices[k]] = i;
            reach.push_back(nl.indices[k]);
          }
      start = end;
    }
    cols.clear();
    for (int j : reach) block(j, cols);
    std::sort(cols.begin(), cols.end());
    std::vector<int> rows;
    block(i, rows);
    for (int r : rows) pat.offsets[r + 1] = static_cast<long>(cols.size());
    // Rows of one particle are consecutive in the state: append their column lists in order.
    for (std::size_t q = 0; q < rows.size(); ++q) pat.indices.insert(pat.indices.end(), cols.begin(), cols.end());
  }
  for (int r = 0; r < m_size; ++r) pat.offsets[r + 1] += pat.offsets[r];
  return pat;
}

}  // namespace sphstab
