#include "sphstab/core/status.hpp"

#include "sphstab/core/named_values.hpp"

namespace sphstab {

constexpr NamedValue<Status> kStatusNames[] = {{Status::Successful, "successful"},
                                               {Status::NotComputed, "not-computed"},
                                               {Status::NotConverging, "not-converging"},
                                               {Status::NumericalIssue, "numerical-issue"}};

std::string status_name(Status status) { return name_of(status, kStatusNames); }

}  // namespace sphstab
