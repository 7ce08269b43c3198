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
const char* kWho = "VariationalTotalLagrangian";
}

template <int Dim>
VariationalTotalLagrangian<Dim>::VariationalTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                                                            std::shared_ptr<const HyperelasticModel<Dim>> material,
                                                            const Eigen::VectorXd& density,
                                                            std::shared_ptr<const GradientProvider<Dim>> gradient,
                                                            HourglassOptions hourglass)
    : m_disc(std::move(discretisation)), m_material(std::move(material)), m_gradient(std::move(gradient)) {
  if (!m_disc) throw std::invalid_argument(std::string(kWho) + ": discretisation is null");
  if (!m_material) throw std::invalid_argument(std::string(kWho) + ": material is null");
  const Discretisation<Dim>& d = *m_disc;
  const int N = d.size();
  m_rho = detail::particle_density(density, N, kWho);
  if (m_gradient && !m_gradient->keeps_pattern())
    throw std::invalid_argument(std::string(kWho) + ": gradient '" + m_gradient->name() +
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
  std::vector<char> is_active(N, 0);
  for (int i : d.free)
    for (long k = d.neighbours.offsets[i]; k < d.neighbours.offsets[i + 1]; ++k) is_active[d.neighbours.indices[k]] = 1;
  for (int i = 0; i < N; ++i)
    if (is_active[i]) m_active.push_back(i);
  m_fixed_u = Eigen::VectorXd::Zero(Dim * (N - d.free_count()));
  m_hg = HourglassControl<Dim>(d, hourglass.coefficient > 0 ? m_material->lame().young() : 0.0, m_rho, hourglass, kWho);
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
  if (load != 0)
    throw std::invalid_argument(std::string(kWho) + "::with_load: no affine load (got " + format_number(load) +
                                "); prescribe displacements with set_fixed_displacement");
  return std::make_unique<VariationalTotalLagrangian<Dim>>(*this);
}

template <int Dim>
SparsityPattern VariationalTotalLagrangian<Dim>::dof_pattern() const {
  // a_k reads P_i for i a neighbour of k, and P_i reads u through row i of K: two hops
  return coupling_pattern(m_disc->neighbours, m_disc->free_slot, Dim, 2);
}

template <int Dim>
Eigen::VectorXd VariationalTotalLagrangian<Dim>::dof_mass() const {
  return detail::lumped_dof_mass(*m_disc, m_rho);
}

template <int Dim>
void VariationalTotalLagrangian<Dim>::set_fixed_displacement(const Eigen::VectorXd& d) {
  detail::check_fixed_displacement(d, m_fixed_u.size(), kWho);
  m_fixed_u = d;
}

template <int Dim>
template <class Scalar>
typename VariationalTotalLagrangian<Dim>::template Workspace<Scalar>& VariationalTotalLagrangian<Dim>::workspace()
    const {
  if constexpr (std::is_same_v<Scalar, double>)
    return m_work_real;
  else
    return m_work_complex;
}

template <int Dim>
template <class Scalar>
void VariationalTotalLagrangian<Dim>::deformation(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                                  Positions<Dim, Scalar>& uall,
                                                  std::vector<Deformation<Scalar, Dim>>& F) const {
  const Discretisation<Dim>& d = *m_disc;
  detail::full_displacement_into<Dim, Scalar>(d, u, m_fixed_u, kWho, uall);
  F.assign(d.size(), Deformation<Scalar, Dim>::Constant(Scalar(std::numeric_limits<double>::quiet_NaN())));
  for (int i : m_active) {
    Deformation<Scalar, Dim> f = Deformation<Scalar, Dim>::Identity();
    for (int b = 0; b < Dim; ++b)
      for (typename SparseMatrix<>::InnerIterator it((*m_K)[b], i); it; ++it) {
        const int j = static_cast<int>(it.col());
        for (int a = 0; a < Dim; ++a) f(a, b) += Scalar(uall(j, a) - uall(i, a)) * it.value();
      }
    const double J = detail::re(Scalar(f.determinant()));
    if (!(J > 0))
      throw std::invalid_argument(std::string(kWho) + ": J = det F = " + format_number(J) + " <= 0 at particle " +
                                  std::to_string(i) + " (inverted; reduce the load or the time step)");
    F[i] = f;
  }
}

template <int Dim>
template <class Scalar>
void VariationalTotalLagrangian<Dim>::evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                               Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  const Discretisation<Dim>& d = *m_disc;
  // Scratch kept between calls (the header's thread-safety note): no allocation once sized.
  Workspace<Scalar>& ws = workspace<Scalar>();
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
template <class Scalar>
Scalar VariationalTotalLagrangian<Dim>::energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const {
  Workspace<Scalar>& ws = workspace<Scalar>();
  std::vector<Deformation<Scalar, Dim>>& F = ws.F;
  deformation(u, ws.u, F);
  Scalar U(0);
  for (int i : m_active) U += m_disc->particles.volume[i] * m_material->energy(F[i]);
  return U;
}

template <int Dim>
Eigen::MatrixXd VariationalTotalLagrangian<Dim>::deformation_gradients(const Eigen::VectorXd& u) const {
  Positions<Dim> uall;
  std::vector<Deformation<double, Dim>> F;
  deformation(u, uall, F);
  return detail::deformation_table<Dim>(F);
}

template <int Dim>
Eigen::MatrixXd VariationalTotalLagrangian<Dim>::stresses(const Eigen::VectorXd& u) const {
  Positions<Dim> uall;
  std::vector<Deformation<double, Dim>> F;
  deformation(u, uall, F);
  return detail::stress_table<Dim>(*m_material, F, m_active);
}

template class VariationalTotalLagrangian<1>;
template class VariationalTotalLagrangian<2>;
// The member templates the header's inline overrides call (acceleration, strain_energy): instantiated here, so the
// symbols exist whether or not the compiler inlines them into the class's own instantiation.
template void VariationalTotalLagrangian<1>::evaluate<double>(const Eigen::VectorXd&, Eigen::VectorXd&) const;
template double VariationalTotalLagrangian<1>::energy<double>(const Eigen::VectorXd&) const;
template void VariationalTotalLagrangian<1>::evaluate<std::complex<double>>(const Eigen::VectorXcd&,
                                                                            Eigen::VectorXcd&) const;
template std::complex<double> VariationalTotalLagrangian<1>::energy<std::complex<double>>(
    const Eigen::VectorXcd&) const;
template void VariationalTotalLagrangian<2>::evaluate<double>(const Eigen::VectorXd&, Eigen::VectorXd&) const;
template double VariationalTotalLagrangian<2>::energy<double>(const Eigen::VectorXd&) const;
template void VariationalTotalLagrangian<2>::evaluate<std::complex<double>>(const Eigen::VectorXcd&,
                                                                            Eigen::VectorXcd&) const;
template std::complex<double> VariationalTotalLagrangian<2>::energy<std::complex<double>>(
    const Eigen::VectorXcd&) const;

}  // namespace sphstab
