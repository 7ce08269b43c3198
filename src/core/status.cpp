#include "sphstab/core/status.hpp"

namespace sphstab {

std::string status_name(Status status) {
  switch (status) {
    case Status::Successful:
      return "successful";
    case Status::NotComputed:
      return "not-computed";
    case Status::NotConverging:
      return "not-converging";
    case Status::NumericalIssue:
      return "numerical-issue";
  }
  return "?";
}

}  // namespace sphstab
