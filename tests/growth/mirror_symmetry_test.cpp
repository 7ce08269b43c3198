#include "sphstab/growth/mirror_symmetry.hpp"

#include <gtest/gtest.h>

#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/growth/linear_growth.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace mirror_symmetry_test {

TEST(MirrorSymmetry, ClassesPartitionTheFieldsAndBlockDiagonaliseASymmetricJacobian) {
  const int n = 7;
  Kernel<2> k(KernelType::CubicSpline);
  auto set = make_lattice<2>(LatticeType::Square, n, {.spacing = 1.0, .support_radius = k.support_radius(1.3)});
  auto d = make_discretisation(set, k, 1.3);
  Eigen::VectorXd pos(d->dofs());
  for (int f = 0; f < d->free_count(); ++f) pos.segment<2>(2 * f) = d->particles.x.row(d->free[f]).transpose();
  const MirrorSymmetry s = mirror_symmetry(pos, Eigen::Vector2d(0.5 * n, 0.5 * n), 1e-9);
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(d->dofs(), d->dofs());
  std::vector<Eigen::MatrixXd> bases;
  for (int px : {1, -1})
    for (int py : {1, -1}) {
      const Eigen::MatrixXd Q = symmetry_basis(s, px, py);
      EXPECT_LT((Q.transpose() * Q - Eigen::MatrixXd::Identity(Q.cols(), Q.cols())).cwiseAbs().maxCoeff(), 1e-14);
      P += Q * Q.transpose();
      bases.push_back(Q);
    }
  EXPECT_LT((P - Eigen::MatrixXd::Identity(d->dofs(), d->dofs())).cwiseAbs().maxCoeff(), 1e-14);
  // Basic SPH under isotropic tension commutes with the reflections; the union of the block spectra is the spectrum.
  ElasticForm2D force(d, ElasticMaterial::from_lame(1.2, 0.8, 7.8), MomentumForm::Plus,
                      PreStrain::from_area_ratio(1.03));
  const SparseMatrix<> A = jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
  EXPECT_LT(commutation_error(s, A), 1e-13);
  double gamma = 0;
  for (const auto& Q : bases) gamma = std::max(gamma, matrix_growth(Q.transpose() * Eigen::MatrixXd(A) * Q).gamma);
  EXPECT_NEAR(gamma, matrix_growth(Eigen::MatrixXd(A)).gamma, 1e-9 * gamma);
  // the centre particle moving along +x lies in the class (-1, +1)
  Eigen::VectorXd v = Eigen::VectorXd::Zero(d->dofs());
  v[2 * (n * n / 2)] = 1.0;
  EXPECT_NEAR(class_share(s, -1, 1, v), 1.0, 1e-15);
  EXPECT_NEAR(class_share(s, 1, 1, v), 0.0, 1e-15);
}

TEST(MirrorSymmetry, BadInput) {
  Eigen::VectorXd pos(4);
  pos << 0, 0, 1, 0.5;  // not symmetric about (0.5, 0)
  EXPECT_THROW(mirror_symmetry(pos, Eigen::Vector2d(0.5, 0), 1e-9), std::invalid_argument);
  EXPECT_THROW(mirror_symmetry(Eigen::VectorXd::Zero(3), Eigen::Vector2d(0, 0), 1e-9), std::invalid_argument);
  pos << 0, 0, 1, 0;
  const MirrorSymmetry s = mirror_symmetry(pos, Eigen::Vector2d(0.5, 0), 1e-9);
  EXPECT_THROW(symmetry_basis(s, 2, 1), std::invalid_argument);
  EXPECT_THROW(reflect(s, 2, pos), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
