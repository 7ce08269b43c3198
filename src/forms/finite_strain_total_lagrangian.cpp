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
const char* kFiniteStrainWho = "FiniteStrainTotalLagrangian";
}

template <int Dim>
FiniteStrainTotalLagrangian<Dim>::FiniteStrainTotalLagrangian(std::shared_ptr<const Discretisation<Dim>> discretisation,
                                                              std::shared_ptr<const HyperelasticModel<Dim>> material,
                                                              const Eigen::VectorXd& density,
                                                              FiniteStrainOptions<Dim> options)
    : HyperelasticBody<Dim>(std::move(discretisation), std::move(material), density, kFiniteStrainWho),
      m_options(std::move(options)) {
  const Discretisation<Dim>& d = *m_disc;
  if (!(d.h > 0) || !std::isfinite(d.h))
    throw std::invalid_argument(std::string(kFiniteStrainWho) + ": smoothing length h must be finite and > 0 (got " +
                                format_number(d.h) + ")");
  this->m_difference = m_options.strain_sum == StrainSum::Difference;
  if (m_options.divergence == StressDivergence::Adjoint)
    throw std::invalid_argument(std::string(kFiniteStrainWho) +
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

  // Hourglass control [Ganzenmueller2015]: the pair coefficients, once at the reference positions.
  m_hg = HourglassControl<Dim>(d, m_options.hourglass > 0 ? m_material->material().young() : 0.0, m_rho,
                               {.coefficient = m_options.hourglass, .projection = m_options.hourglass_projection},
                               kFiniteStrainWho);
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
  this->check_no_load(load);
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
template <class Scalar>
void FiniteStrainTotalLagrangian<Dim>::evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                                Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  const Discretisation<Dim>& d = *m_disc;
  // Scratch kept between calls (the header's thread-safety note): no allocation once sized.
  Workspace<Scalar>& ws = this->template workspace<Scalar>();
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
void FiniteStrainTotalLagrangian<Dim>::acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const { evaluate(u, a); }
template <int Dim>
void FiniteStrainTotalLagrangian<Dim>::acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const { evaluate(u, a); }

template class FiniteStrainTotalLagrangian<1>;
template class FiniteStrainTotalLagrangian<2>;

}  // namespace sphstab
