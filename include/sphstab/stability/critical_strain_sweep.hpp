#pragma once
/// \file critical_strain_sweep.hpp
/// The critical pre-strain of an elastic lattice over kernels x h/dx x momentum forms, each case through the
/// critical-load front door (critical_load_problem.hpp: route choice, memory estimate, fallbacks), with the
/// infinite-lattice limit beside each 2D case (critical_strain_infinite_2d of the same kernel, h, material, form and
/// pre-strain: the inf over the Brillouin zone of the exact Fourier symbol's per-k critical strain). What
/// `sphstab tcrit --dim 2|3` prints, one row per case.
///
/// \code{.cpp}
/// sphstab::CriticalStrainSweep<2> s{.base = {.lattice = sphstab::LatticeType::Hexagonal, .n = 32},
///                                   .kernels = {sphstab::KernelType::CubicSpline}, .hs = {1.2, 1.3, 1.4},
///                                   .forms = {sphstab::MomentumForm::Conservative}};
/// for (const auto& c : sphstab::critical_strain_sweep(s))
///   std::cout << c.problem.h << " " << c.result.load << " " << c.infinite.e << "\n";
/// \endcode
#include <functional>
#include <string>
#include <vector>

#include "sphstab/stability/critical_load_problem.hpp"

namespace sphstab {

template <int Dim>
struct CriticalStrainCase {
  ElasticLatticeProblem<Dim> problem;  ///< the case (base with this kernel, h and form)
  CriticalLoadResult result;           ///< critical_load(problem, direction, options)
  SymbolCriticalStrain infinite;       ///< 2D: the infinite lattice; 3D: not computed (e NaN)
};

template <int Dim>
struct CriticalStrainSweep {
  ElasticLatticeProblem<Dim> base;  ///< lattice, n, periodic, material, pre-strain (kernel, h and form are swept)
  std::vector<KernelType> kernels = {KernelType::CubicSpline};
  std::vector<double> hs = {1.3};  ///< h / dx
  std::vector<MomentumForm> forms = {MomentumForm::Conservative};
  LoadDirection direction = LoadDirection::Tension;
  CriticalLoadRouteOptions options;  ///< as for critical_load(problem, ...); memory_label is set per case from below
  /// The text before " needs ~X GB ..." in a memory refusal, per route and case; empty: the front door's own.
  std::function<std::string(CriticalLoadRoute, const ElasticLatticeProblem<Dim>&)> memory_label;
  std::function<void()> on_case;  ///< called after each case (progress)
};

/// Cases in the order kernel, h, form (form fastest). Every case's route and memory are checked
/// (choose_critical_load_route) before the first is computed, so a refusal costs nothing. Throws
/// std::invalid_argument for an empty list, and as critical_load(problem, ...) does.
template <int Dim>
std::vector<CriticalStrainCase<Dim>> critical_strain_sweep(const CriticalStrainSweep<Dim>& sweep);

}  // namespace sphstab
