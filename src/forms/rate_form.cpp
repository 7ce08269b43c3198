#include "sphstab/forms/rate_form.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "sphstab/core/format.hpp"
#include "sphstab/models/artificial_stress.hpp"
#include "sphstab/numerics/real_part.hpp"

namespace sphstab {

RateFormMaterial RateFormMaterial::from_youngs(double youngs_modulus, double poisson_ratio, double density) {
  if (!(youngs_modulus > 0) || !std::isfinite(youngs_modulus))
    throw std::invalid_argument("RateFormMaterial: Young's modulus must be finite and > 0 (got " +
                                format_number(youngs_modulus) + ")");
  if (!(poisson_ratio > -1 && poisson_ratio < 0.5))
    throw std::invalid_argument("RateFormMaterial: Poisson's ratio must lie in (-1, 1/2) (got " +
                                format_number(poisson_ratio) + ")");
  RateFormMaterial m{.density = density,
                     .bulk_modulus = youngs_modulus / (3 * (1 - 2 * poisson_ratio)),
                     .shear_modulus = youngs_modulus / (2 * (1 + poisson_ratio))};
  m.validate("RateFormMaterial");
  return m;
}

double RateFormMaterial::sound_speed() const { return std::sqrt(bulk_modulus / density); }
double RateFormMaterial::p_wave_speed() const { return std::sqrt((bulk_modulus + 4 * shear_modulus / 3) / density); }

void RateFormMaterial::validate(const char* who) const {
  const auto ok = [](double v, bool strict) { return std::isfinite(v) && (strict ? v > 0 : v >= 0); };
  if (!ok(density, true) || !ok(bulk_modulus, true) || !ok(shear_modulus, false))
    throw std::invalid_argument(std::string(who) + ": need density > 0, bulk modulus > 0, shear modulus >= 0 (got " +
                                format_number(density) + ", " + format_number(bulk_modulus) + ", " +
                                format_number(shear_modulus) + ")");
}

ContinuityForm parse_continuity_form(const std::string& name) {
  if (name == "summation") return ContinuityForm::Summation;
  if (name == "divergence") return ContinuityForm::Divergence;
  throw std::invalid_argument("unknown continuity form '" + name + "' (valid: summation, divergence)");
}

ViscositySwitch parse_viscosity_switch(const std::string& name) {
  if (name == "off") return ViscositySwitch::Off;
  if (name == "compression") return ViscositySwitch::Compression;
  if (name == "always") return ViscositySwitch::Always;
  throw std::invalid_argument("unknown viscosity switch '" + name + "' (valid: off, compression, always)");
}

RateFormGradient parse_rate_form_gradient(const std::string& name) {
  if (name == "plain") return RateFormGradient::Plain;
  if (name == "ncsph") return RateFormGradient::Ncsph;
  throw std::invalid_argument("unknown rate-form gradient '" + name + "' (valid: plain, ncsph)");
}

RateFormMomentum parse_rate_form_momentum(const std::string& name) {
  if (name == "symmetric") return RateFormMomentum::Symmetric;
  if (name == "antisymmetric") return RateFormMomentum::Antisymmetric;
  if (name == "cij") return RateFormMomentum::Cij;
  if (name == "ssph") return RateFormMomentum::StabilisedSph;
  throw std::invalid_argument("unknown rate-form momentum '" + name + "' (valid: symmetric, antisymmetric, cij, ssph)");
}

namespace {

bool uses_local_means(RateFormMomentum m) { return m == RateFormMomentum::Cij || m == RateFormMomentum::StabilisedSph; }

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
}

template <int Dim>
void RateFormScheme<Dim>::rate(const Eigen::VectorXcd& y, Eigen::VectorXcd& dydt) const {
  evaluate(y, dydt);
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

  // Pair geometry: r_ij (minimum image decided on the real part), |r_ij|^2 and |r_ij|.
  Vec box;
  for (int a = 0; a < Dim; ++a) box[a] = Scalar(p.box_hi[a] - p.box_lo[a]);
  const auto geometry = [&](int i, int j, Vec& r, Scalar& r2, Scalar& rr) {
    r = x[i] - x[j];
    for (int a = 0; a < Dim; ++a)
      if (p.periodic[a]) {
        const double L = p.box_hi[a] - p.box_lo[a], dr = detail::re(r[a]);
        if (dr > 0.5 * L)
          r[a] -= box[a];
        else if (dr < -0.5 * L)
          r[a] += box[a];
      }
    r2 = Scalar(0);
    for (int a = 0; a < Dim; ++a) r2 += r[a] * r[a];
    rr = sqrt(r2);
  };

  // Per-pair arrays only where a pass other than the main loop reads them: the NCSPH gradient (grad W, W, r) and the
  // local means of C_ij / S-SPH (grad W); then also r and r^2 for the viscosity and W for XSPH and artificial
  // stress. The plain symmetric/antisymmetric forms keep no per-pair arrays: the main loop computes grad_i W_ij (and
  // r, r^2, W where the pair terms read them) one row at a time, XSPH computes W_ij where it uses it, with the same
  // operations.
  const bool plain = o.gradient == RateFormGradient::Plain;
  const bool pair_arrays = !plain || uses_local_means(o.momentum);
  const bool viscous = o.viscosity != ViscositySwitch::Off;
  const bool keep_r = pair_arrays && (!plain || viscous), keep_r2 = pair_arrays && viscous;
  const bool keep_w = pair_arrays && (!plain || o.xsph > 0 || o.artificial_stress > 0);
  const long nnz = nl.nonzeros();
  std::vector<Vec>&rij = ws.rij, &grad = ws.grad, &gh = ws.gh;
  std::vector<Scalar>&w = ws.w, &r2s = ws.r2s;
  if (pair_arrays) {
    grad.resize(nnz);
    if (keep_r) rij.resize(nnz);
    if (keep_r2) r2s.resize(nnz);
    if (keep_w) w.resize(nnz);
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
        Scalar r2, rr;
        geometry(i, j, r, r2, rr);
        if (keep_r) rij[k] = r;
        if (keep_r2) r2s[k] = r2;
        if (keep_w) w[k] = kernel.value(rr, h);
        grad[k] = (kernel.d1(rr, h) / rr) * r;
      }
  }

  // Current volumes and the gradient Ghat_ij with V_j included (plain or NCSPH).
  std::vector<Scalar>& vol = ws.vol;
  vol.resize(n);
  for (int i = 0; i < n; ++i) vol[i] = m_mass[i] / rho[i];
  if (pair_arrays) {
    gh.resize(nnz);
    for (int i = 0; i < n; ++i)
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) gh[k] = vol[nl.indices[k]] * grad[k];
  }
  if (o.gradient == RateFormGradient::Ncsph)
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
      if (!Mr.allFinite())
        throw std::domain_error("RateFormScheme: NCSPH moment matrix of particle " + std::to_string(i) +
                                " is not finite (non-finite positions or densities in the state)");
      const Eigen::JacobiSVD<Eigen::Matrix<double, Dim, Dim>> svd(Mr);
      const double smax = svd.singularValues()(0), smin = svd.singularValues()(Dim - 1);
      if (!(smin > 1e-12 * smax))
        throw std::domain_error("RateFormScheme: NCSPH moment matrix of particle " + std::to_string(i) +
                                " is singular (rcond " + format_number(smax > 0 ? smin / smax : 0.0) + ")");
      const Mat Minv_t = M.inverse().transpose();
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) gh[k] = Minv_t * gh[k];
    }

  // XSPH velocity [GMS2001, (3.6)].
  for (int i = 0; i < n; ++i) {
    vhat[i] = v[i];
    if (o.xsph > 0 && m_x_off[i] >= 0 && !is_driven(i))  // fixed particles do not move; driven ones move with v
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        if (j == i) continue;
        Scalar wk;
        if (keep_w) {
          wk = w[k];
        } else {
          Vec r;
          Scalar r2, rr;
          geometry(i, j, r, r2, rr);
          wk = kernel.value(rr, h);
        }
        vhat[i] += (o.xsph * m_mass[j] * wk / (0.5 * (rho[i] + rho[j]))) * (v[j] - v[i]);
      }
  }

  // Stress, artificial stress.
  std::vector<Mat>&sigma = ws.sigma, &R = ws.R;
  sigma.resize(n);
  R.resize(n);
  for (int i = 0; i < n; ++i) {
    const Scalar pressure = K * (rho[i] / rho0 - 1.0);
    Mat s;
    if constexpr (Dim == 1) {
      s(0, 0) = S[i][0];
    } else {
      s << S[i][0], S[i][2], S[i][2], S[i][1];
    }
    sigma[i] = s - pressure * Mat::Identity();
    R[i].setZero();
    if (o.artificial_stress > 0) {
      if constexpr (Dim == 1) {
        if (detail::re(sigma[i](0, 0)) > 0) R[i](0, 0) = -o.artificial_stress * sigma[i](0, 0) / (rho[i] * rho[i]);
      } else {
        const SymmetricTensor2<Scalar> t{sigma[i](0, 0), sigma[i](1, 1), sigma[i](0, 1)};
        const SymmetricTensor2<Scalar> r = artificial_stress(t, rho[i], o.artificial_stress);
        R[i] << r.xx, r.xy, r.xy, r.yy;
      }
    }
  }

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
    for (int i = 0; i < n; ++i) {
      Vec gs = Vec::Zero();
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        row_mean[i] += gh[k];
        gs += grad[k];
      }
      row_mean[i] /= m_counts[i];
      col_mean[i] = (-vol[i] / m_counts[i]) * gs;
    }
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

  dydt.setZero(m_size);
  const double c0 = m_material.sound_speed(), eta2 = 0.01 * h * h;
  for (int i = 0; i < n; ++i) {
    const bool free = m_x_off[i] >= 0;
    if (!free && m_rho_off[i] < 0) continue;
    Mat L = Mat::Zero();
    Scalar drho(0);
    Vec acc = Vec::Zero();
    const Mat si = sigma[i] / (rho[i] * rho[i]);
    // grad_i W_ij (and r_ij, r_ij^2, W_ij where the pair terms read them) of row i: the pair arrays, or computed for
    // this row first, in a short loop of independent pairs, with the same operations.
    const long k0 = nl.offsets[i], k1 = nl.offsets[i + 1];
    const Vec *gp, *rp = nullptr;
    const Scalar *r2p = nullptr, *wp = nullptr;
    if (pair_arrays) {
      gp = grad.data() + k0;
      if (keep_r) rp = rij.data() + k0;
      if (keep_r2) r2p = r2s.data() + k0;
      if (keep_w) wp = w.data() + k0;
    } else {
      const std::size_t len = static_cast<std::size_t>(k1 - k0);
      if (ws.row_grad.size() < len) {
        ws.row_grad.resize(len);
        ws.row_r.resize(len);
        ws.row_r2.resize(len);
        ws.row_w.resize(len);
      }
      Vec* g = ws.row_grad.data();
      Vec* rv = ws.row_r.data();
      Scalar* r2v = ws.row_r2.data();
      Scalar* wv = ws.row_w.data();
      const bool want_w = free && o.artificial_stress > 0;
      for (long k = k0; k < k1; ++k) {
        const int j = nl.indices[k];
        if (j == i) continue;
        Vec r;
        Scalar r2, rr;
        geometry(i, j, r, r2, rr);
        g[k - k0] = (kernel.d1(rr, h) / rr) * r;
        if (viscous) {
          rv[k - k0] = r;
          r2v[k - k0] = r2;
        }
        if (want_w) wv[k - k0] = kernel.value(rr, h);
      }
      gp = g;
      rp = rv;
      r2p = r2v;
      wp = wv;
    }
    for (long k = k0; k < k1; ++k) {
      const int j = nl.indices[k];
      if (j == i) {  // only a corrected gradient has a self term (it makes the rows sum to zero)
        if (free && o.momentum == RateFormMomentum::Symmetric && !plain) acc += (2.0 / rho[i]) * (sigma[i] * gh[k]);
        if (free && o.momentum == RateFormMomentum::Cij)
          acc += (sigma[i] / rho[i]) * (gh[k] - row_mean[i] - col_mean[i] + mean_mean[i]);
        continue;
      }
      const Vec& gk = gp[k - k0];
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
        const Scalar vr = vij.cwiseProduct(rp[k - k0]).sum();
        if (o.viscosity == ViscositySwitch::Always || detail::re(vr) < 0) {
          const Scalar mu_ij = h * vr / (r2p[k - k0] + eta2), rho_bar = 0.5 * (rho[i] + rho[j]);
          Scalar pi = -o.viscosity_alpha * c0 * mu_ij;
          if (o.viscosity == ViscositySwitch::Compression) pi += o.viscosity_beta * mu_ij * mu_ij;
          pair -= (pi / rho_bar) * Mat::Identity();
        }
      }
      if (o.artificial_stress > 0) {
        const Scalar f = artificial_stress_pair_factor<Scalar>(wp[k - k0], m_w_dp, o.artificial_stress_exponent);
        pair += f * (R[i] + R[j]);
      }
      const Mat sj = sigma[j] / (rho[j] * rho[j]);
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
    if (o.continuity == ContinuityForm::Divergence) drho = -rho[i] * L.trace();
    if (free) {
      dydt.template segment<Dim>(m_x_off[i]) = vhat[i];
      if (is_driven(i))  // the prescribed acceleration replaces the SPH force
        dydt.template segment<Dim>(m_x_off[i] + Dim) = m_driven_acc[m_driven_slot[i]].template cast<Scalar>();
      else
        dydt.template segment<Dim>(m_x_off[i] + Dim) = acc;
    }
    if (m_rho_off[i] < 0) continue;
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

template class RateFormScheme<1>;
template class RateFormScheme<2>;

}  // namespace sphstab
