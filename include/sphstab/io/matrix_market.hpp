#pragma once
/// \file matrix_market.hpp
/// Matrix Market (.mtx) files for operator matrices, readable by scipy.io.mmread, MATLAB, Julia, Eigen's loadMarket.
/// Sparse matrices are written as "coordinate real general" with every STORED entry (explicit zeros included, so
/// the file shows the operator's pattern; 1-based indices); dense ones as "array real general" (column-major).
/// Values are printed with 17 significant digits (round-trip exact for doubles).
#include <Eigen/Core>
#include <string>

#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// Writes A (every stored entry) to path as coordinate real general. `comment` lines (may contain '\n') follow
/// the banner as "% ..." lines. Throws std::runtime_error if the file cannot be written.
void write_matrix_market(const std::string& path, const SparseMatrix<double>& A, const std::string& comment = "");
/// Writes a dense matrix as array real general (column-major).
void write_matrix_market(const std::string& path, const Eigen::MatrixXd& A, const std::string& comment = "");

/// Reads a real general Matrix Market file (coordinate or array) into a row-major sparse matrix (array files keep
/// every entry; repeated coordinate entries are summed). Throws std::runtime_error for a missing/malformed file or an
/// unsupported field/symmetry (complex, pattern, symmetric).
SparseMatrix<double> read_matrix_market(const std::string& path);

}  // namespace sphstab
