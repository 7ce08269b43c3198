#include "sphstab/io/csv.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace sphstab {

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string out;
  for (std::size_t c = 0; c < fields.size(); ++c) out += (c ? "," : "") + csv_quote(fields[c]);
  return out + "\n";
}

namespace {

std::vector<std::string> split_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cur;
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    char c = line[k];
    if (quoted) {
      if (c == '"') {
        if (k + 1 < line.size() && line[k + 1] == '"') {
          cur += '"';
          ++k;
        } else {
          quoted = false;
        }
      } else {
        cur += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  cells.push_back(cur);
  return cells;
}

}  // namespace

std::string format_csv_cell(const CsvCell& cell) {
  if (cell.kind == CsvCell::Kind::Real) {
    const double d = cell.real;
    if (std::isnan(d)) return "nan";
    if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
    char buf[64];
    auto res = std::to_chars(buf, buf + sizeof(buf), d);
    return std::string(buf, res.ptr);
  }
  if (cell.kind == CsvCell::Kind::Integer) return std::to_string(cell.integer);
  return csv_quote(cell.text);
}

CsvWriter::CsvWriter(const std::string& path, std::vector<std::string> columns, bool flush_every_row)
    : m_path(path), m_columns(std::move(columns)), m_flush(flush_every_row) {
  if (m_columns.empty()) throw std::invalid_argument("CsvWriter: empty column list for '" + path + "'");
  m_out.open(path, std::ios::out | std::ios::trunc);
  if (!m_out) throw std::runtime_error("CsvWriter: cannot open '" + path + "' for writing");
  for (std::size_t k = 0; k < m_columns.size(); ++k) m_out << (k ? "," : "") << csv_quote(m_columns[k]);
  m_out << '\n';
  flush();
}

void CsvWriter::check_stream() {
  if (!m_out) throw std::runtime_error("CsvWriter: error writing '" + m_path + "' (disk full or I/O error)");
}

void CsvWriter::flush() {
  m_out.flush();
  check_stream();
}

void CsvWriter::row(const std::vector<CsvCell>& cells) {
  if (!m_out.is_open()) throw std::invalid_argument("CsvWriter::row: writer is not open");
  if (cells.size() != m_columns.size())
    throw std::invalid_argument("CsvWriter::row: " + std::to_string(cells.size()) + " cells for " +
                                std::to_string(m_columns.size()) + " columns");
  for (std::size_t k = 0; k < cells.size(); ++k) m_out << (k ? "," : "") << format_csv_cell(cells[k]);
  m_out << '\n';
  ++m_rows;
  if (m_flush) m_out.flush();
  check_stream();
}

int CsvTable::column_index(const std::string& name) const {
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k] == name) return static_cast<int>(k);
  std::string all;
  for (const auto& c : columns) all += (all.empty() ? "" : ", ") + c;
  throw std::invalid_argument("CsvTable: no column '" + name + "' (columns: " + all + ")");
}

std::vector<double> CsvTable::numeric_column(const std::string& name) const {
  const int k = column_index(name);
  std::vector<double> out;
  out.reserve(rows.size());
  for (const auto& r : rows) {
    const std::string& s = r[k];
    if (s == "nan") {
      out.push_back(std::nan(""));
      continue;
    }
    if (s == "inf" || s == "-inf") {
      out.push_back(s[0] == '-' ? -HUGE_VAL : HUGE_VAL);
      continue;
    }
    double v = 0;
    auto res = std::from_chars(s.data(), s.data() + s.size(), v);
    if (res.ec != std::errc() || res.ptr != s.data() + s.size())
      throw std::invalid_argument("CsvTable::numeric_column: cell '" + s + "' in column '" + name +
                                  "' is not a number");
    out.push_back(v);
  }
  return out;
}

std::vector<std::string> CsvTable::text_column(const std::string& name) const {
  const int k = column_index(name);
  std::vector<std::string> out;
  for (const auto& r : rows) out.push_back(r[k]);
  return out;
}

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("read_csv: cannot open '" + path + "'");
  CsvTable t;
  std::string line;
  if (!std::getline(in, line)) return t;
  t.columns = split_line(line);
  long lineno = 1;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty() || line == "\r") continue;
    auto cells = split_line(line);
    if (cells.size() != t.columns.size())
      throw std::invalid_argument("read_csv: line " + std::to_string(lineno) + " of '" + path + "' has " +
                                  std::to_string(cells.size()) + " cells, header has " +
                                  std::to_string(t.columns.size()));
    t.rows.push_back(std::move(cells));
  }
  return t;
}

}  // namespace sphstab
