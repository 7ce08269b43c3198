#include "sphstab/forms/elastic_bar.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/core/named_values.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {

constexpr NamedValue<StrainGradient> kStrainGradientNames[] = {
    {StrainGradient::Plain, "plain"}, {StrainGradient::Minus, "minus"}, {StrainGradient::Corrected, "corrected"}};
constexpr NamedValue<StressDivergence> kStressDivergenceNames[] = {{StressDivergence::Plain, "plain"},
                                                                   {StressDivergence::Plus, "plus"},
                                                                   {StressDivergence::Minus, "minus"},
                                                                   {StressDivergence::Adjoint, "adjoint"}};

std::string strain_gradient_name(StrainGradient g) { return name_of(g, kStrainGradientNames); }
std::string stress_divergence_name(StressDivergence d) { return name_of(d, kStressDivergenceNames); }
std::string bar_boundary_name(BarBoundary b) { return b == BarBoundary::Mirror ? "mirror" : "none"; }
std::string lagrangian_frame_name(LagrangianFrame f) { return f == LagrangianFrame::Total ? "TL" : "UL"; }

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

}  // namespace

ElasticBar1D::ElasticBar1D(const ElasticBarOptions& opt) : m_opt(opt), m_kernel(opt.kernel) {
  auto pos = [](double x) { return x > 0 && std::isfinite(x); };
  if (opt.particles < 2)
    throw std::invalid_argument("ElasticBar1D: need at least 2 particles (got " + std::to_string(opt.particles) + ")");
  if (!pos(opt.length) || !pos(opt.density) || !pos(opt.youngs_modulus) || !pos(opt.h_over_dx))
    throw std::invalid_argument("ElasticBar1D: length, density, youngs_modulus and h_over_dx must be finite and > 0");
  if (!(opt.skin_over_dx >= 0) || !std::isfinite(opt.skin_over_dx))
    throw std::invalid_argument("ElasticBar1D: skin_over_dx must be finite and >= 0");
  m_n = opt.particles;
  m_dx = opt.length / m_n;
  m_h = opt.h_over_dx * m_dx;
  int layers = 0;
  if (opt.boundary == BarBoundary::Mirror) {
    layers = fixed_layers_needed(m_kernel.support_radius(m_h), m_dx);
    if (opt.frame == LagrangianFrame::Updated) layers += 1;  // compressed neighbourhoods reach one layer further
  }
  if (layers > m_n)
    throw std::invalid_argument("ElasticBar1D: " + std::to_string(layers) + " mirror layers need at least as many " +
                                "particles (got " + std::to_string(m_n) + ")");
  LatticeOptions lo;
  lo.spacing = m_dx;
  lo.fixed_layers = layers;
  m_set = make_lattice<1>(LatticeType::Line, m_n, lo);
  const int N = m_set.size();
  m_map.resize(N);
  m_sign_u.assign(N, 1.0);
  m_sign_s.assign(N, 1.0);
  for (int p = 0; p < N; ++p) {
    if (p < m_n) {
      m_map[p] = p;
      continue;
    }
    const long idx = std::lround(m_set.x(p, 0) / m_dx - 0.5);
    const long m = idx < 0 ? -idx - 1 : 2L * m_n - 1 - idx;
    if (m < 0 || m >= m_n) throw std::logic_error("ElasticBar1D: ghost without a mirror image");
    m_map[p] = static_cast<int>(m);
    m_sign_s[p] = -1.0;
  }
  m_X = m_set.x.col(0).head(m_n);
  m_V = m_set.volume.head(m_n);
  m_nl = find_neighbours(m_set, m_kernel.support_radius(m_h));
  build_tl();
  m_current = m_set;
  m_x = m_set.x;
}

double ElasticBar1D::wave_speed() const { return std::sqrt(m_opt.youngs_modulus / m_opt.density); }

void ElasticBar1D::build_tl() {
  auto ops = assemble_operators<1, double>(m_set, m_nl, m_kernel, m_h, {.kernel = true, .gradient = true});
  const SparseMatrix<>& G = ops.G[0];
  const SparseMatrix<>& W = ops.W;
  const bool minus_u = m_opt.gradient != StrainGradient::Plain;
  const bool corrected = m_opt.gradient == StrainGradient::Corrected;
  const double alpha = divergence_alpha(m_opt.divergence);
  Triplets tb, tc, tw;
  for (int i = 0; i < m_n; ++i) {
    double rs = 0, rw = 0, m1 = 0;
    for (SparseMatrix<>::InnerIterator it(G, i); it; ++it) {
      const int j = static_cast<int>(it.col());
      rs += it.value();
      m1 += it.value() * (m_set.x(j, 0) - m_set.x(i, 0));
    }
    const double scale = corrected ? 1.0 / m1 : 1.0;
    for (SparseMatrix<>::InnerIterator it(G, i); it; ++it) {
      const int j = static_cast<int>(it.col());
      tb.emplace_back(i, m_map[j], scale * m_sign_u[j] * it.value());
      if (m_opt.divergence != StressDivergence::Adjoint) tc.emplace_back(i, m_map[j], m_sign_s[j] * it.value());
    }
    for (SparseMatrix<>::InnerIterator it(W, i); it; ++it) {
      const int j = static_cast<int>(it.col());
      rw += it.value();
      tw.emplace_back(i, m_map[j], m_sign_u[j] * it.value());
    }
    if (minus_u) tb.emplace_back(i, i, -scale * rs);
    if (alpha != 0) tc.emplace_back(i, i, alpha * rs);
    tw.emplace_back(i, i, -rw);
  }
  m_B.resize(m_n, m_n);
  m_B.setFromTriplets(tb.begin(), tb.end());
  m_Wx.resize(m_n, m_n);
  m_Wx.setFromTriplets(tw.begin(), tw.end());
  if (m_opt.divergence == StressDivergence::Adjoint) {
    // C = -V^{-1} B^T V.
    SparseMatrix<> Bt = m_B.transpose();
    m_C = -(m_V.cwiseInverse().asDiagonal() * Bt * m_V.asDiagonal());
  } else {
    m_C.resize(m_n, m_n);
    m_C.setFromTriplets(tc.begin(), tc.end());
  }
  m_C *= m_opt.youngs_modulus / m_opt.density;
  m_B.makeCompressed();
  m_C.makeCompressed();
  m_eps.resize(m_n);
}

SparseMatrix<> ElasticBar1D::stiffness_matrix() const {
  SparseMatrix<> A = -(m_C * m_B);
  return A;
}

void ElasticBar1D::update_current(const Eigen::VectorXd& u) const {
  const int N = m_set.size();
  for (int p = 0; p < N; ++p) m_x(p, 0) = m_set.x(p, 0) + m_sign_u[p] * u[m_map[p]];
  const double skin = m_opt.skin_over_dx * m_dx;
  const bool rebuild = m_nl_current.size() == 0 || m_u_at_build.size() != u.size() ||
                       (u - m_u_at_build).cwiseAbs().maxCoeff() > 0.5 * skin;
  if (rebuild) {
    m_current.x = m_x;
    m_nl_current = find_neighbours(m_current, m_kernel.support_radius(m_h) + skin);
    m_u_at_build = u;
    ++m_builds;
  }
}

void ElasticBar1D::acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const {
  if (u.size() != m_n)
    throw std::invalid_argument("ElasticBar1D::acceleration: u has " + std::to_string(u.size()) +
                                " entries, expected " + std::to_string(m_n));
  a.resize(m_n);
  if (m_opt.frame == LagrangianFrame::Total) {
    m_eps.noalias() = m_B * u;
    a.noalias() = m_C * m_eps;
    return;
  }
  // Updated Lagrangian: reassemble G at x = X + u, then the same sums row by row.
  update_current(u);
  auto ops =
      assemble_operators<1, double>(m_set, m_nl_current, m_kernel, m_h, {.kernel = false, .gradient = true}, &m_x);
  ++m_assemblies;
  const SparseMatrix<>& G = ops.G[0];
  const bool minus_u = m_opt.gradient != StrainGradient::Plain;
  const double E = m_opt.youngs_modulus, rho = m_opt.density;
  strain_rows(G, m_x, u, m_eps, m_rowsum, m_scale);
  m_sig = E * m_eps;
  if (m_opt.divergence == StressDivergence::Adjoint) {
    a.setZero();
    for (int i = 0; i < m_n; ++i) {
      const double vs = m_scale[i] * m_V[i] * m_sig[i];
      for (SparseMatrix<>::InnerIterator it(G, i); it; ++it) {
        const int j = static_cast<int>(it.col());
        a[m_map[j]] += m_sign_u[j] * it.value() * vs;
      }
      if (minus_u) a[i] -= m_rowsum[i] * vs;
    }
    a = -(a.array() / (rho * m_V.array())).matrix();
    return;
  }
  const double alpha = divergence_alpha(m_opt.divergence);
  for (int i = 0; i < m_n; ++i) {
    double s = 0;
    for (SparseMatrix<>::InnerIterator it(G, i); it; ++it) {
      const int j = static_cast<int>(it.col());
      s += it.value() * m_sign_s[j] * m_sig[m_map[j]];
    }
    a[i] = (s + alpha * m_rowsum[i] * m_sig[i]) / rho;
  }
}

void ElasticBar1D::strain_rows(const SparseMatrix<>& G, const Positions<1>& x, const Eigen::VectorXd& u,
                               Eigen::VectorXd& eps, Eigen::VectorXd& rowsum, Eigen::VectorXd& scale) const {
  eps.resize(m_n);
  rowsum.resize(m_n);
  scale.setOnes(m_n);
  for (int i = 0; i < m_n; ++i) {
    double rs = 0, s = 0, m1 = 0;
    for (SparseMatrix<>::InnerIterator it(G, i); it; ++it) {
      const int j = static_cast<int>(it.col());
      rs += it.value();
      s += it.value() * m_sign_u[j] * u[m_map[j]];
      m1 += it.value() * (x(j, 0) - x(i, 0));
    }
    rowsum[i] = rs;
    if (m_opt.gradient == StrainGradient::Corrected) scale[i] = 1.0 / m1;
    eps[i] = m_opt.gradient == StrainGradient::Plain ? s : scale[i] * (s - rs * u[i]);
  }
}

Eigen::VectorXd ElasticBar1D::strain(const Eigen::VectorXd& u) const {
  if (u.size() != m_n) throw std::invalid_argument("ElasticBar1D::strain: u has the wrong size");
  if (m_opt.frame == LagrangianFrame::Total) return m_B * u;
  update_current(u);
  auto ops =
      assemble_operators<1, double>(m_set, m_nl_current, m_kernel, m_h, {.kernel = false, .gradient = true}, &m_x);
  Eigen::VectorXd eps, rs, scale;
  strain_rows(ops.G[0], m_x, u, eps, rs, scale);
  return eps;
}

double ElasticBar1D::strain_energy(const Eigen::VectorXd& u) const {
  Eigen::VectorXd eps = strain(u);
  return 0.5 * m_opt.youngs_modulus * (m_V.array() * eps.array().square()).sum();
}

VelocityHook ElasticBar1D::xsph_hook(double eps) const {
  if (!(eps >= 0) || !std::isfinite(eps))
    throw std::invalid_argument("ElasticBar1D::xsph_hook: eps must be finite and >= 0");
  return [this, eps](const Eigen::VectorXd&, const Eigen::VectorXd& v, Eigen::VectorXd& w) {
    w = v;
    w.noalias() += eps * (m_Wx * v);
  };
}

SecondOrderSystem ElasticBar1D::system() const {
  SecondOrderSystem s;
  s.acceleration = [this](const Eigen::VectorXd& u, Eigen::VectorXd& a) { acceleration(u, a); };
  s.strain_energy = [this](const Eigen::VectorXd& u) { return strain_energy(u); };
  s.dofs_per_particle = 1;
  s.mass = masses();
  s.reference_positions = m_X;
  return s;
}

}  // namespace sphstab
