// The compiled part of the Python package sphstab (python/sphstab/__init__.py wraps it): the library's own front doors,
// no second copy of their logic. Errors: std::invalid_argument -> ValueError and other std::exception -> RuntimeError
// (pybind11's translation), MemoryLimitError -> sphstab.MemoryLimitError (a RuntimeError); the message is the
// library's one line, the same text the CLI prints after "sphstab: error: ".
#include "bindings.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/threads.hpp"

PYBIND11_MODULE(_sphstab, m) {
  namespace py = pybind11;
  m.doc() = "sphstab: stability of SPH for elastic solids (the C++ library's front doors)";
  py::register_exception<sphstab::MemoryLimitError>(m, "MemoryLimitError", PyExc_RuntimeError);
  m.def(
      "set_max_memory",
      [](const py::object& limit) {
        // The CLI's --max-memory: bytes, or text such as "4G"; 0 or None: the machine's memory.
        if (limit.is_none()) return sphstab::set_memory_limit_bytes(0);
        if (py::isinstance<py::str>(limit))
          return sphstab::set_memory_limit_bytes(sphstab::parse_memory_size(limit.cast<std::string>()));
        sphstab::set_memory_limit_bytes(limit.cast<double>());
      },
      py::arg("limit"),
      "The memory the size estimates allow (the CLI's --max-memory): bytes or text such as '4G'; None: the "
      "machine's. A computation estimated above it raises MemoryLimitError before it allocates.");
  m.def("max_memory", &sphstab::memory_limit_bytes, "The memory the size estimates allow, in bytes.");
  m.def("set_threads", &sphstab::set_threads, py::arg("threads"),
        "The OpenMP threads of later computations (the CLI's --threads; results are the same bits for any count). "
        "ValueError for threads < 1.");
  m.def("set_fixed_threads", &sphstab::set_fixed_threads, py::arg("fixed"),
        "True: a run steps on exactly threads() threads; False (default): a run with several measures its steps with "
        "them and with one and steps with the faster (the CLI's --fixed-threads; the same bits either way).");
  m.def("threads", &sphstab::max_threads, "The OpenMP threads computations use (default: OMP_NUM_THREADS, else 1).");
  m.def("wait_policy", &sphstab::wait_policy,
        "The OpenMP wait policy in force: 'OMP_WAIT_POLICY=<v>', 'GOMP_SPINCOUNT=<v>' or 'default'; sphstab/__init__.py "
        "sets OMP_WAIT_POLICY=program_wait_policy when the environment chose none.");
  m.attr("program_wait_policy") = sphstab::kProgramWaitPolicy;
  sphstab::python::bind_kernels(m);
  sphstab::python::bind_particles(m);
  sphstab::python::bind_stability(m);
  sphstab::python::bind_scenes(m);
  sphstab::python::bind_critical_loads(m);
}
