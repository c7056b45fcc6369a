// test_fuzz_regressions.cpp — replays, in the ordinary build, every input that once
// made a fuzz target of fuzz/ fail (kept under tests/robustness/regressions/<target>/
// after the fix) and the fuzz seeds, through the same entry functions
// (fuzz/entries.hpp).  Each must return normally: bad input is an InputError, caught
// inside the entry; anything else escaping (another exception) fails the test, and a
// crash fails the executable.  Under scripts/sanitize.sh the sanitizers check the
// replay too.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "entries.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> files_in(const fs::path& dir, const std::string& extension = "") {
  std::vector<fs::path> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && (extension.empty() || e.path().extension() == extension) &&
        e.path().filename().string()[0] != '.')
      out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const fs::path kRegressions = fs::path(CDYN_SOURCE_DIR) / "tests" / "robustness" / "regressions";

template <class Entry>
int replay(const std::vector<fs::path>& files, Entry entry) {
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    EXPECT_NO_THROW(entry(read(f)));
  }
  return static_cast<int>(files.size());
}

}  // namespace

TEST(FuzzRegressions, Scene) {
  const int n = replay(files_in(kRegressions / "scene"), cdyn::fuzz::scene_input);
  const int seeds = replay(files_in(fs::path(CDYN_SOURCE_DIR) / "data" / "scenes", ".toml"), cdyn::fuzz::scene_input);
  std::printf("scene: %d regression inputs, %d seeds replayed\n", n, seeds);
}

TEST(FuzzRegressions, Expression) {
  const int n = replay(files_in(kRegressions / "expression"), cdyn::fuzz::expression_input);
  std::printf("expression: %d regression inputs replayed\n", n);
}

TEST(FuzzRegressions, Mesh) {
  const int n = replay(files_in(kRegressions / "mesh"), cdyn::fuzz::mesh_input);
  const int seeds = replay(files_in(fs::path(CDYN_SOURCE_DIR) / "fuzz" / "seeds", ".msh"), cdyn::fuzz::mesh_input);
  std::printf("mesh: %d regression inputs, %d seeds replayed\n", n, seeds);
}
