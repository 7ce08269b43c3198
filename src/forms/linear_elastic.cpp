#include "sphstab/forms/linear_elastic.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/numerics/instantiation.hpp"

namespace sphstab {

namespace {

constexpr int stress_components(int dim) { return dim * (dim + 1) / 2; }

/// Compact index of σ_ab: diagonal first (a == b -> a), then off-diagonals (xy, xz, yz).
template <int Dim>
constexpr int sidx(int a, int b) {
  if (a == b) return a;
  if (a > b) std::swap(a, b);
  if constexpr (Dim == 2) return 2;
  return Dim + (a == 0 ? (b == 1 ? 0 : 1) : 2);
}


}  // namespace

template <int Dim>
LinearElasticSph<Dim>::LinearElasticSph(const ParticleSet<Dim>& particles, const Kernel<Dim>& kernel, double h,
                                        const LinearElasticOptions& opt)
    : m_p(particles), m_kernel(kernel), m_h(h), m_opt(opt) {
  m_p.validate("LinearElasticSph");
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("LinearElasticSph: h must be finite and > 0 (got " + format_number(h) + ")");
  opt.material.validate("LinearElasticSph");
  if (opt.gradient == StrainGradient::Corrected || opt.divergence == StressDivergence::Adjoint)
    throw std::invalid_argument("LinearElasticSph: only Plain/Minus gradients and Plain/Plus/Minus divergences");
  if (!(opt.skin >= 0)) throw std::invalid_argument("LinearElasticSph: skin must be >= 0");
  const int N = m_p.size();
  m_nfree = m_p.count(Role::Free);
  for (int i = 0; i < m_nfree; ++i)
    if (m_p.role[i] != Role::Free)
      throw std::invalid_argument("LinearElasticSph: free particles must come first (lattice ordering)");
  m_nl = find_neighbours(m_p, m_kernel.support_radius(h));
  if (opt.frame == LagrangianFrame::Total) build_tl();
  m_current = m_p;
  m_x = m_p.x;
  m_grad.resize(static_cast<long>(N) * Dim * Dim);
  m_sig.resize(static_cast<long>(N) * stress_components(Dim));
  m_uall.setZero(static_cast<long>(N) * Dim);
}

template <int Dim>
void LinearElasticSph<Dim>::build_tl() {
  const int N = m_p.size();
  auto ops = assemble_operators<Dim, double>(m_p, m_nl, m_kernel, m_h, {.kernel = false, .gradient = true});
  // B^a = (G^a - [minus] diag(G^a 1)) restricted to free columns; C^a = (G^a + α diag(G^a 1)) on free rows.
  const double alpha = divergence_alpha(m_opt.divergence);
  const bool minus = m_opt.gradient == StrainGradient::Minus;
  for (int a = 0; a < Dim; ++a) {
    SparseMatrix<>& G = ops.G[a];
    Eigen::VectorXd rs = Eigen::VectorXd::Zero(N);
    for (int i = 0; i < N; ++i)
      for (SparseMatrix<>::InnerIterator it(G, i); it; ++it) rs[i] += it.value();
    if (m_nfree == N) {  // all free: modify copies of G's CSR in place (no triplets; keeps memory low at 1e6)
      m_B[a] = G;
      m_C[a] = std::move(G);
      for (int i = 0; i < N; ++i) {
        m_B[a].coeffRef(i, i) -= minus ? rs[i] : 0.0;  // the diagonal is in the pattern (self neighbour)
        m_C[a].coeffRef(i, i) += alpha * rs[i];
      }
      continue;
    }
    std::vector<Eigen::Triplet<double>> tb, tc;
    tb.reserve(G.nonZeros());
    tc.reserve(G.nonZeros());
    for (int i = 0; i < N; ++i)
      for (SparseMatrix<>::InnerIterator it(G, i); it; ++it) {
        const int j = static_cast<int>(it.col());
        double vb = it.value(), vc = it.value();
        if (j == i) {
          vb -= minus ? rs[i] : 0.0;
          vc += alpha * rs[i];
        }
        if (j < m_nfree) tb.emplace_back(i, j, vb);
        if (i < m_nfree) tc.emplace_back(i, j, vc);
      }
    m_B[a].resize(N, m_nfree);
    m_B[a].setFromTriplets(tb.begin(), tb.end());
    m_C[a].resize(m_nfree, N);
    m_C[a].setFromTriplets(tc.begin(), tc.end());
    m_B[a].makeCompressed();
    m_C[a].makeCompressed();
  }
  for (int a = 1; a < Dim; ++a)
    if (m_B[a].nonZeros() != m_B[0].nonZeros() || m_C[a].nonZeros() != m_C[0].nonZeros())
      throw std::logic_error("LinearElasticSph: operator patterns differ between axes");
}

template <int Dim>
double LinearElasticSph<Dim>::p_wave_speed() const {
  return std::sqrt((m_opt.material.lambda() + 2.0 * m_opt.material.mu()) / m_opt.material.density());
}

template <int Dim>
long LinearElasticSph<Dim>::stored_nonzeros() const {
  if (m_opt.frame != LagrangianFrame::Total) return 0;
  long s = 0;
  for (int a = 0; a < Dim; ++a) s += m_B[a].nonZeros() + m_C[a].nonZeros();
  return s;
}

template <int Dim>
double LinearElasticSph<Dim>::tl_bytes_per_acceleration() const {
  if (m_opt.frame != LagrangianFrame::Total) return 0;
  const double N = m_p.size(), n = m_nfree, S = stress_components(Dim);
  const double nb = static_cast<double>(m_B[0].nonZeros()), nc = static_cast<double>(m_C[0].nonZeros());
  const double grad = nb * (4 + 8.0 * Dim) + 4 * (N + 1) + 8.0 * Dim * n + 8.0 * Dim * Dim * N;
  const double stress = 8.0 * Dim * Dim * N + 8 * S * N;
  const double div = nc * (4 + 8.0 * Dim) + 4 * (n + 1) + 8 * S * N + 8.0 * Dim * n;
  return grad + stress + div;
}

template <int Dim>
void LinearElasticSph<Dim>::gradient_pass(const int* outer, const int* inner, const std::array<const double*, Dim>& val,
                                          int rows) const {
  const double* u = m_uall.data();
  double* g = m_grad.data();
#pragma omp parallel for schedule(static) num_threads(threads_for(rows))
  for (int i = 0; i < rows; ++i) {
    double acc[Dim][Dim] = {};
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const double* uj = u + static_cast<long>(inner[k]) * Dim;
      for (int a = 0; a < Dim; ++a) {
        const double v = val[a][k];
        for (int b = 0; b < Dim; ++b) acc[a][b] += v * uj[b];
      }
    }
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) g[(static_cast<long>(i) * Dim + a) * Dim + b] = acc[a][b];
  }
}

template <int Dim>
void LinearElasticSph<Dim>::stress_from_gradients(int N) const {
  constexpr int S = stress_components(Dim);
  const double lam = m_opt.material.lambda(), mu = m_opt.material.mu();
#pragma omp parallel for schedule(static) num_threads(threads_for(N))
  for (int i = 0; i < N; ++i) {
    const double* g = m_grad.data() + static_cast<long>(i) * Dim * Dim;  // g[a*Dim+b] = ∂_a u_b
    double tr = 0;
    for (int a = 0; a < Dim; ++a) tr += g[a * Dim + a];
    double* s = m_sig.data() + static_cast<long>(i) * S;
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b) {
        const double eps = 0.5 * (g[a * Dim + b] + g[b * Dim + a]);
        s[sidx<Dim>(a, b)] = 2.0 * mu * eps + (a == b ? lam * tr : 0.0);
      }
  }
}

template <int Dim>
void LinearElasticSph<Dim>::divergence_pass(const int* outer, const int* inner,
                                            const std::array<const double*, Dim>& val, int rows,
                                            const std::array<const double*, Dim>* rowsum, double alpha,
                                            Eigen::VectorXd& a_out) const {
  constexpr int S = stress_components(Dim);
  const double* sig = m_sig.data();
  const double inv_rho = 1.0 / m_opt.material.density();
#pragma omp parallel for schedule(static) num_threads(threads_for(rows))
  for (int i = 0; i < rows; ++i) {
    double acc[Dim] = {};
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const double* sj = sig + static_cast<long>(inner[k]) * S;
      for (int a = 0; a < Dim; ++a) {
        const double v = val[a][k];
        for (int b = 0; b < Dim; ++b) acc[b] += v * sj[sidx<Dim>(a, b)];
      }
    }
    if (rowsum && alpha != 0) {
      const double* si = sig + static_cast<long>(i) * S;
      for (int a = 0; a < Dim; ++a)
        for (int b = 0; b < Dim; ++b) acc[b] += alpha * (*rowsum)[a][i] * si[sidx<Dim>(a, b)];
    }
    for (int b = 0; b < Dim; ++b) a_out[static_cast<long>(i) * Dim + b] = acc[b] * inv_rho;
  }
}

template <int Dim>
void LinearElasticSph<Dim>::update_current(const Eigen::VectorXd& u) const {
  const int N = m_p.size();
  for (int i = 0; i < N; ++i)
    for (int b = 0; b < Dim; ++b) m_x(i, b) = m_p.x(i, b) + (i < m_nfree ? u[static_cast<long>(i) * Dim + b] : 0.0);
  const bool rebuild = m_nl_current.size() == 0 || m_u_at_build.size() != u.size() ||
                       (u - m_u_at_build).cwiseAbs().maxCoeff() > 0.5 * m_opt.skin;
  if (!rebuild) return;
  m_current.x = m_x;
  for (int b = 0; b < Dim; ++b)
    if (m_p.periodic[b]) {  // wrap into the box for the search; assembly uses minimum images
      const double lo = m_p.box_lo[b], L = m_p.box_hi[b] - m_p.box_lo[b];
      for (int i = 0; i < N; ++i) {
        double& x = m_current.x(i, b);
        x -= L * std::floor((x - lo) / L);
        if (x >= lo + L) x = lo;
      }
    }
  m_nl_current = find_neighbours(m_current, m_kernel.support_radius(m_h) + m_opt.skin);
  for (int a = 0; a < Dim; ++a) m_Gul[a] = pattern_matrix<double>(m_nl_current);
  m_u_at_build = u;
  ++m_builds;
}

template <int Dim>
void LinearElasticSph<Dim>::reassemble_in_place() const {
  const int N = m_p.size();
  const double support = m_kernel.support_radius(m_h);
  std::array<double, Dim> box{};
  for (int b = 0; b < Dim; ++b) box[b] = m_p.periodic[b] ? m_p.box_hi[b] - m_p.box_lo[b] : 0.0;
  std::array<double*, Dim> val;
  for (int a = 0; a < Dim; ++a) {
    val[a] = m_Gul[a].valuePtr();
    m_rowsum[a].setZero(N);
  }
  // Same entries as assemble_operators (G^a_ij = W'(r) (x_i - x_j)^a / r V_j, minimum image, 0 beyond the support).
  // Each row writes only its own entries and row sums, in the serial order: threads keep the bits.
#pragma omp parallel for schedule(static) num_threads(threads_for(N))
  for (int i = 0; i < N; ++i)
    for (long k = m_nl_current.offsets[i]; k < m_nl_current.offsets[i + 1]; ++k) {
      const int j = m_nl_current.indices[k];
      double d[Dim], r2 = 0;
      for (int b = 0; b < Dim; ++b) {
        d[b] = m_x(i, b) - m_x(j, b);
        if (box[b] > 0) d[b] -= box[b] * std::round(d[b] / box[b]);
        r2 += d[b] * d[b];
      }
      const double r = std::sqrt(r2);
      if (j == i || r2 == 0 || r >= support) {
        for (int a = 0; a < Dim; ++a) val[a][k] = 0.0;
        continue;
      }
      const double f = m_kernel.d1(r, m_h) / r * m_p.volume[j];
      for (int a = 0; a < Dim; ++a) {
        val[a][k] = f * d[a];
        m_rowsum[a][i] += f * d[a];
      }
    }
}

template <int Dim>
void LinearElasticSph<Dim>::acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const {
  const int N = m_p.size();
  if (u.size() != static_cast<long>(m_nfree) * Dim)
    throw std::invalid_argument("LinearElasticSph::acceleration: u has " + std::to_string(u.size()) +
                                " entries, expected " + std::to_string(static_cast<long>(m_nfree) * Dim));
  a.resize(u.size());
  if (m_opt.frame == LagrangianFrame::Total) {
    m_uall.head(u.size()) = u;  // fixed particles keep u = 0 (B has no fixed columns anyway)
    std::array<const double*, Dim> vb, vc;
    for (int d = 0; d < Dim; ++d) {
      vb[d] = m_B[d].valuePtr();
      vc[d] = m_C[d].valuePtr();
    }
    gradient_pass(m_B[0].outerIndexPtr(), m_B[0].innerIndexPtr(), vb, N);
    stress_from_gradients(N);
    divergence_pass(m_C[0].outerIndexPtr(), m_C[0].innerIndexPtr(), vc, m_nfree, nullptr, 0.0, a);
    return;
  }
  update_current(u);
  reassemble_in_place();
  accumulate_from_gradients(m_Gul, u, a);
}

template <int Dim>
void LinearElasticSph<Dim>::accumulate_from_gradients(const std::array<SparseMatrix<>, Dim>& G,
                                                      const Eigen::VectorXd& u, Eigen::VectorXd& a) const {
  const int N = m_p.size();
  m_uall.setZero();
  m_uall.head(u.size()) = u;
  const auto& rs = m_rowsum;  // filled by reassemble_in_place
  std::array<const double*, Dim> val, rsp;
  for (int d = 0; d < Dim; ++d) {
    val[d] = G[d].valuePtr();
    rsp[d] = rs[d].data();
  }
  gradient_pass(G[0].outerIndexPtr(), G[0].innerIndexPtr(), val, N);
  if (m_opt.gradient == StrainGradient::Minus)
#pragma omp parallel for schedule(static) num_threads(threads_for(N))
    for (int i = 0; i < N; ++i)
      for (int d = 0; d < Dim; ++d)
        for (int b = 0; b < Dim; ++b)
          m_grad[(static_cast<long>(i) * Dim + d) * Dim + b] -= rs[d][i] * m_uall[static_cast<long>(i) * Dim + b];
  stress_from_gradients(N);
  divergence_pass(G[0].outerIndexPtr(), G[0].innerIndexPtr(), val, m_nfree, &rsp, divergence_alpha(m_opt.divergence),
                  a);
}

template <int Dim>
void LinearElasticSph<Dim>::acceleration_pair_loop(const Eigen::VectorXd& u, Eigen::VectorXd& a) const {
  constexpr int S = stress_components(Dim);
  const int N = m_p.size();
  if (u.size() != static_cast<long>(m_nfree) * Dim)
    throw std::invalid_argument("LinearElasticSph::acceleration_pair_loop: u has the wrong size");
  a.resize(u.size());
  const bool ul = m_opt.frame == LagrangianFrame::Updated;
  const NeighbourList* nl = &m_nl;
  if (ul) {
    update_current(u);
    nl = &m_nl_current;
  } else {
    m_x = m_p.x;
  }
  m_uall.setZero();
  m_uall.head(u.size()) = u;
  const double support = m_kernel.support_radius(m_h);
  const bool minus = m_opt.gradient == StrainGradient::Minus;
  const double alpha = divergence_alpha(m_opt.divergence);
  std::array<double, Dim> box{};
  for (int b = 0; b < Dim; ++b) box[b] = m_p.periodic[b] ? m_p.box_hi[b] - m_p.box_lo[b] : 0.0;
  // ∇_i W_ij V_j at the current/reference positions (zero beyond the support).
  auto grad_w = [&](int i, int j, double* gw) -> bool {
    double d[Dim], r2 = 0;
    for (int b = 0; b < Dim; ++b) {
      d[b] = m_x(i, b) - m_x(j, b);
      if (box[b] > 0) d[b] -= box[b] * std::round(d[b] / box[b]);
      r2 += d[b] * d[b];
    }
    if (r2 == 0) return false;
    const double r = std::sqrt(r2);
    if (r >= support) return false;
    const double f = m_kernel.d1(r, m_h) / r * m_p.volume[j];
    for (int b = 0; b < Dim; ++b) gw[b] = f * d[b];
    return true;
  };
  // Pass 1: displacement gradient at every particle.
#pragma omp parallel for schedule(static) num_threads(threads_for(N))
  for (int i = 0; i < N; ++i) {
    double acc[Dim][Dim] = {};
    const double* ui = m_uall.data() + static_cast<long>(i) * Dim;
    for (long k = nl->offsets[i]; k < nl->offsets[i + 1]; ++k) {
      const int j = nl->indices[k];
      double gw[Dim];
      if (j == i || !grad_w(i, j, gw)) continue;
      const double* uj = m_uall.data() + static_cast<long>(j) * Dim;
      for (int c = 0; c < Dim; ++c)
        for (int b = 0; b < Dim; ++b) acc[c][b] += gw[c] * (uj[b] - (minus ? ui[b] : 0.0));
    }
    for (int c = 0; c < Dim; ++c)
      for (int b = 0; b < Dim; ++b) m_grad[(static_cast<long>(i) * Dim + c) * Dim + b] = acc[c][b];
  }
  stress_from_gradients(N);
  // Pass 2: divergence at the free particles.
  const double inv_rho = 1.0 / m_opt.material.density();
#pragma omp parallel for schedule(static) num_threads(threads_for(m_nfree))
  for (int i = 0; i < m_nfree; ++i) {
    double acc[Dim] = {};
    const double* si = m_sig.data() + static_cast<long>(i) * S;
    for (long k = nl->offsets[i]; k < nl->offsets[i + 1]; ++k) {
      const int j = nl->indices[k];
      double gw[Dim];
      if (j == i || !grad_w(i, j, gw)) continue;
      const double* sj = m_sig.data() + static_cast<long>(j) * S;
      for (int c = 0; c < Dim; ++c)
        for (int b = 0; b < Dim; ++b) acc[b] += gw[c] * (sj[sidx<Dim>(c, b)] + alpha * si[sidx<Dim>(c, b)]);
    }
    for (int b = 0; b < Dim; ++b) a[static_cast<long>(i) * Dim + b] = acc[b] * inv_rho;
  }
}

template <int Dim>
double LinearElasticSph<Dim>::strain_energy(const Eigen::VectorXd& u) const {
  constexpr int S = stress_components(Dim);
  const int N = m_p.size();
  if (m_opt.frame == LagrangianFrame::Total) {
    m_uall.setZero();
    m_uall.head(u.size()) = u;
    std::array<const double*, Dim> vb;
    for (int d = 0; d < Dim; ++d) vb[d] = m_B[d].valuePtr();
    gradient_pass(m_B[0].outerIndexPtr(), m_B[0].innerIndexPtr(), vb, N);
    stress_from_gradients(N);
  } else {  // gradient at the current positions (accumulate_from_gradients leaves ∇u and σ in the buffers)
    Eigen::VectorXd a(u.size());
    update_current(u);
    reassemble_in_place();
    accumulate_from_gradients(m_Gul, u, a);
  }
  double e = 0;
  for (int i = 0; i < N; ++i) {
    const double* g = m_grad.data() + static_cast<long>(i) * Dim * Dim;
    const double* s = m_sig.data() + static_cast<long>(i) * S;
    double w = 0;
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) w += s[sidx<Dim>(a, b)] * 0.5 * (g[a * Dim + b] + g[b * Dim + a]);
    e += 0.5 * m_p.volume[i] * w;
  }
  return e;
}

template <int Dim>
SecondOrderSystem LinearElasticSph<Dim>::system(bool pair_loop) const {
  SecondOrderSystem s;
  if (pair_loop)
    s.acceleration = [this](const Eigen::VectorXd& u, Eigen::VectorXd& a) { acceleration_pair_loop(u, a); };
  else
    s.acceleration = [this](const Eigen::VectorXd& u, Eigen::VectorXd& a) { acceleration(u, a); };
  s.strain_energy = [this](const Eigen::VectorXd& u) { return strain_energy(u); };
  s.dofs_per_particle = Dim;
  s.mass = m_opt.material.density() * m_p.volume.head(m_nfree);
  s.reference_positions.resize(static_cast<long>(m_nfree) * Dim);
  for (int i = 0; i < m_nfree; ++i)
    for (int b = 0; b < Dim; ++b) s.reference_positions[static_cast<long>(i) * Dim + b] = m_p.x(i, b);
  return s;
}

#define SPHSTAB_INSTANTIATE(D) template class LinearElasticSph<D>;
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
