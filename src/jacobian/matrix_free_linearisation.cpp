#include "sphstab/jacobian/matrix_free_linearisation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"

namespace sphstab {

namespace {

long free_row_pairs(const Discretisation<2>& d) {
  long pairs = 0;
  for (int i : d.free) pairs += d.neighbours.count(i);
  return pairs;
}

/// The force's discretisation, after checking that the closed form covers the force.
const Discretisation<2>& covered_discretisation(const ElasticForm2D& force) {
  require_closed_form_coverage(force, "MatrixFreeLinearisation");
  return force.discretisation();
}

}  // namespace

double MatrixFreeLinearisation::estimated_bytes(const Discretisation<2>& d) {
  const double n = d.size(), nf = d.free_count(), pairs = d.neighbours.nonzeros();
  const double free_pairs = free_row_pairs(d);
  // CSR (8 per offset, 4 per index), G pairs and row sums, free map and stress rows, H of the free rows with eta,
  // the stress buffer, the free positions.
  return 8 * (n + 1) + 4 * pairs + 16 * pairs + 16 * n + 4 * (2 * n + nf) + 8 * (nf + 1) + 24 * free_pairs + 24 * nf +
         24 * n + 16 * nf;
}

MatrixFreeLinearisation::MatrixFreeLinearisation(const Discretisation<2>& d, const Operators<2>& ops,
                                                 const ElasticMaterial& material, MomentumForm form,
                                                 PreStrainKind kind) {
  material.validate("MatrixFreeLinearisation");
  require_closed_form_operators(d, ops, "MatrixFreeLinearisation");
  build(d, ops, material, form, kind);
}

MatrixFreeLinearisation::MatrixFreeLinearisation(const Discretisation<2>& d, const ElasticMaterial& material,
                                                 MomentumForm form, PreStrainKind kind) {
  material.validate("MatrixFreeLinearisation");
  // The five operator matrices exist (12 bytes per entry) while the needed values are copied.
  const double operators = 5.0 * 12 * d.neighbours.nonzeros();
  require_memory(operators + estimated_bytes(d),
                 "MatrixFreeLinearisation: " + std::to_string(d.dofs()) + " DOFs with the operators G, H");
  const Operators<2> ops = assemble_operators<2>(d.particles, d.neighbours, d.kernel, d.h,
                                                 {.kernel = false, .gradient = true, .hessian = true});
  build(d, ops, material, form, kind);
}

MatrixFreeLinearisation::MatrixFreeLinearisation(const ElasticForm2D& force)
    : MatrixFreeLinearisation(covered_discretisation(force), force.material(), force.form(), force.prestrain().kind) {}

void MatrixFreeLinearisation::build(const Discretisation<2>& d, const Operators<2>& ops,
                                    const ElasticMaterial& material, MomentumForm form, PreStrainKind kind) {
  require_memory(estimated_bytes(d), "MatrixFreeLinearisation: " + std::to_string(d.dofs()) + " DOFs");
  const int n = d.size(), nf = d.free_count();
  const NeighbourList& nl = d.neighbours;
  const bool cons = form == MomentumForm::Conservative;
  m_form = form;
  m_inv_rho = 1.0 / material.rho;
  m_lambda = material.lambda;
  m_mu = material.mu;
  m_alpha = cons ? 1.0 : momentum_form_alpha(form);
  m_a1_factor = cons ? 2.0 * m_inv_rho : (1.0 + momentum_form_alpha(form)) * m_inv_rho;
  m_s0 = PreStrain{kind, 1.0}.stress(material);
  m_free = d.free;
  m_free_positions = d.free_positions();
  m_free_slot = d.free_slot;
  m_offsets = nl.offsets;
  m_indices = nl.indices;

  const long pairs = nl.nonzeros();
  const double* gx = ops.G[0].valuePtr();
  const double* gy = ops.G[1].valuePtr();
  m_g.resize(2 * pairs);
  m_gsum.assign(2 * n, 0.0);
  double gmax = 0;
  for (int i = 0; i < n; ++i)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      m_g[2 * k] = gx[k];
      m_g[2 * k + 1] = gy[k];
      m_gsum[2 * i] += gx[k];
      m_gsum[2 * i + 1] += gy[k];
      gmax = std::max({gmax, std::abs(gx[k]), std::abs(gy[k])});
    }

  std::vector<char> needed(n, 0);
  for (int i : d.free)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) needed[nl.indices[k]] = 1;
  m_stress_rows.clear();
  for (int j = 0; j < n; ++j)
    if (needed[j]) m_stress_rows.push_back(j);

  const double* hxx = ops.H[0][0].valuePtr();
  const double* hxy = ops.H[0][1].valuePtr();
  const double* hyy = ops.H[1][1].valuePtr();
  m_h_offsets.assign(nf + 1, 0);
  for (int f = 0; f < nf; ++f) m_h_offsets[f + 1] = m_h_offsets[f] + nl.count(d.free[f]);
  m_h.resize(3 * m_h_offsets[nf]);
  m_eta.assign(3 * nf, 0.0);
  for (int f = 0; f < nf; ++f) {
    const int i = d.free[f];
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const long t = 3 * (m_h_offsets[f] + k - nl.offsets[i]);
      m_h[t] = hxx[k];
      m_h[t + 1] = hxy[k];
      m_h[t + 2] = hyy[k];
      m_eta[3 * f] += hxx[k];  // eta sums over all neighbours, fixed ones included
      m_eta[3 * f + 1] += hxy[k];
      m_eta[3 * f + 2] += hyy[k];
    }
  }
  m_sigma.assign(3 * n, 0.0);

  // The flags of analytic_jacobian_2d, with the same tolerances.
  bool complete = true, equal_volumes = true;
  for (int i : d.free) {
    if (std::abs(m_gsum[2 * i]) > 1e-10 * gmax || std::abs(m_gsum[2 * i + 1]) > 1e-10 * gmax) complete = false;
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
      if (std::abs(d.particles.volume[nl.indices[k]] - d.particles.volume[i]) > 1e-12 * std::abs(d.particles.volume[i]))
        equal_volumes = false;
  }
  m_complete = complete;
  m_symmetric = complete && equal_volumes && (cons || form == MomentumForm::Minus || kind == PreStrainKind::Isotropic);
}

double MatrixFreeLinearisation::memory_bytes() const {
  auto bytes = [](const auto& v) { return static_cast<double>(v.capacity() * sizeof(v[0])); };
  return bytes(m_free) + bytes(m_free_slot) + bytes(m_offsets) + bytes(m_indices) + bytes(m_g) + bytes(m_gsum) +
         bytes(m_stress_rows) + bytes(m_h_offsets) + bytes(m_h) + bytes(m_eta) + bytes(m_sigma) +
         8.0 * static_cast<double>(m_free_positions.size());
}

void MatrixFreeLinearisation::check_vectors(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            const Eigen::Ref<Eigen::VectorXd>& y, const char* who) const {
  if (x.size() != dofs() || y.size() != dofs())
    throw std::invalid_argument(std::string("MatrixFreeLinearisation::") + who + ": x has " + std::to_string(x.size()) +
                                " and y " + std::to_string(y.size()) + " entries, need " + std::to_string(dofs()) +
                                " (2 per free particle)");
  const double *xb = x.data(), *yb = y.data();
  if (xb < yb + y.size() && yb < xb + x.size())
    throw std::invalid_argument(std::string("MatrixFreeLinearisation::") + who +
                                ": x and y share storage (pass a separate output vector)");
}

void MatrixFreeLinearisation::apply_A0(const Eigen::Ref<const Eigen::VectorXd>& x,
                                       Eigen::Ref<Eigen::VectorXd> y) const {
  check_vectors(x, y, "apply_A0");
  apply_combination(1.0, 0.0, x, y);
}

void MatrixFreeLinearisation::apply_A1(const Eigen::Ref<const Eigen::VectorXd>& x,
                                       Eigen::Ref<Eigen::VectorXd> y) const {
  check_vectors(x, y, "apply_A1");
  apply_combination(0.0, 1.0, x, y);
}

void MatrixFreeLinearisation::apply_combination(double c0, double c1, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                Eigen::Ref<Eigen::VectorXd> y) const {
  check_vectors(x, y, "apply");
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
      double gxx = 0, gxy = 0, gyx = 0, gyy = 0;  // g^{cd}: component c, derivative d
      for (long k = m_offsets[j]; k < m_offsets[j + 1]; ++k) {
        const int kf = m_free_slot[m_indices[k]];
        if (kf < 0) continue;
        const double ux = xp[2 * kf], uy = xp[2 * kf + 1], wx = m_g[2 * k], wy = m_g[2 * k + 1];
        gxx += ux * wx;
        gxy += ux * wy;
        gyx += uy * wx;
        gyy += uy * wy;
      }
      const int jf = m_free_slot[j];
      if (jf >= 0) {
        const double ux = xp[2 * jf], uy = xp[2 * jf + 1], sx = m_gsum[2 * j], sy = m_gsum[2 * j + 1];
        gxx -= ux * sx;
        gxy -= ux * sy;
        gyx -= uy * sx;
        gyy -= uy * sy;
      }
      const double tr = gxx + gyy;
      sigma[3 * j] = lam * tr + 2 * mu * gxx;
      sigma[3 * j + 1] = lam * tr + 2 * mu * gyy;
      sigma[3 * j + 2] = mu * (gxy + gyx);
    }
  }

  const int nf = free_count();
  const Eigen::Matrix2d& s0 = m_s0;
  const bool cons = m_form == MomentumForm::Conservative;
#pragma omp parallel for schedule(static) num_threads(threads_for(nf))
  for (int f = 0; f < nf; ++f) {
    const int i = m_free[f];
    double yx = 0, yy = 0;
    if (with_a0) {
      // Step 3 (items 2, 3): y_i^a = -(1/rho) sum_j P^b_ij sigma_j^{ab}, P = G + alpha diag(g) (G_ii = 0).
      const double* si = sigma + 3 * i;
      double ax = m_alpha * (m_gsum[2 * i] * si[0] + m_gsum[2 * i + 1] * si[2]);
      double ay = m_alpha * (m_gsum[2 * i] * si[2] + m_gsum[2 * i + 1] * si[1]);
      for (long k = m_offsets[i]; k < m_offsets[i + 1]; ++k) {
        const double* s = sigma + 3 * m_indices[k];
        const double px = m_g[2 * k], py = m_g[2 * k + 1];
        ax += px * s[0] + py * s[2];
        ay += px * s[2] + py * s[1];
      }
      yx = -c0 * m_inv_rho * ax;
      yy = -c0 * m_inv_rho * ay;
    }
    if (with_a1) {
      // A1 x: (L v)_i = eta_i v_i - sum_{k free} H_ik v_k with v = x and, conservative, v = s0 x.
      const double* eta = m_eta.data() + 3 * f;
      const double xi = xp[2 * f], yi = xp[2 * f + 1];
      double lx = eta[0] * xi + eta[1] * yi, ly = eta[1] * xi + eta[2] * yi;
      const double vxi = s0(0, 0) * xi + s0(0, 1) * yi, vyi = s0(1, 0) * xi + s0(1, 1) * yi;
      double mx = eta[0] * vxi + eta[1] * vyi, my = eta[1] * vxi + eta[2] * vyi;
      const double* h = m_h.data() + 3 * m_h_offsets[f];
      for (long k = m_offsets[i]; k < m_offsets[i + 1]; ++k, h += 3) {
        const int kf = m_free_slot[m_indices[k]];
        if (kf < 0) continue;
        const double xk = xp[2 * kf], yk = xp[2 * kf + 1];
        lx -= h[0] * xk + h[1] * yk;
        ly -= h[1] * xk + h[2] * yk;
        if (cons) {
          const double vx = s0(0, 0) * xk + s0(0, 1) * yk, vy = s0(1, 0) * xk + s0(1, 1) * yk;
          mx -= h[0] * vx + h[1] * vy;
          my -= h[1] * vx + h[2] * vy;
        }
      }
      double rx = s0(0, 0) * lx + s0(0, 1) * ly, ry = s0(1, 0) * lx + s0(1, 1) * ly;
      if (cons) rx += mx, ry += my;
      yx -= c1 * m_a1_factor * rx;
      yy -= c1 * m_a1_factor * ry;
    }
    yp[2 * f] = yx;
    yp[2 * f + 1] = yy;
  }
}

}  // namespace sphstab
