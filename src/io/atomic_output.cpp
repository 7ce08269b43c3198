#include "sphstab/io/atomic_output.hpp"

#include <cstdio>
#include <stdexcept>
#include <utility>

namespace sphstab {

AtomicOutput::AtomicOutput(std::string path, std::string who)
    : m_path(std::move(path)), m_part(m_path + ".part"), m_who(std::move(who)) {
  m_out.open(m_part, std::ios::out | std::ios::trunc | std::ios::binary);
  if (!m_out) throw std::runtime_error(m_who + ": cannot open '" + m_path + "' for writing");
}

AtomicOutput::~AtomicOutput() {
  if (m_done) return;
  m_out.close();
  std::remove(m_part.c_str());
}

void AtomicOutput::commit() {
  if (m_done) throw std::logic_error(m_who + ": '" + m_path + "' committed twice");
  m_out.flush();
  const bool written = m_out.good();
  m_out.close();
  m_done = true;
  if (!written || m_out.fail()) {
    std::remove(m_part.c_str());
    throw std::runtime_error(m_who + ": error writing '" + m_path + "' (disk full or I/O error)");
  }
  if (std::rename(m_part.c_str(), m_path.c_str()) != 0) {
    std::remove(m_part.c_str());
    throw std::runtime_error(m_who + ": cannot replace '" + m_path + "'");
  }
}

}  // namespace sphstab
