#include "sphstab/operators/ismail_boundary.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace sphstab {

EtaBoundary1D::EtaBoundary1D(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h, int boundary,
                             std::vector<int> targets, BoundaryCondition condition, double normal)
    : m_boundary(boundary), m_size(particles.size()), m_targets(std::move(targets)) {
  if (boundary < 0 || boundary >= m_size) throw std::invalid_argument("EtaBoundary1D: boundary index out of range");
  for (int q : m_targets)
    if (q == boundary)
      throw std::invalid_argument("EtaBoundary1D: the boundary particle cannot be a target (2.39: 0 < |x_b - x_q|)");
  init(particles, kernel, h, particles.x(boundary, 0), condition, normal);
}

EtaBoundary1D::EtaBoundary1D(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h, double boundary_point,
                             std::vector<int> targets, BoundaryCondition condition, double normal)
    : m_size(particles.size()), m_targets(std::move(targets)) {
  if (!std::isfinite(boundary_point)) throw std::invalid_argument("EtaBoundary1D: boundary point must be finite");
  init(particles, kernel, h, boundary_point, condition, normal);
}

void EtaBoundary1D::init(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h, double xb,
                         BoundaryCondition condition, double normal) {
  const std::string name = "EtaBoundary1D: ";
  if (!(h > 0)) throw std::invalid_argument(name + "h must be > 0");
  if (std::abs(normal) != 1.0) throw std::invalid_argument(name + "normal must be +1 or -1");
  if (m_targets.empty()) throw std::invalid_argument(name + "no target particles (give the ghosts beyond b)");
  const double radius = kernel.support_radius(h);
  const bool neumann = condition == BoundaryCondition::Neumann;
  auto dw = [&](int q) {  // dW(x_b - x_q)/dx_b
    const double d = xb - particles.x(q, 0), r = std::abs(d);
    return r > 0 ? kernel.d1(r, h) * d / r : 0.0;
  };
  double scale = 0;
  for (int q = 0; q < m_size; ++q) {
    const double r = std::abs(xb - particles.x(q, 0));
    if (r >= radius) continue;
    m_cover.push_back(q);
    scale += std::pow(kernel.value(r, h), 2) * particles.volume[q];
  }
  m_weight.resize(static_cast<Eigen::Index>(m_cover.size()));
  for (std::size_t k = 0; k < m_cover.size(); ++k) {
    const int q = m_cover[k];
    m_weight[k] = (neumann ? normal * dw(q) : kernel.value(std::abs(xb - particles.x(q, 0)), h)) * particles.volume[q];
  }
  m_shape.resize(static_cast<Eigen::Index>(m_targets.size()));
  std::vector<char> seen(m_size, 0);
  for (std::size_t k = 0; k < m_targets.size(); ++k) {
    const int q = m_targets[k];
    if (q < 0 || q >= m_size) throw std::invalid_argument(name + "target index out of range");
    if (seen[q]++) throw std::invalid_argument(name + "duplicate target " + std::to_string(q));
    const double r = std::abs(xb - particles.x(q, 0));
    if (r >= radius) throw std::invalid_argument(name + "target " + std::to_string(q) + " outside the support of b");
    m_shape[k] = kernel.value(r, h);
    m_denominator += m_shape[k] * (neumann ? normal * dw(q) : m_shape[k]) * particles.volume[q];
  }
  if (!(std::abs(m_denominator) > 1e-12 * scale))
    throw std::invalid_argument(name + "denominator " + std::to_string(m_denominator) +
                                " vanishes (a symmetric correction set? use the one-sided ghosts)");
}

double EtaBoundary1D::value(const Eigen::VectorXd& f) const {
  if (f.size() != m_size) throw std::invalid_argument("EtaBoundary1D: field size != particle count");
  double s = 0;
  for (std::size_t k = 0; k < m_cover.size(); ++k) s += f[m_cover[k]] * m_weight[k];
  return s;
}

double EtaBoundary1D::apply(Eigen::VectorXd& f, double prescribed) const {
  const double eta = (prescribed - value(f)) / m_denominator;
  for (std::size_t k = 0; k < m_targets.size(); ++k) f[m_targets[k]] += eta * m_shape[k];
  return eta;
}

ModifiedMatrixDirichlet::ModifiedMatrixDirichlet(const SparseMatrix<>& w, std::vector<int> constrained)
    : m_constrained(std::move(constrained)) {
  const std::string name = "ModifiedMatrixDirichlet: ";
  const int n = static_cast<int>(w.rows());
  if (w.cols() != n) throw std::invalid_argument(name + "W must be square");
  if (m_constrained.empty()) throw std::invalid_argument(name + "no constrained particles");
  m_is_constrained.assign(n, 0);
  std::vector<int> slot(n, -1);
  for (std::size_t k = 0; k < m_constrained.size(); ++k) {
    const int c = m_constrained[k];
    if (c < 0 || c >= n) throw std::invalid_argument(name + "constrained index out of range");
    if (m_is_constrained[c]++) throw std::invalid_argument(name + "duplicate constrained index " + std::to_string(c));
    slot[c] = static_cast<int>(k);
  }
  const int m = static_cast<int>(m_constrained.size());
  std::vector<Eigen::Triplet<double>> cc, ci;
  for (int k = 0; k < m; ++k)
    for (SparseMatrix<>::InnerIterator it(w, m_constrained[k]); it; ++it)
      (m_is_constrained[it.col()] ? cc : ci)
          .emplace_back(k, m_is_constrained[it.col()] ? slot[it.col()] : static_cast<int>(it.col()), it.value());
  Eigen::SparseMatrix<double> a(m, m);
  a.setFromTriplets(cc.begin(), cc.end());
  m_w_c.resize(m, n);
  m_w_c.setFromTriplets(ci.begin(), ci.end());
  m_lu = std::make_shared<Eigen::SparseLU<Eigen::SparseMatrix<double>>>();
  m_lu->analyzePattern(a);
  m_lu->factorize(a);
  bool ok = m_lu->info() == Eigen::Success;
  if (ok) {  // a zero pivot that round-off made tiny: check a solve
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m), x = m_lu->solve(ones);
    ok = x.allFinite() && (a * x - ones).norm() <= 1e-8 * std::sqrt(static_cast<double>(m));
  }
  if (!ok)
    throw std::invalid_argument(name + "the constrained block W_CC (" + std::to_string(m) +
                                " particles) is singular: duplicate positions or zero volumes in the constrained set?");
}

void ModifiedMatrixDirichlet::apply(Eigen::VectorXd& f, const Eigen::VectorXd& prescribed) const {
  if (f.size() != m_w_c.cols()) throw std::invalid_argument("ModifiedMatrixDirichlet: field size != particle count");
  if (prescribed.size() != static_cast<Eigen::Index>(m_constrained.size()))
    throw std::invalid_argument("ModifiedMatrixDirichlet: one prescribed value per constrained particle expected");
  const Eigen::VectorXd rhs = prescribed - m_w_c * f;  // m_w_c has no constrained columns
  const Eigen::VectorXd fc = m_lu->solve(rhs);
  for (std::size_t k = 0; k < m_constrained.size(); ++k) f[m_constrained[k]] = fc[static_cast<Eigen::Index>(k)];
}

}  // namespace sphstab
