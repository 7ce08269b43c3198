#include "sphstab/system/semi_discrete_system.hpp"

#include <stdexcept>
#include <string>

namespace sphstab {

namespace {

template <class Vector>
void second_order_rate(const ForceFunction& force, const Vector& y, Vector& dydt) {
  const int n = force.dofs();
  if (y.size() != 2 * n)
    throw std::invalid_argument("SecondOrderForm::rate: y has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(2 * n));
  Vector a;
  force.acceleration(Vector(y.head(n)), a);
  dydt.resize(2 * n);
  dydt.head(n) = y.tail(n);
  dydt.tail(n) = a;
}

}  // namespace

SecondOrderForm::SecondOrderForm(std::shared_ptr<const ForceFunction> force) : m_force(std::move(force)) {
  if (!m_force) throw std::invalid_argument("SecondOrderForm: null force function");
}

void SecondOrderForm::rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) const {
  second_order_rate(*m_force, y, dydt);
}

void SecondOrderForm::rate(const Eigen::VectorXcd& y, Eigen::VectorXcd& dydt) const {
  second_order_rate(*m_force, y, dydt);
}

SparsityPattern SecondOrderForm::pattern() const {
  // [[0, I], [P, 0]]: u' reads v (identity block), v' = a(u) reads u through the force's pattern P.
  const SparsityPattern p = m_force->dof_pattern();
  const int n = m_force->dofs();
  SparsityPattern out;
  out.rows = out.cols = 2 * n;
  out.offsets.assign(2 * n + 1, 0);
  out.indices.reserve(n + p.nonzeros());
  for (int r = 0; r < n; ++r) {
    out.indices.push_back(n + r);
    out.offsets[r + 1] = static_cast<long>(out.indices.size());
  }
  for (int r = 0; r < n; ++r) {
    for (long k = p.offsets[r]; k < p.offsets[r + 1]; ++k) out.indices.push_back(p.indices[k]);
    out.offsets[n + r + 1] = static_cast<long>(out.indices.size());
  }
  return out;
}

}  // namespace sphstab
