// The critical-strain sweep (critical_strain_sweep.hpp): case order, each case equal to the front door called on its
// own, the infinite-lattice column, and a refusal before any case is computed.
#include "sphstab/stability/critical_strain_sweep.hpp"

#include <gtest/gtest.h>

#include "sphstab/core/memory_budget.hpp"

namespace sphstab {
namespace critical_strain_sweep_test {

TEST(CriticalStrainSweep, CasesInOrderAndEqualToTheFrontDoor) {
  int calls = 0;
  const CriticalStrainSweep<2> s{.base = {.lattice = LatticeType::Hexagonal, .n = 8},
                                 .kernels = {KernelType::CubicSpline, KernelType::WendlandC4},
                                 .hs = {1.2, 1.4},
                                 .forms = {MomentumForm::Conservative, MomentumForm::Plus},
                                 .direction = LoadDirection::Compression,
                                 .on_case = [&] { ++calls; }};
  const auto cases = critical_strain_sweep(s);
  ASSERT_EQ(cases.size(), 8u);
  EXPECT_EQ(calls, 8);
  // Row 6: wendland-c4, h = 1.4, conservative (form fastest, then h, then kernel).
  const auto& c = cases[6];
  EXPECT_EQ(c.problem.kernel, KernelType::WendlandC4);
  EXPECT_EQ(c.problem.h, 1.4);
  EXPECT_EQ(c.problem.form, MomentumForm::Conservative);
  EXPECT_EQ(c.problem.lattice, LatticeType::Hexagonal);
  const CriticalLoadResult r = critical_load(c.problem, LoadDirection::Compression);
  EXPECT_EQ(c.result.load, r.load);  // the same computation, bit for bit
  EXPECT_EQ(c.result.route, CriticalLoadRoute::Assembled);
  const SymbolCriticalStrain inf = critical_strain_infinite_2d(
      ElasticSymbol2D(LatticeType::Hexagonal, Kernel<2>(KernelType::WendlandC4), 1.4, 1.0, c.problem.material,
                      MomentumForm::Conservative, PreStrainKind::Isotropic),
      LoadDirection::Compression);
  EXPECT_EQ(c.infinite.e, inf.e);
}

TEST(CriticalStrainSweep, RefusesBeforeComputingAnyCase) {
  int calls = 0;
  set_memory_limit_bytes(1e6);
  CriticalStrainSweep<3> s{.base = {.n = 40}, .hs = {1.3, 1.5}, .on_case = [&] { ++calls; }};
  s.memory_label = [](CriticalLoadRoute r, const ElasticLatticeProblem<3>& p) {
    return critical_load_route_name(r) + " h " + std::to_string(p.h);
  };
  try {
    critical_strain_sweep(s);
    ADD_FAILURE() << "no refusal";
  } catch (const MemoryLimitError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("matrix-free h 1.3", 0), 0u) << e.what();
  }
  set_memory_limit_bytes(0);
  EXPECT_EQ(calls, 0);
  EXPECT_THROW(critical_strain_sweep(CriticalStrainSweep<2>{.hs = {}}), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
