#include "sphstab/forms/finite_strain_total_lagrangian.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "form_detail.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/numerics/real_part.hpp"
#include "total_lagrangian_detail.hpp"

namespace sphstab {

namespace {
const char* kWho = "FiniteStrainTotalLagrangian";
}

template <int Dim>
FiniteStrainTotalLagrangian<Dim>::FiniteStrainTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                                                              std::shared_ptr<const HyperelasticModel<Dim>> material,
                                                              const Eigen::VectorXd& density,
                                                              FiniteStrainOptions<Dim> options)
    : m_disc(std::move(discretisation)), m_material(std::move(material)), m_options(std::move(options)) {
  if (!m_disc) throw std::invalid_argument(std::string(kWho) + ": discretisation is null");
  if (!m_material) throw std::invalid_argument(std::string(kWho) + ": material is null");
  const Discretisation<Dim>& d = *m_disc;
  if (!(d.h > 0) || !std::isfinite(d.h))
    throw std::invalid_argument(std::string(kWho) + ": smoothing length h must be finite and > 0 (got " +
                                format_number(d.h) + ")");
  const int N = d.size();
  m_rho = detail::particle_density(density, N, kWho);
  if (m_options.divergence == StressDivergence::Adjoint)
    throw std::invalid_argument(std::string(kWho) +
                                ": the adjoint divergence is not offered; use plain, plus or minus");

  // Reference operators, assembled once at X (Ismail's SPH matrices X, Y).
  const OperatorRequest request = detail::form_request<Dim>(m_options.gradient.get(), false);
  Operators<Dim> ops = assemble_operators<Dim, double>(d.particles, d.neighbours, d.kernel, d.h, request);
  auto G = std::make_shared<std::array<SparseMatrix<>, Dim>>();
  for (int b = 0; b < Dim; ++b) (*G)[b] = ops.G[b];
  m_G = G;
  std::array<SparseMatrix<>, Dim> K;
  const Positions<Dim> X = d.particles.x;
  m_plain_strain = !detail::corrected_gradient<Dim, double>(m_options.gradient.get(), d, X, ops, K, true);
  m_K = m_plain_strain ? m_G : std::make_shared<const std::array<SparseMatrix<>, Dim>>(std::move(K));

  // Active particles: free ones and their neighbours.
  std::vector<char> is_active(N, 0);
  for (int i : d.free)
    for (long k = d.neighbours.offsets[i]; k < d.neighbours.offsets[i + 1]; ++k) is_active[d.neighbours.indices[k]] = 1;
  for (int i = 0; i < N; ++i)
    if (is_active[i]) m_active.push_back(i);
  m_fixed_u = Eigen::VectorXd::Zero(Dim * (N - d.free_count()));

  // Hourglass control [Ganzenmueller2015]: the pair coefficients, once at the reference positions.
  m_hg =
      HourglassControl<Dim>(d, m_options.hourglass > 0 ? m_material->lame().young() : 0.0, m_rho,
                            {.coefficient = m_options.hourglass, .projection = m_options.hourglass_projection}, kWho);
}

template <int Dim>
std::string FiniteStrainTotalLagrangian<Dim>::name() const {
  std::ostringstream s;
  s << "tl-finite-strain-" << Dim << "d/" << m_material->name() << "/"
    << (m_plain_strain ? std::string("plain") : m_options.gradient->name()) << "-"
    << (m_options.strain_sum == StrainSum::Difference ? "difference" : "direct") << "/"
    << stress_divergence_name(m_options.divergence);
  if (m_options.hourglass > 0)
    s << "/hourglass-" << (m_options.hourglass_projection == HourglassProjection::Full ? "full-" : "")
      << format_number(m_options.hourglass);
  return s.str();
}

template <int Dim>
bool FiniteStrainTotalLagrangian<Dim>::conservative() const {
  return m_plain_strain && m_options.strain_sum == StrainSum::Difference &&
         m_options.divergence == StressDivergence::Plus && m_options.hourglass == 0;
}

template <int Dim>
std::unique_ptr<ForceFunction> FiniteStrainTotalLagrangian<Dim>::with_load(double load) const {
  if (load != 0)
    throw std::invalid_argument(std::string(kWho) + "::with_load: the finite-strain form has no affine load (got " +
                                format_number(load) + "); prescribe displacements with set_fixed_displacement");
  return std::make_unique<FiniteStrainTotalLagrangian<Dim>>(*this);
}

template <int Dim>
SparsityPattern FiniteStrainTotalLagrangian<Dim>::dof_pattern() const {
  // a_i reads P_j (j a neighbour of i), P_j reads u_k through row j of K: two hops for a local K.
  bool local = true;
  for (int b = 0; b < Dim; ++b) local = local && (*m_K)[b].nonZeros() == m_disc->neighbours.nonzeros();
  return coupling_pattern(m_disc->neighbours, m_disc->free_slot, Dim, local ? 2 : kFullReach);
}

template <int Dim>
Eigen::VectorXd FiniteStrainTotalLagrangian<Dim>::dof_mass() const {
  return detail::lumped_dof_mass(*m_disc, m_rho);
}

template <int Dim>
void FiniteStrainTotalLagrangian<Dim>::set_fixed_displacement(const Eigen::VectorXd& d) {
  detail::check_fixed_displacement(d, m_fixed_u.size(), kWho);
  m_fixed_u = d;
}

template <int Dim>
template <class Scalar>
typename FiniteStrainTotalLagrangian<Dim>::template Workspace<Scalar>& FiniteStrainTotalLagrangian<Dim>::workspace()
    const {
  if constexpr (std::is_same_v<Scalar, double>)
    return m_work_real;
  else
    return m_work_complex;
}

template <int Dim>
template <class Scalar>
void FiniteStrainTotalLagrangian<Dim>::deformation(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                                   Positions<Dim, Scalar>& uall,
                                                   std::vector<Deformation<Scalar, Dim>>& F) const {
  const Discretisation<Dim>& d = *m_disc;
  detail::full_displacement_into<Dim, Scalar>(d, u, m_fixed_u, kWho, uall);
  F.assign(d.size(), Deformation<Scalar, Dim>::Constant(Scalar(std::numeric_limits<double>::quiet_NaN())));
  const bool difference = m_options.strain_sum == StrainSum::Difference;
  for (int i : m_active) {
    Deformation<Scalar, Dim> f = Deformation<Scalar, Dim>::Identity();
    for (int b = 0; b < Dim; ++b)
      for (typename SparseMatrix<>::InnerIterator it((*m_K)[b], i); it; ++it) {
        const int j = static_cast<int>(it.col());
        for (int a = 0; a < Dim; ++a)
          f(a, b) += (difference ? Scalar(uall(j, a) - uall(i, a)) : uall(j, a)) * it.value();  // (Grad u)^{ab}
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
void FiniteStrainTotalLagrangian<Dim>::evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                                Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  const Discretisation<Dim>& d = *m_disc;
  // Scratch kept between calls (the header's thread-safety note): no allocation once sized.
  Workspace<Scalar>& ws = workspace<Scalar>();
  std::vector<Deformation<Scalar, Dim>>&F = ws.F, &P = ws.P;
  deformation(u, ws.u, F);
  P.assign(d.size(), Deformation<Scalar, Dim>::Zero());
  for (int i : m_active) P[i] = m_material->stress(F[i]);
  const double alpha = m_options.divergence == StressDivergence::Plus    ? 1.0
                       : m_options.divergence == StressDivergence::Minus ? -1.0
                                                                         : 0.0;
  a.setZero(d.dofs());
  for (int f = 0; f < d.free_count(); ++f) {
    const int i = d.free[f];
    Eigen::Matrix<Scalar, Dim, 1> ai = Eigen::Matrix<Scalar, Dim, 1>::Zero();
    for (int b = 0; b < Dim; ++b)
      for (typename SparseMatrix<>::InnerIterator it((*m_G)[b], i); it; ++it) {
        const int j = static_cast<int>(it.col());
        // a_i^a = (1/rho0_i) sum_j (P_j^{ab} + alpha P_i^{ab}) G^b_ij   [Ismail2009, (5.6), (5.8)]
        ai += (P[j].col(b) + alpha * P[i].col(b)) * it.value();
      }
    for (int c = 0; c < Dim; ++c) a[f * Dim + c] = ai[c] / m_rho[i];
  }
  if (m_hg.active()) m_hg.add(d, ws.u, F, a);
}

template <int Dim>
template <class Scalar>
Scalar FiniteStrainTotalLagrangian<Dim>::energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const {
  Workspace<Scalar>& ws = workspace<Scalar>();
  std::vector<Deformation<Scalar, Dim>>& F = ws.F;
  deformation(u, ws.u, F);
  Scalar U(0);
  for (int i : m_active) U += m_disc->particles.volume[i] * m_material->energy(F[i]);
  return U;
}

template <int Dim>
Eigen::MatrixXd FiniteStrainTotalLagrangian<Dim>::deformation_gradients(const Eigen::VectorXd& u) const {
  Positions<Dim> uall;
  std::vector<Deformation<double, Dim>> F;
  deformation(u, uall, F);
  return detail::deformation_table<Dim>(F);
}

template <int Dim>
Eigen::MatrixXd FiniteStrainTotalLagrangian<Dim>::stresses(const Eigen::VectorXd& u) const {
  Positions<Dim> uall;
  std::vector<Deformation<double, Dim>> F;
  deformation(u, uall, F);
  return detail::stress_table<Dim>(*m_material, F, m_active);
}

template class FiniteStrainTotalLagrangian<1>;
template class FiniteStrainTotalLagrangian<2>;
// The member templates the header's inline overrides call (acceleration, strain_energy): instantiated here, so the
// symbols exist whether or not the compiler inlines them into the class's own instantiation.
template void FiniteStrainTotalLagrangian<1>::evaluate<double>(const Eigen::VectorXd&, Eigen::VectorXd&) const;
template double FiniteStrainTotalLagrangian<1>::energy<double>(const Eigen::VectorXd&) const;
template void FiniteStrainTotalLagrangian<1>::evaluate<std::complex<double>>(const Eigen::VectorXcd&,
                                                                             Eigen::VectorXcd&) const;
template std::complex<double> FiniteStrainTotalLagrangian<1>::energy<std::complex<double>>(
    const Eigen::VectorXcd&) const;
template void FiniteStrainTotalLagrangian<2>::evaluate<double>(const Eigen::VectorXd&, Eigen::VectorXd&) const;
template double FiniteStrainTotalLagrangian<2>::energy<double>(const Eigen::VectorXd&) const;
template void FiniteStrainTotalLagrangian<2>::evaluate<std::complex<double>>(const Eigen::VectorXcd&,
                                                                             Eigen::VectorXcd&) const;
template std::complex<double> FiniteStrainTotalLagrangian<2>::energy<std::complex<double>>(
    const Eigen::VectorXcd&) const;

}  // namespace sphstab
