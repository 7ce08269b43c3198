// RateFormScheme<2>: the 2D instantiation of the definitions in rate_form_impl.hpp (rate_form.cpp holds Dim = 1).
#include "rate_form_impl.hpp"

namespace sphstab {

template class RateFormScheme<2>;

}  // namespace sphstab
