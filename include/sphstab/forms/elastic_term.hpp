#pragma once
/// \file elastic_term.hpp
/// Additional momentum-equation terms for ElasticForm2D: acceleration contributions that read the current state of
/// every particle (positions, displacements, stresses and operators at x = x0 + u) and are added to the base form.
/// Examples: the GMS artificial stress (artificial_stress_term.hpp) and the S-SPH correction of Powell ch. 4
/// (stabilised_sph.hpp). Like GradientProvider, a term is one templated implementation used for real time stepping
/// and for complex-step Jacobians, so the linearisation differentiates exactly what is time-stepped.
///
/// \note Complex-step safety: a term must be analytic in the displacements wherever it is smooth, and take every
///       branch (switches, tension tests) on real parts only. The complex-step Jacobian is then the derivative of
///       the term with the branch state of the real point frozen.
#include <Eigen/Core>
#include <complex>
#include <string>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {

class ElasticMaterial;

/// Everything a term may read, all at the current positions (all N particles, free and fixed).
template <class Scalar>
struct ElasticTermContext {
  const Discretisation<2>& discretisation;                 ///< reference set, neighbour list (the pattern)
  const ElasticMaterial& material;                         ///< lambda, mu, rho
  const Positions<2, Scalar>& positions;                   ///< x = x0 + u, N x 2
  const Positions<2, Scalar>& displacement;                ///< u of every particle (fixed: prescribed), N x 2
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 3>& stress;  ///< sigma_i incl. pre-stress, N x 3 (xx, yy, xy)
  const Operators<2, Scalar>& operators;                   ///< W (if requested), G, H (if requested) at x
};

/// Accelerations of all N particles, N x 2 (a term adds to it; only the free rows are used).
template <class Scalar>
using ParticleAccelerations = Eigen::Matrix<Scalar, Eigen::Dynamic, 2>;

/// Base class of additional momentum terms (see the file comment).
class ElasticTerm2D {
 public:
  virtual ~ElasticTerm2D() = default;
  virtual std::string name() const = 0;
  /// Operators the term needs besides G (W for kernel values, H for curvature terms).
  virtual OperatorRequest requirements() const { return {.kernel = false, .gradient = true, .hessian = false}; }
  /// Neighbour-graph hops from particle i whose displacements row i of the term may read (for the Jacobian
  /// sparsity pattern): 2 when it reads stresses of neighbours, more for means of means.
  virtual int dependence_radius() const { return 2; }
  /// Adds the term's accelerations of all particles to `acc` (N x 2, already sized).
  virtual void add(const ElasticTermContext<double>& context, ParticleAccelerations<double>& acc) const = 0;
  virtual void add(const ElasticTermContext<std::complex<double>>& context,
                   ParticleAccelerations<std::complex<double>>& acc) const = 0;
};

/// CRTP helper: Derived implements `template <class Scalar> void add_impl(const ElasticTermContext<Scalar>&,
/// ParticleAccelerations<Scalar>&) const`; both overloads forward to it.
template <class Derived>
class ElasticTermT : public ElasticTerm2D {
 public:
  void add(const ElasticTermContext<double>& c, ParticleAccelerations<double>& acc) const override {
    static_cast<const Derived&>(*this).add_impl(c, acc);
  }
  void add(const ElasticTermContext<std::complex<double>>& c,
           ParticleAccelerations<std::complex<double>>& acc) const override {
    static_cast<const Derived&>(*this).add_impl(c, acc);
  }
};

}  // namespace sphstab
