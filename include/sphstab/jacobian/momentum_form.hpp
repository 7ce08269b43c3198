#pragma once
/// \file momentum_form.hpp
/// The 1D momentum-equation forms of Powell §3.4 (DESIGN.md): f_i = sum_j (s_j + alpha s_i) G_ij with
/// s_i = <u_x>_i + T, alpha = 0 "uncorrected", 1 "plus", -1 "minus"; "conservative" is f = -dU/du with
/// U = 1/2 sum_i s_i^2 (Powell (3.22)-(3.27)).
#include <string>
#include <vector>

namespace sphstab {

enum class MomentumForm { Uncorrected, Plus, Minus, Conservative };

/// Parses "uncorrected", "plus", "minus", "conservative"; throws std::invalid_argument naming the valid choices.
MomentumForm parse_momentum_form(const std::string& name);
/// The canonical name accepted by parse_momentum_form.
std::string momentum_form_name(MomentumForm form);
/// All forms, in declaration order.
const std::vector<MomentumForm>& all_momentum_forms();

/// The factor n in A(T) = K - n T L on a regular lattice (Powell (3.40)): 1 uncorrected, 2 plus, 4 conservative,
/// 0 minus (the minus form's A does not depend on T, Powell (3.38)).
int tension_factor(MomentumForm form);

}  // namespace sphstab
