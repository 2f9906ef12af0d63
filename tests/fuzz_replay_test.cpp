// Runs the fuzz seed corpus and every saved crash input through the same
// entry points as the libFuzzer targets, in every build: a fixed crash stays
// fixed even where no fuzzer runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fuzz/fuzz_entry.h"

namespace fs = std::filesystem;

namespace {

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Files directly in the given folders whose name ends with one of `exts`
// (an empty list: every file).
std::vector<fs::path> inputs(const std::vector<fs::path>& dirs, const std::vector<std::string>& exts) {
  std::vector<fs::path> out;
  for (const fs::path& d : dirs) {
    if (!fs::is_directory(d)) continue;
    for (const auto& e : fs::directory_iterator(d)) {
      if (!e.is_regular_file()) continue;
      bool ok = exts.empty();
      for (const std::string& x : exts) ok = ok || e.path().extension() == x;
      if (ok) out.push_back(e.path());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

template <class Fn>
size_t replay(const std::vector<fs::path>& files, Fn&& fn) {
  for (const fs::path& p : files) {
    SCOPED_TRACE(p.string());
    std::string bytes = read_bytes(p);
    EXPECT_NO_THROW(fn(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
  }
  return files.size();
}

const fs::path kSrc = LANTERN_SOURCE_DIR;

}  // namespace

TEST(FuzzReplay, PbrtCorpusAndRegressions) {
  auto files = inputs({kSrc / "tests/fuzz/corpus/pbrt", kSrc / "scenes"}, {".pbrt"});
  auto regressions = inputs({kSrc / "tests/fuzz/regressions/pbrt"}, {});
  files.insert(files.end(), regressions.begin(), regressions.end());
  EXPECT_GE(replay(files, lantern::fuzz::load_pbrt), 7u);
}

TEST(FuzzReplay, PlyCorpusAndRegressions) {
  auto files = inputs({kSrc / "tests/fuzz/corpus/ply", kSrc / "tests/fuzz/regressions/ply"}, {});
  EXPECT_GE(replay(files, lantern::fuzz::load_ply), 4u);
}
