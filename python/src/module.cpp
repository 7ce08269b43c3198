// The compiled part of the Python package sphstab (python/sphstab/__init__.py wraps it): the library's own front doors,
// no second copy of their logic. Errors: std::invalid_argument -> ValueError and other std::exception -> RuntimeError
// (pybind11's translation), MemoryLimitError -> sphstab.MemoryLimitError (a RuntimeError); the message is the
// library's one line, the same text the CLI prints after "sphstab: error: ".
#include "bindings.hpp"
#include "sphstab/core/memory_budget.hpp"

PYBIND11_MODULE(_sphstab, m) {
  namespace py = pybind11;
  m.doc() = "sphstab: stability of SPH for elastic solids (the C++ library's front doors)";
  py::register_exception<sphstab::MemoryLimitError>(m, "MemoryLimitError", PyExc_RuntimeError);
  sphstab::python::bind_kernels(m);
  sphstab::python::bind_particles(m);
  sphstab::python::bind_stability(m);
  sphstab::python::bind_scenes(m);
  sphstab::python::bind_critical_loads(m);
}
