// `sphstab scene plate|rings|slab|symmetric-impact|bar-impact|clamped-beam`.
// plate, rings, slab: the test cases of Gray, Monaghan & Swift [GMS2001, §7] run with their scheme
// (forms/rate_form.hpp: continuity -rho tr L, XSPH 1/2, viscosity alpha = 1, beta = 2 with the compression switch,
// artificial stress eps, n = 4; GMS predictor-corrector with a Verlet neighbour list, one rate evaluation per step for
// the plate and the rings (results/gms-pc1) unless --integrator says otherwise), GMS units (rho0 = K = 1), its
// time series printed as CSV: step, t, kinetic energy, bond-graph fragments (analysis/fragments.hpp, bonds < 1.5 dp)
// and the scene's measure (plate: tip deflection; rings: largest fragment count of one ring; slab: narrowest width
// between the driven zones, analysis/neck.hpp). A run that fractures is a result; one that stops (non-finite state,
// density <= 0) keeps its rows and VTK frames and ends with a row naming the status, step, time and particle.
// symmetric-impact, bar-impact, clamped-beam: Powell's impact problems [Powell2012, ch. 4 §4]
// (problems/powell_impact.hpp) in g-cm-us, one rate-form formulation (--formulation sph | ncsph | ssph: MCM's,
// powell_formulation_options) run as Powell ran them: the staggered leap-frog (algorithm 1.1) with the velocity
// smoothing (2.71), eps 0.1, at dt = TSSFAC h / c_P (--cfl, default the deck's 0.8); the measure is the problem's
// (pressure at A; the bar's length; the beam's midline deflection). TL-SPH runs on u'' = a(u), not this scheme: the
// impact studies run it. The studies gms-plate, gms-rings, gms-slab and powell-* hold the validated runs; this command
// is for one-off runs.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "parse.hpp"
#include "rate_form_args.hpp"
#include "sphstab/analysis/fragments.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/integrate/scene_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/rate_form_vtk.hpp"
#include "sphstab/io/run_output.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/problems/gms_scenes.hpp"
#include "sphstab/problems/powell_impact.hpp"

namespace sphstab::cli {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Memory of a GMS scene per particle: the set, ~30 neighbour pairs and the Verlet skin's, the scheme's per-pair
// workspace and the state vectors. Measured: 1.7 kB per particle (peak RSS 8.46 GB at rings --dp 0.003, 4.9e6
// particles, one thread); 2 kB leaves a margin.
constexpr double kSceneBytesPerParticle = 2000;

std::string num(double v) { return format_csv_cell(CsvCell(v)); }  // shortest round trip

struct SceneArgs {
  std::string scene, dp, across = "10", thickness = "2", length = "20", mu, nu, eps = "0.3", tip_speed = "0.01", speed,
                         yield, t_end, skin = "0.5", cfl, record_every = "100", out, pair_loop = "auto", formulation,
                         integrator = "auto";
};

bool is_impact(const std::string& scene) {
  return scene == "symmetric-impact" || scene == "bar-impact" || scene == "clamped-beam";
}

/// Powell's impact problem with the command's parameters (its defaults: problem_defaults, dx 0.02).
Scene<2> make_impact_scene(const SceneArgs& a) {
  PowellImpactOptions o;
  o.problem = a.scene == "symmetric-impact" ? ImpactProblem::Symmetric
              : a.scene == "bar-impact"     ? ImpactProblem::Bar
                                            : ImpactProblem::Beam;
  o.scheme = powell_formulation_options(a.formulation.empty() ? "ssph" : a.formulation);
  if (!a.dp.empty()) o.spacing = parse_double(a.dp, "scene: --dp");
  if (!a.speed.empty()) o.speed = parse_double(a.speed, "scene: --speed");
  if (!a.t_end.empty()) o.t_end = parse_double(a.t_end, "scene: --t-end");
  if (o.problem == ImpactProblem::Beam) o.clamp_layers = impact_clamp_layers(0.1, o.spacing);  // the study's clamp
  return powell_impact_scene(o);
}

double checked(const std::string& text, const std::string& what, double lo, bool lo_open, double hi, bool hi_open) {
  const double v = parse_double(text, "scene: " + what);
  const bool ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  if (!ok)
    throw std::invalid_argument("scene: " + what + " must be in " + (lo_open ? "(" : "[") + format_number(lo) + ", " +
                                format_number(hi) + (hi_open ? ")" : "]") + " (got " + text + ")");
  return v;
}
double positive(const std::string& text, const std::string& what) { return checked(text, what, 0, true, kInf, true); }

/// The library's scene (problems/gms_scenes.hpp) with the command's parameters; out-of-range values are one error line.
Scene<2> make_scene(const SceneArgs& a) {
  const std::string& s = a.scene;
  if (is_impact(s)) return make_impact_scene(a);
  if (s != "plate" && s != "rings" && s != "slab")
    throw std::invalid_argument("scene: unknown scene '" + s +
                                "' (valid: plate, rings, slab, symmetric-impact, bar-impact, clamped-beam)");
  if (!a.mu.empty() && !a.nu.empty()) throw std::invalid_argument("scene: give --mu or --nu, not both");
  double mu = s == "slab" ? 0.3 : 0.22;  // GMS §7.2, §7.3; the plate's Table 1 first row
  if (!a.mu.empty()) mu = checked(a.mu, "--mu", 0, false, kInf, true);
  if (!a.nu.empty()) {  // K = 1: mu = 3 K (1 - 2 nu) / (2 (1 + nu))
    const double nu = checked(a.nu, "--nu (Poisson's ratio)", -1, true, 0.5, true);
    mu = 3 * (1 - 2 * nu) / (2 * (1 + nu));
  }
  GmsSceneOptions o{.material = ElasticMaterial::from_bulk_shear(1, mu, 1),
                    .scheme = gms_scheme_options(checked(a.eps, "--eps (artificial stress)", 0, false, kInf, true))};
  // GMS's scheme (plain gradient, symmetric momentum) takes the pair loop: auto is pairs (issue 35).
  o.scheme.pair_loop = a.pair_loop == "auto" ? PairLoop::Pairs : parse_pair_loop(a.pair_loop);
  const double yield = a.yield.empty() ? kInf : positive(a.yield, "--yield (von Mises yield stress)");
  // A run that cannot finish is refused before its particles are built (issue 36: --dp 0.003 built 4.4 M particles
  // first): the step rule of Scene::time_step and the estimated count; run_scene checks again with the exact count.
  auto require_steps = [&](double particles, double dp, double default_t_end) {
    const double t_end = a.t_end.empty() ? default_t_end : positive(a.t_end, "--t-end");
    const double cfl = positive(a.cfl.empty() ? "0.5" : a.cfl, "--cfl");
    require_run_length(t_end, cfl * o.h_over_spacing * dp / o.material.p_wave_speed(),
                       static_cast<long>(std::min(particles, 1e18)), "scene");
  };
  // A scene of millions of particles takes minutes to build before the run's first progress line: say so once it is
  // accepted.
  auto announce = [&](double particles) {
    if (particles >= 1e5)
      std::fprintf(stderr, "scene: building %s (about %.3g particles, ~%s)\n", s.c_str(), particles,
                   format_bytes(kSceneBytesPerParticle * particles).c_str());
  };
  Scene<2> sc;
  if (s == "plate") {
    if (!a.dp.empty()) throw std::invalid_argument("scene: the plate takes --across (dp = H / across), not --dp");
    const double H = positive(a.thickness, "--thickness H"), L = positive(a.length, "--length L");
    const int across = static_cast<int>(parse_integer(a.across, 2, 1000, "scene: --across"));
    const double vf = parse_double(a.tip_speed, "scene: --tip-speed");
    const double particles = (L / (H / across) + 4) * across;
    require_memory(kSceneBytesPerParticle * particles,
                   "scene: plate of " + a.across + " across and length " + a.length);
    announce(particles);
    sc = gms_plate_scene({.length = L, .thickness = H, .across = across}, vf, o);
  } else if (s == "rings") {
    const double dp = a.dp.empty() ? 0.1 : positive(a.dp, "--dp");
    // Two annuli r_in = 3 < r < r_out = 4 (colliding_rings.hpp) on a grid of dp: 2 pi (16 - 9) / dp^2 particles.
    const double particles = 2 * M_PI * 7 / (dp * dp);
    require_steps(particles, dp, kGmsRingsRunLength);
    require_memory(kSceneBytesPerParticle * (particles + 100), "scene: rings at --dp " + format_number(dp));
    announce(particles);
    sc = gms_rings_scene({.spacing = dp, .speed = parse_double(a.speed.empty() ? "0.059" : a.speed, "scene: --speed")},
                         o);
  } else {
    const double dp = a.dp.empty() ? 0.04 : positive(a.dp, "--dp");
    // The 3 x 1 slab (plastic_slab.hpp) on a grid of dp: (3 / dp + 1) (1 / dp + 1) particles.
    const double particles = (3 / dp + 1) * (1 / dp + 1);
    require_steps(particles, dp, kGmsSlabRunLength);
    require_memory(kSceneBytesPerParticle * particles, "scene: slab at --dp " + format_number(dp));
    announce(particles);
    sc = gms_slab_scene({.spacing = dp}, a.yield.empty() ? 0.03 : yield, o);  // GMS §7.3: Y = 0.03
  }
  if (s != "slab") sc.yield_stress = yield;
  return sc;
}

void run_scene(const SceneArgs& a) {
  const Scene<2> sc = make_scene(a);
  const RateFormScheme<2>& scheme = *sc.scheme;
  const double t_end = a.t_end.empty() ? sc.t_end : positive(a.t_end, "--t-end");
  const double skin = positive(a.skin, "--skin") * sc.spacing;
  const double dt = a.cfl.empty() ? sc.time_step(sc.cfl) : sc.time_step(positive(a.cfl, "--cfl"));
  const int every = static_cast<int>(parse_integer(a.record_every, 1, 1'000'000'000, "scene: --record-every"));
  require_run_length(t_end, dt, scheme.discretisation().particles.size(), "scene");
  std::vector<std::pair<double, std::string>> frames;
  if (!a.out.empty()) std::filesystem::create_directories(a.out);
  const double bond = 1.5 * sc.spacing;
  const SceneMeasure<2>& measure = sc.measures.front();
  std::printf("%s", csv_line({"step", "t", "kinetic", "fragments", measure.name, "status", "particle"}).c_str());
  RateFormRunOptions o = scene_run_options(sc, a.integrator);  // the scene's integrator unless chosen
  o.dt = dt;
  o.t_end = t_end;
  o.record_every = every;
  o.neighbour_skin = skin;
  o.observer = [&](long step, double t, const Eigen::VectorXd& y) {
    const Eigen::Matrix2Xd x = rate_form_positions(scheme, y);
    std::printf("%s", csv_line({std::to_string(step), num(t), num(scheme.kinetic_energy(y)),
                                std::to_string(find_fragments(x, bond).count()), num(measure.value(x, y)), "", ""})
                          .c_str());
    std::fflush(stdout);
    if (!a.out.empty()) {
      const std::string name = "scene_" + std::to_string(step) + ".vtp";
      write_rate_form_vtp(a.out + "/" + name, scheme, y);
      frames.emplace_back(t, name);
      write_pvd(a.out + "/scene.pvd", frames);  // kept current, so a run that stops leaves a readable series
    }
  };
  ProgressReport progress("scene " + a.scene);  // a line on stderr at most every 2 s, and the end
  o.observers = {&progress};
  const RateFormRunResult r = run_rate_form(scheme, sc.y0, o);
  std::printf("%s", csv_line({std::to_string(r.steps), num(r.time), "", "", "", run_status_name(r.status),
                              std::to_string(r.particle)})
                        .c_str());
  if (!r.completed()) std::fprintf(stderr, "scene: stopped: %s\n", r.message.c_str());
}

}  // namespace

void register_scene_command(CLI::App& app) {
  auto a = std::make_shared<SceneArgs>();
  auto* cmd = app.add_subcommand(
      "scene",
      "Run a GMS 2001 test case (plate | rings | slab) with GMS's scheme in GMS units, or one of Powell's impact "
      "problems (symmetric-impact | bar-impact | clamped-beam) with MCM's scheme in g-cm-us; CSV rows of step, t, "
      "kinetic "
      "energy, fragments and the scene's measure, and a final row with the run's status and particle");
  cmd->add_option("scene", a->scene,
                  "plate (§7.1 cantilever) | rings (§7.2) | slab (§7.3, von Mises) | symmetric-impact | bar-impact | "
                  "clamped-beam (Powell ch. 4 §4.1-4.3)")
      ->required();
  cmd->add_option("--dp", a->dp, "rings / slab / impacts: grid spacing > 0 (default 0.1 / 0.04 / 0.02 cm)");
  cmd->add_option("--formulation", a->formulation, "impacts: sph | ncsph | ssph (MCM's rate forms; default ssph)");
  cmd->add_option("--across", a->across, "plate: particles across H (default 10; dp = H / across)");
  cmd->add_option("--thickness", a->thickness, "plate: H > 0 (default 2)");
  cmd->add_option("--length", a->length, "plate: L > 0 (default 20)");
  cmd->add_option("--mu", a->mu, "shear modulus > 0 over K (default 0.22; slab 0.3)");
  cmd->add_option("--nu", a->nu, "or Poisson's ratio in (-1, 0.5) (mu = 3 (1 - 2 nu) / (2 (1 + nu)))");
  cmd->add_option("--eps", a->eps, "artificial stress >= 0 (default 0.3)");
  cmd->add_option("--tip-speed", a->tip_speed, "plate: V_f of (7.3)-(7.4) (default 0.01)");
  cmd->add_option("--speed", a->speed,
                  "rings: speed of each ring over c0 (default 0.059); impacts: v0 in cm/us (default 0.06; beam 0.3)");
  cmd->add_option("--yield", a->yield, "von Mises yield stress > 0 (slab default 0.03; others elastic)");
  cmd->add_option("--t-end", a->t_end, "run length > 0 (default plate 1.25 thin-plate periods, rings 100, slab 200)");
  cmd->add_option("--skin", a->skin, "Verlet skin of the neighbour list in dp, > 0 (default 0.5)");
  cmd->add_option("--cfl", a->cfl, "dt = cfl h / c_P, > 0 (default 0.5; impacts 0.8, the MCM deck's TSSFAC)");
  cmd->add_option("--record-every", a->record_every, "a row every k steps, and the last (default 100)");
  cmd->add_option("--pair-loop", a->pair_loop,
                  "auto = pairs (each pair once, about twice as fast; results/gms-speed) | rows (every pair from both "
                  "sides) (default auto; both threaded, the same bits on any thread count)");
  cmd->add_option("--integrator", a->integrator,
                  "auto = the scene's (plate, rings: pc1, one rate evaluation per step, results/gms-pc1; slab: pc; "
                  "impacts: leapfrog) | pc (GMS's predictor-corrector, two rate evaluations per step) | pc1 | leapfrog");
  cmd->add_option("--out", a->out, "also write VTK snapshots DIR/scene_<step>.vtp at every row and DIR/scene.pvd");
  cmd->callback([a, cmd] {
    // An option of another scene is a mistake, not a no-op (issue 36): one line naming where it applies.
    const std::vector<std::pair<const char*, const char*>> only = {{"--across", "plate"},
                                                                   {"--thickness", "plate"},
                                                                   {"--length", "plate"},
                                                                   {"--tip-speed", "plate"},
                                                                   {"--speed", "rings"}};
    const bool impact = is_impact(a->scene);
    for (const auto& [option, scene] : only)
      if (cmd->count(option) > 0 && a->scene != scene && !(impact && std::string(option) == "--speed"))
        throw std::invalid_argument(std::string("scene: ") + option + " applies to the " + scene +
                                    (std::string(option) == "--speed" ? " and the impacts" : "") + " only (not to " +
                                    a->scene + ")");
    // GMS's material and scheme options do not apply to the impacts (steel, MCM's scheme), nor --formulation to GMS's.
    for (const char* option : {"--mu", "--nu", "--eps", "--yield", "--pair-loop"})
      if (impact && cmd->count(option) > 0)
        throw std::invalid_argument(std::string("scene: ") + option + " applies to the GMS scenes only (not to " +
                                    a->scene + ": steel, MCM's scheme)");
    if (!impact && cmd->count("--formulation") > 0)
      throw std::invalid_argument("scene: --formulation applies to the impact problems only (not to " + a->scene + ")");
    run_scene(*a);
  });
}

}  // namespace sphstab::cli
