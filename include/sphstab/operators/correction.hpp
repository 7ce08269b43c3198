#pragma once
/// \file correction.hpp
/// Kernel corrections by name, and one entry point that applies a correction to the gradient matrices of
/// assemble_operators (used by `sphstab operators --correction NAME`).
///
/// | name                    | operator (per axis)                                         | header             |
/// |-------------------------|-------------------------------------------------------------|--------------------|
/// | none                    | G                                                           | operators.hpp      |
/// | minus                   | G - diag(G 1), Powell (1.15)                                | minus_gradient.hpp |
/// | shepard                 | Shepard gradient, Powell (3.61)                             | shepard.hpp        |
/// | column-shepard          | column Shepard gradient, Powell (3.62) as printed           | column_shepard.hpp |
/// | ncsph                   | normalised-corrected gradient, Powell (1.19)                | ncsph.hpp          |
/// | local-polish            | C_ij, Powell (4.9) / algorithm 4.1                          | local_polish.hpp   |
/// | mean-polish             | global row+column mean polish, algorithm 3.1 / (3.64), dense| mean_polish.hpp    |
/// | shepard-column-polish   | Shepard then column mean polish, ch. 3 §4.1.1 item 4, dense | mean_polish.hpp    |
#include <array>
#include <complex>
#include <string>
#include <vector>

#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/local_polish.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/operators/shepard.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

enum class Correction { None, Minus, Shepard, ColumnShepard, Ncsph, LocalPolish, MeanPolish, ShepardColumnPolish };

/// Parses "none", "minus", "shepard", "column-shepard", "ncsph", "local-polish", "mean-polish",
/// "shepard-column-polish"; throws std::invalid_argument listing the valid names otherwise.
Correction parse_correction(const std::string& name);
/// The canonical name accepted by parse_correction.
std::string correction_name(Correction correction);
/// All corrections, in declaration order.
const std::vector<Correction>& all_corrections();
/// True for the global polishes, whose result is dense (every entry stored).
bool correction_is_dense(Correction correction);

/// Options of apply_correction.
template <int Dim>
struct CorrectionOptions {
  /// local-polish: how n_i is counted.
  NeighbourCounting counting = NeighbourCounting::Actual;
  /// local-polish: when non-null, the means use the first-step Shepard gradient (4.18) with these per-axis
  /// reference sums (e.g. shepard_reference of the operators at t = 0).
  const std::array<ShepardReference, Dim>* reference = nullptr;
  /// mean-polish: polish over the free particles only (N = number of free particles) instead of all.
  bool polish_free_only = false;
  /// ncsph: smallest accepted reciprocal condition number of the moment matrices.
  double min_rcond = 1e-12;
};

/// Applies a correction to the gradient matrices ops.G (ops.W is needed by shepard, column-shepard, ncsph,
/// shepard-column-polish and the (4.18) option). Returns G[a] corrected, N x N; the dense polishes come back
/// as sparse matrices with all N^2 entries stored (dense_to_sparse_all_entries).
/// @param[in] positions  as for ncsph_gradient (optional; the positions the operators were assembled at).
/// Throws std::invalid_argument for missing operators, size mismatches, a singular NCSPH moment matrix, or an
/// option that does not apply to the correction.
template <int Dim, class Scalar>
std::array<SparseMatrix<Scalar>, Dim> apply_correction(Correction correction, const ParticleSet<Dim>& particles,
                                                       const NeighbourList& neighbours,
                                                       const Operators<Dim, Scalar>& ops,
                                                       const CorrectionOptions<Dim>& options = {},
                                                       const Positions<Dim, Scalar>* positions = nullptr);

}  // namespace sphstab
