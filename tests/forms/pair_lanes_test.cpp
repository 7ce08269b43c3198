// The pair loop's row scalars by vector lanes (src/forms/rate_form/pair_lanes.hpp) against the scalar functions they
// stand for, bit for bit: W and dW/dr / r (CubicFunctions::row_pairs), f^4 (PairFactor::row_by_reciprocal), 1 /
// rhobar and Pi / rhobar (pair_viscosity.hpp), on rows of every length 0..13 (whole vectors and every remainder) whose
// radii cover the inner piece, the outer piece, the support's exterior, the breakpoints s = 1 and 2 exactly and r = 0,
// for both builds (the baseline's 2 lanes; the AVX2 clone's 4 where the CPU has it).
#include "../../src/forms/rate_form/pair_lanes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "../../src/forms/rate_form/artificial_stress.hpp"
#include "../../src/forms/rate_form/dispatch.hpp"
#include "../../src/forms/rate_form/kernel_rows.hpp"
#include "../../src/forms/rate_form/pair_viscosity.hpp"
#include "sphstab/core/simd_dispatch.hpp"
#include "sphstab/kernel/kernel.hpp"

namespace sphstab {
namespace pair_lanes_test {

namespace rd = rate_form_detail;

/// One row: inputs, and the outputs of the lanes and of the scalar functions.
struct Row {
  std::vector<double> r2, vr, rhoj;
  std::vector<double> w, gf, f, ib, c;  // by lanes (padded to whole vectors)
};

/// `len` pairs for kernel support 2h: radii drawn over [0, 2.4h], with the breakpoints and r = 0 in the first slots.
Row make_row(std::size_t len, double h, std::mt19937& rng) {
  std::uniform_real_distribution<double> r(0.0, 2.4 * h), v(-1.0, 1.0), rho(0.8, 1.2);
  const std::size_t padded = (len + rd::kMaxPairLanes - 1) / rd::kMaxPairLanes * rd::kMaxPairLanes;
  Row row;
  for (std::vector<double>* a : {&row.r2, &row.vr, &row.rhoj, &row.w, &row.gf, &row.f, &row.ib, &row.c})
    a->assign(padded, -7.0);  // lanes past len hold anything
  const double special[] = {h * h, 4 * h * h, 0.0};
  for (std::size_t q = 0; q < len; ++q) {
    const double rq = r(rng);
    row.r2[q] = q < 3 ? special[q] : rq * rq;
    row.vr[q] = q == 4 ? 0.0 : v(rng);
    row.rhoj[q] = rho(rng);
  }
  return row;
}

template <ViscositySwitch kV, bool kS, bool kX>
void expect_same_bits(bool avx2, const std::string& what) {
  const Kernel<2> kernel(KernelType::CubicSpline);
  const double h = 1.3, rho_i = 1.05;
  const rd::CubicFunctions<2> kf(kernel, h);
  const rd::PairFactor factor(kernel.value(1.0, h), 4);
  const std::array<double, 4> k = kf.pair_constants();
  const rd::PairLaneConstants lane{.inv_h = k[0],
                                   .cw = k[1],
                                   .cd_h = k[2],
                                   .cd_out = k[3],
                                   .inv_w_dp = factor.reciprocal_w_dp(),
                                   .h = h,
                                   .eta2 = 0.01 * h * h,
                                   .alpha_c0 = -0.7,
                                   .beta = 1.9};
  constexpr bool kViscous = kV != ViscositySwitch::Off;
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  std::mt19937 rng(17);
  long compared = 0;
  for (std::size_t len = 0; len <= 13; ++len) {
    Row row = make_row(len, h, rng);
    rd::pair_lanes<kV, kS, kX>(avx2, lane,
                               rd::PairLaneRow{.len = len,
                                               .rho_i = rho_i,
                                               .r2 = row.r2.data(),
                                               .vr = row.vr.data(),
                                               .rhoj = row.rhoj.data(),
                                               .w = row.w.data(),
                                               .gf = row.gf.data(),
                                               .f = row.f.data(),
                                               .ib = row.ib.data(),
                                               .c = row.c.data()});
    // The scalar functions, on r = sqrt(r^2).
    std::vector<double> r(len), w(len), gf(len), f(len);
    for (std::size_t q = 0; q < len; ++q) r[q] = std::sqrt(row.r2[q]);
    kf.row_pairs(len, r.data(), w.data(), gf.data());
    factor.row_by_reciprocal(len, w.data(), f.data());
    for (std::size_t q = 0; q < len; ++q) {
      const std::string at = what + ", len " + std::to_string(len) + ", pair " + std::to_string(q);
      EXPECT_EQ(bits(row.w[q]), bits(w[q])) << at << ": W " << row.w[q] << " vs " << w[q];
      EXPECT_EQ(bits(row.gf[q]), bits(gf[q])) << at << ": dW/dr / r " << row.gf[q] << " vs " << gf[q];
      if constexpr (kS) EXPECT_EQ(bits(row.f[q]), bits(f[q])) << at << ": f^4";
      if constexpr (kViscous || kX) {
        const double ib = 2.0 / (rho_i + row.rhoj[q]);
        EXPECT_EQ(bits(row.ib[q]), bits(ib)) << at << ": 1 / rhobar";
        if constexpr (kViscous) {
          const double mu = rd::viscosity_mu(h, row.vr[q], row.r2[q], lane.eta2);
          const double cq = rd::viscosity_pi(mu, lane.alpha_c0, lane.beta, kV == ViscositySwitch::Compression) * ib;
          const double c = kV == ViscositySwitch::Compression && !(row.vr[q] < 0) ? 0.0 : cq;
          EXPECT_EQ(bits(row.c[q]), bits(c)) << at << ": Pi / rhobar";
        }
      }
      ++compared;
    }
  }
  EXPECT_EQ(compared, 91);
}

/// Every term combination the pair loop compiles, on the build `avx2` names.
void expect_all_same_bits(bool avx2) {
  const std::string build = avx2 ? "AVX2" : "baseline";
  for (ViscositySwitch v : {ViscositySwitch::Off, ViscositySwitch::Compression, ViscositySwitch::Always})
    for (bool stress : {false, true})
      rd::with_term_tags(v, stress, [&](auto viscosity_tag, auto stress_tag) {
        constexpr ViscositySwitch kV = decltype(viscosity_tag)::value;
        constexpr bool kS = decltype(stress_tag)::value;
        const std::string what =
            build + ", viscosity " + std::to_string(static_cast<int>(kV)) + ", stress " + std::to_string(kS);
        expect_same_bits<kV, kS, false>(avx2, what + ", no XSPH");
        expect_same_bits<kV, kS, true>(avx2, what + ", XSPH");
      });
}

TEST(PairLanes, BaselineLanesAreTheScalarFunctionsBits) { expect_all_same_bits(false); }

TEST(PairLanes, Avx2LanesAreTheScalarFunctionsBits) {
  if (!avx2_enabled()) GTEST_SKIP() << "no AVX2 on this CPU (or SPHSTAB_SIMD=baseline): only the baseline build runs";
  expect_all_same_bits(true);
}

}  // namespace pair_lanes_test
}  // namespace sphstab
