#include "sphstab/forms/rate_form.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

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
std::string RateFormScheme<Dim>::name() const {
  std::string s = "rate-form-" + std::to_string(Dim) + "d(" +
                  (m_options.continuity == ContinuityForm::Summation ? "summation" : "divergence");
  if (m_options.xsph > 0) s += ", xsph " + format_number(m_options.xsph);
  if (m_options.viscosity != ViscositySwitch::Off)
    s += std::string(", viscosity ") +
         (m_options.viscosity == ViscositySwitch::Compression ? "compression" : "always") + " " +
         format_number(m_options.viscosity_alpha) + "/" + format_number(m_options.viscosity_beta);
  if (m_options.artificial_stress > 0) s += ", artificial stress " + format_number(m_options.artificial_stress);
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
  double m = m_density;
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

  // Unpack: fixed particles sit at their initial positions at rest; frozen ones keep the initial rho and S.
  std::vector<Vec> x(n), v(n), vhat(n);
  std::vector<Scalar> rho(n);
  std::vector<Eigen::Matrix<Scalar, kStress, 1>> S(n);
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

  // Pair geometry, once: r_ij (minimum image decided on the real part), W_ij and grad_i W_ij.
  const long nnz = nl.nonzeros();
  std::vector<Vec> rij(nnz), grad(nnz);
  std::vector<Scalar> w(nnz), r2s(nnz);
  Vec box;
  for (int a = 0; a < Dim; ++a) box[a] = Scalar(p.box_hi[a] - p.box_lo[a]);
  for (int i = 0; i < n; ++i)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (j == i) {
        rij[k].setZero();
        grad[k].setZero();
        w[k] = Scalar(kernel.value(0.0, h));
        r2s[k] = Scalar(0);
        continue;
      }
      Vec r = x[i] - x[j];
      for (int a = 0; a < Dim; ++a)
        if (p.periodic[a]) {
          const double L = p.box_hi[a] - p.box_lo[a], dr = detail::re(r[a]);
          if (dr > 0.5 * L)
            r[a] -= box[a];
          else if (dr < -0.5 * L)
            r[a] += box[a];
        }
      Scalar r2(0);
      for (int a = 0; a < Dim; ++a) r2 += r[a] * r[a];
      const Scalar rr = sqrt(r2);
      rij[k] = r;
      r2s[k] = r2;
      w[k] = kernel.value(rr, h);
      grad[k] = (kernel.d1(rr, h) / rr) * r;
    }

  // XSPH velocity [GMS2001, (3.6)].
  for (int i = 0; i < n; ++i) {
    vhat[i] = v[i];
    if (o.xsph > 0 && m_x_off[i] >= 0)  // fixed particles do not move
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        if (j == i) continue;
        vhat[i] += (o.xsph * m_mass[j] * w[k] / (0.5 * (rho[i] + rho[j]))) * (v[j] - v[i]);
      }
  }

  // Stress, artificial stress.
  std::vector<Mat> sigma(n), R(n);
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

  dydt.setZero(m_size);
  const double c0 = m_material.sound_speed(), eta2 = 0.01 * h * h;
  for (int i = 0; i < n; ++i) {
    const bool free = m_x_off[i] >= 0;
    if (!free && m_rho_off[i] < 0) continue;
    Mat L = Mat::Zero();
    Scalar drho(0);
    Vec acc = Vec::Zero();
    const Mat si = sigma[i] / (rho[i] * rho[i]);
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (j == i) continue;
      const Vec& g = grad[k];
      const Vec dv = vhat[j] - vhat[i];
      L += (m_mass[j] / rho[j]) * dv * g.transpose();  // L^ab = dv^a/dx^b  [GMS2001, (3.10)]
      if (o.continuity == ContinuityForm::Summation)
        drho -= m_mass[j] * dv.cwiseProduct(g).sum();  // not dot(): it conjugates complex steps
      if (!free) continue;
      Mat bracket = si + sigma[j] / (rho[j] * rho[j]);
      if (o.viscosity != ViscositySwitch::Off) {
        const Vec vij = v[i] - v[j];
        const Scalar vr = vij.cwiseProduct(rij[k]).sum();
        if (o.viscosity == ViscositySwitch::Always || detail::re(vr) < 0) {
          const Scalar mu_ij = h * vr / (r2s[k] + eta2), rho_bar = 0.5 * (rho[i] + rho[j]);
          Scalar pi = -o.viscosity_alpha * c0 * mu_ij;
          if (o.viscosity == ViscositySwitch::Compression) pi += o.viscosity_beta * mu_ij * mu_ij;
          bracket -= (pi / rho_bar) * Mat::Identity();
        }
      }
      if (o.artificial_stress > 0) {
        const Scalar f = artificial_stress_pair_factor<Scalar>(w[k], m_w_dp, o.artificial_stress_exponent);
        bracket += f * (R[i] + R[j]);
      }
      acc += m_mass[j] * (bracket * g);
    }
    if (o.continuity == ContinuityForm::Divergence) drho = -rho[i] * L.trace();
    if (free) {
      dydt.template segment<Dim>(m_x_off[i]) = vhat[i];
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
  const int n = m_disc->size(), hops = m_options.xsph > 0 ? 2 : 1;
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
