// RateFormScheme<Dim> (forms/rate_form.hpp): the option parsers and the scheme's set-up members for
// Dim = 1 and 2. The rates themselves (evaluate, absorb, rate) are in rate_form/evaluate.hpp, instantiated by
// rate_form_rate_*.cpp, one dimension and scalar per translation unit so that they compile side by side.
#include "sphstab/forms/rate_form.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "rate_form/dispatch.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/named_values.hpp"

namespace sphstab {

constexpr NamedValue<ContinuityForm> kContinuityNames[] = {{ContinuityForm::Summation, "summation"},
                                                           {ContinuityForm::Divergence, "divergence"}};
constexpr NamedValue<ViscositySwitch> kViscositySwitchNames[] = {
    {ViscositySwitch::Off, "off"}, {ViscositySwitch::Compression, "compression"}, {ViscositySwitch::Always, "always"}};
constexpr NamedValue<RateFormGradient> kGradientNames[] = {{RateFormGradient::Plain, "plain"},
                                                           {RateFormGradient::Ncsph, "ncsph"}};
constexpr NamedValue<RateFormMomentum> kMomentumNames[] = {{RateFormMomentum::Symmetric, "symmetric"},
                                                           {RateFormMomentum::Antisymmetric, "antisymmetric"},
                                                           {RateFormMomentum::Cij, "cij"},
                                                           {RateFormMomentum::StabilisedSph, "ssph"}};
constexpr NamedValue<PairLoop> kPairLoopNames[] = {{PairLoop::Rows, "rows"}, {PairLoop::Pairs, "pairs"}};

ContinuityForm parse_continuity_form(const std::string& name) {
  return parse_named(name, kContinuityNames, "continuity form");
}
ViscositySwitch parse_viscosity_switch(const std::string& name) {
  return parse_named(name, kViscositySwitchNames, "viscosity switch");
}
RateFormGradient parse_rate_form_gradient(const std::string& name) {
  return parse_named(name, kGradientNames, "rate-form gradient");
}
RateFormMomentum parse_rate_form_momentum(const std::string& name) {
  return parse_named(name, kMomentumNames, "rate-form momentum");
}
PairLoop parse_pair_loop(const std::string& name) { return parse_named(name, kPairLoopNames, "pair loop"); }

using rate_form_detail::uses_local_means;

template <int Dim>
RateFormScheme<Dim>::RateFormScheme(std::shared_ptr<const Discretisation<Dim>> disc, const ElasticMaterial& material,
                                    const RateFormOptions& options, double density, const Eigen::VectorXd& deviator)
    : m_disc(std::move(disc)), m_material(material), m_options(options) {
  const char* who = "RateFormScheme";
  if (!m_disc) throw std::invalid_argument("RateFormScheme: null discretisation");
  m_material.validate(who, ShearModulusRule::NonNegative);  // mu = 0: a fluid (the EOS alone)
  m_density = std::isnan(density) ? material.density() : density;
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
    throw std::invalid_argument(
        "RateFormScheme: bulk_viscosity_quadratic and bulk_viscosity_linear must be finite and "
        ">= 0 (got " +
        format_number(options.bulk_viscosity_quadratic) + ", " + format_number(options.bulk_viscosity_linear) + ")");
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
      s[m_rho_off[i]] = m_material.density();
      s.segment(m_rho_off[i] + 1, kStress).setConstant(m_material.bulk_modulus());
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

template class RateFormScheme<1>;
template class RateFormScheme<2>;

}  // namespace sphstab
