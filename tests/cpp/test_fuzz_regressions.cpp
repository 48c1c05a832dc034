// The fuzzers' findings, replayed through the very decoders and checks of the fuzz targets
// (tests/fuzz/replay.h). tests/fuzz/regressions/<target>/fixed/ holds inputs that once broke and now
// must pass; .../open/ holds findings not fixed yet: their tests carry the DISABLED_ prefix, so ctest
// leaves them out (run them with --gtest_also_run_disabled_tests --gtest_filter='FuzzRegressions.*').
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "replay.h"

namespace {

namespace fs = std::filesystem;
using Case = std::string (*)(const std::uint8_t*, std::size_t);

std::vector<fs::path> inputs(const std::string& dir) {
  std::vector<fs::path> out;
  const fs::path p = fs::path(MESHROUND_FUZZ_REGRESSIONS) / dir;
  if (fs::is_directory(p))
    for (const auto& e : fs::directory_iterator(p))
      if (e.is_regular_file()) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

void replay(const std::string& dir, Case run) {
  for (const fs::path& p : inputs(dir)) {
    std::ifstream f(p, std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_EQ(run(bytes.data(), bytes.size()), "") << p.filename().string();
  }
}

}  // namespace

TEST(FuzzRegressions, RoundFixed) { replay("round/fixed", meshround::fuzz::round_case); }
TEST(FuzzRegressions, ArraysFixed) { replay("arrays/fixed", meshround::fuzz::arrays_case); }
// Open findings (listed in tests/fuzz/regressions/README.md): unsound results, sanitizer reports, hangs.
TEST(FuzzRegressions, DISABLED_RoundOpen) { replay("round/open", meshround::fuzz::round_case); }
TEST(FuzzRegressions, DISABLED_ArraysOpen) { replay("arrays/open", meshround::fuzz::arrays_case); }
