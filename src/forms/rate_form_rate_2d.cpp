// RateFormScheme<2>::rate on real states: the definitions of rate_form/evaluate.hpp for one
// dimension and scalar per translation unit.
#include "rate_form/evaluate.hpp"

namespace sphstab {

template void RateFormScheme<2>::rate(const Eigen::VectorXd&, Eigen::VectorXd&) const;

}  // namespace sphstab
