#pragma once
// Shared test fixture for the kernel-correction tests: a lattice, its neighbour list and operators.
#include <complex>

#include "../forms/forms_fixture.hpp"  // max_abs
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab::test {

using Complex = std::complex<double>;

template <int Dim>
struct Case {
  ParticleSet<Dim> set;
  NeighbourList nl;
  Operators<Dim, double> ops;
  Operators<Dim, Complex> cops;  // the same operators assembled with a complex scalar at real positions
};

/// n per side, h = h_over_dx * dx (dx = 1), cubic spline unless told; fixed_layers -1 = complete layers.
template <int Dim>
Case<Dim> make_case(LatticeType type, int n, double h_over_dx, double perturbation, bool periodic = false,
                    int fixed_layers = -1, KernelType kernel = KernelType::CubicSpline, std::uint64_t seed = 7) {
  Kernel<Dim> w(kernel);
  const double h = h_over_dx;
  Case<Dim> c;
  c.set = make_lattice<Dim>(type, n,
                            {.spacing = 1.0,
                             .fixed_layers = periodic ? -1 : fixed_layers,
                             .support_radius = w.support_radius(h),
                             .periodic = periodic,
                             .perturbation = perturbation,
                             .seed = seed});
  c.nl = find_neighbours(c.set, w.support_radius(h));
  c.ops = assemble_operators<Dim, double>(c.set, c.nl, w, h, {.kernel = true, .gradient = true, .hessian = false});
  Positions<Dim, Complex> x = c.set.x.template cast<Complex>();
  c.cops =
      assemble_operators<Dim, Complex>(c.set, c.nl, w, h, {.kernel = true, .gradient = true, .hessian = false}, &x);
  return c;
}

/// max |A - Re(B)| + max |Im(B)| over the union of patterns (complex-step instantiation vs double one).
inline double complex_mismatch(const SparseMatrix<double>& a, const SparseMatrix<Complex>& b) {
  Eigen::MatrixXcd d = Eigen::MatrixXcd(b) - Eigen::MatrixXd(a).cast<Complex>();
  return d.cwiseAbs().maxCoeff();
}


inline Eigen::VectorXd row_sums(const SparseMatrix<double>& a) { return a * Eigen::VectorXd::Ones(a.cols()); }
inline Eigen::VectorXd column_sums(const SparseMatrix<double>& a) {
  return SparseMatrix<double>(a.transpose()) * Eigen::VectorXd::Ones(a.rows());
}

}  // namespace sphstab::test
