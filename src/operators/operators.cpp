#include "sphstab/operators/operators.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pair_derivatives.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/numerics/dual.hpp"
#include "sphstab/numerics/instantiation.hpp"

namespace sphstab {

namespace detail {

/// Gives m the neighbour-list pattern in place (Eigen 3.4 sparse matrices have no move semantics, so
/// building a temporary and assigning it would copy every array). Values are left for the caller.
template <class Scalar>
void set_pattern(SparseMatrix<Scalar>& m, const NeighbourList& nl) {
  const int n = nl.size();
  if (m.rows() == n && m.cols() == n && m.isCompressed() && m.nonZeros() == nl.nonzeros() &&
      std::equal(nl.offsets.begin(), nl.offsets.end(), m.outerIndexPtr()) &&
      std::equal(nl.indices.begin(), nl.indices.end(), m.innerIndexPtr()))
    return;  // already this pattern: keep the storage
  m.resize(n, n);
  m.resizeNonZeros(nl.nonzeros());
  int* outer = m.outerIndexPtr();
  for (int i = 0; i <= n; ++i) outer[i] = static_cast<int>(nl.offsets[i]);
  std::copy(nl.indices.begin(), nl.indices.end(), m.innerIndexPtr());
}

}  // namespace detail

template <class Scalar>
SparseMatrix<Scalar> pattern_matrix(const NeighbourList& nl) {
  SparseMatrix<Scalar> m;
  detail::set_pattern(m, nl);
  std::fill(m.valuePtr(), m.valuePtr() + nl.nonzeros(), Scalar(0));
  return m;
}

template <int Dim, class Scalar>
Operators<Dim, Scalar> assemble_operators(const ParticleSet<Dim>& p, const NeighbourList& nl, const Kernel<Dim>& kernel,
                                          double h, OperatorRequest req, const Positions<Dim, Scalar>* positions) {
  Operators<Dim, Scalar> ops;
  assemble_operators_into(ops, p, nl, kernel, h, req, positions);
  return ops;
}

template <int Dim, class Scalar>
void assemble_operators_into(Operators<Dim, Scalar>& ops, const ParticleSet<Dim>& p, const NeighbourList& nl,
                             const Kernel<Dim>& kernel, double h, OperatorRequest req,
                             const Positions<Dim, Scalar>* positions) {
  p.validate("assemble_operators");
  check_length(h, "assemble_operators: smoothing length h");
  if (nl.size() != p.size())
    throw std::invalid_argument("assemble_operators: neighbour list has " + std::to_string(nl.size()) +
                                " rows but the particle set has " + std::to_string(p.size()) + " particles");
  if (positions && positions->rows() != p.size())
    throw std::invalid_argument("assemble_operators: positions have the wrong number of rows");
  if (nl.radius + 1e-12 * h < kernel.support_radius(h) * (1 - 1e-12))
    throw std::invalid_argument("assemble_operators: neighbour radius " + format_number(nl.radius) +
                                " is smaller than the kernel support " + format_number(kernel.support_radius(h)));

  const int matrices = (req.kernel ? 1 : 0) + (req.gradient ? Dim : 0) + (req.hessian ? Dim * Dim : 0);
  const auto& first = req.kernel ? ops.W : (req.gradient ? ops.G[0] : ops.H[0][0]);
  const bool reuse = first.rows() == nl.size() && first.nonZeros() == nl.nonzeros();  // re-assembly: no new storage
  if (!reuse)
    require_memory(
        matrices * (static_cast<double>(nl.nonzeros()) * (sizeof(Scalar) + sizeof(int)) + 4.0 * (nl.size() + 1)),
        "assemble_operators: " + std::to_string(matrices) + " matrices of " + std::to_string(nl.nonzeros()) +
            " entries");
  if (req.kernel) detail::set_pattern(ops.W, nl);
  if (req.gradient)
    for (int a = 0; a < Dim; ++a) detail::set_pattern(ops.G[a], nl);
  if (req.hessian)
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b) detail::set_pattern(ops.H[a][b], nl);

  Scalar* w = req.kernel ? ops.W.valuePtr() : nullptr;
  std::array<Scalar*, Dim> g{};
  std::array<std::array<Scalar*, Dim>, Dim> hh{};
  if (req.gradient)
    for (int a = 0; a < Dim; ++a) g[a] = ops.G[a].valuePtr();
  if (req.hessian)
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b) hh[a][b] = ops.H[a][b].valuePtr();

  const double w0 = kernel.value(0.0, h);
  std::array<double, Dim> box;
  for (int a = 0; a < Dim; ++a) box[a] = p.box_hi[a] - p.box_lo[a];
  const double d20 = kernel.d2(0.0, h);
  for (int i = 0; i < p.size(); ++i) {
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      const double vj = p.volume[j];
      if (req.gradient)
        for (int a = 0; a < Dim; ++a) g[a][k] = Scalar(0);
      if (req.hessian)
        for (int a = 0; a < Dim; ++a)
          for (int b = a; b < Dim; ++b) hh[a][b][k] = Scalar(0);
      if (i == j) {
        if (w) w[k] = Scalar(w0 * vj);
        continue;  // G_ii = 0 and H_ii = 0 by convention
      }
      const Eigen::Matrix<Scalar, 1, Dim> d = detail::pair_separation<Dim, Scalar>(p, positions, box, i, j);
      using std::sqrt;
      Scalar r2(0);  // analytic square (not |.|^2) so that complex steps pass through
      for (int a = 0; a < Dim; ++a) r2 += d[a] * d[a];
      if (detail::re(r2) == 0.0) {  // coincident points: the limits of W, grad W (0) and the Hessian
        if (w) w[k] = Scalar(w0 * vj);
        if (req.hessian)
          for (int a = 0; a < Dim; ++a) hh[a][a][k] = Scalar(d20 * vj);
        continue;
      }
      const Scalar r = sqrt(r2);
      if (w) w[k] = kernel.value(r, h) * vj;
      if (req.gradient || req.hessian) {
        std::array<Scalar, Dim> gk;
        std::array<std::array<Scalar, Dim>, Dim> hk;
        detail::pair_derivatives<Dim, Scalar>(kernel, h, d, r2, r, vj, req.gradient ? gk.data() : nullptr,
                                              req.hessian ? &hk : nullptr);
        if (req.gradient)
          for (int a = 0; a < Dim; ++a) g[a][k] = gk[a];
        if (req.hessian)
          for (int a = 0; a < Dim; ++a)
            for (int b = a; b < Dim; ++b) hh[a][b][k] = hk[a][b];
      }
    }
  }
  if (req.hessian)
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < a; ++b) ops.H[a][b] = ops.H[b][a];  // a copy: callers may modify one
}

template <int Dim>
SparseMatrix<> kernel_matrix(const ParticleSet<Dim>& p, const NeighbourList& nl, const Kernel<Dim>& k, double h) {
  auto ops = assemble_operators<Dim, double>(p, nl, k, h, {.kernel = true, .gradient = false, .hessian = false});
  SparseMatrix<> w;
  w.swap(ops.W);
  return w;
}

template <int Dim>
SparseMatrix<> gradient_matrix(const ParticleSet<Dim>& p, const NeighbourList& nl, const Kernel<Dim>& k, double h,
                               int axis) {
  if (axis < 0 || axis >= Dim)
    throw std::invalid_argument("gradient_matrix: axis " + std::to_string(axis) + " out of range for dimension " +
                                std::to_string(Dim));
  return assemble_operators<Dim, double>(p, nl, k, h, {.kernel = false, .gradient = true, .hessian = false}).G[axis];
}

template SparseMatrix<double> pattern_matrix<double>(const NeighbourList&);
template SparseMatrix<std::complex<double>> pattern_matrix<std::complex<double>>(const NeighbourList&);

#define SPHSTAB_INSTANTIATE(D)                                                                                      \
  template Operators<D, double> assemble_operators<D, double>(const ParticleSet<D>&, const NeighbourList&,          \
                                                              const Kernel<D>&, double, OperatorRequest,            \
                                                              const Positions<D, double>*);                         \
  template Operators<D, std::complex<double>> assemble_operators<D, std::complex<double>>(                          \
      const ParticleSet<D>&, const NeighbourList&, const Kernel<D>&, double, OperatorRequest,                       \
      const Positions<D, std::complex<double>>*);                                                                   \
  template SparseMatrix<> kernel_matrix<D>(const ParticleSet<D>&, const NeighbourList&, const Kernel<D>&, double);  \
  template SparseMatrix<> gradient_matrix<D>(const ParticleSet<D>&, const NeighbourList&, const Kernel<D>&, double, \
                                             int);
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

// Dual numbers (numerics/dual.hpp): nested exact derivatives for the corrected conservative forms.
#define SPHSTAB_INSTANTIATE(D, S)                                                                                  \
  template Operators<D, S> assemble_operators<D, S>(const ParticleSet<D>&, const NeighbourList&, const Kernel<D>&, \
                                                    double, OperatorRequest, const Positions<D, S>*);              \
  template void assemble_operators_into<D, S>(Operators<D, S>&, const ParticleSet<D>&, const NeighbourList&,       \
                                              const Kernel<D>&, double, OperatorRequest, const Positions<D, S>*);
SPHSTAB_INSTANTIATE(1, Dual<double>)
SPHSTAB_INSTANTIATE(2, Dual<double>)
SPHSTAB_INSTANTIATE(1, Dual<std::complex<double>>)
SPHSTAB_INSTANTIATE(2, Dual<std::complex<double>>)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
