// The private search index (cpp_core/src/box_tree.h): exact closest primitives, the same answer as
// trying every primitive (ties to the smallest id), at a cost that follows the primitives near the
// query, not the empty space around them.
#include <gtest/gtest.h>

#include <random>

#include "box_tree.h"
#include "meshround/mesh.h"

using namespace meshround;

namespace {

struct Soup {
  std::vector<std::array<Vec3, 3>> tri;
  std::vector<Vec3> boxes() const {
    std::vector<Vec3> out;
    for (const auto& t : tri) out.push_back(t[0].cwiseMin(t[1]).cwiseMin(t[2])), out.push_back(t[0].cwiseMax(t[1]).cwiseMax(t[2]));
    return out;
  }
  double d2(int i, const Vec3& p) const {
    return (closest_point_on_triangle(p, tri[i][0], tri[i][1], tri[i][2], nullptr) - p).squaredNorm();
  }
};

// Small triangles scattered in a 100 mm cube, and a few long slivers across it (a CAD facet).
Soup random_soup(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 100), e(-1, 1);
  Soup s;
  for (int i = 0; i < n; ++i) {
    const Vec3 c(u(rng), u(rng), u(rng));
    s.tri.push_back({c, c + Vec3(e(rng), e(rng), e(rng)), c + Vec3(e(rng), e(rng), e(rng))});
  }
  for (int i = 0; i < 5; ++i) s.tri.push_back({Vec3(0, u(rng), u(rng)), Vec3(100, u(rng), u(rng)), Vec3(100, u(rng), u(rng) + 0.01)});
  return s;
}

}  // namespace

TEST(BoxTree, NearestEqualsBruteForce) {
  const Soup s = random_soup(5000, 1);
  const BoxTree tree(s.boxes());
  ASSERT_EQ(tree.size(), int(s.tri.size()));
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-50, 150);
  for (int q = 0; q < 500; ++q) {
    const Vec3 p(u(rng), u(rng), u(rng));
    double best = INFINITY;
    int best_id = -1;
    for (int i = 0; i < int(s.tri.size()); ++i)
      if (s.d2(i, p) < best) best = s.d2(i, p), best_id = i;
    double d2;
    const int id = tree.nearest(p, [&](int i) { return s.d2(i, p); }, &d2);
    EXPECT_EQ(id, best_id);
    EXPECT_EQ(d2, best);  // bit for bit: the same function on the same facet
  }
}

TEST(BoxTree, TiesGoToTheSmallestId) {
  // Four copies of one segment's box, and the query equally near all of them.
  std::vector<Vec3> boxes;
  for (int i = 0; i < 9; ++i) boxes.push_back(Vec3(0, 0, 0)), boxes.push_back(Vec3(1, 0, 0));
  const BoxTree tree(boxes);
  const Vec3 p(0.5, 2, 0);
  EXPECT_EQ(tree.nearest(p, [&](int) { return 4.0; }), 0);
}

TEST(BoxTree, EmptyTree) {
  const BoxTree tree({});
  double d2 = 0;
  EXPECT_EQ(tree.nearest(Vec3::Zero(), [](int) { return 0.0; }, &d2), -1);
  EXPECT_EQ(d2, INFINITY);
}

TEST(BoxTree, FarQueriesMeasureFewPrimitives) {
  // A 200 x 200 grid of unit squares (two triangles each) in z = 0: a query 3 m away or one just above
  // the sheet measures a handful of facets, not the sheet (a uniform grid of cell ~1 would walk
  // billions of empty cells for the far one).
  Soup s;
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 200; ++j) {
      const Vec3 a(i, j, 0), b(i + 1, j, 0), c(i + 1, j + 1, 0), d(i, j + 1, 0);
      s.tri.push_back({a, b, c}), s.tri.push_back({a, c, d});
    }
  const BoxTree tree(s.boxes());
  for (const Vec3& p : {Vec3(100.3, 50.6, 0.01), Vec3(37, 3000, 40), Vec3(-3000, -3000, 3000)}) {
    int visited = 0;
    double d2;
    const int id = tree.nearest(p, [&](int i) { return s.d2(i, p); }, &d2, &visited);
    ASSERT_GE(id, 0);
    double best = INFINITY;
    for (int i = 0; i < int(s.tri.size()); ++i) best = std::min(best, s.d2(i, p));
    EXPECT_EQ(d2, best);
    EXPECT_LT(visited, 2000) << "at " << format_point(p);  // of 80000
  }
}
