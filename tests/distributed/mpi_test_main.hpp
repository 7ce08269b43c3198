#pragma once
// The main() of the MPI test programs: every rank runs every test, rank 0 alone prints, and a failure on any rank
// fails the run (the exit code of rank 0 is what ctest sees).
#include <gtest/gtest.h>

#include "sphstab/distributed/petsc_critical_load.hpp"

namespace sphstab::test {

/// Starts PETSc/SLEPc (and MPI) for the program's lifetime, points `session` at it and runs the tests.
inline int run_tests_on_all_ranks(int argc, char** argv, PetscSession*& session) {
  PetscSession s(&argc, &argv);
  session = &s;
  testing::InitGoogleTest(&argc, argv);
  if (s.rank() != 0) {  // one report, from rank 0; every rank still runs and fails on its own
    auto& listeners = testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int failed = RUN_ALL_TESTS();
  const bool any_failed = max_over_ranks(failed ? 1.0 : 0.0) > 0;
  session = nullptr;
  return any_failed ? 1 : 0;
}

}  // namespace sphstab::test
