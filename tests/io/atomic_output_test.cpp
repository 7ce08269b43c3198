// Files written whole or not at all (io/atomic_output.hpp) by the .mtx and VTK writers: a write that fails — here
// a file-size limit (RLIMIT_FSIZE, the same EFBIG a full disk gives as ENOSPC) — throws one line naming the file,
// leaves an existing file untouched and no partial file behind; a write that succeeds leaves only the target.
#include "sphstab/io/atomic_output.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <Eigen/Core>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "sphstab/io/csv.hpp"
#include "sphstab/io/matrix_market.hpp"
#include "sphstab/io/vtk.hpp"

namespace sphstab {
namespace atomic_output_test {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sphstab_atomic_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string contents(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Lowers the file-size limit for the scope (writes beyond it fail with EFBIG; SIGXFSZ ignored).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &m_old);
    m_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit lim = m_old;
    lim.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lim);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &m_old);
    std::signal(SIGXFSZ, m_handler);
  }

 private:
  rlimit m_old{};
  void (*m_handler)(int) = nullptr;
};

TEST(AtomicOutput, AFailedWriteThrowsAndLeavesTheOldFileAndNoPart) {
  const fs::path mtx = scratch("big.mtx"), vtp = scratch("big.vtp");
  {
    std::ofstream(mtx) << "old matrix\n";
    std::ofstream(vtp) << "old vtp\n";
  }
  const Eigen::MatrixXd A = Eigen::MatrixXd::Constant(300, 300, 1.0 / 3.0);  // ~2 MB as text
  const Eigen::MatrixXd points = Eigen::MatrixXd::Constant(40000, 2, 1.0 / 7.0);
  {
    const FileSizeLimit limit(64 * 1024);
    try {
      write_matrix_market(mtx.string(), A);
      FAIL() << "write_matrix_market past the file-size limit did not throw";
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("write_matrix_market: error writing '" + mtx.string() + "'"), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
    EXPECT_THROW(write_vtp(vtp.string(), points, {}), std::runtime_error);
  }
  EXPECT_EQ(contents(mtx), "old matrix\n");
  EXPECT_EQ(contents(vtp), "old vtp\n");
  EXPECT_FALSE(fs::exists(mtx.string() + ".part"));
  EXPECT_FALSE(fs::exists(vtp.string() + ".part"));
  // Without the limit the same writes replace the files completely.
  write_matrix_market(mtx.string(), A);
  EXPECT_EQ(read_matrix_market(mtx.string()).rows(), 300);
  EXPECT_FALSE(fs::exists(mtx.string() + ".part"));
  fs::remove_all(mtx.parent_path());
}

// CsvWriter streams rows (runs write them as they go), so it cannot rename at the end; it checks the stream after
// every row instead and throws one line naming the file.
TEST(AtomicOutput, CsvRowsThatCannotBeWrittenThrow) {
  const fs::path p = scratch("rows.csv");
  const FileSizeLimit limit(16 * 1024);
  CsvWriter w(p.string(), {"k", "value"});
  long written = 0;
  try {
    for (long k = 0; k < 100000; ++k, ++written) w.row({k, 1.0 / 3.0});
    FAIL() << "100000 rows past a 16 kB limit did not throw";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("CsvWriter: error writing '" + p.string() + "'"), std::string::npos) << msg;
  }
  EXPECT_GT(written, 100);
  EXPECT_LT(written, 5000);
  fs::remove_all(p.parent_path());
}

TEST(AtomicOutput, UncommittedOutputIsRemovedAndAnUnwritableTargetIsOneLine) {
  const fs::path p = scratch("never.txt");
  {
    AtomicOutput out(p.string(), "test");
    out.stream() << "partial";
  }
  EXPECT_FALSE(fs::exists(p));
  EXPECT_FALSE(fs::exists(p.string() + ".part"));
  try {
    AtomicOutput out((p.parent_path() / "no_such_dir" / "x.txt").string(), "test");
    FAIL() << "opened a file in a missing directory";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("test: cannot open"), std::string::npos) << e.what();
  }
  AtomicOutput out(p.string(), "test");
  out.stream() << "whole\n";
  out.commit();
  EXPECT_EQ(contents(p), "whole\n");
  EXPECT_THROW(out.commit(), std::logic_error);
  fs::remove_all(p.parent_path());
}

}  // namespace atomic_output_test
}  // namespace sphstab
