#include "sphstab/forms/hyperelastic_body.hpp"

#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "form_detail.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/numerics/real_part.hpp"
#include "total_lagrangian_detail.hpp"

namespace sphstab {

template <int Dim>
HyperelasticBody<Dim>::HyperelasticBody(std::shared_ptr<const Discretisation<Dim>> discretisation,
                                        std::shared_ptr<const HyperelasticModel<Dim>> material,
                                        const Eigen::VectorXd& density, std::string who)
    : m_who(std::move(who)), m_disc(std::move(discretisation)), m_material(std::move(material)) {
  if (!m_disc) throw std::invalid_argument(m_who + ": discretisation is null");
  if (!m_material) throw std::invalid_argument(m_who + ": material is null");
  const Discretisation<Dim>& d = *m_disc;
  const int N = d.size();
  m_rho = detail::particle_density(density, N, m_who.c_str());
  // Active particles: free ones and their neighbours.
  std::vector<char> is_active(N, 0);
  for (int i : d.free)
    for (long k = d.neighbours.offsets[i]; k < d.neighbours.offsets[i + 1]; ++k) is_active[d.neighbours.indices[k]] = 1;
  for (int i = 0; i < N; ++i)
    if (is_active[i]) m_active.push_back(i);
  m_fixed_u = Eigen::VectorXd::Zero(Dim * (N - d.free_count()));
}

template <int Dim>
Eigen::VectorXd HyperelasticBody<Dim>::lumped_mass() const {
  return detail::lumped_dof_mass(*m_disc, m_rho);
}

template <int Dim>
void HyperelasticBody<Dim>::check_no_load(double load) const {
  if (load != 0)
    throw std::invalid_argument(m_who + "::with_load: the finite-strain forms have no affine load (got " +
                                format_number(load) + "); prescribe displacements with set_fixed_displacement");
}

template <int Dim>
void HyperelasticBody<Dim>::set_fixed_displacement(const Eigen::VectorXd& d) {
  detail::check_fixed_displacement(d, m_fixed_u.size(), m_who.c_str());
  m_fixed_u = d;
}

template <int Dim>
template <class Scalar>
typename HyperelasticBody<Dim>::template Workspace<Scalar>& HyperelasticBody<Dim>::workspace() const {
  return m_work.template get<Scalar>();
}

template <int Dim>
template <class Scalar>
void HyperelasticBody<Dim>::deformation(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                        Positions<Dim, Scalar>& uall, std::vector<Deformation<Scalar, Dim>>& F) const {
  const Discretisation<Dim>& d = *m_disc;
  detail::full_displacement_into<Dim, Scalar>(d, u, m_fixed_u, m_who.c_str(), uall);
  F.assign(d.size(), Deformation<Scalar, Dim>::Constant(Scalar(std::numeric_limits<double>::quiet_NaN())));
  for (int i : m_active) {
    Deformation<Scalar, Dim> f = Deformation<Scalar, Dim>::Identity();
    for (int b = 0; b < Dim; ++b)
      for (typename SparseMatrix<>::InnerIterator it((*m_K)[b], i); it; ++it) {
        const int j = static_cast<int>(it.col());
        for (int a = 0; a < Dim; ++a)
          f(a, b) += (m_difference ? Scalar(uall(j, a) - uall(i, a)) : uall(j, a)) * it.value();  // (Grad u)^{ab}
      }
    const double J = detail::re(Scalar(f.determinant()));
    if (!(J > 0))
      throw std::invalid_argument(m_who + ": J = det F = " + format_number(J) + " <= 0 at particle " +
                                  std::to_string(i) + " (inverted; reduce the load or the time step)");
    F[i] = f;
  }
}

template <int Dim>
template <class Scalar>
Scalar HyperelasticBody<Dim>::energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const {
  Workspace<Scalar>& ws = workspace<Scalar>();
  deformation(u, ws.u, ws.F);
  Scalar U(0);
  for (int i : m_active) U += m_disc->particles.volume[i] * m_material->energy(ws.F[i]);
  return U;
}

template <int Dim>
Eigen::MatrixXd HyperelasticBody<Dim>::deformation_gradients(const Eigen::VectorXd& u) const {
  Positions<Dim> uall;
  std::vector<Deformation<double, Dim>> F;
  deformation(u, uall, F);
  return detail::deformation_table<Dim>(F);
}

template <int Dim>
Eigen::MatrixXd HyperelasticBody<Dim>::stresses(const Eigen::VectorXd& u) const {
  Positions<Dim> uall;
  std::vector<Deformation<double, Dim>> F;
  deformation(u, uall, F);
  return detail::stress_table<Dim>(*m_material, F, m_active);
}

template class HyperelasticBody<1>;
template class HyperelasticBody<2>;
// The member templates the forms call with real and complex states.
#define SPHSTAB_BODY_MEMBERS(D, S)                                                                             \
  template HyperelasticBody<D>::Workspace<S>& HyperelasticBody<D>::workspace<S>() const;                       \
  template void HyperelasticBody<D>::deformation<S>(const Eigen::Matrix<S, Eigen::Dynamic, 1>&,                \
                                                    Positions<D, S>&, std::vector<Deformation<S, D>>&) const; \
  template S HyperelasticBody<D>::energy<S>(const Eigen::Matrix<S, Eigen::Dynamic, 1>&) const;
SPHSTAB_BODY_MEMBERS(1, double)
SPHSTAB_BODY_MEMBERS(1, std::complex<double>)
SPHSTAB_BODY_MEMBERS(2, double)
SPHSTAB_BODY_MEMBERS(2, std::complex<double>)
#undef SPHSTAB_BODY_MEMBERS

}  // namespace sphstab
