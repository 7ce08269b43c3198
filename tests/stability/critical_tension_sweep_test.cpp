// The 1D critical-tension sweep (critical_tension_sweep.hpp): each plain case equal to critical_tension_1d, the
// estimates only in tension, one case per criterion for a corrected form, and the no-neighbour rule.
#include "sphstab/stability/critical_tension_sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sphstab/core/memory_budget.hpp"
#include "sphstab/particles/lattice_presets.hpp"

namespace sphstab {
namespace critical_tension_sweep_test {

TEST(CriticalTensionSweep, PlainCasesAreTheEngineWithTheEstimates) {
  const CriticalTensionSweep s{.n = 30,
                               .kernels = {KernelType::CubicSpline, KernelType::QuinticSpline},
                               .hs = {1.0, 1.3},
                               .forms = {MomentumForm::Plus, MomentumForm::Conservative}};
  const auto cases = critical_tension_sweep(s);
  ASSERT_EQ(cases.size(), 8u);
  const CriticalTensionCase& c = cases[7];  // quintic, h = 1.3, conservative
  EXPECT_EQ(c.kernel, KernelType::QuinticSpline);
  EXPECT_EQ(c.h, 1.3);
  EXPECT_EQ(c.form, MomentumForm::Conservative);
  const Kernel<1> k(KernelType::QuinticSpline);
  const CriticalLoad ref = critical_tension_1d(tension_lattice_1d(k, 1.3, 30), k, 1.3, MomentumForm::Conservative, [] {
    CriticalLoadOptions o = CriticalLoadOptions::tension_1d();
    o.want_mode = true;  // the sweep keeps the mode (method Both)
    return o;
  }());
  EXPECT_EQ(c.result.load, ref.load);
  ASSERT_TRUE(c.estimates.has_value());
  EXPECT_TRUE(std::isfinite(c.infinite));
  EXPECT_TRUE(std::isnan(c.symbol));  // not periodic
  EXPECT_EQ(c.criterion, "definiteness");
  // Compression: no tension estimates, the reason says how the search ran.
  CriticalTensionSweep sc = s;
  sc.direction = LoadDirection::Compression;
  const auto comp = critical_tension_sweep(sc);
  EXPECT_FALSE(comp[7].estimates.has_value());
  EXPECT_TRUE(std::isnan(comp[7].infinite));
  EXPECT_EQ(comp[7].reason.rfind("compression:", 0), 0u);
}

TEST(CriticalTensionSweep, CorrectedFormsAndTheNoNeighbourRule) {
  const CriticalTensionSweep s{
      .n = 30, .hs = {0.3, 1.3}, .forms = {MomentumForm::Plus}, .correction = Correction::Shepard};
  const auto cases = critical_tension_sweep(s);
  ASSERT_GE(cases.size(), 2u);
  EXPECT_EQ(cases[0].h, 0.3);
  EXPECT_TRUE(std::isnan(cases[0].result.load));
  EXPECT_EQ(cases[0].result.status, Status::NumericalIssue);
  EXPECT_EQ(cases[0].criterion, "none");
  for (std::size_t i = 1; i < cases.size(); ++i) {
    EXPECT_EQ(cases[i].h, 1.3);
    EXPECT_EQ(cases[i].reason.rfind("corrected ", 0), 0u) << cases[i].reason;
    EXPECT_FALSE(cases[i].estimates.has_value());
  }
  EXPECT_THROW(critical_tension_sweep(CriticalTensionSweep{.periodic = true, .correction = Correction::Shepard}),
               std::invalid_argument);
}

TEST(CriticalTensionSweep, RefusesBeforeBuilding) {
  int calls = 0;
  CriticalTensionSweep s{.n = 100000000, .hs = {1.3}, .on_case = [&] { ++calls; }};
  s.memory_label = [](double h) { return "mine " + std::to_string(h); };
  try {
    critical_tension_sweep(s);
    ADD_FAILURE() << "no refusal";
  } catch (const MemoryLimitError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("mine 1.3", 0), 0u) << e.what();
  }
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace sphstab
