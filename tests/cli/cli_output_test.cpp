// Output that cannot be written is an error, not a success (issue 36): every subcommand that prints its result on
// standard output, run by the built program (SPHSTAB_CLI) with stdout on /dev/full, exits 1 with one error line; the
// same commands on a pipe that the reader closes early (`| head -c 1`) end without an error line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace cli_output_test {

const std::vector<std::string> kCommands = {"kernels", "tcrit --n 10", "spectrum --n 6", "run --n 5 --t-end 0.5",
                                            "scene rings --dp 0.2 --t-end 0.5"};

std::filesystem::path scratch() {
  auto dir = std::filesystem::temp_directory_path() / ("sphstab_cli_output_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> out;
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

int exit_status(const std::string& cmd) {
  const int st = std::system(cmd.c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}


TEST(CliOutput, AFullStandardOutputIsOneErrorLineAndExitOne) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this machine";
  const auto dir = scratch();
  for (const auto& args : kCommands) {
    const auto err = dir / "stderr";
    const int status = exit_status(std::string(SPHSTAB_CLI) + " " + args + " > /dev/full 2> " + err.string());
    EXPECT_EQ(status, 1) << args;
    const auto lines = lines_of(err);
    ASSERT_EQ(lines.size(), 1u) << args;
    EXPECT_NE(lines[0].find("sphstab: error: cannot write the output to standard output"), std::string::npos)
        << args << ": " << lines[0];
  }
  std::filesystem::remove_all(dir);
}

TEST(CliOutput, AReaderThatStopsEarlyIsNotAnError) {
  const auto dir = scratch();
  for (const auto& args : kCommands) {
    const auto err = dir / "stderr";
    exit_status(std::string(SPHSTAB_CLI) + " " + args + " 2> " + err.string() + " | head -c 1 > /dev/null");
    EXPECT_TRUE(lines_of(err).empty()) << args << ": " << (lines_of(err).empty() ? "" : lines_of(err)[0]);
  }
  std::filesystem::remove_all(dir);
}

TEST(CliOutput, ANormalRunStillSucceeds) {
  const auto dir = scratch();
  for (const auto& args : kCommands) {
    const auto out = dir / "stdout";
    EXPECT_EQ(exit_status(std::string(SPHSTAB_CLI) + " " + args + " > " + out.string() + " 2> /dev/null"), 0) << args;
    EXPECT_FALSE(lines_of(out).empty()) << args;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace cli_output_test
