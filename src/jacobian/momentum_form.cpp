#include "sphstab/jacobian/momentum_form.hpp"

#include <stdexcept>

namespace sphstab {

MomentumForm parse_momentum_form(const std::string& name) {
  for (MomentumForm f : all_momentum_forms())
    if (momentum_form_name(f) == name) return f;
  throw std::invalid_argument("unknown form '" + name + "' (valid: uncorrected, plus, minus, conservative)");
}

std::string momentum_form_name(MomentumForm form) {
  switch (form) {
    case MomentumForm::Uncorrected:
      return "uncorrected";
    case MomentumForm::Plus:
      return "plus";
    case MomentumForm::Minus:
      return "minus";
    case MomentumForm::Conservative:
      return "conservative";
  }
  throw std::invalid_argument("momentum_form_name: invalid MomentumForm value");
}

const std::vector<MomentumForm>& all_momentum_forms() {
  static const std::vector<MomentumForm> forms{MomentumForm::Uncorrected, MomentumForm::Plus, MomentumForm::Minus,
                                               MomentumForm::Conservative};
  return forms;
}

int tension_factor(MomentumForm form) {
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
  throw std::invalid_argument("tension_factor: invalid MomentumForm value");
}

}  // namespace sphstab
