#include "sphstab/forms/elasticity_2d.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "form_detail.hpp"
#include "sphstab/core/named_values.hpp"

// Derivation of the conservative force (checked against a complex-step gradient of U in the tests).
// With w^b_ij = dW(x_i - x_j)/dx_i^b (antisymmetric) and w^{bc}_ij = d^2W/dx_i^b dx_i^c (symmetric),
// G^b_ij = w^b_ij V_j and H^{bc}_ij = w^{bc}_ij V_j. D_i^{ab} = sum_j (u_j^a - u_i^a) G^b_ij, and dG^b_ij/du_k^c =
// H^{bc}_ij (delta_ik - delta_jk). Since dpsi/dD = C:eps + sigma0 = sigma (symmetric),
//   dU/du_k^c = sum_i V_i sigma_i^{ab} dD_i^{ab}/du_k^c
//             = -V_k sum_j V_j [(sigma_j + sigma_k)^{cb} w^b_kj + (sigma_j + sigma_k)^{ab} (u_k^a - u_j^a) w^{bc}_kj],
// so a_k^c = -(1/(rho V_k)) dU/du_k^c = (1/rho) sum_j (sigma_j + sigma_k)^{ab} [delta_ac G^b_kj + (u_k^a - u_j^a)
// H^{bc}_kj] for any particle volumes. In 1D this is Powell (3.27).

namespace sphstab {

constexpr NamedValue<PreStrainKind> kPreStrainNames[] = {{PreStrainKind::Isotropic, "isotropic"},
                                                         {PreStrainKind::UniaxialX, "uniaxial"},
                                                         {PreStrainKind::Isotropic, "iso"},
                                                         {PreStrainKind::UniaxialX, "uniaxial-x"}};

PreStrainKind parse_prestrain_kind(const std::string& name) { return parse_named(name, kPreStrainNames, "pre-strain"); }
std::string prestrain_kind_name(PreStrainKind kind) { return name_of(kind, kPreStrainNames); }

PreStrain PreStrain::from_area_ratio(double xi) {
  if (!(xi > 0) || !std::isfinite(xi))
    throw std::invalid_argument("PreStrain::from_area_ratio: area ratio V/V0 must be finite and > 0 (got " +
                                std::to_string(xi) + ")");
  return {PreStrainKind::Isotropic, std::sqrt(xi) - 1.0};
}

Eigen::Matrix2d PreStrain::stress(const ElasticMaterial& m) const {
  Eigen::Matrix2d s = Eigen::Matrix2d::Zero();
  if (kind == PreStrainKind::Isotropic) {
    s.diagonal().setConstant(2.0 * (m.lambda() + m.mu()) * strain);
  } else {
    s.diagonal().setConstant(m.lambda() * strain);
    s(0, 0) += 2.0 * m.mu() * strain;
  }
  return s;
}

ElasticForm2D::ElasticForm2D(std::shared_ptr<const Discretisation<2>> discretisation, const ElasticMaterial& material,
                             MomentumForm form, const PreStrain& prestrain,
                             std::shared_ptr<const GradientProvider<2>> gradient)
    : m_disc(std::move(discretisation)),
      m_material(material),
      m_form(form),
      m_prestrain(prestrain),
      m_gradient(std::move(gradient)) {
  if (!m_disc) throw std::invalid_argument("ElasticForm2D: discretisation is null");
  m_material.validate("ElasticForm2D");
  if (!std::isfinite(prestrain.strain))
    throw std::invalid_argument("ElasticForm2D: pre-strain must be finite (got " + std::to_string(prestrain.strain) +
                                ")");
  if (form == MomentumForm::Conservative && m_gradient && !m_gradient->is_plain())
    throw std::invalid_argument(
        "ElasticForm2D: the conservative form derives from U with the plain kernel gradient; "
        "gradient provider '" +
        m_gradient->name() + "' cannot be used with it");
  m_fixed_u = Eigen::VectorXd::Zero(2 * (m_disc->size() - m_disc->free_count()));
}

std::string ElasticForm2D::name() const {
  std::ostringstream s;
  s << "elastic2d/" << momentum_form_name(m_form) << "/"
    << (m_prestrain.kind == PreStrainKind::Isotropic ? "iso" : "uniaxial-x") << "/e=" << m_prestrain.strain;
  if (m_gradient && !m_gradient->is_plain()) s << "/" << m_gradient->name() << (m_corrected_strain ? "(both)" : "");
  for (const auto& t : m_terms) s << "+" << t->name();
  return s.str();
}

std::unique_ptr<ForceFunction> ElasticForm2D::with_load(double load) const {
  if (!std::isfinite(load))
    throw std::invalid_argument("ElasticForm2D::with_load: pre-strain must be finite (got " + std::to_string(load) +
                                ")");
  auto copy = std::make_unique<ElasticForm2D>(*this);
  copy->m_prestrain.strain = load;
  return copy;
}

SparsityPattern ElasticForm2D::dof_pattern() const {
  const int reach = m_gradient ? m_gradient->dependence_radius() : 1;
  // divergence: Ghat_ij (reach) and sigma_j, j in N(i); a corrected strain makes sigma_j reach 1 + reach hops
  int radius = std::max(2, m_corrected_strain ? 1 + reach : reach);
  for (const auto& t : m_terms) radius = std::max(radius, t->dependence_radius());
  return coupling_pattern(m_disc->neighbours, m_disc->free_slot, 2, radius);
}

void ElasticForm2D::set_corrected_strain(bool on) {
  if (on && (!m_gradient || m_gradient->is_plain()))
    throw std::invalid_argument("ElasticForm2D::set_corrected_strain: needs a non-plain gradient provider");
  if (on && m_form == MomentumForm::Conservative)
    throw std::invalid_argument(
        "ElasticForm2D::set_corrected_strain: the conservative form derives its force from the plain strain");
  m_corrected_strain = on;
}

void ElasticForm2D::add_term(std::shared_ptr<const ElasticTerm2D> term) {
  if (!term) throw std::invalid_argument("ElasticForm2D::add_term: term is null");
  m_terms.push_back(std::move(term));
}

void ElasticForm2D::set_terms(std::vector<std::shared_ptr<const ElasticTerm2D>> terms) {
  for (const auto& t : terms)
    if (!t) throw std::invalid_argument("ElasticForm2D::set_terms: term is null");
  m_terms = std::move(terms);
}

Eigen::VectorXd ElasticForm2D::dof_mass() const {
  Eigen::VectorXd m(dofs());
  for (int f = 0; f < m_disc->free_count(); ++f)
    m[2 * f] = m[2 * f + 1] = m_material.density() * m_disc->particles.volume[m_disc->free[f]];
  return m;
}

void ElasticForm2D::set_fixed_displacement(const Eigen::VectorXd& d) {
  const int n = 2 * (m_disc->size() - m_disc->free_count());
  if (d.size() != n || !d.allFinite())
    throw std::invalid_argument("ElasticForm2D::set_fixed_displacement: expected " + std::to_string(n) +
                                " finite entries (got " + std::to_string(d.size()) + ")");
  m_fixed_u = d;
}

template <class Scalar>
void ElasticForm2D::strain_state(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u, Positions<2, Scalar>& uall,
                                 Eigen::Matrix<Scalar, Eigen::Dynamic, 4>& grad, Operators<2, Scalar>& ops,
                                 bool hessian, std::array<SparseMatrix<Scalar>, 2>* corrected) const {
  const Discretisation<2>& d = *m_disc;
  uall = detail::full_displacement<2, Scalar>(d, u, m_fixed_u, "ElasticForm2D");
  Positions<2, Scalar> x = d.particles.x.template cast<Scalar>() + uall;
  OperatorRequest request = detail::form_request<2>(m_gradient.get(), hessian);
  for (const auto& t : m_terms) {
    const OperatorRequest r = t->requirements();
    request.kernel = request.kernel || r.kernel;
    request.hessian = request.hessian || r.hessian;
  }
  Operators<2, Scalar> fresh = assemble_operators<2, Scalar>(d.particles, d.neighbours, d.kernel, d.h, request, &x);
  detail::take_operators(ops, fresh);
  // (grad u)_i^{ab} = sum_j (u_j^a - u_i^a) K^b_ij, stored at column a * 2 + b; K = G, or Ghat with a corrected strain
  const NeighbourList& nl = d.neighbours;
  std::array<SparseMatrix<Scalar>, 2> local;
  std::array<SparseMatrix<Scalar>, 2>& ghat = corrected ? *corrected : local;
  const bool use_ghat = m_corrected_strain && detail::corrected_gradient<2, Scalar>(m_gradient.get(), d, x, ops, ghat);
  const Scalar* g0 = use_ghat ? ghat[0].valuePtr() : ops.G[0].valuePtr();
  const Scalar* g1 = use_ghat ? ghat[1].valuePtr() : ops.G[1].valuePtr();
  grad.resize(d.size(), 4);
  for (int i = 0; i < d.size(); ++i) {
    Scalar dxx(0), dxy(0), dyx(0), dyy(0);
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      const Scalar ux = uall(j, 0) - uall(i, 0), uy = uall(j, 1) - uall(i, 1);
      dxx += ux * g0[k];
      dxy += ux * g1[k];
      dyx += uy * g0[k];
      dyy += uy * g1[k];
    }
    grad(i, 0) = dxx;
    grad(i, 1) = dxy;
    grad(i, 2) = dyx;
    grad(i, 3) = dyy;
  }
}

namespace {
/// sigma = lambda tr(eps) I + 2 mu eps + sigma0 from grad u (row a*2+b); returns (sxx, syy, sxy).
template <class Scalar>
Eigen::Matrix<Scalar, 1, 3> stress_of(const Eigen::Matrix<Scalar, 1, 4>& D, const ElasticMaterial& m,
                                      const Eigen::Matrix2d& s0) {
  const Scalar exx = D[0], eyy = D[3], exy = 0.5 * (D[1] + D[2]);
  const Scalar tr = exx + eyy;
  Eigen::Matrix<Scalar, 1, 3> s;
  s[0] = m.lambda() * tr + 2.0 * m.mu() * exx + s0(0, 0);
  s[1] = m.lambda() * tr + 2.0 * m.mu() * eyy + s0(1, 1);
  s[2] = 2.0 * m.mu() * exy + s0(0, 1);
  return s;
}
}  // namespace

template <class Scalar>
void ElasticForm2D::evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                             Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  const Discretisation<2>& d = *m_disc;
  const NeighbourList& nl = d.neighbours;
  const bool cons = m_form == MomentumForm::Conservative;
  Positions<2, Scalar> uall;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 4> grad;
  Operators<2, Scalar> ops;
  std::array<SparseMatrix<Scalar>, 2> corrected;
  strain_state(u, uall, grad, ops, cons, &corrected);
  const Eigen::Matrix2d s0 = m_prestrain.stress(m_material);
  Eigen::Matrix<Scalar, Eigen::Dynamic, 3> sig(d.size(), 3);
  for (int i = 0; i < d.size(); ++i)
    sig.row(i) = stress_of<Scalar>(Eigen::Matrix<Scalar, 1, 4>(grad.row(i)), m_material, s0);
  const double inv_rho = 1.0 / m_material.density();
  a.resize(d.dofs());

  if (cons) {
    // a_i^c = (1/rho) sum_j S^{ab} [delta_ac G^b_ij + (u_i^a - u_j^a) H^{bc}_ij],  S = sigma_j + sigma_i
    const Scalar* g0 = ops.G[0].valuePtr();
    const Scalar* g1 = ops.G[1].valuePtr();
    const Scalar* hxx = ops.H[0][0].valuePtr();
    const Scalar* hxy = ops.H[0][1].valuePtr();
    const Scalar* hyy = ops.H[1][1].valuePtr();
    for (int f = 0; f < d.free_count(); ++f) {
      const int i = d.free[f];
      Scalar ax(0), ay(0);
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        const Scalar sxx = sig(j, 0) + sig(i, 0), syy = sig(j, 1) + sig(i, 1), sxy = sig(j, 2) + sig(i, 2);
        const Scalar dx = uall(i, 0) - uall(j, 0), dy = uall(i, 1) - uall(j, 1);
        const Scalar wx = sxx * dx + sxy * dy;  // w^b = S^{ab} d^a
        const Scalar wy = sxy * dx + syy * dy;
        ax += sxx * g0[k] + sxy * g1[k] + wx * hxx[k] + wy * hxy[k];
        ay += sxy * g0[k] + syy * g1[k] + wx * hxy[k] + wy * hyy[k];
      }
      a[2 * f] = inv_rho * ax;
      a[2 * f + 1] = inv_rho * ay;
    }
    add_terms<Scalar>(d, uall, sig, ops, a);
    return;
  }
  // a_i^a = (1/rho) sum_j (sigma_j^{ab} + alpha sigma_i^{ab}) Ghat^b_ij
  const double alpha = momentum_form_alpha(m_form);
  Positions<2, Scalar> x;
  bool use_corrected = m_corrected_strain && m_gradient && !m_gradient->is_plain();  // already computed above
  if (!use_corrected && m_gradient && !m_gradient->is_plain()) {
    x = d.particles.x.template cast<Scalar>() + uall;
    use_corrected = detail::corrected_gradient<2, Scalar>(m_gradient.get(), d, x, ops, corrected);
  }
  const Scalar* g0 = use_corrected ? corrected[0].valuePtr() : ops.G[0].valuePtr();
  const Scalar* g1 = use_corrected ? corrected[1].valuePtr() : ops.G[1].valuePtr();
  for (int f = 0; f < d.free_count(); ++f) {
    const int i = d.free[f];
    Scalar ax(0), ay(0);
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      const Scalar sxx = sig(j, 0) + alpha * sig(i, 0), syy = sig(j, 1) + alpha * sig(i, 1),
                   sxy = sig(j, 2) + alpha * sig(i, 2);
      ax += sxx * g0[k] + sxy * g1[k];
      ay += sxy * g0[k] + syy * g1[k];
    }
    a[2 * f] = inv_rho * ax;
    a[2 * f + 1] = inv_rho * ay;
  }
  add_terms<Scalar>(d, uall, sig, ops, a);
}

template <class Scalar>
void ElasticForm2D::add_terms(const Discretisation<2>& d, const Positions<2, Scalar>& uall,
                              const Eigen::Matrix<Scalar, Eigen::Dynamic, 3>& sig, const Operators<2, Scalar>& ops,
                              Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  if (m_terms.empty()) return;
  const Positions<2, Scalar> x = d.particles.x.template cast<Scalar>() + uall;
  const ElasticTermContext<Scalar> context{d, m_material, x, uall, sig, ops};
  ParticleAccelerations<Scalar> acc = ParticleAccelerations<Scalar>::Zero(d.size(), 2);
  for (const auto& t : m_terms) t->add(context, acc);
  for (int f = 0; f < d.free_count(); ++f) {
    a[2 * f] += acc(d.free[f], 0);
    a[2 * f + 1] += acc(d.free[f], 1);
  }
}

template <class Scalar>
Scalar ElasticForm2D::energy(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u) const {
  Positions<2, Scalar> uall;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 4> grad;
  Operators<2, Scalar> ops;
  strain_state(u, uall, grad, ops, false);
  const Eigen::Matrix2d s0 = m_prestrain.stress(m_material);
  const double lam = m_material.lambda(), mu = m_material.mu();
  Scalar e(0);
  for (int i = 0; i < m_disc->size(); ++i) {
    const Scalar exx = grad(i, 0), eyy = grad(i, 3), exy = 0.5 * (grad(i, 1) + grad(i, 2));
    const Scalar tr = exx + eyy;
    const Scalar psi = 0.5 * lam * tr * tr + mu * (exx * exx + eyy * eyy + 2.0 * exy * exy) + s0(0, 0) * grad(i, 0) +
                       s0(0, 1) * (grad(i, 1) + grad(i, 2)) + s0(1, 1) * grad(i, 3);
    e += m_disc->particles.volume[i] * psi;
  }
  return e;
}

Eigen::MatrixX3d ElasticForm2D::stress(const Eigen::VectorXd& u) const {
  Positions<2, double> uall;
  Eigen::Matrix<double, Eigen::Dynamic, 4> grad;
  Operators<2, double> ops;
  strain_state(u, uall, grad, ops, false);
  const Eigen::Matrix2d s0 = m_prestrain.stress(m_material);
  Eigen::MatrixX3d sig(m_disc->size(), 3);
  for (int i = 0; i < m_disc->size(); ++i)
    sig.row(i) = stress_of<double>(Eigen::Matrix<double, 1, 4>(grad.row(i)), m_material, s0);
  return sig;
}

template void ElasticForm2D::evaluate<double>(const Eigen::VectorXd&, Eigen::VectorXd&) const;
template void ElasticForm2D::evaluate<std::complex<double>>(const Eigen::VectorXcd&, Eigen::VectorXcd&) const;
template double ElasticForm2D::energy<double>(const Eigen::VectorXd&) const;
template std::complex<double> ElasticForm2D::energy<std::complex<double>>(const Eigen::VectorXcd&) const;

}  // namespace sphstab
