#include "sphstab/forms/total_lagrangian.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sphstab {

TotalLagrangianForm2D::TotalLagrangianForm2D(std::shared_ptr<const Discretisation<2>> discretisation,
                                             const ElasticMaterial& material, const PreStrain& prestrain)
    : m_disc(std::move(discretisation)), m_material(material), m_prestrain(prestrain) {
  if (!m_disc) throw std::invalid_argument("TotalLagrangianForm2D: discretisation is null");
  m_material.validate("TotalLagrangianForm2D");
  if (!std::isfinite(prestrain.strain))
    throw std::invalid_argument("TotalLagrangianForm2D: pre-strain must be finite (got " +
                                std::to_string(prestrain.strain) + ")");
  for (int f = 0; f < m_disc->free_count(); ++f)
    if (m_disc->free[f] != f)
      throw std::invalid_argument("TotalLagrangianForm2D: the free particles must come first (lattice ordering)");
  LinearElasticOptions opt;
  opt.material = material;
  opt.gradient = StrainGradient::Minus;
  opt.divergence = StressDivergence::Plus;
  opt.frame = LagrangianFrame::Total;
  m_sph = std::make_shared<const LinearElasticSph<2>>(m_disc->particles, m_disc->kernel, m_disc->h, opt);
  compute_offset();
}

void TotalLagrangianForm2D::compute_offset() {
  // a0_i = (1/rho) sum_j (sigma0 + sigma0) G0_ij = (2/rho) sigma0 . (G0 1)_i
  const Discretisation<2>& d = *m_disc;
  auto ops = assemble_operators<2, double>(d.particles, d.neighbours, d.kernel, d.h,
                                           {.kernel = false, .gradient = true, .hessian = false});
  const Eigen::Matrix2d s0 = m_prestrain.stress(m_material);
  m_a0.setZero(d.dofs());
  for (int f = 0; f < d.free_count(); ++f) {
    const int i = d.free[f];
    Eigen::Vector2d g = Eigen::Vector2d::Zero();
    for (int b = 0; b < 2; ++b)
      for (SparseMatrix<>::InnerIterator it(ops.G[b], i); it; ++it) g[b] += it.value();
    const Eigen::Vector2d a = (2.0 / m_material.density()) * (s0 * g);
    m_a0[2 * f] = a[0];
    m_a0[2 * f + 1] = a[1];
  }
}

std::string TotalLagrangianForm2D::name() const {
  std::ostringstream s;
  s << "tl2d/" << (m_prestrain.kind == PreStrainKind::Isotropic ? "iso" : "uniaxial-x") << "/e=" << m_prestrain.strain;
  return s.str();
}

void TotalLagrangianForm2D::acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const {
  if (u.size() != dofs())
    throw std::invalid_argument("TotalLagrangianForm2D: displacement has " + std::to_string(u.size()) +
                                " entries, expected " + std::to_string(dofs()));
  a.resize(dofs());
  m_sph->acceleration(u, a);
  a += m_a0;
}

void TotalLagrangianForm2D::acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const {
  if (u.size() != dofs())
    throw std::invalid_argument("TotalLagrangianForm2D: displacement has " + std::to_string(u.size()) +
                                " entries, expected " + std::to_string(dofs()));
  Eigen::VectorXd ar(dofs()), ai(dofs());
  m_sph->acceleration(u.real(), ar);
  m_sph->acceleration(u.imag(), ai);
  a.resize(dofs());
  a.real() = ar + m_a0;
  a.imag() = ai;
}

std::unique_ptr<ForceFunction> TotalLagrangianForm2D::with_load(double load) const {
  if (!std::isfinite(load))
    throw std::invalid_argument("TotalLagrangianForm2D::with_load: pre-strain must be finite (got " +
                                std::to_string(load) + ")");
  auto copy = std::make_unique<TotalLagrangianForm2D>(*this);
  copy->m_prestrain.strain = load;
  copy->compute_offset();
  return copy;
}

SparsityPattern TotalLagrangianForm2D::dof_pattern() const {
  return coupling_pattern(m_disc->neighbours, m_disc->free_slot, 2, 2);
}

Eigen::VectorXd TotalLagrangianForm2D::dof_mass() const {
  Eigen::VectorXd m(dofs());
  for (int f = 0; f < m_disc->free_count(); ++f)
    m[2 * f] = m[2 * f + 1] = m_material.density() * m_disc->particles.volume[m_disc->free[f]];
  return m;
}

double TotalLagrangianForm2D::strain_energy(const Eigen::VectorXd& u) const {
  // sum_i V_i sigma0 : (grad u)_i = -(M a0) . u (the pre-stress work; see the header)
  return m_sph->strain_energy(u) - dof_mass().cwiseProduct(m_a0).dot(u);
}

std::complex<double> TotalLagrangianForm2D::strain_energy(const Eigen::VectorXcd& u) const {
  // Quadratic part Q(u) = 1/2 u^T K u: Q(x + i y) = Q(x) - Q(y) + i x^T K y. The bilinear term is evaluated as
  // (Q(x + t y) - Q(x - t y)) / (2 t) with t = |x|/|y|, exact for a quadratic Q and free of the cancellation that
  // a complex step (|y| ~ 1e-30) would cause. The pre-stress part is linear: l.x + i l.y.
  const Eigen::VectorXd x = u.real(), y = u.imag();
  const Eigen::VectorXd l = -dof_mass().cwiseProduct(m_a0);
  const double nx = x.norm(), ny = y.norm();
  double xky = 0;
  if (nx > 0 && ny > 0) {
    const double t = nx / ny;
    xky = (m_sph->strain_energy(x + t * y) - m_sph->strain_energy(x - t * y)) / (2 * t);
  }
  return {m_sph->strain_energy(x) - m_sph->strain_energy(y) + l.dot(x), xky + l.dot(y)};
}

}  // namespace sphstab
