#pragma once
/// \file status.hpp
/// Outcome of a numerical computation (Spectra's CompInfo / Eigen's ComputationInfo manners).
#include <string>

namespace sphstab {

/// Reported by solvers through `info()` or a result struct; never thrown.
enum class Status {
  Successful,      ///< computed and trustworthy within the stated tolerance
  NotComputed,     ///< no computation requested or performed yet
  NotConverging,   ///< an iteration stopped at its limit
  NumericalIssue,  ///< factorisation failure, singular or indefinite input where definiteness was needed
};

/// "successful", "not-computed", "not-converging", "numerical-issue".
std::string status_name(Status status);

}  // namespace sphstab
