// No committed file names a path outside the repository. sphstab cites papers by their docs/references.md key and
// section, equation or table ([Powell2012, Table 2.1]), never the notes the project was started from, and its results
// carry no directory of the machine they were produced on. The rule, checked on every file `git ls-files` lists
// (every file of the tree but .git and build directories when the source is not a git checkout), text files only:
//
//   anywhere         a machine's work or home directory: /work, /root or /home followed by a slash;
//                    the notes folder the project was started from and its files (shared + /notes, notes + /seed +
//                    dash, seed + dash + <name>.md) and the folders beside the repository that held them
//                    (../shared + /, shared + /seeds);
//   recorded output  /tmp followed by a slash as well, in results/ and in data files anywhere (.csv, .json, .mtx,
//                    .vtp, .pvd, .tsv): a path there was recorded by a run. Scripts, sources and docs may use /tmp as
//                    a scratch place (benchmarks/distributed/critical_strain_petsc.sh does), so it is not flagged
//                    in them.
//
// System paths (/usr/bin/python3, /usr/share/spectra/cmake) are where Debian installs things, not a machine's
// directories, and are allowed. A benchmark json records the program's absolute path; benchmarks/relative_executable.py
// rewrites it (the speed studies' run.sh call it). The needles below are assembled from pieces so that this file does
// not match them itself. The checker is tested on a synthetic tree first, like the layer check (layers_test.cpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace recorded_paths_test {

namespace fs = std::filesystem;

const std::string kSlash = "/";

/// Needles flagged in every tracked text file.
std::vector<std::string> everywhere() {
  return {kSlash + "work" + kSlash,        kSlash + "root" + kSlash,        kSlash + "home" + kSlash,
          "shared" + kSlash + "notes",     "notes" + kSlash + "seed" + "-", ".." + kSlash + "shared" + kSlash,
          "shared" + kSlash + "seed" + "s"};
}

/// A notes file named by itself (seed, a dash, a name, .md), without its folder.
const std::regex& notes_file() {
  static const std::regex re("seed" + std::string("-[A-Za-z0-9_-]+[.]md"));
  return re;
}

/// Needle flagged in recorded output only.
std::string temporary() { return kSlash + "tmp" + kSlash; }

bool is_recorded_output(const std::string& rel) {
  if (rel.rfind("results/", 0) == 0) return true;
  for (const char* ext : {".csv", ".json", ".mtx", ".vtp", ".pvd", ".tsv"}) {
    const std::string e(ext);
    if (rel.size() >= e.size() && rel.compare(rel.size() - e.size(), e.size(), e) == 0) return true;
  }
  return false;
}

/// One message per offending line: "file:line: needle: the line".
std::vector<std::string> path_offences(const fs::path& root, const std::vector<std::string>& files) {
  std::vector<std::string> out;
  const auto needles = everywhere();
  for (const std::string& rel : files) {
    std::ifstream in(root / rel, std::ios::binary);
    if (!in) continue;  // listed but deleted in the working tree
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    if (text.substr(0, 8000).find('\0') != std::string::npos) continue;  // binary (PNG, ...), like grep -I
    const bool recorded = is_recorded_output(rel);
    std::istringstream lines(text);
    std::string line;
    int number = 0;
    while (std::getline(lines, line)) {
      ++number;
      std::vector<std::string> found;
      for (const auto& n : needles)
        if (line.find(n) != std::string::npos) found.push_back(n);
      std::smatch m;
      if (std::regex_search(line, m, notes_file())) found.push_back(m.str());
      if (recorded && line.find(temporary()) != std::string::npos) found.push_back(temporary());
      for (const auto& n : found)
        out.push_back(rel + ":" + std::to_string(number) + ": '" + n + "': " + line.substr(0, 160));
    }
  }
  return out;
}

/// The tracked files of the tree at root (git ls-files), or every file but .git and build directories when root is not
/// a git checkout (a source archive). `from_git` says which.
std::vector<std::string> tree_files(const fs::path& root, bool& from_git) {
  std::vector<std::string> files;
  // safe.directory: the listing is read-only, and the test may run as another user than the checkout's owner.
  const std::string cmd = "git -c safe.directory='*' -C '" + root.string() + "' ls-files -z 2>/dev/null";
  if (FILE* pipe = popen(cmd.c_str(), "r")) {
    std::string name;
    for (int c; (c = std::fgetc(pipe)) != EOF;) {
      if (c == '\0') {
        if (!name.empty()) files.push_back(name);
        name.clear();
      } else {
        name.push_back(static_cast<char>(c));
      }
    }
    const int status = pclose(pipe);
    if (status == 0 && !files.empty()) {
      from_git = true;
      return files;
    }
  }
  from_git = false;
  files.clear();
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    // .git is a directory in a clone and a file naming the main checkout in a worktree: skipped either way.
    if (it->path().filename() == ".git" || (it->is_directory() && fs::exists(it->path() / "CMakeCache.txt"))) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file()) files.push_back(fs::relative(it->path(), root).generic_string());
  }
  return files;
}

struct SyntheticTree {
  // One directory per test: ctest runs the tests of this file in parallel processes.
  fs::path root = fs::temp_directory_path() /
                  (std::string("sphstab_paths_") + testing::UnitTest::GetInstance()->current_test_info()->name());
  SyntheticTree() { fs::remove_all(root); }
  ~SyntheticTree() { fs::remove_all(root); }
  void write(const std::string& rel, const std::string& text) const {
    fs::create_directories((root / rel).parent_path());
    std::ofstream(root / rel, std::ios::binary) << text;
  }
};

TEST(RecordedPaths, CheckerAcceptsCitationsSystemPathsAndScratchFilesInScripts) {
  SyntheticTree t;
  t.write("studies/a/README.md", "**What the thesis claims** ([Powell2012, Table 2.1]):\n");
  t.write("scripts/run.sh",
          "#!/usr/bin/env bash\n" + std::string("/usr/bin/python3 x.py 2>") + temporary() + "x.err\n");
  t.write("results/a/benchmark.json", "{\"executable\": \"build/bin/a_benchmark\"}\n");
  const auto v = path_offences(t.root, {"studies/a/README.md", "scripts/run.sh", "results/a/benchmark.json"});
  EXPECT_TRUE(v.empty()) << v.front();
}

TEST(RecordedPaths, CheckerFlagsEachRule) {
  SyntheticTree t;
  const std::string notes = kSlash + "work" + kSlash + "shared" + kSlash + "notes" + kSlash + "seed" + "-gms.md";
  t.write("studies/a/README.md", "ok\nnotes in `" + notes + "` §4.2\n");                     // 3 needles on line 2
  t.write("include/b.hpp", "/// typo (" + std::string("seed") + "-gms.md [RC])\n");          // the file name alone
  t.write("docs/c.md", "see `.." + kSlash + "shared" + kSlash + "DESIGN.md`\n");             // next to the repository
  t.write("results/d/e.json", "\"executable\": \"" + kSlash + "root" + kSlash + "b/x\"\n");  // a home directory
  t.write("results/d/f.csv", "run,dir\n1," + temporary() + "out\n");                         // /tmp in recorded output
  t.write("studies/g/reference_h.csv", "# from " + temporary() + "h\n");                     // ... and in a data file
  t.write("results/d/plot.png", std::string("\x89PNG\0\0", 6) + notes + "\n");               // binary: skipped
  const auto v = path_offences(t.root, {"studies/a/README.md", "include/b.hpp", "docs/c.md", "results/d/e.json",
                                        "results/d/f.csv", "studies/g/reference_h.csv", "results/d/plot.png"});
  std::string all;
  for (const auto& s : v) all += s + "\n";
  ASSERT_EQ(v.size(), 9u) << all;  // 4 on the README's line: the work directory, the notes folder twice, the file
  EXPECT_EQ(v[0].rfind("studies/a/README.md:2: '" + kSlash + "work" + kSlash + "'", 0), 0u) << v[0];
  EXPECT_EQ(v[4].rfind("include/b.hpp:1: 'seed" + std::string("-gms.md'"), 0), 0u) << v[4];
  EXPECT_EQ(v[5].rfind("docs/c.md:1:", 0), 0u) << v[5];
  EXPECT_EQ(v[6].rfind("results/d/e.json:1:", 0), 0u) << v[6];
  EXPECT_EQ(v[7].rfind("results/d/f.csv:2: '" + temporary() + "'", 0), 0u) << v[7];
  EXPECT_EQ(v[8].rfind("studies/g/reference_h.csv:1:", 0), 0u) << v[8];
}

TEST(RecordedPaths, TheTreeNamesNoPathOutsideTheRepository) {
  const fs::path root(SPHSTAB_SOURCE_DIR);
  bool from_git = false;
  const auto files = tree_files(root, from_git);
  ASSERT_GT(files.size(), 100u) << "no files found under " << root;
  const auto v = path_offences(root, files);
  std::string all;
  for (const auto& s : v) all += s + "\n";
  EXPECT_TRUE(v.empty()) << v.size() << " lines name a path outside the repository (files from "
                         << (from_git ? "git ls-files" : "a walk of the tree")
                         << "; cite [Key, section] of docs/references.md instead):\n"
                         << all;
}

}  // namespace recorded_paths_test
