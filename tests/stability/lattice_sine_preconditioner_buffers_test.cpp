// LatticeSinePreconditioner::apply keeps its per-thread buffers between calls (a new 16 MB field per call cost
// 4096 page faults at n = 1000): a second call, a call with more threads than the first, and calls from two threads
// at once on the same object (the second allocates its own buffers) all give the first call's bits.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <thread>

#include "sphstab/core/threads.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/lattice_sine_preconditioner.hpp"
#include "sphstab/stability/lattice_stencil.hpp"
#include "sphstab/numerics/random_vector.hpp"

namespace sphstab {
namespace lattice_sine_preconditioner_buffers_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);

Eigen::MatrixXd random_block(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
  return random_vector(static_cast<int>(rows * cols), 1.0, seed).reshaped(rows, cols);
}

TEST(LatticeSinePreconditionerBuffers, ReusedBuffersGiveTheSameBits) {
  const int n = 24;
  const Kernel<2> k(KernelType::CubicSpline);
  const auto d = make_discretisation(strain_lattice_2d(LatticeType::Square, k, 1.3, n), k, 1.3);
  const MatrixFreeLinearisation<2> lin(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const LatticeStencil<2> st = probe_lattice_stencil(lin, LoadDirection::Tension);
  const LatticeSinePreconditioner<2> t(st, n, 0.02);
  const Eigen::MatrixXd x = random_block(t.dofs(), 5, 3);  // 10 fields: 5 pairs
  Eigen::MatrixXd first(t.dofs(), 5), again(t.dofs(), 5);
  set_threads(1);
  t.apply(x, first);
  t.apply(x, again);
  EXPECT_TRUE(again == first);
  set_threads(2);  // one more thread's buffers
  again.setZero();
  t.apply(x, again);
  EXPECT_TRUE(again == first);
  set_threads(1);
  // One column alone (its two components still one pair): the same bits as in the block.
  Eigen::MatrixXd one(t.dofs(), 1);
  t.apply(x.col(2), one);
  EXPECT_TRUE(one == first.col(2));
  // Two callers at once on one object.
  Eigen::MatrixXd a(t.dofs(), 5), b(t.dofs(), 5);
  std::thread other([&] { t.apply(x, a); });
  t.apply(x, b);
  other.join();
  EXPECT_TRUE(a == first);
  EXPECT_TRUE(b == first);
}

}  // namespace lattice_sine_preconditioner_buffers_test
}  // namespace sphstab
