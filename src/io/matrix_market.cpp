#include "sphstab/io/matrix_market.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace sphstab {

namespace {

std::FILE* open_for_writing(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("write_matrix_market: cannot open '" + path + "' for writing");
  return f;
}

void write_comment(std::FILE* f, const std::string& comment) {
  std::istringstream lines(comment);
  std::string line;
  while (std::getline(lines, line)) std::fprintf(f, "%% %s\n", line.c_str());
}

void close_checked(std::FILE* f, const std::string& path) {
  const bool ok = !std::ferror(f);
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("write_matrix_market: error writing '" + path + "'");
}

}  // namespace

void write_matrix_market(const std::string& path, const SparseMatrix<double>& A, const std::string& comment) {
  std::FILE* f = open_for_writing(path);
  std::fprintf(f, "%%%%MatrixMarket matrix coordinate real general\n");
  write_comment(f, comment);
  std::fprintf(f, "%ld %ld %ld\n", static_cast<long>(A.rows()), static_cast<long>(A.cols()),
               static_cast<long>(A.nonZeros()));
  for (int i = 0; i < A.outerSize(); ++i)
    for (SparseMatrix<double>::InnerIterator it(A, i); it; ++it)
      std::fprintf(f, "%ld %ld %.17g\n", static_cast<long>(it.row()) + 1, static_cast<long>(it.col()) + 1, it.value());
  close_checked(f, path);
}

void write_matrix_market(const std::string& path, const Eigen::MatrixXd& A, const std::string& comment) {
  std::FILE* f = open_for_writing(path);
  std::fprintf(f, "%%%%MatrixMarket matrix array real general\n");
  write_comment(f, comment);
  std::fprintf(f, "%ld %ld\n", static_cast<long>(A.rows()), static_cast<long>(A.cols()));
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = 0; i < A.rows(); ++i) std::fprintf(f, "%.17g\n", A(i, j));
  close_checked(f, path);
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
