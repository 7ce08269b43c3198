// Per-particle fields of a rate-form state (forms/rate_form_state.hpp) and its VTK snapshot (io/rate_form_vtk.hpp):
// fixed particles read at their reference positions with zero velocity and the initial density / deviator when they
// do not evolve; sigma = -K (rho / rho0 - 1) I + S; the snapshot reads back the same numbers.
#include "sphstab/forms/rate_form_state.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "sphstab/io/rate_form_vtk.hpp"
#include "sphstab/numerics/random_vector.hpp"

namespace sphstab {
namespace rate_form_state_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_bulk_shear(3.0, 0.5, 2.0);

/// A 4 x 3 block at dx = 1 whose bottom row is fixed.
std::shared_ptr<const Discretisation<2>> block() {
  ParticleSet<2> p;
  p.x.resize(12, 2);
  p.volume = Eigen::VectorXd::Ones(12);
  p.role.assign(12, Role::Free);
  p.spacing = 1.0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      p.x.row(j * 4 + i) << i, j;
      if (j == 0) p.role[j * 4 + i] = Role::Fixed;
    }
  return make_discretisation(p, Kernel<2>(KernelType::CubicSpline), 1.3);
}

TEST(RateFormState, FieldsOfFreeAndFixedParticles) {
  const Eigen::Vector3d deviator(0.1, -0.3, 0.2);
  for (bool evolve : {true, false}) {
    const RateFormScheme<2> s(block(), kMaterial, {.evolve_fixed = evolve}, 2.5, deviator);
    const Eigen::VectorXd y = s.uniform_state() + random_vector(s.size(), 0.1, 7);
    const Eigen::Matrix2Xd x = rate_form_positions(s, y), v = rate_form_velocities(s, y);
    const Eigen::VectorXd rho = rate_form_densities(s, y);
    const std::vector<Eigen::Matrix2d> sigma = rate_form_stresses(s, y);
    for (int i = 0; i < 12; ++i) {
      const bool fixed = i < 4;
      const Eigen::Vector2d x_expected = fixed ? Eigen::Vector2d(s.discretisation().particles.x.row(i).transpose())
                                               : Eigen::Vector2d(y.segment<2>(s.position_offset(i)));
      EXPECT_EQ(x.col(i), x_expected) << i;
      EXPECT_EQ(v.col(i), fixed ? Eigen::Vector2d::Zero() : Eigen::Vector2d(y.segment<2>(s.velocity_offset(i))));
      const bool own = !fixed || evolve;
      const double r = own ? y[s.density_offset(i)] : 2.5;
      const Eigen::Vector3d S = own ? Eigen::Vector3d(y.segment<3>(s.stress_offset(i))) : deviator;
      EXPECT_EQ(rho[i], r);
      const double p = 3.0 * (r / 2.0 - 1);
      EXPECT_DOUBLE_EQ(sigma[i](0, 0), S[0] - p);
      EXPECT_DOUBLE_EQ(sigma[i](1, 1), S[1] - p);
      EXPECT_EQ(sigma[i](0, 1), S[2]);
      EXPECT_EQ(sigma[i](1, 0), S[2]);
    }
  }
}

TEST(RateFormState, OneDimensionalStressAndWrongSize) {
  ParticleSet<1> p;
  p.x.resize(5, 1);
  p.volume = Eigen::VectorXd::Ones(5);
  p.role.assign(5, Role::Free);
  p.spacing = 1.0;
  for (int i = 0; i < 5; ++i) p.x(i, 0) = i;
  const RateFormScheme<1> s(make_discretisation(p, Kernel<1>(KernelType::CubicSpline), 1.2), kMaterial);
  Eigen::VectorXd y = s.uniform_state();
  y[s.density_offset(2)] = 2.2, y[s.stress_offset(2)] = 0.4;
  EXPECT_NEAR(rate_form_stresses(s, y)[2](0, 0), 0.4 - 3.0 * 0.1, 1e-15);
  EXPECT_EQ(rate_form_stresses(s, y)[1](0, 0), 0.0);
  const Eigen::VectorXd bad = Eigen::VectorXd::Zero(s.size() + 1);
  EXPECT_THROW(rate_form_positions(s, bad), std::invalid_argument);
  EXPECT_THROW(rate_form_velocities(s, bad), std::invalid_argument);
  EXPECT_THROW(rate_form_densities(s, bad), std::invalid_argument);
  EXPECT_THROW(rate_form_stresses(s, bad), std::invalid_argument);
}

TEST(RateFormVtk, SnapshotReadsBack) {
  RateFormScheme<2> s(block(), kMaterial, {.evolve_fixed = false});
  s.set_driven({5}, {Eigen::Vector2d(1, 0)});
  const Eigen::VectorXd y = s.uniform_state() + random_vector(s.size(), 0.1, 11);
  const Eigen::Matrix3Xd S = rate_form_deviators(s, y);
  const std::string path = (std::filesystem::temp_directory_path() / "sphstab_rate_form_vtk_test.vtp").string();
  const Eigen::VectorXd tag = Eigen::VectorXd::LinSpaced(12, 0, 11);
  write_rate_form_vtp(path, s, y, {{"tag", 1, tag}});
  const VtpData d = read_vtp(path);
  std::remove(path.c_str());
  const Eigen::Matrix2Xd x = rate_form_positions(s, y), v = rate_form_velocities(s, y);
  const std::vector<Eigen::Matrix2d> sigma = rate_form_stresses(s, y);
  ASSERT_EQ(d.points.rows(), 12);
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(d.points.row(i).head<2>().transpose(), x.col(i));
    EXPECT_EQ(d.field("velocity").values.segment<2>(3 * i), v.col(i));  // 2-vectors are stored padded to 3
    EXPECT_EQ(d.field("sigma_xx").values[i], sigma[i](0, 0));
    EXPECT_EQ(d.field("sigma_yy").values[i], sigma[i](1, 1));
    EXPECT_EQ(d.field("sigma_xy").values[i], sigma[i](0, 1));
    EXPECT_EQ(d.field("pressure").values[i], 3.0 * (rate_form_densities(s, y)[i] / 2.0 - 1));
    EXPECT_EQ(d.field("fixed").values[i], i < 4 ? 1.0 : 0.0);
    EXPECT_EQ(d.field("driven").values[i], i == 5 ? 1.0 : 0.0);
    const double szz = -(S(0, i) + S(1, i));  // plane strain: the completed deviator is traceless
    EXPECT_NEAR(d.field("von_mises").values[i],
                std::sqrt(1.5 * (S(0, i) * S(0, i) + S(1, i) * S(1, i) + szz * szz + 2 * S(2, i) * S(2, i))), 1e-15);
    EXPECT_EQ(d.field("tag").values[i], i);
  }
}

}  // namespace
}  // namespace sphstab
