#include "sphstab/jacobian/analytic_jacobian_2d.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/forms/elastic_term.hpp"

namespace sphstab {

namespace {

/// Builds a row-major dofs x dofs matrix (2 x 2 blocks per free-particle pair) from per-row block lists.
/// `row_blocks(f, cols, blocks)` fills the free slots (ascending) and blocks of block row f.
template <class RowFn>
SparseMatrix<> block_matrix(int nfree, RowFn&& row_blocks, long nnz_hint) {
  const int n = 2 * nfree;
  SparseMatrix<> m(n, n);
  std::vector<int> outer(n + 1, 0), inner;
  std::vector<double> values;
  inner.reserve(nnz_hint);
  values.reserve(nnz_hint);
  std::vector<int> cols;
  std::vector<Eigen::Matrix2d> blocks;
  for (int f = 0; f < nfree; ++f) {
    row_blocks(f, cols, blocks);
    for (int a = 0; a < 2; ++a) {
      for (size_t t = 0; t < cols.size(); ++t)
        for (int c = 0; c < 2; ++c) {
          inner.push_back(2 * cols[t] + c);
          values.push_back(blocks[t](a, c));
        }
      outer[2 * f + a + 1] = static_cast<int>(inner.size());
    }
  }
  m.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), m.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), m.innerIndexPtr());
  std::copy(values.begin(), values.end(), m.valuePtr());
  return m;
}

}  // namespace

namespace {

/// Checked before anything is assembled: A0 couples neighbours of neighbours (G G), A1 neighbours, in 2 x 2 blocks of
/// 12 bytes per entry (value + index), twice for the row buffers; plus the five operator matrices if asked.
void require_jacobian_memory(const Discretisation<2>& d, bool with_operators) {
  const double r = d.neighbours.radius, pairs = expected_neighbour_pairs(d.particles, r);
  const double pairs2 = expected_neighbour_pairs(d.particles, 2 * r);
  const double free_fraction = static_cast<double>(d.free_count()) / d.size();
  const double bytes = 2 * free_fraction * (pairs2 + pairs) * 4 * 12 + (with_operators ? 5 * pairs * 12 : 0.0);
  require_memory(bytes, "analytic_jacobian_2d: " + std::to_string(2L * d.free_count()) + " DOFs, ~" +
                            format_number(4 * free_fraction * pairs2, 3) + " nonzeros in A0");
}

}  // namespace

Linearisation analytic_jacobian_2d(const Discretisation<2>& d, const Operators<2>& ops, const ElasticMaterial& material,
                                   MomentumForm form, PreStrainKind kind) {
  material.validate("analytic_jacobian_2d");
  require_jacobian_memory(d, false);
  const int n = d.size(), nf = d.free_count();
  const NeighbourList& nl = d.neighbours;
  require_closed_form_operators(d, ops, "analytic_jacobian_2d");

  Linearisation jac;
  jac.dofs_per_particle = 2;
  jac.free_index = d.free;
  jac.x.resize(nf, 2);
  for (int f = 0; f < nf; ++f) jac.x.row(f) = d.particles.x.row(d.free[f]);
  jac.periodic = d.particles.periodic[0] && d.particles.periodic[1];
  jac.spacing = d.particles.spacing;

  const double* gx = ops.G[0].valuePtr();
  const double* gy = ops.G[1].valuePtr();
  const double* hxx = ops.H[0][0].valuePtr();
  const double* hxy = ops.H[0][1].valuePtr();
  const double* hyy = ops.H[1][1].valuePtr();
  // Row sums over all neighbours and the position of the diagonal entry of every row.
  std::vector<double> gsx(n, 0.0), gsy(n, 0.0), hsxx(n, 0.0), hsxy(n, 0.0), hsyy(n, 0.0);
  std::vector<long> diag(n, -1);
  double gmax = 0;
  for (int i = 0; i < n; ++i)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      gsx[i] += gx[k];
      gsy[i] += gy[k];
      hsxx[i] += hxx[k];
      hsxy[i] += hxy[k];
      hsyy[i] += hyy[k];
      gmax = std::max({gmax, std::abs(gx[k]), std::abs(gy[k])});
      if (nl.indices[k] == i) diag[i] = k;
    }

  // Preconditions of the symmetry statement: complete neighbourhoods and equal volumes around free particles.
  bool complete = true, equal_volumes = true;
  for (int i : d.free) {
    if (std::abs(gsx[i]) > 1e-10 * gmax || std::abs(gsy[i]) > 1e-10 * gmax) complete = false;
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
      if (std::abs(d.particles.volume[nl.indices[k]] - d.particles.volume[i]) > 1e-12 * std::abs(d.particles.volume[i]))
        equal_volumes = false;
  }
  jac.complete = complete;
  jac.symmetric =
      complete && equal_volumes &&
      (form == MomentumForm::Conservative || form == MomentumForm::Minus || kind == PreStrainKind::Isotropic);

  const bool cons = form == MomentumForm::Conservative;
  const double alpha = cons ? 1.0 : momentum_form_alpha(form);
  const double inv_rho = 1.0 / material.density(), lam = material.lambda(), mu = material.mu();
  const Eigen::Matrix2d s0 = PreStrain{kind, 1.0}.stress(material);

  // A0: fused Gustavson product over (i free, j in N(i), k free in N(j)) with a dense block accumulator.
  std::vector<int> mark(nf, -1);
  std::vector<Eigen::Matrix2d> acc(nf);
  long hint0 = 0;
  jac.A0 = block_matrix(
      nf,
      [&](int f, std::vector<int>& cols, std::vector<Eigen::Matrix2d>& blocks) {
        const int i = d.free[f];
        cols.clear();
        for (long kij = nl.offsets[i]; kij < nl.offsets[i + 1]; ++kij) {
          const int j = nl.indices[kij];
          double px = gx[kij], py = gy[kij];
          if (j == i) px += alpha * gsx[i], py += alpha * gsy[i];
          for (long kjk = nl.offsets[j]; kjk < nl.offsets[j + 1]; ++kjk) {
            const int kf = d.free_slot[nl.indices[kjk]];
            if (kf < 0) continue;
            double qx = gx[kjk], qy = gy[kjk];
            if (kjk == diag[j]) qx -= gsx[j], qy -= gsy[j];
            if (mark[kf] != f) {
              mark[kf] = f;
              acc[kf].setZero();
              cols.push_back(kf);
            }
            // lambda p q^T + mu q p^T + mu (p . q) I (products formed before scaling: symmetric to round-off)
            const double pxqx = px * qx, pxqy = px * qy, pyqx = py * qx, pyqy = py * qy, pq = pxqx + pyqy;
            Eigen::Matrix2d& b = acc[kf];
            b(0, 0) += lam * pxqx + mu * pxqx + mu * pq;
            b(0, 1) += lam * pxqy + mu * pyqx;
            b(1, 0) += lam * pyqx + mu * pxqy;
            b(1, 1) += lam * pyqy + mu * pyqy + mu * pq;
          }
        }
        std::sort(cols.begin(), cols.end());
        blocks.resize(cols.size());
        for (size_t t = 0; t < cols.size(); ++t) blocks[t] = -inv_rho * acc[cols[t]];
      },
      hint0);

  // A1: free-block initial-stress operator L_ik = delta_ik eta_i - H_ik.
  auto a1_block = [&](const Eigen::Matrix2d& l) -> Eigen::Matrix2d {
    if (cons) return -2.0 * inv_rho * (s0 * l + l * s0);
    return -(1.0 + alpha) * inv_rho * (s0 * l);
  };
  jac.A1 = block_matrix(
      nf,
      [&](int f, std::vector<int>& cols, std::vector<Eigen::Matrix2d>& blocks) {
        const int i = d.free[f];
        cols.clear();
        blocks.clear();
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
          const int kf = d.free_slot[nl.indices[k]];
          if (kf < 0) continue;
          Eigen::Matrix2d l;
          if (nl.indices[k] == i)
            l << hsxx[i], hsxy[i], hsxy[i], hsyy[i];
          else
            l << -hxx[k], -hxy[k], -hxy[k], -hyy[k];
          cols.push_back(kf);
          blocks.push_back(a1_block(l));
        }
      },
      0);
  return jac;
}

Linearisation analytic_jacobian_2d(const Discretisation<2>& d, const ElasticMaterial& material, MomentumForm form,
                                   PreStrainKind kind) {
  material.validate("analytic_jacobian_2d");
  require_jacobian_memory(d, true);
  const Operators<2> ops = assemble_operators<2>(d.particles, d.neighbours, d.kernel, d.h,
                                                 {.kernel = false, .gradient = true, .hessian = true});
  return analytic_jacobian_2d(d, ops, material, form, kind);
}

Linearisation analytic_jacobian_2d(const ElasticForm2D& force) {
  require_closed_form_coverage(force, "analytic_jacobian_2d");
  return analytic_jacobian_2d(force.discretisation(), force.material(), force.form(), force.prestrain().kind);
}

void require_closed_form_coverage(const ElasticForm2D& force, const std::string& who) {
  if (force.gradient_provider() && !force.gradient_provider()->is_plain())
    throw std::invalid_argument(who + ": gradient provider '" + force.gradient_provider()->name() +
                                "' is not covered by the closed form (use affine_jacobian)");
  if (force.fixed_displacement().size() > 0 && force.fixed_displacement().cwiseAbs().maxCoeff() != 0.0)
    throw std::invalid_argument(who +
                                ": the closed form is the linearisation at rest with zero fixed displacements "
                                "(use affine_jacobian)");
  if (!force.terms().empty())  // e.g. the artificial stress: its linearisation is not in the closed form
    throw std::invalid_argument(who + ": additional momentum terms ('" + force.terms()[0]->name() +
                                "') are not covered by the closed form (use affine_jacobian)");
}

void require_closed_form_operators(const Discretisation<2>& d, const Operators<2>& ops, const std::string& who) {
  const int n = d.size();
  const auto check = [&](const SparseMatrix<>& m, const char* name) {
    if (m.rows() != n || m.cols() != n || m.nonZeros() != d.neighbours.nonzeros() || !m.isCompressed())
      throw std::invalid_argument(who + ": operator " + name + " must be " + std::to_string(n) + " x " +
                                  std::to_string(n) +
                                  " with the neighbour-list pattern (assemble with gradient = true, hessian = true)");
  };
  check(ops.G[0], "G[x]");
  check(ops.G[1], "G[y]");
  check(ops.H[0][0], "H[x][x]");
  check(ops.H[0][1], "H[x][y]");
  check(ops.H[1][1], "H[y][y]");
}

}  // namespace sphstab
