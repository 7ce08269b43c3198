// Particle sets and lattices (particles/), neighbour lists (neighbours/), the operator matrices W, G, H and the kernel
// corrections (operators/), for 1, 2 and 3 dimensions.
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bindings.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/correction.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab::python {

namespace {

const char* const kAxis[3] = {"x", "y", "z"};

template <int Dim>
ParticleSet<Dim> particle_set_from_arrays(const Eigen::MatrixXd& x, const Eigen::VectorXd& volume,
                                          const std::optional<std::vector<bool>>& fixed, double spacing) {
  if (x.cols() != Dim)
    throw std::invalid_argument("ParticleSet" + std::to_string(Dim) + "D: x must have " + std::to_string(Dim) +
                                " columns (got " + std::to_string(x.cols()) + ")");
  ParticleSet<Dim> p;
  p.x = x;
  p.volume = volume;
  p.role.assign(x.rows(), Role::Free);
  if (fixed) {
    if (static_cast<Eigen::Index>(fixed->size()) != x.rows())
      throw std::invalid_argument("ParticleSet" + std::to_string(Dim) + "D: fixed must have " +
                                  std::to_string(x.rows()) + " entries (got " + std::to_string(fixed->size()) + ")");
    for (Eigen::Index i = 0; i < x.rows(); ++i) p.role[i] = (*fixed)[i] ? Role::Fixed : Role::Free;
  }
  p.spacing = spacing;
  p.validate(Dim == 1 ? "ParticleSet1D" : Dim == 2 ? "ParticleSet2D" : "ParticleSet3D");
  return p;
}

template <int Dim>
void bind_particle_set(py::module_& m) {
  using Set = ParticleSet<Dim>;
  const std::string name = "ParticleSet" + std::to_string(Dim) + "D";
  py::class_<Set>(m, name.c_str(), "Particles: positions (N x dim), volumes, fixed flags, boundary depth, box.")
      .def(py::init(&particle_set_from_arrays<Dim>), py::arg("x"), py::arg("volume"), py::arg("fixed") = py::none(),
           py::arg("spacing") = 0.0)
      .def_property_readonly("dim", [](const Set&) { return Dim; })
      .def_property_readonly("size", &Set::size)
      .def_property_readonly("x", [](const Set& p) { return Eigen::MatrixXd(p.x); })
      .def_readonly("volume", &Set::volume)
      .def_property_readonly("fixed",
                             [](const Set& p) {
                               py::array_t<bool> f(p.size());
                               for (int i = 0; i < p.size(); ++i) f.mutable_data()[i] = p.role[i] == Role::Fixed;
                               return f;
                             })
      .def_readonly("depth", &Set::depth)
      .def_property_readonly("periodic", [](const Set& p) { return std::vector<bool>(p.periodic.begin(), p.periodic.end()); })
      .def_property_readonly("box_lo", [](const Set& p) { return Eigen::VectorXd(p.box_lo.transpose()); })
      .def_property_readonly("box_hi", [](const Set& p) { return Eigen::VectorXd(p.box_hi.transpose()); })
      .def_readonly("spacing", &Set::spacing)
      .def("__len__", &Set::size);
}

template <int Dim>
Operators<Dim, double> assemble(const ParticleSet<Dim>& set, const NeighbourList& nl, const Kernel<Dim>& kernel,
                                double h, bool hessian) {
  return assemble_operators<Dim, double>(set, nl, kernel, h, {.kernel = true, .gradient = true, .hessian = hessian});
}

/// W, G_a, the corrected G (G_<correction>_a) and H_ab (a <= b) as CSR tuples, named as `sphstab operators` names
/// its .mtx files (without the extension).
template <int Dim>
py::dict operators(const ParticleSet<Dim>& set, const std::string& kernel_name, double h, bool hessian,
                   const std::string& correction_name_, const std::string& counting, bool polish_free) {
  if (!(h > 0) || !std::isfinite(h)) throw std::invalid_argument("operators: h must be finite and > 0");
  const Correction correction = parse_correction(correction_name_);
  const Kernel<Dim> kernel(parse_kernel_type(kernel_name));
  CorrectionOptions<Dim> copt;
  copt.counting = parse_neighbour_counting(counting);
  copt.polish_free_only = polish_free;
  Operators<Dim, double> ops;
  std::array<SparseMatrix<>, Dim> corrected;
  {
    py::gil_scoped_release release;  // the computation touches no Python object
    const NeighbourList nl = find_neighbours(set, kernel.support_radius(h));
    ops = assemble(set, nl, kernel, h, hessian);
    // Called for "none" too, so that options which do not apply to the correction are refused (as the CLI does).
    corrected = apply_correction<Dim, double>(correction, set, nl, ops, copt);
  }
  py::dict out;
  out["W"] = csr_arrays(std::move(ops.W));
  for (int a = 0; a < Dim; ++a) out[(std::string("G_") + kAxis[a]).c_str()] = csr_arrays(std::move(ops.G[a]));
  if (correction != Correction::None)
    for (int a = 0; a < Dim; ++a)
      out[("G_" + correction_name(correction) + "_" + kAxis[a]).c_str()] = csr_arrays(std::move(corrected[a]));
  if (hessian)
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b)
        out[(std::string("H_") + kAxis[a] + kAxis[b]).c_str()] = csr_arrays(std::move(ops.H[a][b]));
  return out;
}

template <int Dim>
void bind_dim(py::module_& m) {
  bind_particle_set<Dim>(m);
  m.def(
      "neighbours",
      [](const ParticleSet<Dim>& p, double radius) { return find_neighbours(p, radius); }, py::arg("particles"),
      py::arg("radius"), "The neighbour list: every j with |x_i - x_j| < radius (i itself included), rows sorted.");
  m.def("_operators", &operators<Dim>, py::arg("particles"), py::arg("kernel"), py::arg("h"), py::arg("hessian"),
        py::arg("correction"), py::arg("counting"), py::arg("polish_free"));
}

}  // namespace

void bind_particles(py::module_& m) {
  py::class_<NeighbourList>(m, "NeighbourList", "CSR neighbour pairs: row i is indices[offsets[i]:offsets[i+1]].")
      .def_readonly("offsets", &NeighbourList::offsets)
      .def_readonly("indices", &NeighbourList::indices)
      .def_readonly("radius", &NeighbourList::radius)
      .def_property_readonly("size", &NeighbourList::size)
      .def_property_readonly("nonzeros", &NeighbourList::nonzeros);
  bind_dim<1>(m);
  bind_dim<2>(m);
  bind_dim<3>(m);

  m.def(
      "lattice",
      [](const std::string& type_name, int n, double spacing, int fixed_layers, double support_radius, bool periodic,
         double stretch, double perturbation, std::uint64_t seed) -> py::object {
        const LatticeType type = parse_lattice_type(type_name);
        LatticeOptions o{.spacing = spacing,
                         .fixed_layers = fixed_layers,
                         .support_radius = support_radius,
                         .periodic = periodic,
                         .stretch = stretch,
                         .perturbation = perturbation,
                         .seed = seed};
        if (n <= 0) throw std::invalid_argument("--n must be > 0 (got " + std::to_string(n) + ")");
        if (type == LatticeType::Line) return py::cast(make_lattice<1>(type, n, o));
        if (type == LatticeType::Cubic) return py::cast(make_lattice<3>(type, n, o));
        return py::cast(make_lattice<2>(type, n, o));
      },
      py::arg("type"), py::arg("n"), py::arg("spacing") = 1.0, py::arg("fixed_layers") = -1,
      py::arg("support_radius") = 0.0, py::arg("periodic") = false, py::arg("stretch") = 1.0,
      py::arg("perturbation") = 0.0, py::arg("seed") = 1,
      "A regular lattice of n free particles per side (line: 1D; square, hex, face-centred: 2D; cubic: 3D), free "
      "block first, then the fixed layers (-1: as many as support_radius needs), or periodic.");
}

}  // namespace sphstab::python
