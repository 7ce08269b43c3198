#pragma once
// The 2D formulations of the Swegle study [Powell2012, ch. 4 §2.2-2.3, Fig. 4.2], each a force function on the
// pre-strained block (problems/swegle.hpp): basic SPH and + XSPH [Powell2012, (2.71)], NCSPH [Powell2012, (1.19)],
// TL-SPH, the corrected momentum equation C_ij [Powell2012, (4.9), (4.10), Fig. 4.3, (4.18)], the S-SPH variants
// [Powell2012, (4.13)-(4.18), algorithm 4.2], SPH + the GMS artificial stress [GMS2001, (6.1)-(6.9)] and the
// conservative form (the 2D version of [Powell2012, (3.27)]). Described in summary.md.in and README.md.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/artificial_stress_term.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/stabilised_sph.hpp"
#include "sphstab/forms/total_lagrangian.hpp"
#include "sphstab/problems/swegle.hpp"

namespace swegle_study {

using namespace sphstab;

/// One 2D formulation of the study (described in summary.md.in and README.md).
struct Formulation {
  std::string name;   ///< key in the CSV files
  bool xsph = false;  ///< XSPH velocity smoothing ([Powell2012, (2.71)], eps = 0.1, Replace mode)
  std::function<std::shared_ptr<ForceFunction>(const SwegleScene&)> make;
  /// The force switches on the sign of the stress (S-SPH, GMS): at xi = 1 (zero stress) the lattice lies on the
  /// switching surface and the linearisation is not unique.
  bool switching = false;
};

inline std::vector<Formulation> formulations() {
  using Force = std::shared_ptr<ForceFunction>;
  auto plus = [](const SwegleScene& s) -> Force {
    return std::make_shared<ElasticForm2D>(s.discretisation, s.material, MomentumForm::Plus, s.prestrain);
  };
  auto ssph = [](StabilisedSphOptions o) {
    return [o](const SwegleScene& s) -> Force {
      return make_stabilised_sph(s.discretisation, s.material, s.prestrain, o);
    };
  };
  std::vector<Formulation> f;
  f.push_back({"sph", false, plus});
  f.push_back({"sph-xsph", true, plus});
  f.push_back({"ncsph", false, [](const SwegleScene& s) -> Force {
                 auto force =
                     std::make_shared<ElasticForm2D>(s.discretisation, s.material, MomentumForm::Plus, s.prestrain,
                                                     make_gradient_provider<2>(Correction::Ncsph));
                 force->set_corrected_strain(true);
                 return force;
               }});
  f.push_back({"tl", false, [](const SwegleScene& s) -> Force {
                 return std::make_shared<TotalLagrangianForm2D>(s.discretisation, s.material, s.prestrain);
               }});
  f.push_back({"cij", false, [](const SwegleScene& s) -> Force {
                 return std::make_shared<ElasticForm2D>(
                     s.discretisation, s.material, MomentumForm::Uncorrected, s.prestrain,
                     make_gradient_provider<2>(Correction::LocalPolish, {.counting = NeighbourCounting::BoundaryLevel,
                                                                         .first_step_shepard = true}));
               }});
  f.push_back({"ssph", true, ssph({}), true});
  f.push_back({"ssph-pp", true, ssph({.symmetrise = false}), true});
  f.push_back({"ssph-pp-noxsph", false, ssph({.symmetrise = false}), true});
  f.push_back({"ssph-printed", true, ssph({.rule = SwitchRule::AsPrinted}), true});
  f.push_back({"sph-gms", false,
               [](const SwegleScene& s) -> Force {
                 return make_artificial_stress_sph(s.discretisation, s.material, s.prestrain);
               },
               true});
  f.push_back({"conservative", false, [](const SwegleScene& s) -> Force {
                 return std::make_shared<ElasticForm2D>(s.discretisation, s.material, MomentumForm::Conservative,
                                                        s.prestrain);
               }});
  return f;
}

}  // namespace swegle_study
