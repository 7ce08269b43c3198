#include "sphstab/forms/momentum_form.hpp"

#include <stdexcept>

#include "sphstab/core/named_values.hpp"

namespace sphstab {

constexpr NamedValue<MomentumForm> kMomentumFormNames[] = {{MomentumForm::Uncorrected, "uncorrected"},
                                                           {MomentumForm::Plus, "plus"},
                                                           {MomentumForm::Minus, "minus"},
                                                           {MomentumForm::Conservative, "conservative"}};

MomentumForm parse_momentum_form(const std::string& name) {
  return parse_named(name, kMomentumFormNames, "momentum form");
}
std::string momentum_form_name(MomentumForm form) { return name_of(form, kMomentumFormNames); }
const std::vector<MomentumForm>& all_momentum_forms() {
  static const std::vector<MomentumForm> forms = values_of(kMomentumFormNames);
  return forms;
}

double momentum_form_alpha(MomentumForm form) {
  switch (form) {
    case MomentumForm::Uncorrected:
      return 0.0;
    case MomentumForm::Plus:
      return 1.0;
    case MomentumForm::Minus:
      return -1.0;
    case MomentumForm::Conservative:
      break;
  }
  throw std::invalid_argument("momentum_form_alpha: the conservative form has no alpha");
}

int initial_stress_multiplier(MomentumForm form) {
  switch (form) {
    case MomentumForm::Uncorrected:
      return 1;
    case MomentumForm::Plus:
      return 2;
    case MomentumForm::Minus:
      return 0;
    case MomentumForm::Conservative:
      return 4;
  }
  return 0;
}

}  // namespace sphstab
