// The layer order of docs/layers.txt holds: no header or source includes a sphstab header of a higher layer, and
// every folder of include/sphstab and src is a listed layer. The checker is tested on a synthetic tree first, so
// that a passing check on the real tree means something.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace layers_test {

namespace fs = std::filesystem;

/// Layer names in order, from a layers file ('#' starts a comment; one name per line).
std::vector<std::string> read_layers(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> layers;
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string name;
    if (words >> name) layers.push_back(name);
  }
  return layers;
}

/// One message per violation: a file in an unlisted folder, or an include of a higher layer.
std::vector<std::string> layer_violations(const fs::path& root, const std::vector<std::string>& layers) {
  std::map<std::string, int> rank;
  for (int k = 0; k < static_cast<int>(layers.size()); ++k) rank[layers[k]] = k;
  const std::regex include_re(R"re(^\s*#\s*include\s*"sphstab/([^/"]+)/[^"]+")re");
  std::vector<std::string> out;
  for (const fs::path base : {root / "include" / "sphstab", root / "src"}) {
    if (!fs::exists(base)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(base)) {
      if (!entry.is_regular_file()) continue;
      const fs::path rel = fs::relative(entry.path(), base);
      const std::string where = (fs::relative(entry.path(), root)).string();
      if (rel.begin() == rel.end() || std::next(rel.begin()) == rel.end()) {
        out.push_back(where + ": not inside a layer folder");
        continue;
      }
      const std::string layer = rel.begin()->string();
      const auto own = rank.find(layer);
      if (own == rank.end()) {
        out.push_back(where + ": folder '" + layer + "' is not a layer of docs/layers.txt");
        continue;
      }
      std::ifstream in(entry.path());
      std::string line;
      int number = 0;
      while (std::getline(in, line)) {
        ++number;
        std::smatch m;
        if (!std::regex_search(line, m, include_re)) continue;
        const auto target = rank.find(m[1].str());
        if (target == rank.end())
          out.push_back(where + ":" + std::to_string(number) + ": includes unknown layer '" + m[1].str() + "'");
        else if (target->second > own->second)
          out.push_back(where + ":" + std::to_string(number) + ": layer '" + layer + "' includes higher layer '" +
                        m[1].str() + "'");
      }
    }
  }
  return out;
}

struct SyntheticTree {
  // One directory per test: ctest runs the tests of this file in parallel processes.
  fs::path root = fs::temp_directory_path() /
                  (std::string("sphstab_layers_") + testing::UnitTest::GetInstance()->current_test_info()->name());
  SyntheticTree() {
    fs::remove_all(root);
    fs::create_directories(root / "include/sphstab/kernel");
    fs::create_directories(root / "include/sphstab/operators");
    fs::create_directories(root / "src/operators");
  }
  ~SyntheticTree() { fs::remove_all(root); }
  void write(const std::string& rel, const std::string& text) const {
    fs::create_directories((root / rel).parent_path());
    std::ofstream(root / rel) << text;
  }
};

TEST(Layers, CheckerAcceptsDownwardIncludes) {
  SyntheticTree t;
  t.write("include/sphstab/kernel/kernel.hpp", "#pragma once\n#include <vector>\n");
  t.write("include/sphstab/operators/operators.hpp", "#include \"sphstab/kernel/kernel.hpp\"\n");
  t.write("src/operators/operators.cpp", "#include \"sphstab/operators/operators.hpp\"\n#include \"detail.hpp\"\n");
  EXPECT_TRUE(layer_violations(t.root, {"kernel", "operators"}).empty());
}

TEST(Layers, CheckerFailsOnAnUpwardInclude) {
  SyntheticTree t;
  t.write("include/sphstab/kernel/kernel.hpp", "#pragma once\n  #  include \"sphstab/operators/operators.hpp\"\n");
  t.write("include/sphstab/operators/operators.hpp", "#include \"sphstab/kernel/kernel.hpp\"\n");
  const auto v = layer_violations(t.root, {"kernel", "operators"});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NE(v[0].find("include/sphstab/kernel/kernel.hpp:2: layer 'kernel' includes higher layer 'operators'"),
            std::string::npos)
      << v[0];
}

TEST(Layers, CheckerFailsOnUnlistedFoldersAndLayers) {
  SyntheticTree t;
  t.write("src/scene/swegle.cpp", "#include \"sphstab/kernel/kernel.hpp\"\n");
  t.write("src/operators/operators.cpp", "#include \"sphstab/stress/artificial_stress.hpp\"\n");
  const auto v = layer_violations(t.root, {"kernel", "operators"});
  ASSERT_EQ(v.size(), 2u);
}

TEST(Layers, LayersFileListsTheExpectedOrder) {
  const auto layers = read_layers(fs::path(SPHSTAB_SOURCE_DIR) / "docs" / "layers.txt");
  ASSERT_GE(layers.size(), 10u);
  auto at = [&](const std::string& name) { return std::find(layers.begin(), layers.end(), name) - layers.begin(); };
  // The data flow of the design: particles -> neighbours -> operators -> forms -> jacobian -> stability -> io.
  EXPECT_LT(at("particles"), at("neighbours"));
  EXPECT_LT(at("neighbours"), at("operators"));
  EXPECT_LT(at("operators"), at("forms"));
  EXPECT_LT(at("forms"), at("jacobian"));
  EXPECT_LT(at("jacobian"), at("stability"));
  EXPECT_LT(at("integrate"), at("io"));
  EXPECT_EQ(layers.back(), "cli");
}

TEST(Layers, TheSourceTreeRespectsTheLayers) {
  const fs::path root(SPHSTAB_SOURCE_DIR);
  const auto v = layer_violations(root, read_layers(root / "docs" / "layers.txt"));
  std::string all;
  for (const auto& s : v) all += s + "\n";
  EXPECT_TRUE(v.empty()) << v.size() << " violations:\n" << all;
}

}  // namespace layers_test
