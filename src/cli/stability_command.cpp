// `sphstab stability`: the linear stability of a particle state read from a file another SPH code wrote (CSV or VTK
// PolyData, io/particle_state_file.hpp): the rate-form scheme built at that state (growth/state_stability.hpp), its
// semi-discrete growth and mode, the integrator's map growth at the run's dt, the detection floor and the verdict
// S/U/I/B, and at rest the step limits; one CSV row, and the modes as a .vtp for ParaView (--modes-vtk).
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "parse.hpp"
#include "rate_form_args.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/status.hpp"
#include "sphstab/growth/state_stability.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/particle_state_file.hpp"

namespace sphstab::cli {

namespace {

struct StabilityArgs {
  RateFormArgs scheme;
  VerdictArgs verdict;
  std::string particles, mass, modes_vtk;
};

std::string num(double v) { return format_csv_cell(CsvCell(v)); }  // shortest round trip

template <int Dim>
void run(const StabilityArgs& a, const RateFormSetup& setup, const VerdictSetup& verdict) {
  ParticleStateFileOptions fo{.h = setup.h_over_dx[0] * setup.dx, .spacing = setup.dx};
  if (!a.mass.empty()) fo.mass = parse_double(a.mass, "stability: --mass");
  const ParticleState<Dim> state = read_particle_state<Dim>(a.particles, fo);
  StateStabilityOptions o{.kernel = setup.kernels[0],
                          .material = setup.material,
                          .scheme = setup.options,
                          .run = verdict.run,
                          .dt = verdict.run.dt,
                          .floor = verdict.floor};
  o.scheme.pair_loop = PairLoop::Rows;  // the Jacobian's loop; the choice does not change the state's rates
  const StateStability r = state_stability(state, o);
  const StabilityVerdict& v = r.verdict;
  if (!a.modes_vtk.empty()) write_state_modes_vtp(a.modes_vtk, state, r);
  std::string out =
      "dim,particles,free,states,at_rest,acceleration_max,growth_rate,lambda_imag,mode_particle,mode_particle_share,"
      "mode_kx_over_pi,mode_ky_over_pi,integrator,dt,floor,map_growth,map_spectral_radius,integrator_excess,"
      "map_mode_particle,verdict,status,reason,leapfrog_limit,pc_limit,courant,time_step_status\n";
  out += csv_line({std::to_string(Dim), std::to_string(r.particles), std::to_string(r.free), std::to_string(r.states),
                   r.at_rest ? "1" : "0", num(r.acceleration_max), num(v.semi_discrete_growth),
                   num(std::abs(v.lambda.imag())), std::to_string(v.semi_discrete_mode.particle),
                   num(v.semi_discrete_mode.particle_share), num(v.semi_discrete_mode.kx_over_pi),
                   num(v.semi_discrete_mode.ky_over_pi), v.integrator, num(v.dt), num(v.floor), num(v.map_growth),
                   num(v.map_spectral_radius), num(v.integrator_excess), std::to_string(v.map_mode.particle),
                   v.status == Status::Successful ? v.letter() : "", status_name(v.status), v.reason,
                   num(r.time_step.leapfrog), num(r.time_step.predictor_corrector), num(r.time_step.courant),
                   status_name(r.time_step.status)});
  std::fputs(out.c_str(), stdout);
}

void run_stability(StabilityArgs& a) {
  if (a.particles.empty()) throw std::invalid_argument("stability: --particles FILE is required (.csv or .vtp)");
  const int dim = particle_state_dimension(a.particles);
  a.scheme.dim = std::to_string(dim);
  const RateFormSetup setup = parse_rate_form_args(a.scheme, "stability", false, 1, 1L << 30, 1L << 15);
  const VerdictSetup verdict = parse_verdict_args(a.verdict, "stability");
  if (!verdict.on) throw std::invalid_argument("stability: give --integrator, --dt and --t-end (the run the verdict is for)");
  if (dim == 1)
    run<1>(a, setup, verdict);
  else
    run<2>(a, setup, verdict);
}

}  // namespace

void register_stability_command(CLI::App& app) {
  auto a = std::make_shared<StabilityArgs>();
  auto* cmd = app.add_subcommand(
      "stability",
      "Linear stability of a particle state from a file (CSV columns x[,y],vx[,vy],density,mass,s_xx[,s_yy,s_xy],fixed; "
      "or a .vtp): the rate-form scheme built at that state, its growth rate and mode, the integrator's map growth, "
      "the verdict S/U/I/B and, at rest, the step limits; one CSV row");
  add_rate_form_options(*cmd, a->scheme, false);
  // The state comes from the file: the lattice options do not apply (the dimension is the file's).
  for (const char* option : {"--dim", "--lattice", "--n", "--periodic", "--xi", "--pair-loop"})
    cmd->remove_option(cmd->get_option(option));
  cmd->get_option("--dx")->description("the particle spacing dp > 0 (h = --h x --dx; the artificial stress's W(dp) "
                                       "and the 2D modes' wavevectors use it) (default " + a->scheme.dx + ")");
  add_verdict_options(*cmd, a->verdict);
  cmd->add_option("--particles", a->particles, "the state: a .csv or .vtp file (see the command's description)");
  cmd->add_option("--mass", a->mass, "the mass of every particle, for a file without masses (e.g. a run's snapshot)");
  cmd->add_option("--modes-vtk", a->modes_vtk,
                  "write the state with its semi-discrete and map modes (velocity shapes) to this .vtp");
  cmd->callback([a] { run_stability(*a); });
}

}  // namespace sphstab::cli
