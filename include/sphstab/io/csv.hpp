#pragma once
/// \file csv.hpp
/// Minimal CSV time-series writer (header + rows, flushed row by row so that a run that stops early keeps
/// everything written so far) and a reader for tests and post-processing.
///
/// Numbers are written in the shortest form that reads back to the same double (std::to_chars), so a
/// write/read round trip is exact. Cells containing a comma, quote or newline are quoted ("" escapes ").
///
/// \code{.cpp}
/// sphstab::CsvWriter csv("energy.csv", {"step", "t", "kinetic"});
/// csv.row({0L, 0.0, 1.5});
/// auto table = sphstab::read_csv("energy.csv");
/// std::vector<double> t = table.numeric_column("t");
/// \endcode
#include <fstream>
#include <string>
#include <vector>

namespace sphstab {

/// One CSV cell: a number (double or integer) or text; implicitly constructible from each.
struct CsvCell {
  enum class Kind { Real, Integer, Text };
  Kind kind = Kind::Real;
  double real = 0;
  long long integer = 0;
  std::string text;
  CsvCell(double x) : kind(Kind::Real), real(x) {}
  CsvCell(int x) : kind(Kind::Integer), integer(x) {}
  CsvCell(long x) : kind(Kind::Integer), integer(x) {}
  CsvCell(long long x) : kind(Kind::Integer), integer(x) {}
  CsvCell(std::string s) : kind(Kind::Text), text(std::move(s)) {}
  CsvCell(const char* s) : kind(Kind::Text), text(s) {}
};

/// `s` as one CSV field: unchanged, or quoted ("" escapes ") when it holds a comma, quote or line break.
std::string csv_quote(const std::string& s);
/// One CSV line (fields quoted as needed, "\n"-terminated).
std::string csv_line(const std::vector<std::string>& fields);

/// Formats one cell as written by CsvWriter (shortest round-trip form for doubles, "nan"/"inf"/"-inf").
std::string format_csv_cell(const CsvCell& cell);

class CsvWriter {
 public:
  CsvWriter() = default;
  /// Opens (truncates) `path` and writes the header. Throws std::invalid_argument for an empty column list
  /// and std::runtime_error if the file cannot be opened.
  CsvWriter(const std::string& path, std::vector<std::string> columns, bool flush_every_row = true);

  bool is_open() const { return m_out.is_open(); }
  const std::vector<std::string>& columns() const { return m_columns; }
  long rows_written() const { return m_rows; }

  /// Writes one row; throws std::invalid_argument if the cell count differs from the column count, and
  /// std::runtime_error("CsvWriter: error writing '<path>' (disk full or I/O error)") when the stream fails (checked
  /// after every row: with flush_every_row the row has reached the file; otherwise at the next buffer flush).
  void row(const std::vector<CsvCell>& cells);
  /// Flushes; throws std::runtime_error as row() when the stream fails.
  void flush();

 private:
  void check_stream();
  std::string m_path;
  std::ofstream m_out;
  std::vector<std::string> m_columns;
  bool m_flush = true;
  long m_rows = 0;
};

/// A parsed CSV file: header and rows of text cells.
struct CsvTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  /// Index of a column; throws std::invalid_argument naming the available columns if absent.
  int column_index(const std::string& name) const;
  /// A column converted to double ("nan", "inf", "-inf" accepted); throws std::invalid_argument on a
  /// non-numeric cell.
  std::vector<double> numeric_column(const std::string& name) const;
  std::vector<std::string> text_column(const std::string& name) const;
};

/// Reads a CSV file written by CsvWriter (first line = header). Throws std::runtime_error if it cannot be
/// opened and std::invalid_argument if a row has a different number of cells than the header.
CsvTable read_csv(const std::string& path);

}  // namespace sphstab
