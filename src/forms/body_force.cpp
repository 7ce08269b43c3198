#include "sphstab/forms/body_force.hpp"

#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

BodyForce::BodyForce(std::shared_ptr<const ForceFunction> inner, const Eigen::VectorXd& acceleration)
    : m_inner(std::move(inner)), m_b(acceleration) {
  if (!m_inner) throw std::invalid_argument("BodyForce: inner force function is null");
  const int d = m_inner->dim();
  if (m_b.size() != d)
    throw std::invalid_argument("BodyForce: acceleration has " + std::to_string(m_b.size()) + " entries, expected " +
                                std::to_string(d) + " (one per component)");
  for (int c = 0; c < d; ++c)
    if (!std::isfinite(m_b[c]))
      throw std::invalid_argument("BodyForce: acceleration component " + std::to_string(c) + " is not finite (got " +
                                  format_number(m_b[c]) + ")");
  m_bdof.resize(m_inner->dofs());
  for (int k = 0; k < m_bdof.size(); ++k) m_bdof[k] = m_b[k % d];
  m_mass = m_inner->dof_mass();
}

std::string BodyForce::name() const {
  std::string s = m_inner->name() + "+body-force(";
  for (int c = 0; c < m_b.size(); ++c) s += (c ? "," : "") + format_number(m_b[c]);
  return s + ")";
}

void BodyForce::acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const {
  m_inner->acceleration(u, a);
  a += m_bdof;
}

void BodyForce::acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const {
  m_inner->acceleration(u, a);
  a += m_bdof.cast<std::complex<double>>();
}

std::unique_ptr<ForceFunction> BodyForce::with_load(double load) const {
  return std::make_unique<BodyForce>(std::shared_ptr<const ForceFunction>(m_inner->with_load(load)), m_b);
}

double BodyForce::strain_energy(const Eigen::VectorXd& u) const {
  return m_inner->strain_energy(u) - (m_mass.array() * m_bdof.array() * u.array()).sum();
}

std::complex<double> BodyForce::strain_energy(const Eigen::VectorXcd& u) const {
  const Eigen::VectorXd mb = m_mass.cwiseProduct(m_bdof);
  return m_inner->strain_energy(u) - (mb.cast<std::complex<double>>().array() * u.array()).sum();
}

}  // namespace sphstab
