#include "sphstab/stability/critical_strain_sweep.hpp"

#include <stdexcept>

namespace sphstab {

template <int Dim>
std::vector<CriticalStrainCase<Dim>> critical_strain_sweep(const CriticalStrainSweep<Dim>& sweep) {
  if (sweep.kernels.empty() || sweep.hs.empty() || sweep.forms.empty())
    throw std::invalid_argument("critical_strain_sweep: kernels, hs and forms must not be empty");
  std::vector<CriticalStrainCase<Dim>> cases;
  for (KernelType kernel : sweep.kernels)
    for (double h : sweep.hs)
      for (MomentumForm form : sweep.forms) {
        CriticalStrainCase<Dim> c;
        c.problem = sweep.base;
        c.problem.kernel = kernel;
        c.problem.h = h;
        c.problem.form = form;
        c.infinite.e = CriticalLoadResult::nan;
        cases.push_back(c);
      }
  auto options_for = [&](const ElasticLatticeProblem<Dim>& p) {
    CriticalLoadRouteOptions o = sweep.options;
    if (sweep.memory_label)
      o.memory_label = [&sweep, p](CriticalLoadRoute route) { return sweep.memory_label(route, p); };
    return o;
  };
  for (const CriticalStrainCase<Dim>& c : cases) choose_critical_load_route(c.problem, options_for(c.problem));
  for (CriticalStrainCase<Dim>& c : cases) {
    const ElasticLatticeProblem<Dim>& p = c.problem;
    if constexpr (Dim == 2)
      c.infinite = critical_strain_infinite_2d(
          ElasticSymbol2D(p.lattice, Kernel<2>(p.kernel), p.h, 1.0, p.material, p.form, p.prestrain), sweep.direction);
    c.result = critical_load(p, sweep.direction, options_for(p));
    if (sweep.on_case) sweep.on_case();
  }
  return cases;
}

template std::vector<CriticalStrainCase<2>> critical_strain_sweep<2>(const CriticalStrainSweep<2>&);
template std::vector<CriticalStrainCase<3>> critical_strain_sweep<3>(const CriticalStrainSweep<3>&);

}  // namespace sphstab
