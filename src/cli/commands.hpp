#pragma once
// Subcommands of the sphstab program: each registers itself on the CLI11 app.
#include <CLI/CLI.hpp>

namespace sphstab::cli {

void register_kernels_command(CLI::App& app);
void register_operators_command(CLI::App& app);
void register_tcrit_command(CLI::App& app);
void register_spectrum_command(CLI::App& app);
void register_run_command(CLI::App& app);
void register_scene_command(CLI::App& app);
void register_jacobian_command(CLI::App& app);
void register_stability_command(CLI::App& app);

inline void register_commands(CLI::App& app) {
  register_kernels_command(app);
  register_operators_command(app);
  register_tcrit_command(app);
  register_spectrum_command(app);
  register_run_command(app);
  register_scene_command(app);
  register_jacobian_command(app);
  register_stability_command(app);
}

}  // namespace sphstab::cli
