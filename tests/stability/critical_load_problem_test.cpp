// The critical-load front door (critical_load_problem.hpp): its route choice (auto, explicit, the memory fallback to
// the matrix-free route, the preconditioner fallback, the distributed extension point), and the routes' agreement on
// small lattices.
#include "sphstab/stability/critical_load_problem.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sphstab/core/memory_budget.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"

namespace sphstab {
namespace critical_load_problem_test {

CriticalLoadRouteOptions route(CriticalLoadRoute r) {
  CriticalLoadRouteOptions o;
  o.route = r;
  return o;
}

/// The assembled route's eigen route only (the CHOLMOD bisection at 1e-13 costs ~6x more at n = 48; the two are
/// checked against each other in critical_strain_test.cpp).
CriticalLoadRouteOptions assembled_eigen() {
  CriticalLoadRouteOptions o = route(CriticalLoadRoute::Assembled);
  o.assembled.method = CriticalLoadMethod::Eigen;
  return o;
}

/// Same value to `rtol`, or the same infinity.
void expect_agree(const CriticalLoadResult& a, const CriticalLoadResult& m, double rtol) {
  ASSERT_EQ(a.status, Status::Successful) << a.reason;
  ASSERT_EQ(m.status, Status::Successful) << m.reason;
  if (std::isfinite(a.load))
    EXPECT_NEAR(m.load / a.load, 1.0, rtol) << a.load << " " << m.load;
  else
    EXPECT_EQ(m.load, a.load);
}

/// Restores the process-wide memory limit at the end of a test.
struct MemoryLimitGuard {
  explicit MemoryLimitGuard(double bytes) { set_memory_limit_bytes(bytes); }
  ~MemoryLimitGuard() { set_memory_limit_bytes(0); }
};

TEST(CriticalLoadProblem, AutoChoosesByTheProblem) {
  // Small 2D block with fixed layers: assembled; periodic: the exact symbols; 3D: matrix-free.
  const ElasticLatticeProblem<2> block{.n = 8};
  EXPECT_EQ(choose_critical_load_route(block).route, CriticalLoadRoute::Assembled);
  EXPECT_EQ(choose_critical_load_route(block).reason.rfind("auto: assembled", 0), 0u);
  EXPECT_EQ(choose_critical_load_route(ElasticLatticeProblem<2>{.n = 9, .periodic = true}).route,
            CriticalLoadRoute::Symbol);
  EXPECT_EQ(choose_critical_load_route(ElasticLatticeProblem<3>{.n = 6}).route, CriticalLoadRoute::MatrixFree);
  const CriticalLoadResult r = critical_load(block, LoadDirection::Tension);
  EXPECT_EQ(r.route, CriticalLoadRoute::Assembled);
  EXPECT_FALSE(r.fallback);
  ASSERT_TRUE(r.assembled.has_value());
  EXPECT_FALSE(r.matrix_free || r.symbol || r.distributed);
  EXPECT_EQ(r.load, r.assembled->load);
  EXPECT_EQ(r.status, Status::Successful) << r.reason;
}

TEST(CriticalLoadProblem, AnExplicitRouteIsHonoured) {
  const ElasticLatticeProblem<2> block{.n = 12};
  const CriticalLoadResult m = critical_load(block, LoadDirection::Tension, route(CriticalLoadRoute::MatrixFree));
  EXPECT_EQ(m.route, CriticalLoadRoute::MatrixFree);
  EXPECT_EQ(m.route_reason, "asked");
  ASSERT_TRUE(m.matrix_free.has_value());
  EXPECT_EQ(m.method, "lobpcg");
  EXPECT_EQ(m.backend, "matrix-free");
  // A route that cannot take the problem is bad input, not a silent switch.
  EXPECT_THROW(critical_load(ElasticLatticeProblem<2>{.lattice = LatticeType::Hexagonal, .n = 8},
                             LoadDirection::Tension, route(CriticalLoadRoute::MatrixFree)),
               std::invalid_argument);
  EXPECT_THROW(critical_load(ElasticLatticeProblem<2>{.n = 9, .periodic = true}, LoadDirection::Tension,
                             route(CriticalLoadRoute::Assembled)),
               std::invalid_argument);
  EXPECT_THROW(critical_load(block, LoadDirection::Tension, route(CriticalLoadRoute::Symbol)), std::invalid_argument);
  EXPECT_THROW(critical_load_memory_bytes(block, CriticalLoadRoute::Auto), std::invalid_argument);
}

TEST(CriticalLoadProblem, TooLargeForTheAssembledRouteGoesMatrixFreeAndSaysSo) {
  // n = 48: the assembled route's estimate (~29 MB) does not fit a limit 14 MB above the resident set, the matrix-free
  // route's (~6 MB, below require_memory's 16 MB threshold for reading the resident set) does.
  const ElasticLatticeProblem<2> block{.n = 48};
  const double assembled = critical_load_memory_bytes(block, CriticalLoadRoute::Assembled);
  const double matrix_free = critical_load_memory_bytes(block, CriticalLoadRoute::MatrixFree);
  ASSERT_GT(assembled, 20e6);
  ASSERT_LT(matrix_free, 10e6);
  CriticalLoadResult r;
  {
    MemoryLimitGuard limit(resident_memory_bytes() + 14e6);
    EXPECT_EQ(choose_critical_load_route(block).route, CriticalLoadRoute::MatrixFree);
    r = critical_load(block, LoadDirection::Tension);
    // Asked explicitly, the assembled route is refused with the memory error instead.
    EXPECT_THROW(critical_load(block, LoadDirection::Tension, route(CriticalLoadRoute::Assembled)), MemoryLimitError);
    // A problem the matrix-free route cannot take (hexagonal) keeps the assembled route, which refuses.
    EXPECT_THROW(choose_critical_load_route(ElasticLatticeProblem<2>{.lattice = LatticeType::Hexagonal, .n = 48}),
                 MemoryLimitError);
  }
  EXPECT_EQ(r.route, CriticalLoadRoute::MatrixFree);
  EXPECT_TRUE(r.fallback);
  EXPECT_EQ(r.route_reason.rfind("fallback: the assembled route's ~", 0), 0u) << r.route_reason;
  EXPECT_EQ(r.reason.rfind("fallback:", 0), 0u) << r.reason;  // said in the reason too
  EXPECT_EQ(r.memory_estimate, matrix_free);
  EXPECT_EQ(r.status, Status::Successful) << r.reason;
  // Same value as the assembled route without the limit (tolerance as in AssembledAndMatrixFreeAgree).
  const CriticalLoadResult a = critical_load(block, LoadDirection::Tension, assembled_eigen());
  EXPECT_NEAR(r.load / a.load, 1.0, 1e-9);
}

TEST(CriticalLoadProblem, MemoryRefusalNamesTheProblemOrTheCallersLabel) {
  MemoryLimitGuard limit(1e6);
  const ElasticLatticeProblem<2> block{.n = 400};
  try {
    choose_critical_load_route(block, route(CriticalLoadRoute::Assembled));
    ADD_FAILURE() << "no refusal";
  } catch (const MemoryLimitError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("critical_load: 2D square n = 400 h/dx = 1.3 assembled route needs ~", 0), 0u)
        << e.what();
  }
  CriticalLoadRouteOptions o = route(CriticalLoadRoute::MatrixFree);
  o.memory_label = [](CriticalLoadRoute r) { return "mine " + critical_load_route_name(r); };
  try {
    choose_critical_load_route(block, o);
    ADD_FAILURE() << "no refusal";
  } catch (const MemoryLimitError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("mine matrix-free needs ~", 0), 0u) << e.what();
  }
}

TEST(CriticalLoadProblem, AssembledAndMatrixFreeAgree) {
  // Square 16 x 16 (2D) and cubic 8 x 8 x 8 (3D, assembled by products): the block LOBPCG stops at a residual of
  // 1e-8, whose eigenvalue error is quadratic in it (~1e-13 measured, matrix_free_critical_load.hpp); 1e-9 leaves
  // room for the Spectra and CHOLMOD round-off of the assembled route.
  // (Both directions are finite at h = 1.3: e_crit = 1.5e-3 in tension, -2.1e-4 in compression.)
  for (LoadDirection d : {LoadDirection::Tension, LoadDirection::Compression}) {
    const ElasticLatticeProblem<2> p2{.n = 16, .h = 1.3};
    const CriticalLoadResult a = critical_load(p2, d, assembled_eigen());
    const CriticalLoadResult m = critical_load(p2, d, route(CriticalLoadRoute::MatrixFree));
    ASSERT_TRUE(std::isfinite(a.load)) << load_direction_name(d);
    expect_agree(a, m, 1e-9);
    EXPECT_EQ(std::signbit(m.load), d == LoadDirection::Compression);
  }
  const ElasticLatticeProblem<3> p3{.n = 8};
  const CriticalLoadResult a = critical_load(p3, LoadDirection::Tension, assembled_eigen());
  const CriticalLoadResult m = critical_load(p3, LoadDirection::Tension);  // auto: matrix-free
  EXPECT_EQ(m.route, CriticalLoadRoute::MatrixFree);
  ASSERT_TRUE(std::isfinite(a.load));
  expect_agree(a, m, 1e-9);
}

TEST(CriticalLoadProblem, NoShiftForThePreconditionerIsAReportedFallback) {
  // h = 1.2 in compression: the square lattice has no interior instability, the sine preconditioner no shift; the
  // block LOBPCG runs without it (n = 12 is below the probe size: the stencil comes from a larger lattice).
  const ElasticLatticeProblem<2> p{.n = 12, .h = 1.2};
  const CriticalLoadResult m = critical_load(p, LoadDirection::Compression, route(CriticalLoadRoute::MatrixFree));
  ASSERT_EQ(m.status, Status::Successful) << m.reason;
  EXPECT_TRUE(m.fallback);
  EXPECT_NE(m.route_reason.find("fallback: no preconditioner"), std::string::npos) << m.route_reason;
  EXPECT_NE(m.reason.find("preconditioner none (symbol ratio"), std::string::npos) << m.reason;
  // No instability in this direction on either route: the same -inf.
  const CriticalLoadResult a = critical_load(p, LoadDirection::Compression, assembled_eigen());
  expect_agree(a, m, 1e-9);
  EXPECT_EQ(m.load, -std::numeric_limits<double>::infinity());
}

TEST(CriticalLoadProblem, PeriodicTakesTheExactSymbols) {
  const ElasticLatticeProblem<2> p{.n = 9, .periodic = true};
  const CriticalLoadResult r = critical_load(p, LoadDirection::Tension);
  ASSERT_TRUE(r.symbol.has_value());
  const ElasticSymbol2D s(LatticeType::Square, Kernel<2>(KernelType::CubicSpline), 1.3, 1.0, p.material, p.form,
                          p.prestrain);
  EXPECT_EQ(r.load, critical_strain_periodic_symbol_2d(s, 9, LoadDirection::Tension).e);
  EXPECT_EQ(r.criterion, Criterion::Spectrum);
  EXPECT_EQ(r.method, "symbol");
}

TEST(CriticalLoadProblem, TheDistributedRouteIsAnInjectedSolver) {
  const ElasticLatticeProblem<2> p{.n = 10};
  // Without a solver (the core library has none): bad input naming the PETSc backend.
  try {
    critical_load(p, LoadDirection::Tension, route(CriticalLoadRoute::Distributed));
    ADD_FAILURE() << "no refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sphstab_petsc"), std::string::npos) << e.what();
  }
  // With one (here the assembled engine standing in for PETSc): its result is the front door's, with its diagnostics.
  CriticalLoadRouteOptions o = route(CriticalLoadRoute::Distributed);
  int calls = 0;
  o.distributed = [&calls](const Linearisation& lin, LoadDirection d) {
    ++calls;
    CriticalLoadOptions c = CriticalLoadOptions::strain_2d();
    c.method = CriticalLoadMethod::Eigen;
    const CriticalLoad r = critical_load(lin, d, c);
    DistributedCriticalLoad out;
    out.load = r.load;
    out.ranks = 1;
    out.solver = "stand-in";
    out.status = r.status;
    return out;
  };
  const CriticalLoadResult r = critical_load(p, LoadDirection::Tension, o);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(r.route, CriticalLoadRoute::Distributed);
  ASSERT_TRUE(r.distributed.has_value());
  EXPECT_EQ(r.method, "stand-in");
  const CriticalLoadResult a = critical_load(p, LoadDirection::Tension, route(CriticalLoadRoute::Assembled));
  EXPECT_NEAR(r.load / a.load, 1.0, 1e-12);  // the same pencil, eigen route only (a.load: eigen route too)
}

TEST(CriticalLoadProblem, RouteNamesRoundTrip) {
  for (CriticalLoadRoute r : {CriticalLoadRoute::Auto, CriticalLoadRoute::Assembled, CriticalLoadRoute::MatrixFree,
                              CriticalLoadRoute::Symbol, CriticalLoadRoute::Distributed})
    EXPECT_EQ(parse_critical_load_route(critical_load_route_name(r)), r);
  EXPECT_EQ(parse_critical_load_route("petsc"), CriticalLoadRoute::Distributed);
  EXPECT_THROW(parse_critical_load_route("fast"), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
