#pragma once
// The six linear SPH formulations of the 1D elastic bar that the speed-vs-error study compares
// (include/sphstab/forms/elastic_bar.hpp): total Lagrangian with the plain, minus [Powell2012, (1.15), (1.34)] and
// first-order corrected (1D analogue of [Powell2012, (1.19)]) gradients, plain with XSPH [Powell2012, (2.71)], and
// updated Lagrangian plain and minus/plus; and the leap-frog system of a bar with a formulation's XSPH hook.
#include <string>
#include <vector>

#include "sphstab/forms/elastic_bar.hpp"

namespace speed_error {

using namespace sphstab;

struct Formulation {
  std::string name;
  LagrangianFrame frame;
  StrainGradient gradient;
  StressDivergence divergence;
  double xsph_eps = 0;      ///< > 0: XSPH velocity smoothing (Powell 2.71, Replace mode)
  double amplitude = 0.01;  ///< v0 (Powell: 0.01 cm/µs); errors are normalised by v0
};

inline const std::vector<Formulation>& formulations() {
  static const std::vector<Formulation> f = {
      {"tl-plain", LagrangianFrame::Total, StrainGradient::Plain, StressDivergence::Plain},
      {"tl-minus", LagrangianFrame::Total, StrainGradient::Minus, StressDivergence::Minus},
      {"tl-corrected", LagrangianFrame::Total, StrainGradient::Corrected, StressDivergence::Adjoint},
      {"tl-plain-xsph", LagrangianFrame::Total, StrainGradient::Plain, StressDivergence::Plain, 0.1},
      {"ul-plain", LagrangianFrame::Updated, StrainGradient::Plain, StressDivergence::Plain},
      {"ul-minus-plus", LagrangianFrame::Updated, StrainGradient::Minus, StressDivergence::Plus}};
  return f;
}

/// The system of `bar` for run_leapfrog, with XSPH velocity smoothing of strength `xsph_eps` used in `mode` when
/// xsph_eps > 0 (captures &bar: keep bar alive).
inline SecondOrderSystem bar_system(const ElasticBar1D& bar, double xsph_eps, VelocityHookMode mode) {
  auto sys = bar.system();
  if (xsph_eps > 0) {
    sys.velocity_hook = bar.xsph_hook(xsph_eps);
    sys.hook_mode = mode;
  }
  return sys;
}

}  // namespace speed_error
