#include "sphstab/jacobian/matrix_free_linearisation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "../operators/pair_derivatives.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"

namespace sphstab {

namespace {

template <int Dim>
long free_row_pairs(const Discretisation<Dim>& d) {
  long pairs = 0;
  for (int i : d.free) pairs += d.neighbours.count(i);
  return pairs;
}

/// The force's discretisation, after checking that the closed form covers the force.
const Discretisation<2>& covered_discretisation(const ElasticForm2D& force) {
  require_closed_form_coverage(force, "MatrixFreeLinearisation");
  return force.discretisation();
}

/// Index of the symmetric pair (a, b), a <= b, in row-by-row order (2D: xx, xy, yy; 3D: xx, xy, xz, yy, yz, zz).
template <int Dim>
constexpr int upper(int a, int b) {
  return a * Dim - a * (a - 1) / 2 + (b - a);
}
/// Index of (a, b) in the stress buffer: the diagonal first, then xy[, xz, yz].
template <int Dim>
constexpr int voigt(int a, int b) {
  if (a == b) return a;
  if (a > b) std::swap(a, b);
  return Dim == 2 ? 2 : (a == 0 ? 2 + b : 5);
}

template <int Dim>
void check_operators(const Discretisation<Dim>& d, const Operators<Dim>& ops, const std::string& who) {
  const int n = d.size();
  const auto check = [&](const SparseMatrix<>& m, const std::string& name) {
    if (m.rows() != n || m.cols() != n || m.nonZeros() != d.neighbours.nonzeros() || !m.isCompressed())
      throw std::invalid_argument(who + ": operator " + name + " must be " + std::to_string(n) + " x " +
                                  std::to_string(n) +
                                  " with the neighbour-list pattern (assemble with gradient = true, hessian = true)");
  };
  const char* axis = "xyz";
  for (int a = 0; a < Dim; ++a) check(ops.G[a], std::string("G[") + axis[a] + "]");
  for (int a = 0; a < Dim; ++a)
    for (int b = a; b < Dim; ++b) check(ops.H[a][b], std::string("H[") + axis[a] + "][" + axis[b] + "]");
}

}  // namespace

template <>
Eigen::Matrix2d prestress<2>(PreStrainKind kind, const ElasticMaterial& material) {
  return PreStrain{kind, 1.0}.stress(material);
}

template <>
Eigen::Matrix3d prestress<3>(PreStrainKind kind, const ElasticMaterial& m) {
  const double lam = m.lambda(), mu = m.mu();
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  if (kind == PreStrainKind::Isotropic)
    s.diagonal().setConstant(3 * lam + 2 * mu);
  else
    s.diagonal() << lam + 2 * mu, lam, lam;
  return s;
}

template <int Dim>
double MatrixFreeLinearisation<Dim>::estimated_bytes(const Discretisation<Dim>& d) {
  const double n = d.size(), nf = d.free_count(), pairs = d.neighbours.nonzeros();
  const double free_pairs = free_row_pairs(d);
  constexpr double S = kSymmetric;
  // CSR (8 per offset, 4 per index), G pairs and row sums, free map and stress rows, H of the free rows with eta,
  // the stress buffer, the free positions.
  return 8 * (n + 1) + 4 * pairs + 8 * Dim * pairs + 8 * Dim * n + 4 * (2 * n + nf) + 8 * (nf + 1) +
         8 * S * free_pairs + 8 * S * nf + 8 * S * n + 8 * Dim * nf;
}

template <int Dim>
MatrixFreeLinearisation<Dim>::MatrixFreeLinearisation(const Discretisation<Dim>& d, const Operators<Dim>& ops,
                                                      const ElasticMaterial& material, MomentumForm form,
                                                      PreStrainKind kind) {
  material.validate("MatrixFreeLinearisation");
  check_operators(d, ops, "MatrixFreeLinearisation");
  build(d, &ops, material, form, kind);
}

template <int Dim>
MatrixFreeLinearisation<Dim>::MatrixFreeLinearisation(const Discretisation<Dim>& d, const ElasticMaterial& material,
                                                      MomentumForm form, PreStrainKind kind) {
  material.validate("MatrixFreeLinearisation");
  if (d.neighbours.radius + 1e-12 * d.h < d.kernel.support_radius(d.h) * (1 - 1e-12))
    throw std::invalid_argument("MatrixFreeLinearisation: neighbour radius " + format_number(d.neighbours.radius) +
                                " is smaller than the kernel support " + format_number(d.kernel.support_radius(d.h)));
  build(d, nullptr, material, form, kind);
}

template <int Dim>
template <int D>
  requires(D == 2 && D == Dim)
MatrixFreeLinearisation<Dim>::MatrixFreeLinearisation(const ElasticForm2D& force)
    : MatrixFreeLinearisation(covered_discretisation(force), force.material(), force.form(), force.prestrain().kind) {}

template <int Dim>
void MatrixFreeLinearisation<Dim>::build(const Discretisation<Dim>& d, const Operators<Dim>* ops,
                                         const ElasticMaterial& material, MomentumForm form, PreStrainKind kind) {
  require_memory(estimated_bytes(d), "MatrixFreeLinearisation: " + std::to_string(d.dofs()) + " DOFs");
  const int n = d.size(), nf = d.free_count();
  const NeighbourList& nl = d.neighbours;
  const bool cons = form == MomentumForm::Conservative;
  m_form = form;
  m_inv_rho = 1.0 / material.density();
  m_lambda = material.lambda();
  m_mu = material.mu();
  m_alpha = cons ? 1.0 : momentum_form_alpha(form);
  m_a1_factor = cons ? 2.0 * m_inv_rho : (1.0 + momentum_form_alpha(form)) * m_inv_rho;
  m_s0 = prestress<Dim>(kind, material);
  m_free = d.free;
  m_free_positions = d.free_positions();
  m_free_slot = d.free_slot;
  m_offsets = nl.offsets;
  m_indices = nl.indices;

  // Pair values: copied from the operators, or computed as assemble_operators does (without its matrices).
  const long pairs = nl.nonzeros();
  m_h_offsets.assign(nf + 1, 0);
  for (int f = 0; f < nf; ++f) m_h_offsets[f + 1] = m_h_offsets[f] + nl.count(d.free[f]);
  m_g.resize(Dim * pairs);
  m_h.resize(kSymmetric * m_h_offsets[nf]);
  const ParticleSet<Dim>& p = d.particles;
  std::array<double, Dim> box;
  for (int a = 0; a < Dim; ++a) box[a] = p.box_hi[a] - p.box_lo[a];
  const double d20 = d.kernel.d2(0.0, d.h);
#pragma omp parallel for schedule(static) num_threads(threads_for(n))
  for (int i = 0; i < n; ++i) {
    const int fi = m_free_slot[i];
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      double* g = m_g.data() + Dim * k;
      double* h = fi >= 0 ? m_h.data() + kSymmetric * (m_h_offsets[fi] + k - nl.offsets[i]) : nullptr;
      if (ops) {
        for (int a = 0; a < Dim; ++a) g[a] = ops->G[a].valuePtr()[k];
        if (h)
          for (int a = 0; a < Dim; ++a)
            for (int b = a; b < Dim; ++b) h[upper<Dim>(a, b)] = ops->H[a][b].valuePtr()[k];
        continue;
      }
      std::array<std::array<double, Dim>, Dim> hk{};
      std::fill(g, g + Dim, 0.0);
      const int j = nl.indices[k];
      if (i != j) {  // G_ii = 0 and H_ii = 0
        const Eigen::Matrix<double, 1, Dim> dx =
            detail::pair_separation<Dim, double>(p, static_cast<const Eigen::MatrixXd*>(nullptr), box, i, j);
        double r2 = 0;
        for (int a = 0; a < Dim; ++a) r2 += dx[a] * dx[a];
        if (r2 == 0.0) {
          for (int a = 0; a < Dim; ++a) hk[a][a] = d20 * p.volume[j];
        } else {
          detail::pair_derivatives<Dim, double>(d.kernel, d.h, dx, r2, std::sqrt(r2), p.volume[j], g, &hk);
        }
      }
      if (h)
        for (int a = 0; a < Dim; ++a)
          for (int b = a; b < Dim; ++b) h[upper<Dim>(a, b)] = hk[a][b];
    }
  }

  m_gsum.assign(Dim * n, 0.0);
  double gmax = 0;
  for (int i = 0; i < n; ++i)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
      for (int a = 0; a < Dim; ++a) {
        m_gsum[Dim * i + a] += m_g[Dim * k + a];
        gmax = std::max(gmax, std::abs(m_g[Dim * k + a]));
      }

  std::vector<char> needed(n, 0);
  for (int i : d.free)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) needed[nl.indices[k]] = 1;
  m_stress_rows.clear();
  for (int j = 0; j < n; ++j)
    if (needed[j]) m_stress_rows.push_back(j);

  m_eta.assign(kSymmetric * nf, 0.0);
  for (int f = 0; f < nf; ++f) {
    const int i = d.free[f];
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const long t = kSymmetric * (m_h_offsets[f] + k - nl.offsets[i]);
      for (int c = 0; c < kSymmetric; ++c) m_eta[kSymmetric * f + c] += m_h[t + c];  // all neighbours, fixed ones too
    }
  }
  m_sigma.assign(kSymmetric * n, 0.0);

  // The flags of analytic_jacobian_2d, with the same tolerances.
  bool complete = true, equal_volumes = true;
  for (int i : d.free) {
    for (int a = 0; a < Dim; ++a)
      if (std::abs(m_gsum[Dim * i + a]) > 1e-10 * gmax) complete = false;
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
      if (std::abs(d.particles.volume[nl.indices[k]] - d.particles.volume[i]) > 1e-12 * std::abs(d.particles.volume[i]))
        equal_volumes = false;
  }
  m_complete = complete;
  m_periodic = true;
  for (int a = 0; a < Dim; ++a) m_periodic = m_periodic && d.particles.periodic[a];
  m_symmetric = complete && equal_volumes && (cons || form == MomentumForm::Minus || kind == PreStrainKind::Isotropic);
}

template <int Dim>
double MatrixFreeLinearisation<Dim>::memory_bytes() const {
  auto bytes = [](const auto& v) { return static_cast<double>(v.capacity() * sizeof(v[0])); };
  return bytes(m_free) + bytes(m_free_slot) + bytes(m_offsets) + bytes(m_indices) + bytes(m_g) + bytes(m_gsum) +
         bytes(m_stress_rows) + bytes(m_h_offsets) + bytes(m_h) + bytes(m_eta) + bytes(m_sigma) +
         8.0 * static_cast<double>(m_free_positions.size());
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::check_vectors(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                 const Eigen::Ref<Eigen::VectorXd>& y, const char* who) const {
  if (x.size() != dofs() || y.size() != dofs())
    throw std::invalid_argument(std::string("MatrixFreeLinearisation::") + who + ": x has " + std::to_string(x.size()) +
                                " and y " + std::to_string(y.size()) + " entries, need " + std::to_string(dofs()) +
                                " (" + std::to_string(Dim) + " per free particle)");
  const double *xb = x.data(), *yb = y.data();
  if (xb < yb + y.size() && yb < xb + x.size())
    throw std::invalid_argument(std::string("MatrixFreeLinearisation::") + who +
                                ": x and y share storage (pass a separate output vector)");
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::apply_A0(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            Eigen::Ref<Eigen::VectorXd> y) const {
  check_vectors(x, y, "apply_A0");
  apply_combination(1.0, 0.0, x, y);
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::apply_A1(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            Eigen::Ref<Eigen::VectorXd> y) const {
  check_vectors(x, y, "apply_A1");
  apply_combination(0.0, 1.0, x, y);
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::apply_combination(double c0, double c1, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                     Eigen::Ref<Eigen::VectorXd> y) const {
  check_vectors(x, y, "apply");
  constexpr int S = kSymmetric;
  const bool with_a0 = c0 != 0.0, with_a1 = c1 != 0.0 && m_a1_factor != 0.0;
  const double* xp = x.data();
  double* yp = y.data();
  const double lam = m_lambda, mu = m_mu;
  double* sigma = m_sigma.data();

  if (with_a0) {
    // Steps 1-2 (derivation item 1): (grad x)_j^{cd} = sum_{k free} Dm^d_jk x_k^c, Dm = G - diag(g); then
    // sigma_j = C : grad x_j (C drops the antisymmetric part). Rows are independent: threads own whole rows (same
    // bits for any thread count, core/threads.hpp).
    const long rows = static_cast<long>(m_stress_rows.size());
#pragma omp parallel for schedule(static) num_threads(threads_for(rows))
    for (long s = 0; s < rows; ++s) {
      const int j = m_stress_rows[s];
      double gr[Dim][Dim] = {};  // gr[c][d]: component c, derivative d
      for (long k = m_offsets[j]; k < m_offsets[j + 1]; ++k) {
        const int kf = m_free_slot[m_indices[k]];
        if (kf < 0) continue;
        const double* u = xp + Dim * kf;
        const double* w = m_g.data() + Dim * k;
        for (int c = 0; c < Dim; ++c)
          for (int d = 0; d < Dim; ++d) gr[c][d] += u[c] * w[d];
      }
      const int jf = m_free_slot[j];
      if (jf >= 0) {
        const double* u = xp + Dim * jf;
        const double* sum = m_gsum.data() + Dim * j;
        for (int c = 0; c < Dim; ++c)
          for (int d = 0; d < Dim; ++d) gr[c][d] -= u[c] * sum[d];
      }
      double tr = gr[0][0];
      for (int c = 1; c < Dim; ++c) tr += gr[c][c];
      double* sj = sigma + S * j;
      for (int c = 0; c < Dim; ++c) sj[c] = lam * tr + 2 * mu * gr[c][c];
      for (int c = 0; c < Dim; ++c)
        for (int d = c + 1; d < Dim; ++d) sj[voigt<Dim>(c, d)] = mu * (gr[c][d] + gr[d][c]);
    }
  }

  const int nf = free_count();
  const Stress& s0 = m_s0;
  const bool cons = m_form == MomentumForm::Conservative;
  // s0 v and the symmetric product M v (M stored a <= b), each component summed in ascending b.
  const auto s0_times = [&s0](const double* v, double* out) {
    for (int a = 0; a < Dim; ++a) {
      double t = s0(a, 0) * v[0];
      for (int b = 1; b < Dim; ++b) t += s0(a, b) * v[b];
      out[a] = t;
    }
  };
  const auto sym_times = [](const double* m, const double* v, int a) {
    double t = m[upper<Dim>(std::min(a, 0), std::max(a, 0))] * v[0];
    for (int b = 1; b < Dim; ++b) t += m[upper<Dim>(std::min(a, b), std::max(a, b))] * v[b];
    return t;
  };
#pragma omp parallel for schedule(static) num_threads(threads_for(nf))
  for (int f = 0; f < nf; ++f) {
    const int i = m_free[f];
    double out[Dim] = {};
    if (with_a0) {
      // Step 3 (items 2, 3): y_i^a = -(1/rho) sum_j P^b_ij sigma_j^{ab}, P = G + alpha diag(g) (G_ii = 0).
      const double* si = sigma + S * i;
      const double* gi = m_gsum.data() + Dim * i;
      double acc[Dim];
      for (int a = 0; a < Dim; ++a) {
        double t = gi[0] * si[voigt<Dim>(a, 0)];
        for (int b = 1; b < Dim; ++b) t += gi[b] * si[voigt<Dim>(a, b)];
        acc[a] = m_alpha * t;
      }
      for (long k = m_offsets[i]; k < m_offsets[i + 1]; ++k) {
        const double* sk = sigma + S * m_indices[k];
        const double* pk = m_g.data() + Dim * k;
        for (int a = 0; a < Dim; ++a) {
          double t = pk[0] * sk[voigt<Dim>(a, 0)];
          for (int b = 1; b < Dim; ++b) t += pk[b] * sk[voigt<Dim>(a, b)];
          acc[a] += t;
        }
      }
      for (int a = 0; a < Dim; ++a) out[a] = -c0 * m_inv_rho * acc[a];
    }
    if (with_a1) {
      // A1 x: (L v)_i = eta_i v_i - sum_{k free} H_ik v_k with v = x and, conservative, v = s0 x.
      const double* eta = m_eta.data() + S * f;
      const double* xi = xp + Dim * f;
      double vi[Dim], l[Dim], m[Dim];
      s0_times(xi, vi);
      for (int a = 0; a < Dim; ++a) {
        l[a] = sym_times(eta, xi, a);
        m[a] = sym_times(eta, vi, a);
      }
      const double* h = m_h.data() + S * m_h_offsets[f];
      for (long k = m_offsets[i]; k < m_offsets[i + 1]; ++k, h += S) {
        const int kf = m_free_slot[m_indices[k]];
        if (kf < 0) continue;
        const double* xk = xp + Dim * kf;
        for (int a = 0; a < Dim; ++a) l[a] -= sym_times(h, xk, a);
        if (cons) {
          double v[Dim];
          s0_times(xk, v);
          for (int a = 0; a < Dim; ++a) m[a] -= sym_times(h, v, a);
        }
      }
      double r[Dim];
      s0_times(l, r);
      if (cons)
        for (int a = 0; a < Dim; ++a) r[a] += m[a];
      for (int a = 0; a < Dim; ++a) out[a] -= c1 * m_a1_factor * r[a];
    }
    for (int a = 0; a < Dim; ++a) yp[Dim * f + a] = out[a];
  }
}

template <int Dim>
Linearisation assemble_by_products(const MatrixFreeLinearisation<Dim>& lin) {
  const long n = lin.dofs();
  require_memory(static_cast<double>(n) * n / 8.0,
                 "assemble_by_products: " + std::to_string(n) + " DOFs (one product per column)");
  std::vector<Eigen::Triplet<double>> t0, t1;
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n), y(n);
  for (long c = 0; c < n; ++c) {
    e[c] = 1;
    lin.apply_A0(e, y);
    for (long r = 0; r < n; ++r)
      if (y[r] != 0.0) t0.emplace_back(r, c, y[r]);
    lin.apply_A1(e, y);
    for (long r = 0; r < n; ++r)
      if (y[r] != 0.0) t1.emplace_back(r, c, y[r]);
    e[c] = 0;
  }
  Linearisation out;
  out.A0.resize(n, n);
  out.A0.setFromTriplets(t0.begin(), t0.end());
  out.A1.resize(n, n);
  out.A1.setFromTriplets(t1.begin(), t1.end());
  out.dofs_per_particle = Dim;
  out.free_index = lin.free_index();
  out.x = lin.free_positions();
  out.symmetric = lin.symmetric();
  out.complete = lin.complete();
  out.periodic = lin.periodic();
  return out;
}

template class MatrixFreeLinearisation<2>;
template class MatrixFreeLinearisation<3>;
template MatrixFreeLinearisation<2>::MatrixFreeLinearisation(const ElasticForm2D& force);
template Linearisation assemble_by_products<2>(const MatrixFreeLinearisation<2>&);
template Linearisation assemble_by_products<3>(const MatrixFreeLinearisation<3>&);

}  // namespace sphstab
