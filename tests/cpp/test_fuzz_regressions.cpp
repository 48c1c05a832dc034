// The fuzzers' findings, replayed through the very decoders and checks of the fuzz targets
// (tests/fuzz/replay.h). tests/fuzz/regressions/<target>/fixed/ holds inputs that once broke and now
// must pass; .../open/ holds findings not fixed yet: their tests carry the DISABLED_ prefix, so ctest
// leaves them out (run them with --gtest_also_run_disabled_tests --gtest_filter='FuzzRegressions.*').
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <BRepPrimAPI_MakeBox.hxx>

#include "deck_case.h"
#include "replay.h"
#include "support.h"

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
TEST(FuzzRegressions, DecksFixed) { replay("decks/fixed", meshround::fuzz::deck_case); }
TEST(FuzzRegressions, ReroundFixed) { replay("reround/fixed", meshround::fuzz::reround_case); }
// Open findings (listed in tests/fuzz/regressions/README.md): unsound results, sanitizer reports, hangs.
TEST(FuzzRegressions, DISABLED_RoundOpen) { replay("round/open", meshround::fuzz::round_case); }
TEST(FuzzRegressions, DISABLED_ArraysOpen) { replay("arrays/open", meshround::fuzz::arrays_case); }
TEST(FuzzRegressions, DISABLED_ReroundOpen) { replay("reround/open", meshround::fuzz::reround_case); }

// The fuzzer's soundness check accepts a good rounding (the standard box edge) and catches a hole, a
// fold and a crossing made in it.
TEST(FuzzSoundness, AcceptsTheBoxRoundingAndCatchesDamage) {
  using namespace meshround;
  const test::TriMesh in = test::mesh_shape(BRepPrimAPI_MakeBox(100, 60, 40).Shape(), 10);
  RoundOptions opt;
  opt.radius = 5;
  const RoundResult res = round_edges(in.V, in.F, {Vec3(37, 60, 40)}, opt);
  fuzz::SoundnessInput s{in.V, in.F, res.vertices, res.triangles, {res.chains[0].chain.front(), res.chains[0].chain.back()}, 15};
  EXPECT_EQ(fuzz::check_sound(s), "");
  // A new facet removed: a hole.
  Triangles holed = res.triangles.topRows(res.triangles.rows() - 1);
  fuzz::SoundnessInput h{in.V, in.F, res.vertices, holed, {}, 0};
  EXPECT_NE(fuzz::check_sound(h), "");
  // The last facet flipped: misoriented edges.
  Triangles flipped = res.triangles;
  std::swap(flipped(flipped.rows() - 1, 1), flipped(flipped.rows() - 1, 2));
  fuzz::SoundnessInput f{in.V, in.F, res.vertices, flipped, {}, 0};
  EXPECT_NE(fuzz::check_sound(f), "");
  // A new vertex pushed through the opposite face of the box: crossings.
  Points moved = res.vertices;
  const int v = res.triangles(res.triangles.rows() - 1, 0);
  moved(v, 1) = -30;
  fuzz::SoundnessInput x{in.V, in.F, moved, res.triangles, {}, 0};
  EXPECT_NE(fuzz::check_sound(x), "");
}

TEST(FuzzSoundness, ExactTriangleTests) {
  using namespace meshround;
  Points V(7, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0,  // t0 in z = 0
      0.2, 0.2, -1, 0.2, 0.2, 1, 5, 5, 5,  // a segment through t0, and a far point
      0.25, 0.25, 0;                          // a point inside t0
  EXPECT_TRUE(fuzz::triangles_intersect(V, {0, 1, 2}, {3, 4, 5}));
  EXPECT_FALSE(fuzz::triangles_intersect(V, {0, 1, 2}, {1, 0, 5}));  // share an edge, not folded
  EXPECT_TRUE(fuzz::triangles_intersect(V, {0, 1, 2}, {0, 1, 6}));   // share an edge, folded onto it
  auto o = [&](double z) { return fuzz::exact::orient3d(V.row(0), V.row(1), V.row(2), Vec3(0.3, 0.3, z)); };
  EXPECT_NE(o(1e-300), 0);  // exact: a denormal height off the plane has a side
  EXPECT_EQ(o(1e-300), -o(-1e-300));
  EXPECT_EQ(fuzz::exact::orient3d(V.row(0), V.row(1), V.row(2), Vec3(0.3, 0.3, 0)), 0);
}
