#include "sphstab/forms/wave_1d.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "form_detail.hpp"

namespace sphstab {

WaveForm1D::WaveForm1D(std::shared_ptr<const Discretisation<1>> discretisation, MomentumForm form, double tension,
                       std::shared_ptr<const GradientProvider<1>> gradient)
    : m_disc(std::move(discretisation)), m_form(form), m_tension(tension), m_gradient(std::move(gradient)) {
  if (!m_disc) throw std::invalid_argument("WaveForm1D: discretisation is null");
  if (!std::isfinite(tension))
    throw std::invalid_argument("WaveForm1D: tension T must be finite (got " + std::to_string(tension) + ")");
  if (form == MomentumForm::Conservative && m_gradient && !m_gradient->is_plain())
    throw std::invalid_argument(
        "WaveForm1D: the conservative form derives from U with the plain kernel gradient; "
        "gradient provider '" +
        m_gradient->name() + "' cannot be used with it");
  m_fixed_u = Eigen::VectorXd::Zero(m_disc->size() - m_disc->free_count());
}

std::string WaveForm1D::name() const {
  std::ostringstream s;
  s << "wave1d/" << momentum_form_name(m_form) << "/T=" << m_tension;
  if (m_gradient && !m_gradient->is_plain()) s << "/" << m_gradient->name();
  return s.str();
}

std::unique_ptr<ForceFunction> WaveForm1D::with_load(double load) const {
  if (!std::isfinite(load))
    throw std::invalid_argument("WaveForm1D::with_load: tension must be finite (got " + std::to_string(load) + ")");
  auto copy = std::make_unique<WaveForm1D>(*this);
  copy->m_tension = load;
  return copy;
}

SparsityPattern WaveForm1D::dof_pattern() const {
  const int radius = std::max(2, m_gradient ? m_gradient->dependence_radius() : 1);
  return coupling_pattern(m_disc->neighbours, m_disc->free_slot, 1, radius);
}

Eigen::VectorXd WaveForm1D::dof_mass() const {
  Eigen::VectorXd m(dofs());
  for (int f = 0; f < m_disc->free_count(); ++f) m[f] = m_disc->particles.volume[m_disc->free[f]];  // rho = 1
  return m;
}

void WaveForm1D::set_fixed_displacement(const Eigen::VectorXd& d) {
  const int nfixed = m_disc->size() - m_disc->free_count();
  if (d.size() != nfixed || !d.allFinite())
    throw std::invalid_argument("WaveForm1D::set_fixed_displacement: expected " + std::to_string(nfixed) +
                                " finite entries (got " + std::to_string(d.size()) + ")");
  m_fixed_u = d;
}

template <class Scalar>
void WaveForm1D::strain_state(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                              Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& uall,
                              Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& s, Operators<1, Scalar>& ops,
                              bool hessian) const {
  const Discretisation<1>& d = *m_disc;
  Positions<1, Scalar> all = detail::full_displacement<1, Scalar>(d, u, m_fixed_u, "WaveForm1D");
  uall = all.col(0);
  Positions<1, Scalar> x = d.particles.x.template cast<Scalar>() + all;
  Operators<1, Scalar> fresh = assemble_operators<1, Scalar>(d.particles, d.neighbours, d.kernel, d.h,
                                                             detail::form_request<1>(m_gradient.get(), hessian), &x);
  detail::take_operators(ops, fresh);
  // s_i = sum_j (u_j - u_i) G_ij + T   (all particles)
  const NeighbourList& nl = d.neighbours;
  const Scalar* g = ops.G[0].valuePtr();
  s.resize(d.size());
  for (int i = 0; i < d.size(); ++i) {
    Scalar sum(0);
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) sum += (uall[nl.indices[k]] - uall[i]) * g[k];
    s[i] = sum + m_tension;
  }
}

template <class Scalar>
void WaveForm1D::evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                          Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  const Discretisation<1>& d = *m_disc;
  const NeighbourList& nl = d.neighbours;
  const bool cons = m_form == MomentumForm::Conservative;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> uall, s;
  Operators<1, Scalar> ops;
  strain_state(u, uall, s, ops, cons);
  a.resize(d.dofs());
  if (cons) {
    // Powell (3.27): a_i = sum_j (s_j + s_i) [G_ij + (u_i - u_j) H_ij]
    const Scalar* g = ops.G[0].valuePtr();
    const Scalar* hh = ops.H[0][0].valuePtr();
    for (int f = 0; f < d.free_count(); ++f) {
      const int i = d.free[f];
      Scalar sum(0);
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        sum += (s[j] + s[i]) * (g[k] + (uall[i] - uall[j]) * hh[k]);
      }
      a[f] = sum;
    }
    return;
  }
  // Powell (3.28): a_i = sum_j (s_j + alpha s_i) Ghat_ij
  const double alpha = momentum_form_alpha(m_form);
  std::array<SparseMatrix<Scalar>, 1> corrected;
  Positions<1, Scalar> x;  // only needed by a non-plain provider
  if (m_gradient && !m_gradient->is_plain()) {
    x = d.particles.x.template cast<Scalar>();
    x.col(0) += uall;
  }
  const bool use_corrected = detail::corrected_gradient<1, Scalar>(m_gradient.get(), d, x, ops, corrected);
  const Scalar* g = use_corrected ? corrected[0].valuePtr() : ops.G[0].valuePtr();
  for (int f = 0; f < d.free_count(); ++f) {
    const int i = d.free[f];
    Scalar sum(0);
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) sum += (s[nl.indices[k]] + alpha * s[i]) * g[k];
    a[f] = sum;
  }
}

template <class Scalar>
Scalar WaveForm1D::energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> uall, s;
  Operators<1, Scalar> ops;
  strain_state(u, uall, s, ops, false);
  Scalar e(0);
  for (int i = 0; i < m_disc->size(); ++i) e += 0.5 * m_disc->particles.volume[i] * s[i] * s[i];
  return e;
}

Eigen::VectorXd WaveForm1D::stress(const Eigen::VectorXd& u) const {
  Eigen::VectorXd uall, s;
  Operators<1, double> ops;
  strain_state(u, uall, s, ops, false);
  return s;
}

template void WaveForm1D::evaluate<double>(const Eigen::VectorXd&, Eigen::VectorXd&) const;
template void WaveForm1D::evaluate<std::complex<double>>(const Eigen::VectorXcd&, Eigen::VectorXcd&) const;
template double WaveForm1D::energy<double>(const Eigen::VectorXd&) const;
template std::complex<double> WaveForm1D::energy<std::complex<double>>(const Eigen::VectorXcd&) const;

}  // namespace sphstab
