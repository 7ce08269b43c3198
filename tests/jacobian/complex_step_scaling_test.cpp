// The complex step scales with each variable (complex_step_jacobian.hpp): the rate-form scheme's J, spectrum and
// leap-frog limit rescale exactly over the supported length range. With every length multiplied by s and the
// material fixed, time scales by s too, so y_s = D y_1 with D = s on positions and 1 on velocities, densities and
// stresses, F_s(D y) = D F_1(y) / s and therefore J_s = D J_1 D^-1 / s: rates and frequencies scale as 1 / s, the
// time step as s. A fixed step of 1e-30 broke this at dx = 1e-40 (|x + ih|^2 = |x|^2 - h^2 + 2ihx with h >> |x|) and
// near 1e58 (issue 36: a 2D growth rate 2 % and 7 % off, the mode at the wrong wavevector).
#include "sphstab/jacobian/complex_step_jacobian.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace complex_step_scaling_test {

TEST(ComplexStepSize, IsTheFixedStepInsideTheBandAndScalesOutside) {
  for (double s : {1e-12, 1e-3, 1.0, 7.8, 1e12}) EXPECT_EQ(complex_step_size(1e-30, s), 1e-30) << s;
  EXPECT_DOUBLE_EQ(complex_step_size(1e-30, 1e-40), 1e-58);
  EXPECT_DOUBLE_EQ(complex_step_size(1e-30, 1e58), 1e16);
  for (double bad : {0.0, -1.0, double(NAN), double(INFINITY)}) EXPECT_THROW(complex_step_size(1e-30, bad), std::invalid_argument);
}

/// A periodic 2D lattice of spacing s with every term that enters J at rest (XSPH, the viscosity's linear part,
/// artificial stress), in compression so that the pressure is not zero.
RateFormScheme<2> scheme_at(double s, LatticeType type) {
  const Kernel<2> k(KernelType::CubicSpline);
  const double h = 1.3 * s;
  const ParticleSet<2> set =
      make_lattice<2>(type, 8, {.spacing = s, .support_radius = k.support_radius(h), .periodic = true});
  const ElasticMaterial m = ElasticMaterial::from_bulk_shear(1.0, 0.3, 1.0);
  return RateFormScheme<2>(make_discretisation(set, k, h), m,
                           {.xsph = 0.5, .viscosity = ViscositySwitch::Always, .artificial_stress = 0.3}, 1.0 / 0.97);
}

TEST(ComplexStepScaling, RateFormJacobianSpectrumAndTimeStepRescaleExactly) {
  for (LatticeType type : {LatticeType::Square, LatticeType::Hexagonal}) {
    const RateFormScheme<2> one = scheme_at(1.0, type);
    const Eigen::VectorXd y1 = one.uniform_state();
    const Eigen::MatrixXd J1(ComplexStepJacobian(one).compute(y1));
    const RateFormSpectrum r1 = rate_form_spectrum(one, y1);
    ASSERT_EQ(r1.status, Status::Successful) << r1.reason;
    const double limit1 = leapfrog_time_step_limit(r1.eigenvalues);
    ASSERT_TRUE(std::isfinite(limit1) && limit1 > 0);
    Eigen::VectorXd d = Eigen::VectorXd::Ones(one.size());  // D: s on the positions
    for (int i = 0; i < one.discretisation().size(); ++i)
      if (one.position_offset(i) >= 0) d.segment<2>(one.position_offset(i)).setConstant(-1);  // marked
    for (double s : {1e-40, 1e-20, 1e20, 1e58}) {
      const RateFormScheme<2> scaled = scheme_at(s, type);
      const Eigen::VectorXd ys = scaled.uniform_state();
      const Eigen::MatrixXd Js(ComplexStepJacobian(scaled).compute(ys));
      // J_s = D J_1 D^-1 / s, entrywise relative to the largest entry of each.
      Eigen::MatrixXd expected = J1 / s;
      for (Eigen::Index r = 0; r < J1.rows(); ++r)
        for (Eigen::Index c = 0; c < J1.cols(); ++c)
          expected(r, c) *= (d[r] < 0 ? s : 1.0) / (d[c] < 0 ? s : 1.0);
      const double err = (Js - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
      EXPECT_LT(err, 1e-12) << "s " << s;
      const RateFormSpectrum rs = rate_form_spectrum(scaled, ys);
      ASSERT_EQ(rs.status, Status::Successful) << rs.reason;
      EXPECT_NEAR(rs.growth_rate * s, r1.growth_rate, 1e-10 * r1.eigenvalues.cwiseAbs().maxCoeff()) << "s " << s;
      EXPECT_NEAR(rs.eigenvalues.cwiseAbs().maxCoeff() * s, r1.eigenvalues.cwiseAbs().maxCoeff(),
                  1e-12 * r1.eigenvalues.cwiseAbs().maxCoeff())
          << "s " << s;
      EXPECT_NEAR(leapfrog_time_step_limit(rs.eigenvalues) / s, limit1, 1e-12 * limit1) << "s " << s;
      std::printf("%s s %.0e: J %.2e relative; growth * s %.12e (s = 1: %.12e); dt limit / s %.12e\n",
                  lattice_name(type).c_str(), s, err, rs.growth_rate * s, r1.growth_rate,
                  leapfrog_time_step_limit(rs.eigenvalues) / s);
    }
  }
}

}  // namespace
}  // namespace sphstab
