#pragma once
// Private helpers shared by the force-function implementations (not installed).
#include <array>
#include <stdexcept>
#include <string>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/gradient_provider.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {
namespace detail {

/// Displacement of every particle into `all` (resized to N x Dim; no allocation when it already has that size): free
/// slots from u, fixed particles from `fixed` (ascending order).
template <int Dim, class Scalar>
inline void full_displacement_into(const Discretisation<Dim>& d, const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                   const Eigen::VectorXd& fixed, const char* who, Positions<Dim, Scalar>& all) {
  if (u.size() != d.dofs())
    throw std::invalid_argument(std::string(who) + ": displacement has " + std::to_string(u.size()) +
                                " entries, expected " + std::to_string(d.dofs()) + " (Dim x free particles)");
  all.resize(d.size(), Dim);
  long next_fixed = 0;
  for (int i = 0; i < d.size(); ++i) {
    const int f = d.free_slot[i];
    for (int a = 0; a < Dim; ++a)
      all(i, a) = f >= 0 ? u[f * Dim + a] : Scalar(fixed.size() ? fixed[next_fixed * Dim + a] : 0.0);
    if (f < 0) ++next_fixed;
  }
}

/// Displacement of every particle (a new N x Dim array; see full_displacement_into).
template <int Dim, class Scalar>
inline Positions<Dim, Scalar> full_displacement(const Discretisation<Dim>& d,
                                                const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& u,
                                                const Eigen::VectorXd& fixed, const char* who) {
  Positions<Dim, Scalar> all;
  full_displacement_into<Dim, Scalar>(d, u, fixed, who, all);
  return all;
}

/// Applies a non-plain provider to a copy of G; returns false (and leaves g untouched) for a plain provider.
/// Unless `any_pattern` (callers that iterate the result's own pattern), the result must keep the neighbour-list
/// pattern: callers that index it with the neighbour list reject non-local (dense) providers here.
template <int Dim, class Scalar>
inline bool corrected_gradient(const GradientProvider<Dim>* provider, const Discretisation<Dim>& d,
                               const Positions<Dim, Scalar>& x, const Operators<Dim, Scalar>& ops,
                               std::array<SparseMatrix<Scalar>, Dim>& g, bool any_pattern = false) {
  if (!provider || provider->is_plain()) return false;
  g = ops.G;
  GradientContext<Dim, Scalar> context{d, x, ops};
  provider->correct(context, g);
  for (int a = 0; a < Dim; ++a) {
    if (g[a].rows() != d.size() || g[a].cols() != d.size())
      throw std::logic_error("gradient provider '" + provider->name() + "' returned a matrix of the wrong size");
    if (!any_pattern && g[a].nonZeros() != d.neighbours.nonzeros())
      throw std::logic_error("gradient provider '" + provider->name() + "' changed the neighbour-list pattern" +
                             (provider->keeps_pattern() ? "" : " (it is non-local; this form needs a local one)"));
  }
  return true;
}

template <int Dim>
inline OperatorRequest form_request(const GradientProvider<Dim>* provider, bool hessian) {
  OperatorRequest req{.kernel = false, .gradient = true, .hessian = hessian};
  if (provider) {
    OperatorRequest p = provider->requirements();
    req.kernel = req.kernel || p.kernel;
    req.hessian = req.hessian || p.hessian;
  }
  return req;
}

/// Eigen 3.4 sparse matrices have no move operations (assignment deep-copies), so hand the operators over by
/// O(1) swaps: `ops = assemble_operators(...)` would copy every matrix into freshly faulted pages.
template <int Dim, class Scalar>
inline void take_operators(Operators<Dim, Scalar>& dst, Operators<Dim, Scalar>& src) {
  dst.W.swap(src.W);
  for (int a = 0; a < Dim; ++a) {
    dst.G[a].swap(src.G[a]);
    for (int b = 0; b < Dim; ++b) dst.H[a][b].swap(src.H[a][b]);
  }
}

}  // namespace detail

}  // namespace sphstab
