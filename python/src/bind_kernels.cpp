// Kernels W(r, h) and their derivatives in 1, 2 and 3 dimensions (kernel/kernel.hpp), and the lattice Fourier symbols
// of the 1D pre-stressed bar (spectral/fourier_symbol.hpp).
#include <stdexcept>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"

namespace sphstab::python {

namespace {

/// A kernel of dimension 1, 2 or 3: the three Kernel<Dim> objects behind one Python type.
struct AnyKernel {
  int dim = 1;
  KernelType type = KernelType::CubicSpline;

  template <class F>
  auto visit(F&& f) const {
    switch (dim) {
      case 1:
        return f(Kernel<1>(type));
      case 2:
        return f(Kernel<2>(type));
      default:
        return f(Kernel<3>(type));
    }
  }
};

AnyKernel make_kernel(const std::string& name, int dim) {
  if (dim < 1 || dim > 3) throw std::invalid_argument("kernel: dim must be 1, 2 or 3 (got " + std::to_string(dim) + ")");
  return {dim, parse_kernel_type(name)};
}

/// order 0, 1, 2: W, dW/dr, d2W/dr2 at every r (any shape), for h > 0.
py::array_t<double> evaluate(const AnyKernel& k, py::array_t<double, py::array::c_style | py::array::forcecast> r,
                             double h, int order) {
  if (!(h > 0) || !std::isfinite(h)) throw std::invalid_argument("kernel: h must be finite and > 0");
  py::array_t<double> out(r.request().shape);
  const double* in = r.data();
  double* res = out.mutable_data();
  const py::ssize_t n = r.size();
  k.visit([&](const auto& kernel) {
    for (py::ssize_t i = 0; i < n; ++i)
      res[i] = order == 0 ? kernel.value(in[i], h) : order == 1 ? kernel.d1(in[i], h) : kernel.d2(in[i], h);
    return 0;
  });
  return out;
}

}  // namespace

void bind_kernels(py::module_& m) {
  m.def(
      "kernel_names",
      [] {
        std::vector<std::string> names;
        for (KernelType t : all_kernel_types()) names.push_back(kernel_name(t));
        return names;
      },
      "The kernels' names, as `sphstab kernels` lists them.");

  py::class_<AnyKernel>(m, "Kernel", "A smoothing kernel W(r, h) of dimension 1, 2 or 3 (support 2h by default).")
      .def(py::init(&make_kernel), py::arg("name") = "cubic", py::arg("dim") = 1)
      .def_property_readonly("name", [](const AnyKernel& k) { return kernel_name(k.type); })
      .def_readonly("dim", &AnyKernel::dim)
      .def(
          "support_radius",
          [](const AnyKernel& k, double h) { return k.visit([&](const auto& w) { return w.support_radius(h); }); },
          py::arg("h"))
      .def(
          "value", [](const AnyKernel& k, py::array_t<double> r, double h) { return evaluate(k, r, h, 0); },
          py::arg("r"), py::arg("h"), "W(r, h) at every r")
      .def(
          "d1", [](const AnyKernel& k, py::array_t<double> r, double h) { return evaluate(k, r, h, 1); },
          py::arg("r"), py::arg("h"), "dW/dr at every r")
      .def(
          "d2", [](const AnyKernel& k, py::array_t<double> r, double h) { return evaluate(k, r, h, 2); },
          py::arg("r"), py::arg("h"), "d2W/dr2 at every r")
      .def("__repr__", [](const AnyKernel& k) {
        return "sphstab.Kernel('" + kernel_name(k.type) + "', dim=" + std::to_string(k.dim) + ")";
      });

  m.def(
      "fourier_symbol_1d",
      [](const std::string& kernel, double h, double dx, py::array_t<double, py::array::c_style | py::array::forcecast> k) {
        const Kernel<1> w(parse_kernel_type(kernel));
        py::array_t<double> g(k.request().shape), l(k.request().shape);
        for (py::ssize_t i = 0; i < k.size(); ++i) {
          const FourierSymbol1D s = fourier_symbol_1d(w, h, dx, k.data()[i]);
          g.mutable_data()[i] = s.g_abs2;
          l.mutable_data()[i] = s.l_hat;
        }
        return py::make_tuple(g, l);
      },
      py::arg("kernel"), py::arg("h"), py::arg("dx"), py::arg("k"),
      "(|g^(k)|^2, L^(k)) of the infinite 1D lattice (Powell (3.40) in Fourier space): the gradient's and the "
      "pre-stress operator's symbols at wavenumbers k.");
}

}  // namespace sphstab::python
