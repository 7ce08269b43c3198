#include "sphstab/io/vtk.hpp"

#include "sphstab/io/atomic_output.hpp"

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace sphstab {

namespace {

void write_numbers(std::ostream& out, const double* data, long count, int per_line) {
  char buf[40];
  for (long k = 0; k < count; ++k) {
    std::snprintf(buf, sizeof(buf), "%.17g", data[k]);
    out << buf << ((k + 1) % per_line == 0 || k + 1 == count ? '\n' : ' ');
  }
}

/// Attribute value of `name="..."` inside a tag's attribute text; empty if absent.
std::string attribute(const std::string& attrs, const std::string& name) {
  const std::string key = name + "=\"";
  std::size_t p = 0;
  while ((p = attrs.find(key, p)) != std::string::npos) {
    if (p == 0 || attrs[p - 1] == ' ' || attrs[p - 1] == '\t' || attrs[p - 1] == '\n') {
      std::size_t q = attrs.find('"', p + key.size());
      if (q == std::string::npos) return {};
      return attrs.substr(p + key.size(), q - p - key.size());
    }
    p += key.size();
  }
  return {};
}

struct Tag {
  std::string name, attrs;
  bool closing = false, self_closing = false;
  std::size_t begin = 0, end = 0;  // [begin, end) of "<...>"
};

/// Next tag at or after pos (skips <?xml ...?> and comments); returns false at the end of the text.
bool next_tag(const std::string& s, std::size_t& pos, Tag& tag, const std::string& path) {
  while (true) {
    std::size_t lt = s.find('<', pos);
    if (lt == std::string::npos) return false;
    if (s.compare(lt, 4, "<!--") == 0) {
      std::size_t e = s.find("-->", lt);
      if (e == std::string::npos) throw std::runtime_error("read_vtp: unterminated comment in '" + path + "'");
      pos = e + 3;
      continue;
    }
    std::size_t gt = s.find('>', lt);
    if (gt == std::string::npos) throw std::runtime_error("read_vtp: unterminated tag in '" + path + "'");
    if (s[lt + 1] == '?') {
      pos = gt + 1;
      continue;
    }
    std::string inner = s.substr(lt + 1, gt - lt - 1);
    tag = Tag{};
    tag.begin = lt;
    tag.end = gt + 1;
    if (!inner.empty() && inner[0] == '/') {
      tag.closing = true;
      inner.erase(0, 1);
    }
    if (!inner.empty() && inner.back() == '/') {
      tag.self_closing = true;
      inner.pop_back();
    }
    std::size_t sp = inner.find_first_of(" \t\n");
    tag.name = inner.substr(0, sp);
    tag.attrs = sp == std::string::npos ? "" : inner.substr(sp + 1);
    pos = gt + 1;
    return true;
  }
}

}  // namespace

void write_vtp(const std::string& path, const Eigen::MatrixXd& points, const std::vector<VtkField>& fields) {
  const long n = points.rows();
  const int d = static_cast<int>(points.cols());
  if (d < 1 || d > 3)
    throw std::invalid_argument("write_vtp: points must have 1, 2 or 3 columns (got " + std::to_string(d) + ")");
  for (const auto& f : fields) {
    if (f.components < 1 || f.components > 3)
      throw std::invalid_argument("write_vtp: field '" + f.name + "' must have 1..3 components (got " +
                                  std::to_string(f.components) + ")");
    if (f.values.size() != n * f.components)
      throw std::invalid_argument("write_vtp: field '" + f.name + "' has " + std::to_string(f.values.size()) +
                                  " values, expected " + std::to_string(n * f.components));
    if (f.name.empty() || f.name.find_first_of("\"<>&") != std::string::npos)
      throw std::invalid_argument("write_vtp: field name '" + f.name + "' is empty or contains \" < > &");
  }
  AtomicOutput file(path, "write_vtp");  // renamed into place only once complete (io/atomic_output.hpp)
  std::ostream& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"" << n
      << "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  out << "      <PointData>\n";
  for (const auto& f : fields) {
    const int nc = f.components == 1 ? 1 : 3;
    out << "        <DataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\"" << nc
        << "\" format=\"ascii\">\n";
    Eigen::VectorXd padded = Eigen::VectorXd::Zero(n * nc);
    for (long i = 0; i < n; ++i)
      for (int c = 0; c < f.components; ++c) padded[i * nc + c] = f.values[i * f.components + c];
    write_numbers(out, padded.data(), padded.size(), nc == 1 ? 6 : 3);
    out << "        </DataArray>\n";
  }
  out << "      </PointData>\n";
  out << "      <Points>\n"
      << "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  Eigen::VectorXd xyz = Eigen::VectorXd::Zero(3 * n);
  for (long i = 0; i < n; ++i)
    for (int c = 0; c < d; ++c) xyz[3 * i + c] = points(i, c);
  write_numbers(out, xyz.data(), xyz.size(), 3);
  out << "        </DataArray>\n      </Points>\n";
  out << "      <Verts>\n        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (long i = 0; i < n; ++i) out << i << ((i + 1) % 12 == 0 || i + 1 == n ? '\n' : ' ');
  out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (long i = 0; i < n; ++i) out << i + 1 << ((i + 1) % 12 == 0 || i + 1 == n ? '\n' : ' ');
  out << "        </DataArray>\n      </Verts>\n";
  out << "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  file.commit();
}

const VtkField& VtpData::field(const std::string& name) const {
  for (const auto& f : fields)
    if (f.name == name) return f;
  throw std::invalid_argument("VtpData::field: no point-data array '" + name + "'");
}

VtpData read_vtp(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("read_vtp: cannot open '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string s = ss.str();

  VtpData data;
  std::vector<std::string> stack;
  std::size_t pos = 0;
  Tag tag;
  long npoints = -1;
  bool seen_root = false;
  while (next_tag(s, pos, tag, path)) {
    if (tag.closing) {
      if (stack.empty() || stack.back() != tag.name)
        throw std::runtime_error("read_vtp: end tag </" + tag.name + "> does not match " +
                                 (stack.empty() ? std::string("nothing") : "<" + stack.back() + ">") + " in '" + path +
                                 "'");
      stack.pop_back();
      continue;
    }
    if (stack.empty()) {
      if (tag.name != "VTKFile" || attribute(tag.attrs, "type") != "PolyData")
        throw std::runtime_error("read_vtp: root element is not <VTKFile type=\"PolyData\"> in '" + path + "'");
      seen_root = true;
    }
    if (tag.name == "Piece") {
      std::string np = attribute(tag.attrs, "NumberOfPoints");
      if (np.empty()) throw std::runtime_error("read_vtp: <Piece> without NumberOfPoints in '" + path + "'");
      npoints = std::stol(np);
    }
    if (tag.name == "DataArray" && !tag.self_closing) {
      const std::string parent = stack.empty() ? "" : stack.back();
      std::size_t close = s.find("</DataArray>", pos);
      if (close == std::string::npos) throw std::runtime_error("read_vtp: unterminated <DataArray> in '" + path + "'");
      if (attribute(tag.attrs, "format") != "ascii")
        throw std::runtime_error("read_vtp: only ascii DataArrays are supported ('" + path + "')");
      std::string nc_text = attribute(tag.attrs, "NumberOfComponents");
      const int nc = nc_text.empty() ? 1 : std::stoi(nc_text);
      std::istringstream body(s.substr(pos, close - pos));
      std::vector<double> values;
      std::string tok;
      while (body >> tok) {
        try {
          std::size_t used = 0;
          values.push_back(std::stod(tok, &used));
          if (used != tok.size()) throw std::invalid_argument(tok);
        } catch (const std::exception&) {
          throw std::runtime_error("read_vtp: '" + tok + "' is not a number in '" + path + "'");
        }
      }
      if (parent == "Points" || parent == "PointData") {
        if (npoints < 0 || static_cast<long>(values.size()) != npoints * nc)
          throw std::runtime_error("read_vtp: DataArray '" + attribute(tag.attrs, "Name") + "' has " +
                                   std::to_string(values.size()) + " values, expected " + std::to_string(npoints * nc) +
                                   " in '" + path + "'");
        Eigen::VectorXd v = Eigen::Map<Eigen::VectorXd>(values.data(), values.size());
        if (parent == "Points") {
          if (nc != 3) throw std::runtime_error("read_vtp: Points must have 3 components in '" + path + "'");
          data.points.resize(npoints, 3);
          for (long i = 0; i < npoints; ++i)
            for (int c = 0; c < 3; ++c) data.points(i, c) = v[3 * i + c];
        } else {
          data.fields.push_back({attribute(tag.attrs, "Name"), nc, v});
        }
      }
      stack.push_back(tag.name);
      pos = close;  // the closing tag is consumed by the loop
      continue;
    }
    if (!tag.self_closing) stack.push_back(tag.name);
  }
  if (!seen_root) throw std::runtime_error("read_vtp: no <VTKFile> element in '" + path + "'");
  if (!stack.empty()) throw std::runtime_error("read_vtp: <" + stack.back() + "> is never closed in '" + path + "'");
  if (npoints < 0 || data.points.rows() != npoints)
    throw std::runtime_error("read_vtp: missing <Points> array in '" + path + "'");
  return data;
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& entries) {
  AtomicOutput file(path, "write_pvd");
  std::ostream& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  char buf[40];
  for (const auto& [t, file] : entries) {
    std::snprintf(buf, sizeof(buf), "%.17g", t);
    out << "    <DataSet timestep=\"" << buf << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
  }
  out << "  </Collection>\n</VTKFile>\n";
  file.commit();
}

}  // namespace sphstab
