// Scale invariance (core/length_scale.hpp): operators at spacing s dx are the exact rescalings of those at dx over the
// whole supported length range, in 1D, 2D and 3D; outside it every entry point refuses with one line naming the range.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/length_scale.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace scale_invariance_test {

struct Assembled {
  NeighbourList nl;
  std::vector<std::vector<double>> W, G, H;  // value arrays: W; G per axis; H per (a, b)
};

template <int Dim>
Assembled assemble_at(LatticeType type, double dx, KernelType kt, double h_over_dx, int n, bool periodic) {
  const Kernel<Dim> kernel(kt);
  const double h = h_over_dx * dx;
  const ParticleSet<Dim> set = make_lattice<Dim>(type, n,
                                                 {.spacing = dx,
                                                  .support_radius = kernel.support_radius(h),
                                                  .periodic = periodic,
                                                  .perturbation = 0.1,
                                                  .seed = 3});
  Assembled out;
  out.nl = find_neighbours(set, kernel.support_radius(h));
  const Operators<Dim> ops =
      assemble_operators<Dim>(set, out.nl, kernel, h, {.kernel = true, .gradient = true, .hessian = true});
  auto values = [](const SparseMatrix<>& m) { return std::vector<double>(m.valuePtr(), m.valuePtr() + m.nonZeros()); };
  out.W.push_back(values(ops.W));
  for (int a = 0; a < Dim; ++a) out.G.push_back(values(ops.G[a]));
  for (int a = 0; a < Dim; ++a)
    for (int b = 0; b < Dim; ++b) out.H.push_back(values(ops.H[a][b]));
  return out;
}

/// Largest |x s^p - y| / max|y| over the arrays (0 for a bitwise rescaling with s a power of two).
double rescaling_error(const std::vector<std::vector<double>>& x, const std::vector<std::vector<double>>& y, double s,
                       int p) {
  double err = 0, scale = 0;
  for (size_t m = 0; m < y.size(); ++m)
    for (size_t k = 0; k < y[m].size(); ++k) {
      scale = std::max(scale, std::abs(y[m][k]));
      err = std::max(err, std::abs(x[m][k] * std::pow(s, p) - y[m][k]));
    }
  return scale > 0 ? err / scale : err;
}

template <int Dim>
void check_range(LatticeType type, int n, KernelType kt, bool periodic) {
  const double h_over_dx = 1.3;
  const Assembled ref = assemble_at<Dim>(type, 1.0, kt, h_over_dx, n, periodic);
  ASSERT_GT(ref.nl.nonzeros(), ref.nl.size());  // real neighbours, not just the diagonal
  // Powers of two from 2^-199 (1.2e-60) to 2^197 (2e59, so that the support 2.6 dx stays below 1e60): bitwise.
  for (int k = -199; k <= 197; k += 18) {
    const double s = std::ldexp(1.0, k);
    const Assembled a = assemble_at<Dim>(type, s, kt, h_over_dx, n, periodic);
    ASSERT_EQ(a.nl.indices, ref.nl.indices) << "dx = 2^" << k;
    EXPECT_EQ(a.W, ref.W) << "dx = 2^" << k;
    EXPECT_EQ(rescaling_error(a.G, ref.G, s, 1), 0.0) << "dx = 2^" << k;
    EXPECT_EQ(rescaling_error(a.H, ref.H, s, 2), 0.0) << "dx = 2^" << k;
  }
  // Decimal ends of the range: rescalings to rounding (each entry is a product of a few correctly rounded factors).
  for (double s : {1e-60 / (h_over_dx * 2) * 10, 1e-30, 3.7e12, 1e58}) {
    const Assembled a = assemble_at<Dim>(type, s, kt, h_over_dx, n, periodic);
    ASSERT_EQ(a.nl.indices, ref.nl.indices) << "dx = " << s;
    EXPECT_LT(rescaling_error(a.W, ref.W, s, 0), 1e-14) << "dx = " << s;
    EXPECT_LT(rescaling_error(a.G, ref.G, s, 1), 1e-14) << "dx = " << s;
    EXPECT_LT(rescaling_error(a.H, ref.H, s, 2), 1e-14) << "dx = " << s;
  }
}

TEST(ScaleInvariance, OperatorsRescaleExactly1D) {
  for (KernelType kt : {KernelType::CubicSpline, KernelType::WendlandC4, KernelType::Gaussian})
    check_range<1>(LatticeType::Line, 12, kt, false);
  check_range<1>(LatticeType::Line, 12, KernelType::QuinticSpline, true);
}

TEST(ScaleInvariance, OperatorsRescaleExactly2D) {
  check_range<2>(LatticeType::Square, 5, KernelType::CubicSpline, false);
  check_range<2>(LatticeType::Hexagonal, 8, KernelType::WendlandC2, true);
}

TEST(ScaleInvariance, OperatorsRescaleExactly3D) {
  check_range<3>(LatticeType::Cubic, 3, KernelType::QuinticSpline, false);
}

TEST(ScaleInvariance, OutsideTheRangeEveryEntryPointRefusesNamingIt) {
  auto expect_range_error = [](auto&& f, const char* what) {
    try {
      f();
      ADD_FAILURE() << what << ": no error";
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("supported length range [1e-60, 1e+60]"), std::string::npos) << what << ": " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << what;
    }
  };
  const Kernel<2> k(KernelType::CubicSpline);
  for (double dx : {1e-300, 1e-61, 1e61, 1e200}) {
    expect_range_error([&] { make_lattice<2>(LatticeType::Square, 4, {.spacing = dx, .support_radius = 2.6 * dx}); },
                       "make_lattice");
    expect_range_error([&] { fixed_layers_needed(2.6 * dx, dx); }, "fixed_layers_needed");
  }
  const ParticleSet<2> set = make_lattice<2>(LatticeType::Square, 4, {.spacing = 1.0, .support_radius = 2.6});
  expect_range_error([&] { find_neighbours(set, 1e-70); }, "find_neighbours");
  const NeighbourList nl = find_neighbours(set, 2.6);
  expect_range_error([&] { assemble_operators<2>(set, nl, k, 1e-65); }, "assemble_operators");
  EXPECT_NO_THROW(check_length(kMinLength, "x"));
  EXPECT_NO_THROW(check_length(kMaxLength, "x"));
  EXPECT_THROW(check_length(std::nextafter(kMinLength, 0.0), "x"), std::invalid_argument);
  EXPECT_THROW(check_length(std::nan(""), "x"), std::invalid_argument);
  EXPECT_THROW(check_length(-1.0, "x"), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
