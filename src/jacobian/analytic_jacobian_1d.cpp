#include "sphstab/jacobian/analytic_jacobian_1d.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "sphstab/core/memory_budget.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"

namespace sphstab {

Linearisation analytic_jacobian_1d(const ParticleSet<1>& p, const Operators<1>& ops, MomentumForm form) {
  p.validate("analytic_jacobian_1d");
  const int n = p.size();
  const SparseMatrix<>& g = ops.G[0];
  const SparseMatrix<>& hess = ops.H[0][0];
  if (g.rows() != n || g.cols() != n)
    throw std::invalid_argument("analytic_jacobian_1d: gradient operator G must be " + std::to_string(n) + " x " +
                                std::to_string(n) + " (assemble with gradient = true)");
  if (hess.rows() != n || hess.cols() != n)
    throw std::invalid_argument("analytic_jacobian_1d: Hessian operator H must be " + std::to_string(n) + " x " +
                                std::to_string(n) + " (assemble with hessian = true)");

  // Triplets, G_f and its transpose, the product A0 = G_f G_f^T (twice the pairs: neighbours of neighbours) and its
  // pruned copy, and L: about 120 bytes per stored entry of G.
  require_memory(
      120.0 * static_cast<double>(g.nonZeros()),
      "analytic_jacobian_1d: " + std::to_string(n) + " particles, " + std::to_string(g.nonZeros()) + " entries in G");
  Linearisation jac;
  jac.free_index = p.indices(Role::Free);
  const int nf = static_cast<int>(jac.free_index.size());
  if (nf == 0) throw std::invalid_argument("analytic_jacobian_1d: the particle set has no free particles");
  jac.periodic = p.periodic[0];
  jac.spacing = p.spacing;
  jac.x.resize(nf, 1);
  std::vector<int> local(n, -1);
  for (int k = 0; k < nf; ++k) {
    local[jac.free_index[k]] = k;
    jac.x(k, 0) = p.x(jac.free_index[k], 0);
  }

  // Preconditions: G antisymmetric on the free rows and zero row sums (complete symmetric neighbourhoods).
  double gmax = 0;
  for (int k = 0; k < g.nonZeros(); ++k) gmax = std::max(gmax, std::abs(g.valuePtr()[k]));
  const double tol = 1e-10 * gmax;
  for (int i : jac.free_index) {
    double row_sum = 0;
    for (SparseMatrix<>::InnerIterator it(g, i); it; ++it) {
      row_sum += it.value();
      const double gji = g.coeff(it.col(), i);
      if (std::abs(it.value() + gji) > tol) {
        std::ostringstream msg;
        msg << "analytic_jacobian_1d: G is not antisymmetric at (" << i << ", " << it.col()
            << "): unequal volumes or positions are not a lattice; (3.40) does not apply (use a generic Jacobian)";
        throw std::invalid_argument(msg.str());
      }
    }
    if (std::abs(row_sum) > tol) {
      std::ostringstream msg;
      msg << "analytic_jacobian_1d: free particle " << i
          << " has an incomplete or asymmetric neighbourhood (|sum_j G_ij| = " << std::abs(row_sum)
          << "); (3.40) needs a regular lattice with complete fixed layers or a periodic box";
      throw std::invalid_argument(msg.str());
    }
  }

  // G_f: free rows of G, all columns; L from H.
  SparseMatrix<> gf(nf, n);
  {
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < nf; ++k)
      for (SparseMatrix<>::InnerIterator it(g, jac.free_index[k]); it; ++it)
        if (it.value() != 0.0) t.emplace_back(k, it.col(), it.value());
    gf.setFromTriplets(t.begin(), t.end());
  }
  SparseMatrix<> gft = gf.transpose();
  jac.A0 = (gf * gft).pruned(0.0, 0.0);
  jac.A0.makeCompressed();
  {
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < nf; ++k) {
      const int i = jac.free_index[k];
      double diag = 0;
      for (SparseMatrix<>::InnerIterator it(hess, i); it; ++it) {
        if (it.col() == i) continue;
        diag += it.value();
        const int m = local[it.col()];
        if (m >= 0) t.emplace_back(k, m, -it.value());
      }
      t.emplace_back(k, k, diag);
    }
    jac.A1.resize(nf, nf);
    jac.A1.setFromTriplets(t.begin(), t.end());  // L
    jac.A1 *= -static_cast<double>(initial_stress_multiplier(form));
    jac.A1.makeCompressed();
  }
  jac.symmetric = true;
  jac.complete = true;
  return jac;
}

Linearisation analytic_jacobian_1d(const ParticleSet<1>& p, const Kernel<1>& kernel, double h, MomentumForm form) {
  const NeighbourList nl = find_neighbours(p, kernel.support_radius(h));
  const Operators<1> ops = assemble_operators(p, nl, kernel, h, {.kernel = false, .gradient = true, .hessian = true});
  return analytic_jacobian_1d(p, ops, form);
}

}  // namespace sphstab
