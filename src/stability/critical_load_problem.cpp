#include "sphstab/stability/critical_load_problem.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/forms/discretisation.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/lattice_sine_preconditioner.hpp"
#include "sphstab/stability/lattice_stencil.hpp"

namespace sphstab {

constexpr NamedValue<CriticalLoadRoute> kRouteNames[] = {{CriticalLoadRoute::Auto, "auto"},
                                                         {CriticalLoadRoute::Assembled, "assembled"},
                                                         {CriticalLoadRoute::MatrixFree, "matrix-free"},
                                                         {CriticalLoadRoute::Symbol, "symbol"},
                                                         {CriticalLoadRoute::Distributed, "distributed"},
                                                         {CriticalLoadRoute::Distributed, "petsc"}};

CriticalLoadRoute parse_critical_load_route(const std::string& name) {
  return parse_named(name, kRouteNames, "critical-load route");
}
std::string critical_load_route_name(CriticalLoadRoute route) { return name_of(route, kRouteNames); }

int probe_lattice_size(double support_over_dx) { return 2 * static_cast<int>(std::ceil(2 * support_over_dx)) + 3; }

namespace {

template <int Dim>
double support_of(const ElasticLatticeProblem<Dim>& p) {
  return Kernel<Dim>(p.kernel).support_radius(p.h);
}

/// The lattice, neighbours, G and H, the Jacobian (analytic_jacobian_2d.cpp) and, for a dense route, dense copies.
/// The Cholesky factor's fill is checked by CHOLMOD's analysis (cholmod_factor.cpp).
double assembled_2d_bytes(int n, double support, bool dense) {
  const double side = n + 2.0 * std::floor(support + 2), particles = side * side, nf = double(n) * n;
  const double q = std::min(particles, 1 + M_PI * support * support),
               q2 = std::min(particles, 1 + 4 * M_PI * support * support);
  return 25 * particles + 66 * particles * q + 96 * nf * (q + q2) + (dense ? 160.0 * nf * nf : 0.0);
}

/// The matrix-free route on a square (cubic) lattice: the particle set and neighbour list the linearisation is built
/// from (about 40 + 4 q bytes per particle, q neighbours within the support), the linearisation by offset (its free
/// positions and index, and Dim + Dim (Dim + 1) / 2 values per site of the free box padded by 2 floor(support):
/// MatrixFreeLinearisation::estimated_bytes) and BlockLobpcg's blocks (10 b + 8 vectors of Dim doubles per free
/// particle, b = 4). Measured peaks: results/critical-strain-large (2D) and results/critical-strain-3d.
template <int Dim>
double matrix_free_bytes(int n, double support) {
  const double side = n + 2.0 * std::floor(support + 2), grid_side = n + 4.0 * std::floor(support);
  const double particles = std::pow(side, Dim), nf = std::pow(double(n), Dim), grid = std::pow(grid_side, Dim);
  const double ball = Dim == 2 ? M_PI * support * support : 4.0 / 3.0 * M_PI * support * support * support;
  const double q = std::min(particles, 1 + ball);
  return particles * (40 + 4 * q) + nf * (4 + 8 * Dim) + 8.0 * (Dim + Dim * (Dim + 1) / 2) * grid + nf * 8 * Dim * 48;
}

template <int Dim>
std::string default_label(const ElasticLatticeProblem<Dim>& p, CriticalLoadRoute route) {
  return "critical_load: " + std::to_string(Dim) + "D " + lattice_name(p.lattice) + " n = " + std::to_string(p.n) +
         " h/dx = " + format_number(p.h, 12) + " " + critical_load_route_name(route) + " route";
}

bool fits(double bytes) {
  try {
    require_memory(bytes, "");
    return true;
  } catch (const MemoryLimitError&) {
    return false;
  }
}

template <int Dim>
void require_route_memory(const ElasticLatticeProblem<Dim>& p, CriticalLoadRoute route, double bytes,
                          const CriticalLoadRouteOptions& o) {
  require_memory(bytes, o.memory_label ? o.memory_label(route) : default_label(p, route));
}

template <int Dim>
void validate(const ElasticLatticeProblem<Dim>& p) {
  if (p.n < 1) throw std::invalid_argument("critical_load: n = " + std::to_string(p.n) + " (need >= 1)");
  if (!(p.h > 0) || !std::isfinite(p.h))
    throw std::invalid_argument("critical_load: h/dx = " + format_number(p.h, 12) + " (> 0)");
  if (Dim == 3 && (p.lattice != LatticeType::Cubic || p.periodic))
    throw std::invalid_argument("critical_load: 3D problems are cubic lattices with fixed layers");
  if (Dim == 2 && p.lattice != LatticeType::Square && p.lattice != LatticeType::Hexagonal &&
      p.lattice != LatticeType::FaceCentred)
    throw std::invalid_argument("critical_load: 2D lattice '" + lattice_name(p.lattice) +
                                "' (use square, hex or face-centred)");
}

/// The matrix-free route applies: square (cubic) lattice with fixed layers (the sine preconditioner's geometry).
template <int Dim>
bool matrix_free_applies(const ElasticLatticeProblem<Dim>& p) {
  return !p.periodic && p.lattice == (Dim == 2 ? LatticeType::Square : LatticeType::Cubic);
}

template <int Dim>
std::shared_ptr<const Discretisation<Dim>> lattice_discretisation(const ElasticLatticeProblem<Dim>& p, int n) {
  const Kernel<Dim> kernel(p.kernel);
  if constexpr (Dim == 2) {
    return make_discretisation(strain_lattice_2d(p.lattice, kernel, p.h, n, p.periodic), kernel, p.h);
  } else {
    return make_discretisation(
        make_lattice<3>(LatticeType::Cubic, n, {.spacing = 1.0, .support_radius = kernel.support_radius(p.h)}), kernel,
        p.h);
  }
}

template <int Dim>
MatrixFreeLinearisation<Dim> matrix_free_of(const ElasticLatticeProblem<Dim>& p, int n) {
  return MatrixFreeLinearisation<Dim>(*lattice_discretisation(p, n), p.material, p.form, p.prestrain);
}

template <int Dim>
Linearisation assembled_of(const ElasticLatticeProblem<Dim>& p) {
  if constexpr (Dim == 2) {
    return analytic_jacobian_2d(*lattice_discretisation(p, p.n), p.material, p.form, p.prestrain);
  } else {
    return assemble_by_products(matrix_free_of(p, p.n));
  }
}

void fill_from_assembled(CriticalLoadResult& r, const CriticalLoad& c, const CriticalLoadOptions& o) {
  r.load = c.load;
  r.load_eigen = c.load_eigen;
  r.load_bisection = c.load_bisection;
  r.relative_difference = c.relative_difference;
  r.criterion = c.criterion;
  r.method = critical_load_method_name(o.method);
  r.backend = c.eigen_backend.empty() ? "none" : c.eigen_backend;
  r.mechanism = c.mechanism;
  r.mode_wavevector = c.mode_wavevector;
  r.status = c.status;
  r.reason = c.reason;
}

/// Block LOBPCG on the matrix-free linearisation. A lattice smaller than the probe size takes the stencil of a
/// probe-size lattice of the same problem; no positive symbol ratio: no shift, so no preconditioner (a fallback).
template <int Dim>
void solve_matrix_free(const ElasticLatticeProblem<Dim>& p, LoadDirection direction,
                       const CriticalLoadRouteOptions& options, CriticalLoadResult& r) {
  const MatrixFreeLinearisation<Dim> lin = matrix_free_of(p, p.n);
  MatrixFreeCriticalLoadOptions o = options.matrix_free;
  const int probe_n = probe_lattice_size(support_of(p));
  MatrixFreeCriticalLoad m;
  bool dropped = false;
  if (o.method != MatrixFreeEigenMethod::BlockLobpcg || o.preconditioner != MatrixFreePreconditioner::LatticeSine ||
      p.n >= probe_n) {
    m = matrix_free_critical_load(lin, direction, o);
    dropped = m.preconditioner.rfind("none (", 0) == 0;
  } else {
    const LatticeStencil<Dim> st = probe_lattice_stencil(matrix_free_of(p, probe_n), direction);
    if (lattice_symbol_ratio_max(st, p.n) > 0) {
      m = matrix_free_critical_load(lin, direction, o, LatticeSinePreconditioner<Dim>(st, p.n, o.margin));
    } else {
      o.preconditioner = MatrixFreePreconditioner::None;  // no shift exists (as the library's own fallback)
      m = matrix_free_critical_load(lin, direction, o);
      m.preconditioner += " (symbol ratio L/K <= 0 on the lattice grid: no interior instability)";
      dropped = true;
    }
  }
  r.load = r.load_eigen = m.load;
  r.criterion = Criterion::Definiteness;
  r.method = "lobpcg";
  r.backend = "matrix-free";
  r.mechanism = std::isfinite(m.load) ? InstabilityMechanism::RealCrossing : InstabilityMechanism::None;
  r.status = m.status;
  r.reason = m.status == Status::Successful
                 ? "block LOBPCG, preconditioner " + m.preconditioner + ": " + std::to_string(m.iterations) +
                       " steps, residual " + format_number(m.residual, 12)
                 : m.reason;
  if (dropped) {
    r.fallback = true;
    r.route_reason += "; fallback: no preconditioner (the lattice symbol has no positive L/K ratio)";
  }
  r.matrix_free = std::move(m);
}

void solve_symbol(const ElasticLatticeProblem<2>& p, LoadDirection direction, CriticalLoadResult& r) {
  const ElasticSymbol2D symbol(p.lattice, Kernel<2>(p.kernel), p.h, 1.0, p.material, p.form, p.prestrain);
  const SymbolCriticalStrain s = critical_strain_periodic_symbol_2d(symbol, p.n, direction);
  r.load = s.e;
  r.criterion = Criterion::Spectrum;
  r.method = "symbol";
  r.backend = "none";
  r.mechanism = s.mechanism;
  r.mode_wavevector.kx_over_pi = s.kx_over_pi;
  r.mode_wavevector.ky_over_pi = s.ky_over_pi;
  r.status = std::isnan(s.e) ? Status::NumericalIssue : Status::Successful;  // NaN: no neighbour
  r.reason = s.reason;
  r.symbol = s;
}

void solve_distributed(const Linearisation& lin, LoadDirection direction, const CriticalLoadRouteOptions& options,
                       CriticalLoadResult& r) {
  const DistributedCriticalLoad d = options.distributed(lin, direction);
  r.load = r.load_eigen = d.load;
  r.criterion = Criterion::Definiteness;
  r.method = d.solver.empty() ? std::string("distributed") : d.solver;
  r.backend = "distributed";
  r.mechanism = std::isfinite(d.load) ? InstabilityMechanism::RealCrossing : InstabilityMechanism::None;
  r.status = d.status;
  r.reason = d.status == Status::Successful
                 ? "distributed on " + std::to_string(d.ranks) + " rank(s) by " + d.solver + ": " +
                       std::to_string(d.iterations) + " iterations; residual " + format_number(d.residual, 12)
                 : d.reason;
  r.distributed = d;
}

}  // namespace

template <int Dim>
double critical_load_memory_bytes(const ElasticLatticeProblem<Dim>& p, CriticalLoadRoute route,
                                  const CriticalLoadRouteOptions& options) {
  const double support = support_of(p);
  const CriticalLoadOptions& a = options.assembled;
  switch (route) {
    case CriticalLoadRoute::Auto:
      throw std::invalid_argument("critical_load_memory_bytes: resolve Auto first (choose_critical_load_route)");
    case CriticalLoadRoute::Symbol:
      return 0;
    case CriticalLoadRoute::MatrixFree:
      return matrix_free_bytes<Dim>(p.n, support);
    case CriticalLoadRoute::Assembled:
    case CriticalLoadRoute::Distributed: {
      // dense copies: the dense backend asked for, or an A small enough for the dense spectrum (non-symmetric A)
      const bool assembled = route == CriticalLoadRoute::Assembled;
      const double dofs = p.dofs();
      const bool dense = assembled && (a.backend == EigenBackend::Dense || dofs <= a.spectrum_dense_max);
      if constexpr (Dim == 2) {
        return assembled_2d_bytes(p.n, support, dense);
      } else {
        // assemble_by_products' bound (dofs^2 / 8) over the matrix-free linearisation it is built from
        return matrix_free_bytes<3>(p.n, support) + dofs * dofs / 8 + (dense ? 40.0 * dofs * dofs : 0.0);
      }
    }
  }
  return 0;
}

template <int Dim>
CriticalLoadRouteChoice choose_critical_load_route(const ElasticLatticeProblem<Dim>& p,
                                                   const CriticalLoadRouteOptions& o) {
  validate(p);
  CriticalLoadRouteChoice c;
  c.route = o.route;
  c.reason = "asked";
  if (o.route == CriticalLoadRoute::Auto) {
    if (p.periodic) {
      c.route = CriticalLoadRoute::Symbol;
      c.reason = "auto: periodic lattice (exact Fourier symbols)";
    } else if (Dim == 3) {
      c.route = CriticalLoadRoute::MatrixFree;
      c.reason = "auto: 3D (matrix-free)";
    } else {
      const double assembled = critical_load_memory_bytes(p, CriticalLoadRoute::Assembled, o);
      const double matrix_free = critical_load_memory_bytes(p, CriticalLoadRoute::MatrixFree, o);
      if (fits(assembled) || !matrix_free_applies(p) || !fits(matrix_free)) {
        c.route = CriticalLoadRoute::Assembled;  // (refused below when it does not fit)
        c.reason = "auto: assembled (~" + format_bytes(assembled) + ")";
      } else {
        c.route = CriticalLoadRoute::MatrixFree;
        c.fallback = true;
        c.reason = "fallback: the assembled route's ~" + format_bytes(assembled) + " does not fit the memory limit (" +
                   format_bytes(memory_limit_bytes()) + " with " + format_bytes(resident_memory_bytes()) +
                   " in use); matrix-free ~" + format_bytes(matrix_free);
      }
    }
  }
  switch (c.route) {
    case CriticalLoadRoute::MatrixFree:
      if (!matrix_free_applies(p))
        throw std::invalid_argument("critical_load: the matrix-free route needs a " +
                                    std::string(Dim == 2 ? "square" : "cubic") +
                                    " lattice with fixed layers (not periodic)");
      break;
    case CriticalLoadRoute::Symbol:
      if (!p.periodic) throw std::invalid_argument("critical_load: the symbol route needs a periodic lattice");
      break;
    case CriticalLoadRoute::Assembled:
    case CriticalLoadRoute::Distributed:
      if (p.periodic)
        throw std::invalid_argument("critical_load: a periodic lattice takes the symbol route (exact Fourier symbols)");
      if (c.route == CriticalLoadRoute::Distributed && !o.distributed)
        throw std::invalid_argument(
            "critical_load: the distributed route needs options.distributed (the PETSc backend: "
            "petsc_critical_load_solver() of library sphstab_petsc, built with SPHSTAB_WITH_PETSC)");
      break;
    case CriticalLoadRoute::Auto:
      break;
  }
  c.memory_estimate = critical_load_memory_bytes(p, c.route, o);
  if (c.route != CriticalLoadRoute::Symbol) require_route_memory(p, c.route, c.memory_estimate, o);
  return c;
}

template <int Dim>
CriticalLoadResult critical_load(const ElasticLatticeProblem<Dim>& p, LoadDirection direction,
                                 const CriticalLoadRouteOptions& options) {
  const CriticalLoadRouteChoice choice = choose_critical_load_route(p, options);
  CriticalLoadResult r;
  r.direction = direction;
  r.route = choice.route;
  r.route_reason = choice.reason;
  r.fallback = choice.fallback;
  r.memory_estimate = choice.memory_estimate;
  switch (choice.route) {
    case CriticalLoadRoute::Assembled: {
      const CriticalLoad c = critical_load(assembled_of(p), direction, options.assembled);
      fill_from_assembled(r, c, options.assembled);
      r.assembled = c;
      break;
    }
    case CriticalLoadRoute::MatrixFree:
      solve_matrix_free(p, direction, options, r);
      break;
    case CriticalLoadRoute::Symbol:
      if constexpr (Dim == 2) solve_symbol(p, direction, r);
      break;
    case CriticalLoadRoute::Distributed:
      solve_distributed(assembled_of(p), direction, options, r);
      break;
    case CriticalLoadRoute::Auto:
      break;
  }
  if (choice.fallback) r.reason = choice.reason + "; " + r.reason;
  return r;
}

template double critical_load_memory_bytes<2>(const ElasticLatticeProblem<2>&, CriticalLoadRoute,
                                              const CriticalLoadRouteOptions&);
template double critical_load_memory_bytes<3>(const ElasticLatticeProblem<3>&, CriticalLoadRoute,
                                              const CriticalLoadRouteOptions&);
template CriticalLoadRouteChoice choose_critical_load_route<2>(const ElasticLatticeProblem<2>&,
                                                               const CriticalLoadRouteOptions&);
template CriticalLoadRouteChoice choose_critical_load_route<3>(const ElasticLatticeProblem<3>&,
                                                               const CriticalLoadRouteOptions&);
template CriticalLoadResult critical_load<2>(const ElasticLatticeProblem<2>&, LoadDirection,
                                             const CriticalLoadRouteOptions&);
template CriticalLoadResult critical_load<3>(const ElasticLatticeProblem<3>&, LoadDirection,
                                             const CriticalLoadRouteOptions&);

}  // namespace sphstab
