// Critical tension of the 1D lattice over kernels x h x forms (stability/critical_tension_sweep.hpp: what `sphstab tcrit`
// prints) and the stability of a given particle state (growth/state_stability.hpp).
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "sphstab/core/status.hpp"
#include "sphstab/growth/state_stability.hpp"
#include "sphstab/io/particle_state_file.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/rate_form_symbol.hpp"
#include "sphstab/stability/critical_tension_sweep.hpp"

namespace sphstab::python {

namespace {

std::vector<CriticalTensionCase> critical_tension(int n, const std::vector<std::string>& kernels,
                                                  const std::vector<double>& hs, const std::vector<std::string>& forms,
                                                  bool periodic, bool compression, const std::string& method,
                                                  const std::string& backend, const std::string& correction,
                                                  const std::string& corrected) {
  CriticalTensionSweep s;
  if (n < 1) throw std::invalid_argument("--n must be > 0 (got " + std::to_string(n) + ")");
  s.n = n;
  s.periodic = periodic;
  s.direction = compression ? LoadDirection::Compression : LoadDirection::Tension;
  s.kernels.clear();
  for (const auto& k : kernels) s.kernels.push_back(parse_kernel_type(k));
  s.hs = hs;
  s.forms.clear();
  for (const auto& f : forms) s.forms.push_back(parse_momentum_form(f));
  s.method = parse_critical_load_method(method);
  s.backend = parse_eigen_backend(backend);
  s.correction = parse_correction(correction);
  s.corrected = parse_corrected_operator(corrected);
  return critical_tension_sweep(s);
}

/// The verdict's mode as (shape as free x dim, particle, share, kx, ky, x_share).
py::dict mode_dict(const VerdictMode& mode, int dim) {
  py::dict d;
  const Eigen::Index rows = dim ? mode.shape.size() / dim : 0;
  d["shape"] = Eigen::MatrixXd(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      mode.shape.data(), rows, dim));
  d["particle"] = mode.particle;
  d["particle_share"] = mode.particle_share;
  d["kx_over_pi"] = mode.kx_over_pi;
  d["ky_over_pi"] = mode.ky_over_pi;
  d["x_share"] = mode.x_share;
  return d;
}

template <int Dim>
ParticleState<Dim> make_state(const Eigen::MatrixXd& x, const Eigen::VectorXd& density, const Eigen::VectorXd& mass,
                              double h, const Eigen::MatrixXd& v, const Eigen::MatrixXd& deviator,
                              const std::vector<bool>& fixed, double spacing) {
  return {.x = x, .v = v, .density = density, .deviator = deviator, .mass = mass, .fixed = fixed, .h = h,
          .spacing = spacing};
}

template <int Dim>
StateStability state_stability_of(const Eigen::MatrixXd& x, const Eigen::VectorXd& density,
                                   const Eigen::VectorXd& mass, double h, const Eigen::MatrixXd& v,
                                   const Eigen::MatrixXd& deviator, const std::vector<bool>& fixed, double spacing,
                                   const StateStabilityOptions& o) {
  return state_stability(make_state<Dim>(x, density, mass, h, v, deviator, fixed, spacing), o);
}

/// J = dF/dy of the rate-form scheme built at the state (coloured complex step, as `sphstab jacobian rate-form`),
/// with the state's layout: per particle the offsets of x, v, rho and S in y (-1 where it carries none).
template <int Dim>
py::tuple jacobian_at(const ParticleState<Dim>& s, const std::string& kernel, const ElasticMaterial& material,
                      const RateFormOptions& options) {
  RateFormAtState<Dim> at;
  SparseMatrix<> J;
  {
    py::gil_scoped_release release;
    at = rate_form_at_state(s, parse_kernel_type(kernel), material, options);
    J = jacobian(*at.scheme, at.y);
  }
  const int n = at.scheme->discretisation().size();
  py::array_t<int> offsets({n, 4});
  for (int i = 0; i < n; ++i) {
    offsets.mutable_at(i, 0) = at.scheme->position_offset(i);
    offsets.mutable_at(i, 1) = at.scheme->velocity_offset(i);
    offsets.mutable_at(i, 2) = at.scheme->density_offset(i);
    offsets.mutable_at(i, 3) = at.scheme->stress_offset(i);
  }
  return py::make_tuple(csr_arrays(std::move(J)), at.y, offsets);
}

/// The Bloch symbol of the rate-form scheme on a periodic lattice at volume strain xi (spectral/rate_form_symbol.hpp)
/// and its dispersion at each row of k (K x Dim, in 1/length): growth rate, omega^2 of the acoustic branches and all
/// eigenvalues of Jhat(k).
template <int Dim>
py::dict dispersion(const std::string& lattice, int n, const std::string& kernel_name, double h_over_dx, double dx,
                    double xi, const ElasticMaterial& material, const RateFormOptions& options,
                    const Eigen::MatrixXd& k) {
  if (k.cols() != Dim)
    throw std::invalid_argument("rate_form_dispersion: k must have " + std::to_string(Dim) + " columns (got " +
                                std::to_string(k.cols()) + ")");
  if (!(xi > 0) || !std::isfinite(xi))
    throw std::invalid_argument("rate_form_dispersion: xi must be finite and > 0 (got " + std::to_string(xi) + ")");
  if (n < 1) throw std::invalid_argument("--n must be > 0 (got " + std::to_string(n) + ")");
  const Kernel<Dim> kernel(parse_kernel_type(kernel_name));
  const double h = h_over_dx * dx;
  Eigen::VectorXd growth(k.rows());
  Eigen::MatrixXcd omega2(k.rows(), Dim), lambda;
  {
    py::gil_scoped_release release;
    const ParticleSet<Dim> set = make_lattice<Dim>(
        parse_lattice_type(lattice), n, {.spacing = dx, .support_radius = kernel.support_radius(h), .periodic = true});
    const RateFormScheme<Dim> scheme(make_discretisation(set, kernel, h), material, options, material.density() / xi);
    const RateFormSymbol<Dim> symbol = rate_form_symbol(scheme, scheme.uniform_state());
    for (Eigen::Index q = 0; q < k.rows(); ++q) {
      const RateFormDispersion d = rate_form_dispersion(symbol, Eigen::Matrix<double, Dim, 1>(k.row(q).transpose()));
      if (q == 0) lambda.resize(k.rows(), d.lambda.size());
      growth[q] = d.growth_rate;
      omega2.row(q) = d.omega2.transpose();
      lambda.row(q) = d.lambda.transpose();
    }
  }
  py::dict out;
  out["growth_rate"] = growth;
  out["omega2"] = omega2;
  out["eigenvalues"] = lambda;
  return out;
}

}  // namespace

void bind_stability(py::module_& m) {
  py::class_<CriticalTensionCase>(m, "CriticalTensionCase",
                                  "One (kernel, h, form) of the 1D critical tension (Powell (3.40)), as a row of "
                                  "`sphstab tcrit`.")
      .def_property_readonly("kernel", [](const CriticalTensionCase& c) { return kernel_name(c.kernel); })
      .def_property_readonly("form", [](const CriticalTensionCase& c) { return momentum_form_name(c.form); })
      .def_readonly("h_over_dx", &CriticalTensionCase::h)
      .def_property_readonly("tcrit", [](const CriticalTensionCase& c) { return c.result.load; })
      .def_property_readonly("tcrit_eig", [](const CriticalTensionCase& c) { return c.result.load_eigen; })
      .def_property_readonly("tcrit_bisect", [](const CriticalTensionCase& c) { return c.result.load_bisection; })
      .def_property_readonly("status", [](const CriticalTensionCase& c) { return status_name(c.result.status); })
      .def_readonly("backend", &CriticalTensionCase::backend)
      .def_readonly("criterion", &CriticalTensionCase::criterion)
      .def_readonly("reason", &CriticalTensionCase::reason)
      .def_readonly("mode_k_over_pi", &CriticalTensionCase::mode_k_over_pi)
      .def_readonly("tcrit_infinite", &CriticalTensionCase::infinite)
      .def_readonly("tcrit_symbol", &CriticalTensionCase::symbol);
  m.def("_critical_tension", &critical_tension, py::arg("n"), py::arg("kernels"), py::arg("hs"), py::arg("forms"),
        py::arg("periodic"), py::arg("compression"), py::arg("method"), py::arg("backend"), py::arg("correction"),
        py::arg("corrected"), py::call_guard<py::gil_scoped_release>());

  m.def("detection_floor", &detection_floor, py::arg("t_end"), py::arg("energy_ratio") = 100.0,
        "ln(energy_ratio) / (2 t_end): the slowest amplitude growth a run of length t_end detects.");

  py::class_<RateFormOptions>(m, "RateFormOptions", "The rate-form scheme's terms (forms/rate_form.hpp).")
      .def(py::init<>())
      .def_property(
          "continuity", [](const RateFormOptions& o) { return o.continuity == ContinuityForm::Summation ? "summation" : "divergence"; },
          [](RateFormOptions& o, const std::string& s) { o.continuity = parse_continuity_form(s); })
      .def_readwrite("xsph", &RateFormOptions::xsph)
      .def_property(
          "viscosity",
          [](const RateFormOptions& o) {
            return o.viscosity == ViscositySwitch::Off ? "off" : o.viscosity == ViscositySwitch::Compression ? "compression" : "always";
          },
          [](RateFormOptions& o, const std::string& s) { o.viscosity = parse_viscosity_switch(s); })
      .def_readwrite("viscosity_alpha", &RateFormOptions::viscosity_alpha)
      .def_readwrite("viscosity_beta", &RateFormOptions::viscosity_beta)
      .def_readwrite("bulk_viscosity_quadratic", &RateFormOptions::bulk_viscosity_quadratic)
      .def_readwrite("bulk_viscosity_linear", &RateFormOptions::bulk_viscosity_linear)
      .def_readwrite("artificial_stress", &RateFormOptions::artificial_stress)
      .def_readwrite("artificial_stress_exponent", &RateFormOptions::artificial_stress_exponent)
      .def_readwrite("evolve_fixed", &RateFormOptions::evolve_fixed)
      .def_property(
          "gradient", [](const RateFormOptions& o) { return o.gradient == RateFormGradient::Plain ? "plain" : "ncsph"; },
          [](RateFormOptions& o, const std::string& s) { o.gradient = parse_rate_form_gradient(s); })
      .def_property(
          "momentum",
          [](const RateFormOptions& o) {
            switch (o.momentum) {
              case RateFormMomentum::Symmetric:
                return "symmetric";
              case RateFormMomentum::Antisymmetric:
                return "antisymmetric";
              case RateFormMomentum::Cij:
                return "cij";
              default:
                return "ssph";
            }
          },
          [](RateFormOptions& o, const std::string& s) { o.momentum = parse_rate_form_momentum(s); })
      .def_readwrite("first_step_shepard", &RateFormOptions::first_step_shepard,
                     "S-SPH: the means of the first-step Shepard gradient, Powell (4.18)");

  py::class_<StabilityVerdict>(m, "StabilityVerdict",
                               "Semi-discrete growth gamma_J, the integrator's map growth gamma_M at dt, the detection "
                               "floor and the class S / U / I / B (growth/stability_verdict.hpp).")
      .def_property_readonly("letter", &StabilityVerdict::letter)
      .def_property_readonly("name", [](const StabilityVerdict& v) { return verdict_name(v.verdict); })
      .def_readonly("integrator", &StabilityVerdict::integrator)
      .def_readonly("dt", &StabilityVerdict::dt)
      .def_readonly("floor", &StabilityVerdict::floor)
      .def_readonly("semi_discrete_growth", &StabilityVerdict::semi_discrete_growth)
      .def_readonly("eigenvalue", &StabilityVerdict::lambda)
      .def_readonly("lambda_max", &StabilityVerdict::lambda_max)
      .def_readonly("map_spectral_radius", &StabilityVerdict::map_spectral_radius)
      .def_readonly("map_growth", &StabilityVerdict::map_growth)
      .def_readonly("integrator_excess", &StabilityVerdict::integrator_excess)
      .def_readonly("resolution", &StabilityVerdict::resolution)
      .def_readonly("map_size", &StabilityVerdict::map_size)
      .def_readonly("map_route", &StabilityVerdict::map_route)
      .def_property_readonly("status", [](const StabilityVerdict& v) { return status_name(v.status); })
      .def_readonly("reason", &StabilityVerdict::reason);

  py::class_<RateFormTimeStep>(m, "RateFormTimeStep",
                               "Step limits at rest: leap-frog 2 / max|Im lambda|, predictor-corrector, effective "
                               "Courant number (growth/rate_form_time_step.hpp).")
      .def_readonly("leapfrog", &RateFormTimeStep::leapfrog)
      .def_readonly("predictor_corrector", &RateFormTimeStep::predictor_corrector)
      .def_readonly("courant", &RateFormTimeStep::courant)
      .def_readonly("max_imag", &RateFormTimeStep::max_imag)
      .def_readonly("cfl_unit", &RateFormTimeStep::cfl_unit)
      .def_property_readonly("status", [](const RateFormTimeStep& t) { return status_name(t.status); })
      .def_readonly("reason", &RateFormTimeStep::reason);

  py::class_<StateStability>(m, "StateStability", "The verdict of a particle state (growth/state_stability.hpp).")
      .def_readonly("verdict", &StateStability::verdict)
      .def_readonly("time_step", &StateStability::time_step)
      .def_readonly("particles", &StateStability::particles)
      .def_readonly("free", &StateStability::free)
      .def_readonly("states", &StateStability::states)
      .def_readonly("at_rest", &StateStability::at_rest)
      .def_readonly("acceleration_max", &StateStability::acceleration_max)
      .def_readonly("rate_scale", &StateStability::rate_scale)
      .def_property_readonly("semi_discrete_mode",
                             [](const StateStability& s) {
                               const int dim = s.free ? static_cast<int>(s.verdict.semi_discrete_mode.shape.size()) / s.free : 1;
                               return mode_dict(s.verdict.semi_discrete_mode, dim ? dim : 1);
                             })
      .def_property_readonly("map_mode", [](const StateStability& s) {
        const int dim = s.free ? static_cast<int>(s.verdict.map_mode.shape.size()) / s.free : 1;
        return mode_dict(s.verdict.map_mode, dim ? dim : 1);
      });

  m.def(
      "_state_stability",
      [](int dim, const Eigen::MatrixXd& x, const Eigen::VectorXd& density, const Eigen::VectorXd& mass, double h,
         const Eigen::MatrixXd& v, const Eigen::MatrixXd& deviator, const std::vector<bool>& fixed, double spacing,
         const std::string& kernel, double rho0, double bulk_modulus, double shear_modulus,
         const RateFormOptions& scheme, const std::string& integrator, double leapfrog_xsph, double dt, double floor,
         const std::string& lattice) {
        StateStabilityOptions o;
        o.kernel = parse_kernel_type(kernel);
        o.material = ElasticMaterial::from_bulk_shear(bulk_modulus, shear_modulus, rho0);
        o.scheme = scheme;
        select_rate_form_integrator(o.run, integrator);
        o.run.leapfrog_xsph = leapfrog_xsph;
        o.dt = dt;
        o.floor = floor;
        if (!lattice.empty()) o.lattice = parse_lattice_type(lattice);
        py::gil_scoped_release release;
        if (dim == 1) return state_stability_of<1>(x, density, mass, h, v, deviator, fixed, spacing, o);
        if (dim == 2) return state_stability_of<2>(x, density, mass, h, v, deviator, fixed, spacing, o);
        throw std::invalid_argument("state: positions must have 1 or 2 columns (got " + std::to_string(dim) + ")");
      },
      py::arg("dim"), py::arg("x"), py::arg("density"), py::arg("mass"), py::arg("h"), py::arg("v"),
      py::arg("deviator"), py::arg("fixed"), py::arg("spacing"), py::arg("kernel"), py::arg("rho0"),
      py::arg("bulk_modulus"), py::arg("shear_modulus"), py::arg("scheme"), py::arg("integrator"),
      py::arg("leapfrog_xsph"), py::arg("dt"), py::arg("floor"), py::arg("lattice"));

  m.def(
      "_rate_form_jacobian",
      [](const Eigen::MatrixXd& x, const Eigen::VectorXd& density, const Eigen::VectorXd& mass, double h,
         const Eigen::MatrixXd& v, const Eigen::MatrixXd& deviator, const std::vector<bool>& fixed, double spacing,
         const std::string& kernel, double rho0, double bulk_modulus, double shear_modulus,
         const RateFormOptions& scheme) {
        const ElasticMaterial material = ElasticMaterial::from_bulk_shear(bulk_modulus, shear_modulus, rho0);
        if (x.cols() == 1)
          return jacobian_at<1>(make_state<1>(x, density, mass, h, v, deviator, fixed, spacing), kernel, material,
                                scheme);
        if (x.cols() == 2)
          return jacobian_at<2>(make_state<2>(x, density, mass, h, v, deviator, fixed, spacing), kernel, material,
                                scheme);
        throw std::invalid_argument("state: positions must have 1 or 2 columns (got " + std::to_string(x.cols()) + ")");
      },
      py::arg("x"), py::arg("density"), py::arg("mass"), py::arg("h"), py::arg("v"), py::arg("deviator"),
      py::arg("fixed"), py::arg("spacing"), py::arg("kernel"), py::arg("rho0"), py::arg("bulk_modulus"),
      py::arg("shear_modulus"), py::arg("scheme"));

  m.def(
      "_rate_form_dispersion",
      [](const std::string& lattice, int n, const std::string& kernel, double h_over_dx, double dx, double xi,
         double rho0, double bulk_modulus, double shear_modulus, const RateFormOptions& scheme,
         const Eigen::MatrixXd& k) {
        const ElasticMaterial material = ElasticMaterial::from_bulk_shear(bulk_modulus, shear_modulus, rho0);
        if (parse_lattice_type(lattice) == LatticeType::Line)
          return dispersion<1>(lattice, n, kernel, h_over_dx, dx, xi, material, scheme, k);
        return dispersion<2>(lattice, n, kernel, h_over_dx, dx, xi, material, scheme, k);
      },
      py::arg("lattice"), py::arg("n"), py::arg("kernel"), py::arg("h_over_dx"), py::arg("dx"), py::arg("xi"),
      py::arg("rho0"), py::arg("bulk_modulus"), py::arg("shear_modulus"), py::arg("scheme"), py::arg("k"));

  m.def(
      "read_particle_state",
      [](const std::string& path, double h, double spacing, double mass) {
        const ParticleStateFileOptions o{.h = h, .spacing = spacing, .mass = mass};
        if (particle_state_dimension(path) == 1) return state_dict(read_particle_state<1>(path, o));
        return state_dict(read_particle_state<2>(path, o));
      },
      py::arg("path"), py::arg("h"), py::arg("spacing") = 0.0, py::arg("mass") = std::nan(""),
      "A particle state from a .csv or .vtp file (io/particle_state_file.hpp) as a dict of arrays: x, v, density, "
      "deviator, mass, fixed, h, spacing (the keywords of state_stability).");
  m.def(
      "_write_state_modes_vtp",
      [](const std::string& path, const Eigen::MatrixXd& x, const Eigen::VectorXd& density, const Eigen::VectorXd& mass,
         double h, const Eigen::MatrixXd& v, const Eigen::MatrixXd& deviator, const std::vector<bool>& fixed,
         double spacing, const StateStability& result) {
        if (x.cols() == 1)
          write_state_modes_vtp<1>(path, make_state<1>(x, density, mass, h, v, deviator, fixed, spacing), result);
        else
          write_state_modes_vtp<2>(path, make_state<2>(x, density, mass, h, v, deviator, fixed, spacing), result);
      },
      py::arg("path"), py::arg("x"), py::arg("density"), py::arg("mass"), py::arg("h"), py::arg("v"),
      py::arg("deviator"), py::arg("fixed"), py::arg("spacing"), py::arg("result"));

  m.def(
      "material_from_youngs",
      [](double youngs, double poisson, double density) {
        const ElasticMaterial mat = ElasticMaterial::from_young_poisson(youngs, poisson, density);
        return py::make_tuple(mat.density(), mat.bulk_modulus(), mat.mu());
      },
      py::arg("youngs"), py::arg("poisson"), py::arg("density"),
      "(rho0, K, mu) of Young's modulus E, Poisson's ratio nu and rho0 (3D moduli).");
}

}  // namespace sphstab::python
