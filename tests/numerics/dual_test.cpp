// Forward-mode dual numbers: exact first derivatives, composition with the complex step (nested derivatives) and
// with the kernels and operators.
#include "sphstab/numerics/dual.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace dual_test {

using D = Dual<double>;
using DC = Dual<std::complex<double>>;

TEST(Dual, ArithmeticGivesExactDerivatives) {
  const D x(0.7, 1.0);
  // f = (3 x^2 - 1/x + 2) / (x + 4) * sqrt(x) * exp(-x)
  auto f = [](auto v) {
    using std::exp;
    using std::sqrt;
    return (3.0 * v * v - 1.0 / v + 2.0) / (v + 4.0) * sqrt(v) * exp(-v);
  };
  const double h = 1e-30;
  const std::complex<double> fc = f(std::complex<double>(0.7, h));
  const D y = f(x);
  EXPECT_NEAR(y.v, f(0.7), 1e-15);
  EXPECT_NEAR(y.d, fc.imag() / h, 1e-14 * std::abs(y.d));  // complex step: exact to round-off
  D z = x;
  z += 2.0;
  z -= x;
  z *= 3.0;
  EXPECT_EQ(z.v, 6.0);
  EXPECT_EQ(z.d, 0.0);
  EXPECT_EQ(D(2.0) - x, D(1.3, -1.0));
  EXPECT_TRUE(D(1.0, 2.0) != D(1.0, 3.0));
  EXPECT_EQ(detail::re(DC(std::complex<double>(1.5, 2.0), 0.0)), 1.5);
}

TEST(Dual, NestedInsideComplexStepGivesSecondDerivative) {
  // d^2/dx^2 of x^3 exp(x) = (x^3 + 6 x^2 + 6 x) exp(x): the dual part carries d/dx, the imaginary step the second.
  const double x0 = 0.4, h = 1e-30;
  const DC x(std::complex<double>(x0, h), 1.0);
  using std::exp;
  const DC y = x * x * x * exp(x);
  const double exact = (x0 * x0 * x0 + 6 * x0 * x0 + 6 * x0) * std::exp(x0);
  EXPECT_NEAR(y.d.imag() / h, exact, 1e-14 * exact);
}

TEST(Dual, KernelDerivativeThroughDual) {
  for (KernelType type : all_kernel_types()) {
    Kernel<1> w(type);
    for (double r : {0.3, 1.1, 1.9, 2.4}) {
      const D v = w.value(D(r, 1.0), 1.3);
      const D g = w.d1(D(r, 1.0), 1.3);
      EXPECT_NEAR(v.d, w.d1(r, 1.3), 1e-13) << kernel_name(type) << " r=" << r;
      EXPECT_NEAR(g.d, w.d2(r, 1.3), 1e-12) << kernel_name(type) << " r=" << r;
    }
  }
}

TEST(Dual, OperatorAssemblyDifferentiatesPositions) {
  // dW_ij/dx_k from a dual seed on particle k equals the gradient matrix (G_ij = dW_ij/dx_i, -G_ij for k = j).
  auto set = make_lattice<1>(LatticeType::Line, 8, {.spacing = 1.0, .support_radius = 2.6, .perturbation = 0.1});
  Kernel<1> w(KernelType::QuinticSpline);
  auto nl = find_neighbours(set, w.support_radius(1.3));
  const Operators<1> ops = assemble_operators<1, double>(set, nl, w, 1.3, {.kernel = true, .gradient = true});
  const int k = 3;
  Positions<1, D> x = set.x.cast<D>();
  x(k, 0).d = 1.0;
  const Operators<1, D> dops = assemble_operators<1, D>(set, nl, w, 1.3, {.kernel = true, .gradient = true}, &x);
  for (int i = 0; i < set.size(); ++i)
    for (long p = nl.offsets[i]; p < nl.offsets[i + 1]; ++p) {
      const int j = nl.indices[p];
      const double expected =
          (i == k ? 1.0 : 0.0) * ops.G[0].valuePtr()[p] - (j == k ? 1.0 : 0.0) * ops.G[0].valuePtr()[p];
      EXPECT_NEAR(dops.W.valuePtr()[p].d, expected, 1e-14) << i << "," << j;
      // value: same formula, but duals round products in another order (a few ulps)
      EXPECT_NEAR(dops.W.valuePtr()[p].v, ops.W.valuePtr()[p], 1e-14 * std::abs(ops.W.valuePtr()[p]));
    }
}

}  // namespace
}  // namespace sphstab
