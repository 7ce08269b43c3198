// RateFormScheme<1>::rate on complex states (complex-step Jacobians): the definitions of rate_form/evaluate.hpp for one
// dimension and scalar per translation unit.
#include "rate_form/evaluate.hpp"

namespace sphstab {

template void RateFormScheme<1>::rate(const Eigen::VectorXcd&, Eigen::VectorXcd&) const;

}  // namespace sphstab
