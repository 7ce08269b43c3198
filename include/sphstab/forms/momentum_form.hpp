#pragma once
/// \file momentum_form.hpp
/// The SPH momentum-equation forms compared in Powell ch. 3 §4 (eq 3.28) and their names.
#include <string>
#include <vector>

namespace sphstab {

/// Momentum form f_i = sum_j (s_j + alpha s_i) G_ij (Powell 3.28; s = stress, G = kernel gradient):
///   Uncorrected alpha = 0, Plus alpha = 1, Minus alpha = -1 (zeroth-order consistent divergence);
///   Conservative: f = -M^{-1} dU/du from a strain energy U (Powell 3.22-3.27).
/// At the lattice equilibrium the Jacobian is A = K - n T L with n = 1, 2, 0, 4 (Powell 3.38, 3.40).
enum class MomentumForm { Uncorrected, Plus, Minus, Conservative };

/// Parses "uncorrected", "plus", "minus", "conservative"; throws std::invalid_argument otherwise.
MomentumForm parse_momentum_form(const std::string& name);
/// The canonical name accepted by parse_momentum_form.
std::string momentum_form_name(MomentumForm form);
/// All forms, in declaration order.
const std::vector<MomentumForm>& all_momentum_forms();
/// alpha of (3.28): 0, 1, -1; throws std::invalid_argument for Conservative (it has no alpha).
double momentum_form_alpha(MomentumForm form);
/// n of (3.40) (multiplier of the initial-stress stiffness at a complete lattice): 1, 2, 0, 4.
int initial_stress_multiplier(MomentumForm form);

}  // namespace sphstab
