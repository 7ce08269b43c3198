// Scenes (problems/scene.hpp: the GMS plate, rings and slab of problems/gms_scenes.hpp, Powell's impact problems of
// problems/powell_impact.hpp) and the run loop
// (integrate/rate_form_run.hpp, run_rate_form) with a Python observer: progress, diagnostics and early stop.
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/integrate/run.hpp"
#include "sphstab/integrate/run_observer.hpp"
#include "sphstab/integrate/scene_run.hpp"
#include "sphstab/problems/gms_scenes.hpp"
#include "sphstab/problems/powell_impact.hpp"
#include "sphstab/problems/scene.hpp"

namespace sphstab::python {

namespace {

using Scene2 = Scene<2>;

/// The state y of the scene as the arrays of growth/state_stability.hpp (x, v, density, deviator, mass, fixed, h,
/// spacing): what state_stability takes, so a scene's state can be asked about directly.
py::dict state_arrays(const Scene2& s, const Eigen::VectorXd& y) {
  const RateFormScheme<2>& scheme = *s.scheme;
  if (y.size() != scheme.size())
    throw std::invalid_argument("Scene.state: y has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(scheme.size()));
  const int n = scheme.discretisation().size();
  ParticleState<2> state{.x = rate_form_positions(scheme, y).transpose(),
                         .v = rate_form_velocities(scheme, y).transpose(),
                         .density = rate_form_densities(scheme, y),
                         .deviator = rate_form_deviators(scheme, y).transpose(),
                         .mass = scheme.mass(),
                         .fixed = std::vector<bool>(n),
                         .h = scheme.discretisation().h,
                         .spacing = s.spacing};
  for (int i = 0; i < n; ++i) state.fixed[i] = scheme.position_offset(i) < 0;
  return state_dict(state);
}

/// A run loop observer that calls a Python function (step, time, y) at every record; a truthy return (a string: the
/// reason) stops the run with status "stopped"; an exception in it stops the run and is raised again after it.
class PythonObserver final : public RunObserver {
 public:
  explicit PythonObserver(py::object f) : m_f(std::move(f)) {}
  void call(long step, double time, const Eigen::VectorXd& y) {
    if (!m_stop.empty()) return;
    py::gil_scoped_acquire gil;
    try {
      py::object r = m_f(step, time, Eigen::VectorXd(y));
      if (py::isinstance<py::str>(r))
        m_stop = r.cast<std::string>();
      else if (r.ptr() != Py_None && py::bool_(r))
        m_stop = "the observer asked to stop";
    } catch (py::error_already_set& e) {
      m_error = std::move(e);
      m_stop = "the observer raised an exception";
    }
  }
  std::string stop_request() override { return m_stop; }
  std::optional<py::error_already_set> m_error;

 private:
  py::object m_f;
  std::string m_stop;
};

RateFormRunResult run_scene(const Scene2& s, double dt, double cfl, double t_end, const std::string& integrator,
                            int record_every, double energy_growth, double xsph, py::object observer) {
  if (!std::isnan(dt) && !std::isnan(cfl)) throw std::invalid_argument("run: give dt or cfl, not both");
  // the scene's step rule, integrator (unless chosen) and XSPH (integrate/scene_run.hpp), as `sphstab scene`
  RateFormRunOptions o = scene_run_options(s, integrator);
  if (!std::isnan(dt)) o.dt = dt;
  if (!std::isnan(cfl)) o.dt = s.time_step(cfl);
  if (!std::isnan(t_end)) o.t_end = t_end;
  o.record_every = record_every;
  o.energy_growth = energy_growth;
  if (!std::isnan(xsph)) o.leapfrog_xsph = xsph;  // run_rate_form refuses it off the leap-frog, or negative
  std::optional<PythonObserver> py_observer;
  if (!observer.is_none()) {
    if (!PyCallable_Check(observer.ptr())) throw std::invalid_argument("run: observer must be callable");
    py_observer.emplace(observer);
    o.observer = [&py_observer](long step, double time, const Eigen::VectorXd& y) { py_observer->call(step, time, y); };
    o.observers.push_back(&*py_observer);
  }
  RateFormRunResult r;
  {
    py::gil_scoped_release release;
    r = run_rate_form(*s.scheme, s.y0, o);
  }
  if (py_observer && py_observer->m_error) throw std::move(*py_observer->m_error);
  return r;
}

}  // namespace

void bind_scenes(py::module_& m) {
  py::class_<Scene2>(m, "Scene2D", "A runnable scene (problems/scene.hpp): the rate-form system at its initial state.")
      .def_readonly("name", &Scene2::name)
      .def_readonly("y0", &Scene2::y0)
      .def_readonly("spacing", &Scene2::spacing)
      .def_readonly("t_end", &Scene2::t_end)
      .def_readonly("yield_stress", &Scene2::yield_stress)
      .def_readonly("neighbour_skin", &Scene2::neighbour_skin)
      .def_readonly("integrator", &Scene2::integrator, "the default integrator: pc, pc1 or leapfrog")
      .def_readonly("leapfrog_xsph", &Scene2::leapfrog_xsph)
      .def_readonly("cfl", &Scene2::cfl, "the default time step is time_step(cfl)")
      .def_property_readonly("particles", [](const Scene2& s) { return s.scheme->discretisation().size(); })
      .def_property_readonly("h", [](const Scene2& s) { return s.scheme->discretisation().h; })
      .def_property_readonly("scheme_options", [](const Scene2& s) { return s.scheme->options(); })
      .def_property_readonly("material",
                             [](const Scene2& s) {
                               const ElasticMaterial& mat = s.scheme->material();
                               return py::dict(py::arg("rho0") = mat.density(),
                                               py::arg("bulk_modulus") = mat.bulk_modulus(),
                                               py::arg("shear_modulus") = mat.mu());
                             })
      .def_property_readonly("measures",
                             [](const Scene2& s) {
                               std::vector<std::string> names;
                               for (const auto& m : s.measures) names.push_back(m.name);
                               return names;
                             })
      .def("time_step", &Scene2::time_step, py::arg("cfl"), "dt = cfl h / c_P")
      .def(
          "measure",
          [](const Scene2& s, const std::string& name, const Eigen::VectorXd& y) {
            if (y.size() != s.scheme->size()) throw std::invalid_argument("Scene.measure: y has the wrong size");
            return s.measure(name).value(rate_form_positions(*s.scheme, y), y);
          },
          py::arg("name"), py::arg("y"))
      .def("state", &state_arrays, py::arg("y"),
           "The state y as the arrays state_stability takes (x, v, density, deviator, mass, fixed, h, spacing).");

  m.def(
      "gms_rings_scene",
      [](double spacing, double inner_radius, double outer_radius, double gap, double speed, double eps) {
        GmsSceneOptions o;
        o.scheme = gms_scheme_options(eps);
        return gms_rings_scene({.inner_radius = inner_radius, .outer_radius = outer_radius, .spacing = spacing,
                                .gap = gap, .speed = speed},
                               o);
      },
      py::arg("spacing") = 0.1, py::arg("inner_radius") = 3.0, py::arg("outer_radius") = 4.0, py::arg("gap") = 0.2,
      py::arg("speed") = 0.059, py::arg("eps") = 0.3,
      "GMS 2001 §7.2: two rubber rings colliding (GMS units), with GMS's scheme (artificial stress eps).");
  m.def(
      "gms_plate_scene",
      [](double length, double thickness, int across, int clamp_layers, double tip_speed, double eps) {
        GmsSceneOptions o;
        o.scheme = gms_scheme_options(eps);
        return gms_plate_scene({.length = length, .thickness = thickness, .across = across,
                                .clamp_layers = clamp_layers},
                               tip_speed, o);
      },
      py::arg("length") = 20.0, py::arg("thickness") = 2.0, py::arg("across") = 10, py::arg("clamp_layers") = 4,
      py::arg("tip_speed") = 0.01, py::arg("eps") = 0.3, "GMS 2001 §7.1: the oscillating cantilever plate.");

  m.def(
      "gms_slab_scene",
      [](double length, double width, double spacing, double end_zone, double acceleration, double yield_stress,
         double eps) {
        GmsSceneOptions o;
        o.scheme = gms_scheme_options(eps);
        // GMS §7.3 (as `sphstab scene slab`): mu = 0.3, K and rho0 kept.
        o.material = ElasticMaterial::from_bulk_shear(o.material.bulk_modulus(), 0.3, o.material.density());
        return gms_slab_scene({.length = length, .width = width, .spacing = spacing, .end_zone = end_zone,
                               .acceleration = acceleration},
                              yield_stress, o);
      },
      py::arg("length") = 3.0, py::arg("width") = 1.0, py::arg("spacing") = 0.04, py::arg("end_zone") = 0.2,
      py::arg("acceleration") = 5e-6, py::arg("yield_stress") = 0.03, py::arg("eps") = 0.3,
      "GMS 2001 §7.3: a von Mises slab pulled at both ends (driven end zones) until it necks.");

  m.def(
      "powell_impact_scene",
      [](const std::string& problem, double spacing, const std::string& formulation, double speed, double t_end) {
        PowellImpactOptions o;
        o.problem = parse_impact_problem(problem);
        o.spacing = spacing;
        o.speed = speed;
        o.t_end = t_end;
        o.scheme = powell_formulation_options(formulation);
        if (o.problem == ImpactProblem::Beam) o.clamp_layers = impact_clamp_layers(0.1, spacing);  // the study's
        return powell_impact_scene(o);
      },
      py::arg("problem"), py::arg("spacing") = 0.02, py::arg("formulation") = "ssph",
      py::arg("speed") = std::nan(""), py::arg("t_end") = std::nan(""),
      "Powell 2012 ch. 4 §4: 'symmetric', 'bar' or 'beam' in g-cm-us (steel), with MCM's rate form 'sph', 'ncsph' "
      "or 'ssph' (speed, t_end: NaN for the problem's defaults). run(scene) runs it as Powell did (the scene's "
      "defaults: leap-frog, XSPH (2.71) 0.1, cfl 0.8).");

  py::class_<RateFormRunResult>(m, "RunResult", "A run's outcome (integrate/run.hpp): status, series, last state.")
      .def_property_readonly("status", [](const RateFormRunResult& r) { return run_status_name(r.status); })
      .def_readonly("message", &RateFormRunResult::message)
      .def_readonly("reason", &RateFormRunResult::reason)
      .def_readonly("steps", &RateFormRunResult::steps)
      .def_readonly("time", &RateFormRunResult::time)
      .def_readonly("dt", &RateFormRunResult::dt)
      .def_readonly("particle", &RateFormRunResult::particle)
      .def_readonly("times", &RateFormRunResult::times)
      .def_readonly("kinetic_energy", &RateFormRunResult::kinetic_energy)
      .def_readonly("y", &RateFormRunResult::y);
  m.def("run", &run_scene, py::arg("scene"), py::arg("dt") = std::nan(""), py::arg("cfl") = std::nan(""),
        py::arg("t_end") = std::nan(""), py::arg("integrator") = "auto", py::arg("record_every") = 1,
        py::arg("energy_growth") = std::numeric_limits<double>::infinity(), py::arg("xsph") = std::nan(""),
        py::arg("observer") = py::none(),
        "Runs a scene with the run loop (run_rate_form) as `sphstab scene` runs it: dt, or cfl times h / c_P (default "
        "the scene's cfl); t_end (default the scene's); integrator 'auto' (the scene's: pc1 for GMS's plate and rings, "
        "pc for the slab, leapfrog for Powell's impacts), 'pc', 'pc1' or 'leapfrog'; xsph: Powell's velocity "
        "smoothing (2.71) on the leap-frog (default the scene's: 0.1 for the impacts); observer(step, time, y) at "
        "every record, a truthy return (or a reason string) stops the run.");
}

}  // namespace sphstab::python
