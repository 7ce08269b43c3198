#include "sphstab/forms/stabilised_sph.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "sphstab/core/named_values.hpp"

namespace sphstab {

namespace {

inline double re(double x) { return x; }
inline double re(const std::complex<double>& x) { return x.real(); }

bool switch_on(SwitchRule rule, double sum, double tolerance) {
  switch (rule) {
    case SwitchRule::Tension:
      return sum > tolerance;
    case SwitchRule::AsPrinted:
      return !(sum > tolerance);
    case SwitchRule::Always:
      return true;
    case SwitchRule::Never:
      return false;
  }
  return false;
}

}  // namespace

constexpr NamedValue<SwitchRule> kSwitchRuleNames[] = {{SwitchRule::Tension, "tension"},
                                                       {SwitchRule::AsPrinted, "as-printed"},
                                                       {SwitchRule::Always, "always"},
                                                       {SwitchRule::Never, "never"}};

std::string switch_rule_name(SwitchRule rule) { return name_of(rule, kSwitchRuleNames); }
SwitchRule parse_switch_rule(const std::string& name) { return parse_named(name, kSwitchRuleNames, "switch rule"); }

StabilisedSphTerm::StabilisedSphTerm(std::shared_ptr<const Discretisation<2>> discretisation,
                                     const StabilisedSphOptions& options)
    : m_disc(std::move(discretisation)), m_options(options) {
  if (!m_disc) throw std::invalid_argument("StabilisedSphTerm: discretisation is null");
  if (!(options.switch_tolerance >= 0))
    throw std::invalid_argument("StabilisedSphTerm: switch_tolerance must be >= 0 (got " +
                                std::to_string(options.switch_tolerance) + ")");
  if (options.excluded_depth < -1)
    throw std::invalid_argument("StabilisedSphTerm: excluded_depth must be >= -1 (got " +
                                std::to_string(options.excluded_depth) + ")");
  const Discretisation<2>& d = *m_disc;
  if (options.excluded_depth >= 0 && static_cast<int>(d.particles.depth.size()) != d.size())
    throw std::invalid_argument("StabilisedSphTerm: excluding the outer layer needs a depth per particle (got " +
                                std::to_string(d.particles.depth.size()) + " for " + std::to_string(d.size()) + ")");
  m_counts = neighbour_counts(d.particles, d.neighbours, options.counting);
  auto ops = assemble_operators<2, double>(d.particles, d.neighbours, d.kernel, d.h,
                                           {.kernel = true, .gradient = true, .hessian = false});
  for (int a = 0; a < 2; ++a) {
    m_reference[a] = shepard_reference(ops.W, ops.G[a]);
    for (int i = 0; i < d.size(); ++i)
      if (!(std::abs(m_reference[a].kernel_sum[i]) > 0))
        throw std::invalid_argument("StabilisedSphTerm: zero reference kernel sum at particle " + std::to_string(i));
  }
}

std::string StabilisedSphTerm::name() const {
  std::string s = "ssph(" + switch_rule_name(m_options.rule);
  if (!m_options.symmetrise) s += ",unsymmetrised";
  if (!m_options.first_step_shepard) s += ",no-4.18";
  if (m_options.counting == NeighbourCounting::Actual) s += ",actual-counts";
  if (is_frozen()) s += ",frozen";
  return s + ")";
}

SwitchState StabilisedSphTerm::switch_state(const Eigen::MatrixX3d& stress, double tol) const {
  const Discretisation<2>& d = *m_disc;
  if (stress.rows() != d.size())
    throw std::invalid_argument("StabilisedSphTerm::switch_state: stress has " + std::to_string(stress.rows()) +
                                " rows, expected " + std::to_string(d.size()));
  if (!m_frozen.empty()) return m_frozen;
  const NeighbourList& nl = d.neighbours;
  SwitchState on(d.size());
  for (int i = 0; i < d.size(); ++i) {
    const bool excluded = m_options.excluded_depth >= 0 && d.particles.depth[i] <= m_options.excluded_depth;
    double sxx = 0, syy = 0;
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      sxx += stress(nl.indices[k], 0);
      syy += stress(nl.indices[k], 1);
    }
    on[i] = {!excluded && switch_on(m_options.rule, sxx, tol), !excluded && switch_on(m_options.rule, syy, tol)};
  }
  return on;
}

std::shared_ptr<StabilisedSphTerm> StabilisedSphTerm::frozen(SwitchState state) const {
  if (static_cast<int>(state.size()) != m_disc->size())
    throw std::invalid_argument("StabilisedSphTerm::frozen: state has " + std::to_string(state.size()) +
                                " entries, expected " + std::to_string(m_disc->size()));
  auto copy = std::make_shared<StabilisedSphTerm>(*this);
  copy->m_frozen = std::move(state);
  return copy;
}

template <class Scalar>
std::array<LocalMeans<Scalar>, 2> StabilisedSphTerm::local_means_of(const Operators<2, Scalar>& ops) const {
  // Algorithm 4.1: means of the first-step Shepard gradient (4.18) per axis, fused into one pass over the pattern
  // (equal to local_means(reference_shepard_gradient(W, G, reference), counts); checked in the tests).
  std::array<LocalMeans<Scalar>, 2> means;
  const Discretisation<2>& d = *m_disc;
  const NeighbourList& nl = d.neighbours;
  const int N = d.size();
  for (int b = 0; b < 2; ++b) {
    LocalMeans<Scalar>& m = means[b];
    m.row = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>::Zero(N);
    m.column = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>::Zero(N);
    m.mean_of_columns = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>::Zero(N);
    const Scalar* g = ops.G[b].valuePtr();
    const Scalar* w = ops.W.valuePtr();
    for (int i = 0; i < N; ++i) {
      const double s0 = m_reference[b].kernel_sum[i], q0 = m_reference[b].gradient_sum[i];
      Scalar row(0);
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const Scalar gt = m_options.first_step_shepard ? (g[k] * s0 - w[k] * q0) / (s0 * s0) : g[k];
        row += gt;
        m.column[nl.indices[k]] += gt;
      }
      m.row[i] = row / m_counts[i];
    }
    for (int j = 0; j < N; ++j) m.column[j] /= m_counts[j];
    for (int i = 0; i < N; ++i) {
      Scalar sum(0);
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) sum += m.column[nl.indices[k]];
      m.mean_of_columns[i] = sum / m_counts[i];
    }
  }
  return means;
}

template <class Scalar>
void StabilisedSphTerm::add_impl(const ElasticTermContext<Scalar>& c, ParticleAccelerations<Scalar>& acc) const {
  const Discretisation<2>& d = *m_disc;
  const NeighbourList& nl = d.neighbours;
  const int N = d.size();
  // A blown-up state is a result, not an exception: propagate NaN instead of tripping the operators' input checks.
  for (int i = 0; i < N; ++i)
    for (int a = 0; a < 2; ++a)
      if (!std::isfinite(re(c.positions(i, a)))) {
        acc.setConstant(Scalar(std::numeric_limits<double>::quiet_NaN()));
        return;
      }
  const Operators<2, Scalar>& ops = c.operators;
  const std::array<LocalMeans<Scalar>, 2> means = local_means_of<Scalar>(ops);
  // Switch state from the real parts of the stresses (frozen for complex steps).
  const Eigen::MatrixX3d real_stress = c.stress.unaryExpr([](const Scalar& s) { return re(s); });
  const SwitchState on =
      switch_state(real_stress, m_options.switch_tolerance * (c.material.lambda() + 2 * c.material.mu()));
  const double inv_rho = 1.0 / c.material.density();
  const Scalar* g0 = ops.G[0].valuePtr();
  const Scalar* g1 = ops.G[1].valuePtr();
  const auto& sig = c.stress;
  for (int i = 0; i < N; ++i) {
    const bool any = on[i][0] || on[i][1];
    if (!m_options.symmetrise && !any) continue;
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      const Scalar sxx = (sig(i, 0) + sig(j, 0)) * inv_rho, syy = (sig(i, 1) + sig(j, 1)) * inv_rho,
                   sxy = (sig(i, 2) + sig(j, 2)) * inv_rho;
      // g_ij = -S_ij . (r_i + c_j - m_i), masked per component by the switch of i
      Scalar gx(0), gy(0);
      if (any) {
        const Scalar dx = means[0].row[i] + means[0].column[j] - means[0].mean_of_columns[i];
        const Scalar dy = means[1].row[i] + means[1].column[j] - means[1].mean_of_columns[i];
        if (on[i][0]) gx = -(sxx * dx + sxy * dy);
        if (on[i][1]) gy = -(sxy * dx + syy * dy);
      }
      if (!m_options.symmetrise) {
        acc(i, 0) += gx;
        acc(i, 1) += gy;
        continue;
      }
      // algorithm 4.2 minus the Plus form's sum_j f_ij already in the base: -f_ij/2 to i and j; +-g_ij/2.
      const Scalar fx = sxx * g0[k] + sxy * g1[k], fy = sxy * g0[k] + syy * g1[k];
      acc(i, 0) += 0.5 * (gx - fx);
      acc(i, 1) += 0.5 * (gy - fy);
      acc(j, 0) -= 0.5 * (gx + fx);
      acc(j, 1) -= 0.5 * (gy + fy);
    }
  }
}

template std::array<LocalMeans<double>, 2> StabilisedSphTerm::local_means_of<double>(const Operators<2, double>&) const;
template std::array<LocalMeans<std::complex<double>>, 2> StabilisedSphTerm::local_means_of<std::complex<double>>(
    const Operators<2, std::complex<double>>&) const;
template void StabilisedSphTerm::add_impl<double>(const ElasticTermContext<double>&,
                                                  ParticleAccelerations<double>&) const;
template void StabilisedSphTerm::add_impl<std::complex<double>>(const ElasticTermContext<std::complex<double>>&,
                                                                ParticleAccelerations<std::complex<double>>&) const;

std::shared_ptr<ElasticForm2D> make_stabilised_sph(std::shared_ptr<const Discretisation<2>> discretisation,
                                                   const ElasticMaterial& material, const PreStrain& prestrain,
                                                   const StabilisedSphOptions& options) {
  auto force = std::make_shared<ElasticForm2D>(discretisation, material, MomentumForm::Plus, prestrain);
  force->add_term(std::make_shared<StabilisedSphTerm>(discretisation, options));
  return force;
}

const StabilisedSphTerm* find_stabilised_sph_term(const ElasticForm2D& force) {
  for (const auto& t : force.terms())
    if (const auto* s = dynamic_cast<const StabilisedSphTerm*>(t.get())) return s;
  return nullptr;
}

std::shared_ptr<ElasticForm2D> freeze_switch(const ElasticForm2D& force, const Eigen::VectorXd& u) {
  const StabilisedSphTerm* term = find_stabilised_sph_term(force);
  if (!term) throw std::invalid_argument("freeze_switch: the force function has no S-SPH term");
  const double tol = term->options().switch_tolerance * (force.material().lambda() + 2 * force.material().mu());
  auto frozen_term = term->frozen(term->switch_state(force.stress(u), tol));
  std::vector<std::shared_ptr<const ElasticTerm2D>> terms;
  for (const auto& t : force.terms()) terms.push_back(t.get() == term ? frozen_term : t);
  auto copy = std::make_shared<ElasticForm2D>(force);
  copy->set_terms(std::move(terms));
  return copy;
}

}  // namespace sphstab
