#include "sphstab/particles/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/numerics/instantiation.hpp"

namespace sphstab {

constexpr NamedValue<LatticeType> kLatticeNames[] = {{LatticeType::Line, "line"},
                                                     {LatticeType::Square, "square"},
                                                     {LatticeType::Hexagonal, "hex"},
                                                     {LatticeType::Hexagonal, "hexagonal"},
                                                     {LatticeType::FaceCentred, "face-centred"},
                                                     {LatticeType::FaceCentred, "fcc"},
                                                     {LatticeType::Cubic, "cubic"}};

LatticeType parse_lattice_type(const std::string& name) { return parse_named(name, kLatticeNames, "lattice"); }
std::string lattice_name(LatticeType type) { return name_of(type, kLatticeNames); }

int fixed_layers_needed(double support_radius, double dx) {
  check_length(dx, "fixed_layers_needed: spacing");
  check_length(support_radius, "fixed_layers_needed: support radius");
  // Every k with k dx < support_radius, plus a borderline layer at exactly the support (to rounding): the
  // neighbour search's strict r < radius may include or exclude it after rounding, and a kernel that does not
  // vanish continuously at its support (truncated Gaussian) must see the same layer on both sides.
  return static_cast<int>(checked_floor_count(support_radius / dx * (1 + 1e-9), kMaxFixedLayers,
                                              "fixed layers (support radius / spacing)"));
}

template <int Dim>
ParticleSet<Dim> make_lattice(LatticeType type, int n, const LatticeOptions& opt) {
  const bool dim_ok =
      (type == LatticeType::Line && Dim == 1) ||
      ((type == LatticeType::Square || type == LatticeType::Hexagonal || type == LatticeType::FaceCentred) &&
       Dim == 2) ||
      (type == LatticeType::Cubic && Dim == 3);
  if (!dim_ok)
    throw std::invalid_argument("make_lattice: lattice '" + lattice_name(type) + "' does not exist in dimension " +
                                std::to_string(Dim));
  if (n <= 0)
    throw std::invalid_argument("make_lattice: number of particles per side must be > 0 (got " + std::to_string(n) +
                                ")");
  const double dx = opt.spacing;
  check_length(dx, "make_lattice: spacing");
  if (opt.fixed_layers < -1)
    throw std::invalid_argument(
        "make_lattice: fixed_layers must be >= 0, or -1 for as many as the support needs (got " +
        std::to_string(opt.fixed_layers) + ")");
  if (opt.periodic && opt.fixed_layers > 0)
    throw std::invalid_argument("make_lattice: a periodic lattice has no fixed layers (got fixed_layers = " +
                                std::to_string(opt.fixed_layers) + ")");
  if (!(opt.stretch > 0) || !std::isfinite(opt.stretch))
    throw std::invalid_argument("make_lattice: stretch must be finite and > 0");
  if (!(opt.perturbation >= 0 && opt.perturbation <= 1))
    throw std::invalid_argument("make_lattice: perturbation must be in [0, 1] spacings (got " +
                                format_number(opt.perturbation) + ")");
  const bool shifted = type == LatticeType::Hexagonal || type == LatticeType::FaceCentred;
  if (opt.periodic && shifted && n % 2 != 0)
    throw std::invalid_argument("make_lattice: periodic hex/face-centred lattices need an even n");

  std::array<double, Dim> step;
  step.fill(dx);
  if (type == LatticeType::Hexagonal) step[1] = dx * std::sqrt(3.0) / 2.0;

  std::array<int, Dim> layers;
  layers.fill(0);
  if (!opt.periodic) {
    if (opt.fixed_layers >= 0) {
      layers.fill(opt.fixed_layers);
    } else {
      check_length(opt.support_radius, "make_lattice: support_radius (to choose the fixed layers)");
      for (int a = 0; a < Dim; ++a) {
        // Shifted rows put a neighbour up to dx/2 further along x.
        double reach = opt.support_radius + ((shifted && a == 0) ? 0.5 * dx : 0.0);
        layers[a] = fixed_layers_needed(reach, step[a]);
      }
    }
  }

  // Enumerate the index box; free block first, then fixed particles, each in lexicographic order. Sizes are counted
  // in checked arithmetic and the memory is estimated before anything is allocated.
  std::array<int, Dim> lo, extent;
  long total = 1, free_count = 1;
  for (int a = 0; a < Dim; ++a) {
    lo[a] = -layers[a];
    extent[a] = checked_index_count(checked_add(n, checked_mul(2, layers[a], "make_lattice"), "make_lattice"),
                                    "make_lattice: particles per side (free + fixed layers)");
    total = checked_mul(total, extent[a], "make_lattice: particle count");
    free_count = checked_mul(free_count, n, "make_lattice: free particle count");
  }
  checked_index_count(total, "make_lattice: particle count");
  require_memory(static_cast<double>(total) * (8.0 * Dim + 13.0),
                 "make_lattice: " + std::to_string(total) + " particles");
  ParticleSet<Dim> set;
  set.x.resize(total, Dim);
  set.volume.resize(total);
  set.role.resize(total);
  set.depth.resize(total);
  const double volume = (type == LatticeType::Hexagonal) ? dx * step[1] : std::pow(dx, Dim);
  long next_free = 0, next_fixed = free_count;
  for (long flat = 0; flat < total; ++flat) {
    std::array<int, Dim> idx;
    long rest = flat;
    for (int a = 0; a < Dim; ++a) {
      idx[a] = lo[a] + static_cast<int>(rest % extent[a]);
      rest /= extent[a];
    }
    bool free = true;
    int depth = opt.periodic ? n : (1 << 29);
    for (int a = 0; a < Dim; ++a) {
      free = free && idx[a] >= 0 && idx[a] < n;
      if (!opt.periodic) depth = std::min({depth, idx[a] - lo[a], lo[a] + extent[a] - 1 - idx[a]});
    }
    long row = free ? next_free++ : next_fixed++;
    for (int a = 0; a < Dim; ++a) set.x(row, a) = (idx[a] + 0.5) * step[a];
    if (shifted && (((idx[1] % 2) + 2) % 2) == 1) set.x(row, 0) += 0.5 * dx;
    set.volume[row] = volume;
    set.role[row] = free ? Role::Free : Role::Fixed;
    set.depth[row] = depth;
  }

  set.spacing = dx;
  if (opt.periodic) {
    set.periodic.fill(true);
    for (int a = 0; a < Dim; ++a) {
      set.box_lo[a] = 0.0;
      set.box_hi[a] = n * step[a];
    }
  }
  if (opt.perturbation > 0) {
    std::mt19937_64 rng(opt.seed);
    std::uniform_real_distribution<double> u(-opt.perturbation * dx, opt.perturbation * dx);
    for (int i = 0; i < set.size(); ++i)
      if (set.role[i] == Role::Free)
        for (int a = 0; a < Dim; ++a) {
          set.x(i, a) += u(rng);
          if (set.periodic[a]) {  // wrap back into the box
            double L = set.box_hi[a] - set.box_lo[a];
            set.x(i, a) -= L * std::floor((set.x(i, a) - set.box_lo[a]) / L);
          }
        }
  }
  if (opt.stretch != 1.0) {
    set.x *= opt.stretch;
    set.volume *= std::pow(opt.stretch, Dim);
    set.spacing *= opt.stretch;
    set.box_lo *= opt.stretch;
    set.box_hi *= opt.stretch;
  }
  return set;
}

#define SPHSTAB_INSTANTIATE(D) template ParticleSet<D> make_lattice<D>(LatticeType, int, const LatticeOptions&);
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
