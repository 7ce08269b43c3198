#include "sphstab/forms/wave_1d.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "form_detail.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/numerics/dual.hpp"

namespace sphstab {

namespace {

int saturating_add(int a, int b) { return std::min(kFullReach, a + b); }

/// For every particle i (all N), the free particles within `radius` graph hops (BFS over the neighbour list).
std::vector<std::vector<int>> reach_sets(const NeighbourList& nl, const std::vector<int>& free_slot, int radius) {
  const int n = nl.size();
  std::vector<std::vector<int>> out(n);
  std::vector<int> mark(n, -1), frontier, next;
  for (int i = 0; i < n; ++i) {
    frontier.assign(1, i);
    mark[i] = i;
    std::vector<int> seen{i};
    for (int hop = 0; hop < radius && !frontier.empty(); ++hop) {
      next.clear();
      for (int p : frontier)
        for (long k = nl.offsets[p]; k < nl.offsets[p + 1]; ++k) {
          const int q = nl.indices[k];
          if (mark[q] == i) continue;
          mark[q] = i;
          next.push_back(q);
          seen.push_back(q);
        }
      frontier.swap(next);
    }
    for (int p : seen)
      if (free_slot[p] >= 0) out[i].push_back(free_slot[p]);
    std::sort(out[i].begin(), out[i].end());
  }
  return out;
}

}  // namespace

constexpr NamedValue<CorrectedOperator> kCorrectedOperatorNames[] = {{CorrectedOperator::Auto, "auto"},
                                                                     {CorrectedOperator::Divergence, "divergence"},
                                                                     {CorrectedOperator::Strain, "strain"},
                                                                     {CorrectedOperator::Both, "both"}};

CorrectedOperator parse_corrected_operator(const std::string& name) {
  return parse_named(name, kCorrectedOperatorNames, "corrected operator");
}
std::string corrected_operator_name(CorrectedOperator t) { return name_of(t, kCorrectedOperatorNames); }

WaveForm1D::WaveForm1D(std::shared_ptr<const Discretisation<1>> discretisation, MomentumForm form, double tension,
                       std::shared_ptr<const GradientProvider<1>> gradient, const WaveForm1DOptions& options)
    : m_disc(std::move(discretisation)), m_form(form), m_tension(tension) {
  if (!m_disc) throw std::invalid_argument("WaveForm1D: discretisation is null");
  if (!std::isfinite(tension))
    throw std::invalid_argument("WaveForm1D: tension T must be finite (got " + std::to_string(tension) + ")");
  const bool cons = form == MomentumForm::Conservative;
  if (gradient && !gradient->is_plain()) {
    m_gradient = std::move(gradient);
    CorrectedOperator target = options.corrected;
    if (target == CorrectedOperator::Auto) target = cons ? CorrectedOperator::Strain : CorrectedOperator::Divergence;
    if (cons && target == CorrectedOperator::Divergence)
      throw std::invalid_argument(
          "WaveForm1D: the conservative form derives its divergence from the energy U = 1/2 sum V s^2; "
          "gradient provider '" +
          m_gradient->name() + "' can only correct its strain (use CorrectedOperator::Strain or Auto)");
    m_strain_corrected = target == CorrectedOperator::Strain || target == CorrectedOperator::Both;
    m_divergence_corrected = !cons && (target == CorrectedOperator::Divergence || target == CorrectedOperator::Both);
    if (m_strain_corrected) {
      m_strain_sum = options.strain_sum.value_or(m_gradient->preferred_strain_sum());
      m_strain_reach = m_gradient->keeps_pattern() ? std::max(1, m_gradient->dependence_radius()) : kFullReach;
    }
  }
  m_fixed_u = Eigen::VectorXd::Zero(m_disc->size() - m_disc->free_count());
  if (cons && m_strain_corrected) {
    // Colouring of J = ds/du: row i (every particle) reads the free DOFs within m_strain_reach hops.
    const auto rows = reach_sets(m_disc->neighbours, m_disc->free_slot, m_strain_reach);
    SparsityPattern p;
    p.rows = m_disc->size();
    p.cols = m_disc->dofs();
    p.offsets.assign(1, 0);
    for (const auto& r : rows) {
      p.indices.insert(p.indices.end(), r.begin(), r.end());
      p.offsets.push_back(static_cast<long>(p.indices.size()));
    }
    const std::vector<int> colour = colour_columns(p);
    m_strain_colour_entries.assign(colour_count(colour), {});
    for (int i = 0; i < p.rows; ++i)
      for (long k = p.offsets[i]; k < p.offsets[i + 1]; ++k)
        m_strain_colour_entries[colour[p.indices[k]]].emplace_back(i, p.indices[k]);
  }
}

std::string WaveForm1D::name() const {
  std::ostringstream s;
  s << "wave1d/" << momentum_form_name(m_form) << "/T=" << m_tension;
  if (m_gradient) {
    s << "/" << m_gradient->name();
    if (m_strain_corrected && m_divergence_corrected)
      s << "@both";
    else
      s << (m_strain_corrected ? "@strain" : "@divergence");
    if (m_strain_corrected && m_strain_sum == StrainSum::Direct) s << "(direct)";
  }
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
  int radius = 2;  // plain: a_i reads s_j (j in N(i)), s_j reads u_m (m in N(j))
  if (m_form == MomentumForm::Conservative) {
    radius = m_strain_corrected ? saturating_add(m_strain_reach, m_strain_reach) : 2;  // a_k = sum_i V_i s_i ds_i/du_k
  } else if (m_gradient) {
    const bool dense_div = m_divergence_corrected && !m_gradient->keeps_pattern();
    const int dep_div = m_divergence_corrected ? m_gradient->dependence_radius() : 1;
    radius = std::max({2, dep_div, saturating_add(dense_div ? kFullReach : 1, m_strain_reach)});
  }
  return coupling_pattern(m_disc->neighbours, m_disc->free_slot, 1, std::min(radius, kFullReach));
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
                              Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& s, Operators<1, Scalar>& ops, bool hessian,
                              SparseMatrix<Scalar>& ghat, bool& corrected) const {
  const Discretisation<1>& d = *m_disc;
  Positions<1, Scalar> all = detail::full_displacement<1, Scalar>(d, u, m_fixed_u, "WaveForm1D");
  uall = all.col(0);
  Positions<1, Scalar> x = d.particles.x.template cast<Scalar>() + all;
  Operators<1, Scalar> fresh = assemble_operators<1, Scalar>(d.particles, d.neighbours, d.kernel, d.h,
                                                             detail::form_request<1>(m_gradient.get(), hessian), &x);
  detail::take_operators(ops, fresh);
  corrected = false;
  if (m_strain_corrected || m_divergence_corrected) {
    std::array<SparseMatrix<Scalar>, 1> g;
    corrected = detail::corrected_gradient<1, Scalar>(m_gradient.get(), d, x, ops, g, /*any_pattern=*/true);
    ghat.swap(g[0]);
  }
  s.resize(d.size());
  if (m_strain_corrected) {
    // Powell (3.55): s_i = sum_j (u_j - beta u_i) Ghat_ij + T, beta = 1 (difference) or 0 (direct)
    const double beta = m_strain_sum == StrainSum::Difference ? 1.0 : 0.0;
    for (int i = 0; i < d.size(); ++i) {
      Scalar sum(0);
      for (typename SparseMatrix<Scalar>::InnerIterator it(ghat, i); it; ++it)
        sum += (uall[it.col()] - beta * uall[i]) * it.value();
      s[i] = sum + m_tension;
    }
    return;
  }
  // s_i = sum_j (u_j - u_i) G_ij + T   (all particles)
  const NeighbourList& nl = d.neighbours;
  const Scalar* g = ops.G[0].valuePtr();
  for (int i = 0; i < d.size(); ++i) {
    Scalar sum(0);
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) sum += (uall[nl.indices[k]] - uall[i]) * g[k];
    s[i] = sum + m_tension;
  }
}

template <class Scalar>
void WaveForm1D::evaluate_energy_gradient(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                          Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  // dU/du_k = sum_i V_i s_i ds_i/du_k; one dual pass per colour c seeds every DOF of colour c, and the columns of a
  // colour share no row, so s_i.d = ds_i/du_k for the one DOF k of colour c that row i reads.
  using D = Dual<Scalar>;
  const Discretisation<1>& d = *m_disc;
  if (u.size() != d.dofs())
    throw std::invalid_argument("WaveForm1D: displacement has " + std::to_string(u.size()) + " entries, expected " +
                                std::to_string(d.dofs()) + " (free particles)");
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> grad = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>::Zero(d.dofs());
  Eigen::Matrix<D, Eigen::Dynamic, 1> ud(d.dofs()), uall, s;
  Operators<1, D> ops;
  SparseMatrix<D> ghat;
  bool corrected = false;
  for (size_t c = 0; c < m_strain_colour_entries.size(); ++c) {
    const auto& entries = m_strain_colour_entries[c];
    for (int k = 0; k < d.dofs(); ++k) ud[k] = D(u[k], Scalar(0));
    for (const auto& e : entries) ud[e.second].d = Scalar(1);
    strain_state<D>(ud, uall, s, ops, false, ghat, corrected);
    for (const auto& e : entries) grad[e.second] += d.particles.volume[e.first] * s[e.first].v * s[e.first].d;
  }
  a.resize(d.dofs());
  for (int f = 0; f < d.free_count(); ++f) a[f] = -grad[f] / d.particles.volume[d.free[f]];
}

template <class Scalar>
void WaveForm1D::evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                          Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& a) const {
  const Discretisation<1>& d = *m_disc;
  const NeighbourList& nl = d.neighbours;
  const bool cons = m_form == MomentumForm::Conservative;
  if (cons && m_strain_corrected) {
    evaluate_energy_gradient(u, a);
    return;
  }
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> uall, s;
  Operators<1, Scalar> ops;
  SparseMatrix<Scalar> ghat;
  bool corrected = false;
  strain_state(u, uall, s, ops, cons, ghat, corrected);
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
  // Powell (3.28): a_i = sum_j (s_j + alpha s_i) D_ij, D = Ghat (corrected divergence) or G
  const double alpha = momentum_form_alpha(m_form);
  if (m_divergence_corrected) {
    for (int f = 0; f < d.free_count(); ++f) {
      const int i = d.free[f];
      Scalar sum(0);
      for (typename SparseMatrix<Scalar>::InnerIterator it(ghat, i); it; ++it)
        sum += (s[it.col()] + alpha * s[i]) * it.value();
      a[f] = sum;
    }
    return;
  }
  const Scalar* g = ops.G[0].valuePtr();
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
  SparseMatrix<Scalar> ghat;
  bool corrected = false;
  strain_state(u, uall, s, ops, false, ghat, corrected);
  Scalar e(0);
  for (int i = 0; i < m_disc->size(); ++i) e += 0.5 * m_disc->particles.volume[i] * s[i] * s[i];
  return e;
}

Eigen::VectorXd WaveForm1D::stress(const Eigen::VectorXd& u) const {
  Eigen::VectorXd uall, s;
  Operators<1, double> ops;
  SparseMatrix<double> ghat;
  bool corrected = false;
  strain_state(u, uall, s, ops, false, ghat, corrected);
  return s;
}

template void WaveForm1D::evaluate<double>(const Eigen::VectorXd&, Eigen::VectorXd&) const;
template void WaveForm1D::evaluate<std::complex<double>>(const Eigen::VectorXcd&, Eigen::VectorXcd&) const;
template double WaveForm1D::energy<double>(const Eigen::VectorXd&) const;
template std::complex<double> WaveForm1D::energy<std::complex<double>>(const Eigen::VectorXcd&) const;

}  // namespace sphstab
