// Linearisations A(load) = A0 + load A1 of elastic lattices (jacobian/: the analytic 1D and 2D Jacobians `sphstab
// jacobian elastic` exports) and the critical pre-strain of 2D/3D lattices through the critical-load front door
// (stability/critical_strain_sweep.hpp: what `sphstab tcrit --dim 2|3` prints).
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "sphstab/core/status.hpp"
#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_strain_sweep.hpp"

namespace sphstab::python {

namespace {

py::tuple elastic_linearisation(int dim, int n, const std::string& kernel_name, double h, const std::string& form_name,
                                const std::string& lattice, double lambda, double mu, const std::string& prestrain) {
  if (n < 1) throw std::invalid_argument("--n must be > 0 (got " + std::to_string(n) + ")");
  const MomentumForm form = parse_momentum_form(form_name);
  const KernelType kt = parse_kernel_type(kernel_name);
  Linearisation lin;
  if (dim == 1) {
    const Kernel<1> kernel(kt);
    py::gil_scoped_release release;
    lin = analytic_jacobian_1d(tension_lattice_1d(kernel, h, n), kernel, h, form);
  } else if (dim == 2) {
    const LatticeType type = parse_lattice_type(lattice);
    const PreStrainKind kind = parse_prestrain_kind(prestrain);
    const ElasticMaterial material = ElasticMaterial::from_lame(lambda, mu, 1.0);
    material.validate("elastic_linearisation");
    const Kernel<2> kernel(kt);
    py::gil_scoped_release release;
    lin = analytic_jacobian_2d(*make_discretisation(strain_lattice_2d(type, kernel, h, n), kernel, h), material, form,
                               kind);
  } else {
    throw std::invalid_argument("elastic_linearisation: dim must be 1 or 2 (got " + std::to_string(dim) + ")");
  }
  return py::make_tuple(csr_arrays(std::move(lin.A0)), csr_arrays(std::move(lin.A1)));
}

/// One case of the sweep, flattened for Python (the fields of `sphstab tcrit --dim 2|3`'s row).
struct StrainCase {
  std::string kernel, form, lattice, route, route_reason, criterion, method, backend, status, reason;
  int dim = 2, n = 0;
  double h_over_dx = NAN, ecrit = NAN, ecrit_eig = NAN, ecrit_bisect = NAN, ecrit_infinite = NAN,
         mode_kx_over_pi = NAN, mode_ky_over_pi = NAN, memory_estimate = NAN;
};

template <int Dim>
std::vector<StrainCase> sweep(const std::string& lattice, int n, bool periodic, const std::vector<std::string>& kernels,
                              const std::vector<double>& hs, const std::vector<std::string>& forms, double lambda,
                              double mu, const std::string& prestrain, bool compression, const std::string& route,
                              const std::string& method, const std::string& backend, const std::string& criterion) {
  CriticalStrainSweep<Dim> s;
  s.base.lattice = parse_lattice_type(lattice);
  if (n < 1) throw std::invalid_argument("--n must be > 0 (got " + std::to_string(n) + ")");
  s.base.n = n;
  s.base.periodic = periodic;
  s.base.material = ElasticMaterial::from_lame(lambda, mu, 1.0);
  s.base.material.validate("critical_strain");
  s.base.prestrain = parse_prestrain_kind(prestrain);
  s.kernels.clear();
  for (const auto& k : kernels) s.kernels.push_back(parse_kernel_type(k));
  s.hs = hs;
  s.forms.clear();
  for (const auto& f : forms) s.forms.push_back(parse_momentum_form(f));
  s.direction = compression ? LoadDirection::Compression : LoadDirection::Tension;
  s.options.route = parse_critical_load_route(route);
  s.options.assembled.method = parse_critical_load_method(method);
  s.options.assembled.backend = parse_eigen_backend(backend);
  s.options.assembled.criterion = parse_criterion(criterion);
  std::vector<CriticalStrainCase<Dim>> cases;
  {
    py::gil_scoped_release release;
    cases = critical_strain_sweep(s);
  }
  std::vector<StrainCase> out;
  for (const auto& c : cases) {
    const CriticalLoadResult& r = c.result;
    out.push_back({.kernel = kernel_name(c.problem.kernel),
                   .form = momentum_form_name(c.problem.form),
                   .lattice = lattice_name(c.problem.lattice),
                   .route = critical_load_route_name(r.route),
                   .route_reason = r.route_reason,
                   .criterion = criterion_name(r.criterion),
                   .method = r.method,
                   .backend = r.backend,
                   .status = status_name(r.status),
                   .reason = r.reason,
                   .dim = Dim,
                   .n = c.problem.n,
                   .h_over_dx = c.problem.h,
                   .ecrit = r.load,
                   .ecrit_eig = r.load_eigen,
                   .ecrit_bisect = r.load_bisection,
                   .ecrit_infinite = c.infinite.e,
                   .mode_kx_over_pi = r.mode_wavevector.kx_over_pi,
                   .mode_ky_over_pi = r.mode_wavevector.ky_over_pi,
                   .memory_estimate = r.memory_estimate});
  }
  return out;
}

}  // namespace

void bind_critical_loads(py::module_& m) {
  m.def("_elastic_linearisation", &elastic_linearisation, py::arg("dim"), py::arg("n"), py::arg("kernel"),
        py::arg("h"), py::arg("form"), py::arg("lattice"), py::arg("lam"), py::arg("mu"), py::arg("prestrain"));

  py::class_<StrainCase>(m, "CriticalStrainCase",
                         "One (kernel, h, form) of a lattice's critical pre-strain through the critical-load front "
                         "door, as a row of `sphstab tcrit --dim 2|3`.")
      .def_readonly("kernel", &StrainCase::kernel)
      .def_readonly("form", &StrainCase::form)
      .def_readonly("lattice", &StrainCase::lattice)
      .def_readonly("dim", &StrainCase::dim)
      .def_readonly("n", &StrainCase::n)
      .def_readonly("h_over_dx", &StrainCase::h_over_dx)
      .def_readonly("ecrit", &StrainCase::ecrit)
      .def_readonly("ecrit_eig", &StrainCase::ecrit_eig)
      .def_readonly("ecrit_bisect", &StrainCase::ecrit_bisect)
      .def_readonly("ecrit_infinite", &StrainCase::ecrit_infinite)
      .def_readonly("mode_kx_over_pi", &StrainCase::mode_kx_over_pi)
      .def_readonly("mode_ky_over_pi", &StrainCase::mode_ky_over_pi)
      .def_readonly("route", &StrainCase::route)
      .def_readonly("route_reason", &StrainCase::route_reason)
      .def_readonly("criterion", &StrainCase::criterion)
      .def_readonly("method", &StrainCase::method)
      .def_readonly("backend", &StrainCase::backend)
      .def_readonly("memory_estimate", &StrainCase::memory_estimate)
      .def_readonly("status", &StrainCase::status)
      .def_readonly("reason", &StrainCase::reason);

  m.def(
      "_critical_strain",
      [](int dim, const std::string& lattice, int n, bool periodic, const std::vector<std::string>& kernels,
         const std::vector<double>& hs, const std::vector<std::string>& forms, double lambda, double mu,
         const std::string& prestrain, bool compression, const std::string& route, const std::string& method,
         const std::string& backend, const std::string& criterion) {
        if (dim == 2)
          return sweep<2>(lattice, n, periodic, kernels, hs, forms, lambda, mu, prestrain, compression, route, method,
                          backend, criterion);
        if (dim == 3)
          return sweep<3>(lattice, n, periodic, kernels, hs, forms, lambda, mu, prestrain, compression, route, method,
                          backend, criterion);
        throw std::invalid_argument("critical_strain: dim must be 2 or 3 (got " + std::to_string(dim) + ")");
      },
      py::arg("dim"), py::arg("lattice"), py::arg("n"), py::arg("periodic"), py::arg("kernels"), py::arg("hs"),
      py::arg("forms"), py::arg("lam"), py::arg("mu"), py::arg("prestrain"), py::arg("compression"), py::arg("route"),
      py::arg("method"), py::arg("backend"), py::arg("criterion"));
}

}  // namespace sphstab::python
