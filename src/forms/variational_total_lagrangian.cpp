#include "sphstab/forms/variational_total_lagrangian.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "form_detail.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/numerics/real_part.hpp"
#include "total_lagrangian_detail.hpp"

namespace sphstab {

namespace {
const char* kVariationalWho = "VariationalTotalLagrangian";
}

template <int Dim>
VariationalTotalLagrangian<Dim>::VariationalTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                                                            std::shared_ptr<const HyperelasticModel<Dim>> material,
                                                            const Eigen::VectorXd& density,
                                                            std::shared_ptr<const GradientProvider<Dim>> gradient,
                                                            HourglassOptions hourglass)
    : HyperelasticBody<Dim>(std::move(discretisation), std::move(material), density, kVariationalWho),
      m_gradient(std::move(gradient)) {
  const Discretisation<Dim>& d = *m_disc;
  const int N = d.size();
  if (m_gradient && !m_gradient->keeps_pattern())
    throw std::invalid_argument(std::string(kVariationalWho) + ": gradient '" + m_gradient->name() +
                                "' is non-local (dense); use a local correction such as ncsph");
  // reference operators, once at X
  const OperatorRequest request = detail::form_request<Dim>(m_gradient.get(), false);
  Operators<Dim> ops = assemble_operators<Dim, double>(d.particles, d.neighbours, d.kernel, d.h, request);
  std::array<SparseMatrix<>, Dim> K;
  const Positions<Dim> X = d.particles.x;
  if (!detail::corrected_gradient<Dim, double>(m_gradient.get(), d, X, ops, K))
    for (int b = 0; b < Dim; ++b) K[b] = ops.G[b];
  m_rowsum.setZero(N, Dim);
  for (int b = 0; b < Dim; ++b)
    for (int i = 0; i < N; ++i)
      for (SparseMatrix<>::InnerIterator it(K[b], i); it; ++it) m_rowsum(i, b) += it.value();
  m_K = std::make_shared<const std::array<SparseMatrix<>, Dim>>(std::move(K));
  m_hg = HourglassControl<Dim>(d, hourglass.coefficient > 0 ? m_material->material().young() : 0.0, m_rho, hourglass,
                               kVariationalWho);
}

template <int Dim>
std::string VariationalTotalLagrangian<Dim>::name() const {
  std::string s =
      "tl-variational/" + m_material->name() + "/" + (m_gradient ? m_gradient->name() : std::string("plain"));
  if (m_hg.active())
    s += "/hourglass-" + std::string(m_hg.options().projection == HourglassProjection::Full ? "full-" : "") +
         format_number(m_hg.options().coefficient);
  return s;
}

template <int Dim>
std::unique_ptr<ForceFunction> VariationalTotalLagrangian<Dim>::with_load(double load) const {
  this->check_no_load(load);
  return std::make_unique<VariationalTotalLagrangian<Dim>>(*this);
}

template <int Dim>
SparsityPattern VariationalTotalLagrangian<Dim>::dof_pattern() const {
  // a_k reads P_i for i a neighbour of k, and P_i reads u through row i of K: two hops
  return coupling_pattern(m_disc->neighbours, m_disc->free_slot, Dim, 2);
}

template <int Dim>
template <class Scalar>
void VariationalTotalLagrangian<Dim>::evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                               Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  const Discretisation<Dim>& d = *m_disc;
  // Scratch kept between calls (the header's thread-safety note): no allocation once sized.
  Workspace<Scalar>& ws = this->template workspace<Scalar>();
  std::vector<Deformation<Scalar, Dim>>& F = ws.F;
  deformation(u, ws.u, F);
  // f_k^a = -sum_i V_i P_i^{ab} K^b_ik + V_k P_k^{ab} rowsum_k^b, accumulated row by row of K
  Eigen::Matrix<Scalar, Eigen::Dynamic, Dim>& force = ws.force;
  force.setZero(d.size(), Dim);
  for (int i : m_active) {
    const Deformation<Scalar, Dim> VP = m_material->stress(F[i]) * d.particles.volume[i];
    for (int b = 0; b < Dim; ++b) {
      for (typename SparseMatrix<>::InnerIterator it((*m_K)[b], i); it; ++it) {
        const int k = static_cast<int>(it.col());
        for (int c = 0; c < Dim; ++c) force(k, c) -= VP(c, b) * it.value();
      }
      for (int c = 0; c < Dim; ++c) force(i, c) += VP(c, b) * m_rowsum(i, b);
    }
  }
  a.resize(d.dofs());
  for (int f = 0; f < d.free_count(); ++f) {
    const int k = d.free[f];
    const double m = m_rho[k] * d.particles.volume[k];
    for (int c = 0; c < Dim; ++c) a[f * Dim + c] = force(k, c) / m;
  }
  if (m_hg.active()) m_hg.add(d, ws.u, F, a);  // [Ganzenmueller2015] with this form's F (forms/hourglass_control.hpp)
}

template <int Dim>
void VariationalTotalLagrangian<Dim>::acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const { evaluate(u, a); }
template <int Dim>
void VariationalTotalLagrangian<Dim>::acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const { evaluate(u, a); }

template class VariationalTotalLagrangian<1>;
template class VariationalTotalLagrangian<2>;

}  // namespace sphstab
