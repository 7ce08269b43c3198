// `sphstab operators`: placeholder registration, filled in by the operators work.
#include "commands.hpp"

namespace sphstab::cli {

void register_operators_command(CLI::App& app) { (void)app; }

}  // namespace sphstab::cli
