#include "sphstab/io/matrix_market.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "sphstab/io/atomic_output.hpp"

namespace sphstab {

namespace {

void write_comment(std::ostream& out, const std::string& comment) {
  std::istringstream lines(comment);
  std::string line;
  while (std::getline(lines, line)) out << "% " << line << '\n';
}

/// One printf-formatted line into the stream (the %.17g of the values: round-trip exact).
template <class... Args>
void line(std::ostream& out, const char* format, Args... args) {
  char buf[96];
  const int n = std::snprintf(buf, sizeof(buf), format, args...);
  out.write(buf, n);
}

}  // namespace

// Written to a temporary file and renamed into place (io/atomic_output.hpp): a failed write leaves no truncated .mtx.
void write_matrix_market(const std::string& path, const SparseMatrix<double>& A, const std::string& comment) {
  AtomicOutput file(path, "write_matrix_market");
  std::ostream& out = file.stream();
  out << "%%MatrixMarket matrix coordinate real general\n";
  write_comment(out, comment);
  line(out, "%ld %ld %ld\n", static_cast<long>(A.rows()), static_cast<long>(A.cols()), static_cast<long>(A.nonZeros()));
  for (int i = 0; i < A.outerSize(); ++i)
    for (SparseMatrix<double>::InnerIterator it(A, i); it; ++it)
      line(out, "%ld %ld %.17g\n", static_cast<long>(it.row()) + 1, static_cast<long>(it.col()) + 1, it.value());
  file.commit();
}

void write_matrix_market(const std::string& path, const Eigen::MatrixXd& A, const std::string& comment) {
  AtomicOutput file(path, "write_matrix_market");
  std::ostream& out = file.stream();
  out << "%%MatrixMarket matrix array real general\n";
  write_comment(out, comment);
  line(out, "%ld %ld\n", static_cast<long>(A.rows()), static_cast<long>(A.cols()));
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = 0; i < A.rows(); ++i) line(out, "%.17g\n", A(i, j));
  file.commit();
}

SparseMatrix<double> read_matrix_market(const std::string& path) {
  const std::string who = "read_matrix_market: '" + path + "': ";
  std::ifstream in(path);
  if (!in) throw std::runtime_error(who + "cannot open");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(who + "empty file");
  std::istringstream banner(line);
  std::string tag, object, format, field, symmetry;
  banner >> tag >> object >> format >> field >> symmetry;
  for (std::string* s : {&object, &format, &field, &symmetry})
    for (char& ch : *s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (tag != "%%MatrixMarket" || object != "matrix") throw std::runtime_error(who + "not a Matrix Market matrix");
  if (field != "real" && field != "double" && field != "integer")
    throw std::runtime_error(who + "unsupported field '" + field + "' (real only)");
  if (symmetry != "general") throw std::runtime_error(who + "unsupported symmetry '" + symmetry + "' (general only)");
  if (format != "coordinate" && format != "array") throw std::runtime_error(who + "unknown format '" + format + "'");
  do {
    if (!std::getline(in, line)) throw std::runtime_error(who + "missing size line");
  } while (line.empty() || line[0] == '%');
  std::istringstream size_line(line);
  long rows = -1, cols = -1, entries = -1;
  size_line >> rows >> cols;
  if (format == "coordinate") size_line >> entries;
  if (rows < 0 || cols < 0 || (format == "coordinate" && entries < 0))
    throw std::runtime_error(who + "malformed size line '" + line + "'");
  std::vector<Eigen::Triplet<double, int>> t;
  if (format == "coordinate") {
    t.reserve(entries);
    for (long k = 0; k < entries; ++k) {
      long i, j;
      double v;
      if (!(in >> i >> j >> v)) throw std::runtime_error(who + "expected " + std::to_string(entries) + " entries");
      if (i < 1 || i > rows || j < 1 || j > cols) throw std::runtime_error(who + "entry index out of range");
      t.emplace_back(static_cast<int>(i - 1), static_cast<int>(j - 1), v);
    }
  } else {
    t.reserve(rows * cols);
    for (long j = 0; j < cols; ++j)
      for (long i = 0; i < rows; ++i) {
        double v;
        if (!(in >> v)) throw std::runtime_error(who + "expected " + std::to_string(rows * cols) + " values");
        t.emplace_back(static_cast<int>(i), static_cast<int>(j), v);
      }
  }
  SparseMatrix<double> A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace sphstab
