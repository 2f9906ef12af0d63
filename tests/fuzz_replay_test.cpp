// Runs the fuzz seed corpus and every saved crash input through the same
// entry points as the libFuzzer targets, in every build: a fixed crash stays
// fixed even where no fuzzer runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>

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

// The NanoVDB seed (stored compressed, as tests/fuzz/run.sh unpacks it),
// written here by NanoVDB itself, and cut and overwritten versions of it.
TEST(FuzzReplay, NvdbSeedsCutsAndRegressions) {
  nanovdb::GridBuilder<float> builder(0.f);
  builder.getAccessor().setValue(nanovdb::Coord(0), 1.f);
  builder.getAccessor().setValue(nanovdb::Coord(3, 9, 2), 2.f);
  const fs::path file = fs::temp_directory_path() / "lantern-replay-seed.nvdb";
  nanovdb::io::writeGrid(file.string(), builder.getHandle<>(1.0, nanovdb::Vec3d(0.0), "density"));
  const std::string seed = read_bytes(file);
  fs::remove(file);
  ASSERT_GT(seed.size(), 1000u);
  auto run = [](const std::string& bytes) {
    EXPECT_NO_THROW(lantern::fuzz::load_nvdb(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
  };
  run(seed);
  for (size_t cut : {size_t(0), size_t(15), size_t(16), size_t(100), size_t(200), seed.size() / 2, seed.size() - 1})
    run(seed.substr(0, cut));
  for (size_t at = 0; at < 400; at += 7) {  // the headers and metadata, overwritten
    std::string bad = seed;
    bad[at] = char(bad[at] ^ 0x5A);
    run(bad);
  }
  auto files = inputs({kSrc / "tests/fuzz/regressions/nvdb"}, {});
  replay(files, lantern::fuzz::load_nvdb);
}

TEST(FuzzReplay, PlyCorpusAndRegressions) {
  auto files = inputs({kSrc / "tests/fuzz/corpus/ply", kSrc / "tests/fuzz/regressions/ply"}, {});
  EXPECT_GE(replay(files, lantern::fuzz::load_ply), 4u);
}
