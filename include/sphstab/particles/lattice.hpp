#pragma once
/// \file lattice.hpp
/// Regular particle lattices with fixed boundary layers (Powell ch. 3 §3.2) or periodic boxes.
#include <cstdint>
#include <string>

#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

enum class LatticeType { Line, Square, Hexagonal, FaceCentred, Cubic };

/// Parses "line", "square", "hex" (or "hexagonal"), "face-centred", "cubic"; throws std::invalid_argument otherwise.
LatticeType parse_lattice_type(const std::string& name);
std::string lattice_name(LatticeType type);

struct LatticeOptions {
  double spacing = 1.0;  ///< dx: nearest-neighbour distance (hex: distance within a row)
  /// Number of fixed layers around the free block; -1 chooses fixed_layers_needed(support_radius, dx). Must be
  /// -1 or 0 for a periodic lattice.
  int fixed_layers = -1;
  double support_radius = 0;  ///< kernel support (2h by default) used when fixed_layers = -1
  bool periodic = false;      ///< periodic box, no fixed layers
  double stretch = 1.0;       ///< uniform pre-strain: positions, spacing and box scaled by this factor
  double perturbation = 0;    ///< random displacement of free particles, uniform in [-p, p] * dx per axis, p <= 1
  std::uint64_t seed = 1;     ///< seed of the perturbation
};

/// Largest fixed-layer count fixed_layers_needed() returns (beyond it the lattice could not be indexed anyway).
inline constexpr long kMaxFixedLayers = 1L << 29;

/// Layers k = 1, 2, ... with k dx <= support_radius (to a relative 1e-9): the fixed layers that complete every
/// free particle's neighbourhood on a line or square lattice. A layer at exactly the support radius is
/// included so that rounding in the neighbour search can never leave a free neighbourhood one-sided.
/// Throws std::invalid_argument for lengths outside check_length()'s range, std::length_error above kMaxFixedLayers.
int fixed_layers_needed(double support_radius, double dx);

/// Regular lattice of n free particles per side (n^Dim free particles), free block first in the ordering,
/// then the fixed layers. Particle i of the free block sits at (i + 1/2) dx, so the free block spans
/// [0, n dx]^Dim; fixed layers continue the lattice outwards.
/// Hexagonal (Dim 2): rows dy = dx sqrt(3)/2 apart, odd rows shifted by dx/2 (all six nearest neighbours at
/// dx). FaceCentred (Dim 2, Gray, Monaghan & Swift 2001 §5): rows dx apart, odd rows shifted by dx/2.
/// Both need even n when periodic. Volumes: dx^Dim, hexagonal dx*dy.
/// Fixed layers (when not periodic) fill the index rectangle around the free block: k layers per axis, k the
/// smallest count that contains every lattice point within support_radius of a free particle.
/// Errors (one line each): spacing or support radius outside check_length()'s range; fixed_layers < -1, or > 0 with
/// periodic; more than kMaxIndexCount particles (std::length_error); the estimated memory above the limit
/// (MemoryLimitError, memory_budget.hpp) -- all checked before anything is allocated.
template <int Dim>
ParticleSet<Dim> make_lattice(LatticeType type, int n, const LatticeOptions& options);

}  // namespace sphstab
