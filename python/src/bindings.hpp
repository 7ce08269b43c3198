#pragma once
// The pieces of the Python module _sphstab (module.cpp): each bind_*.cpp registers one family of the library's front
// doors. Helpers shared by them live here.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "sphstab/growth/state_stability.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab::python {

namespace py = pybind11;

void bind_kernels(py::module_& m);    // kernels, Fourier symbols
void bind_particles(py::module_& m);  // particle sets, lattices, neighbour lists, operators and corrections
void bind_stability(py::module_& m);  // critical tension, the stability of a given state
void bind_scenes(py::module_& m);     // scenes and the run loop
void bind_critical_loads(py::module_& m);  // elastic linearisations, critical pre-strain of 2D/3D lattices

/// A compressed row-major sparse matrix as the tuple (data, indices, indptr, (rows, cols)) of NumPy arrays that view
/// its storage without a copy: the matrix is moved to the heap and owned by a capsule that every array keeps alive.
/// scipy.sparse.csr_matrix((data, indices, indptr), shape=shape, copy=False) then shares the memory (sphstab/__init__.py).
inline py::tuple csr_arrays(SparseMatrix<> matrix) {
  auto* owned = new SparseMatrix<>(std::move(matrix));
  owned->makeCompressed();
  py::capsule owner(owned, [](void* p) { delete static_cast<SparseMatrix<>*>(p); });
  const auto nnz = static_cast<py::ssize_t>(owned->nonZeros());
  py::array_t<double> data({nnz}, {sizeof(double)}, owned->valuePtr(), owner);
  py::array_t<int> indices({nnz}, {sizeof(int)}, owned->innerIndexPtr(), owner);
  py::array_t<int> indptr({static_cast<py::ssize_t>(owned->outerSize() + 1)}, {sizeof(int)}, owned->outerIndexPtr(),
                          owner);
  return py::make_tuple(data, indices, indptr, py::make_tuple(owned->rows(), owned->cols()));
}

/// A particle state as the dict of arrays state_stability takes (x, v, density, deviator, mass, fixed, h, spacing):
/// what read_particle_state and Scene.state return.
template <int Dim>
py::dict state_dict(const ParticleState<Dim>& s) {
  py::dict d;
  d["x"] = s.x;
  d["v"] = s.v;
  d["density"] = s.density;
  d["deviator"] = s.deviator;
  d["mass"] = s.mass;
  d["fixed"] = s.fixed;
  d["h"] = s.h;
  d["spacing"] = s.spacing;
  return d;
}

}  // namespace sphstab::python
