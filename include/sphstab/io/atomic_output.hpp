#pragma once
/// \file atomic_output.hpp
/// A file written whole or not at all: the content goes to a temporary file next to the target (`path` + ".part"),
/// and only commit() — after every write, the flush and the close succeeded — renames it onto `path`. A write that
/// fails (disk full, a file-size limit, an I/O error) throws one line naming the file, and the partial file is
/// removed, so a truncated file that looks complete is never left behind (issue 36: "writes that fail are reported
/// as success"). Used by the matrix (.mtx) and VTK (.vtp, .pvd) writers.
///
/// \code{.cpp}
/// sphstab::AtomicOutput out(path, "write_vtp");
/// out.stream() << ...;
/// out.commit();  // throws std::runtime_error("write_vtp: error writing '<path>' (disk full or I/O error)")
/// \endcode
#include <fstream>
#include <string>

namespace sphstab {

class AtomicOutput {
 public:
  /// Opens `path`.part for writing. Throws std::runtime_error("who: cannot open 'path' for writing") if it cannot.
  AtomicOutput(std::string path, std::string who);
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  /// Without commit(): the partial file is closed and removed; `path` is left as it was.
  ~AtomicOutput();

  std::ostream& stream() { return m_out; }
  /// Flushes, checks, closes and renames onto the target. Throws std::runtime_error naming the file on any failure
  /// (the partial file is removed first).
  void commit();

 private:
  std::string m_path, m_part, m_who;
  std::ofstream m_out;
  bool m_done = false;
};

}  // namespace sphstab
