// Flat polygons as the trim and sew passes hand them over: sides that are never split, inner points only
// where the caller admits them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "meshround/mesh_edit.h"
#include "../../cpp_core/src/planar.h"
#include "../../cpp_core/src/ring_index.h"

using namespace meshround;

namespace {

struct Triangulated {
  double smallest_angle_deg = INFINITY;
  double area = 0;
  int triangles = 0;
  bool inner_points_admitted = true;
};

// The polygon (y, z) in the plane x = 0, triangulated with the given refinement.
Triangulated triangulate_yz(const std::vector<std::pair<double, double>>& yz, const Refinement& refine) {
  Points V(3, 3);  // the edit needs an input mesh; the polygon's points are all new
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Triangles F(1, 3);
  F << 0, 1, 2;
  const MeshTopology input(V, F);
  MeshEdit edit(input);
  std::vector<int> polygon;
  for (auto [y, z] : yz) polygon.push_back(edit.add_point(Vec3(0, y, z)));
  const int given = int(edit.new_points.size());
  std::vector<std::array<int, 3>> tris;
  triangulate_polygon(edit, polygon, Vec3::UnitX(), tris, refine);
  Triangulated out;
  for (const auto& t : tris) {
    const Vec3 a = edit.point(t[0]), b = edit.point(t[1]), c = edit.point(t[2]);
    out.smallest_angle_deg = std::min(out.smallest_angle_deg, smallest_angle(a, b, c) * 180 / M_PI);
    out.area += 0.5 * (b - a).cross(c - a).dot(Vec3::UnitX());
    ++out.triangles;
  }
  for (int k = given; k < int(edit.new_points.size()); ++k)
    if (refine.admit && !refine.admit(edit.new_points[k])) out.inner_points_admitted = false;
  return out;
}

double polygon_area(const std::vector<std::pair<double, double>>& yz) {
  double a = 0;
  for (size_t i = 0; i < yz.size(); ++i) {
    const auto [y0, z0] = yz[i];
    const auto [y1, z1] = yz[(i + 1) % yz.size()];
    a += 0.5 * (y0 * z1 - y1 * z0);
  }
  return a;
}



// The end face of an L-channel (legs 60 and 50 mm, thickness 10) whose inner edge got a 4 mm round, as
// the sew pass fills it: the arc, the trim line's graded points on the legs' edges up to the reach
// (12 mm from the edge), and the long outer sides, shared with facets that stay. Points may only go
// within the reach. The far legs must hinge on the last graded points: the 60 mm side's best apex is
// (22, 10) at 14.7 degrees, and the fan back from there to the corner (0, 0) spans 24.4 degrees, which
// two triangles of at least 10 degrees only fill with the graded point before it 6 mm away. Ear clipping
// with refinement alone fans the corner in 7 degree slivers.
TEST(Triangulate, EndFaceBeyondTheReachHingesOnTheLastGradedPoints) {
  const std::vector<std::pair<double, double>> yz = {
      {0, 0},          {0, 50},         {10, 50},        {10, 22},        {10, 15.963},    {10, 14},
      {10.077, 13.220}, {10.304, 12.469}, {10.674, 11.778}, {11.172, 11.172}, {11.778, 10.674}, {12.469, 10.304},
      {13.220, 10.077}, {14, 10},        {15.963, 10},    {22, 10},        {60, 10},        {60, 0}};
  const Refinement within_reach{20, [](const Vec3& p) { return std::hypot(p.y() - 10, p.z() - 10) <= 12; }};
  const Triangulated t = triangulate_yz(yz, within_reach);
  EXPECT_NEAR(t.area, polygon_area(yz), 1e-9 * std::abs(polygon_area(yz)));  // orientation kept, no overlaps
  EXPECT_TRUE(t.inner_points_admitted);
  EXPECT_GE(t.smallest_angle_deg, 10);
}

// A square needs no inner points to be well shaped; a disc's ring of short sides, triangulated
// without points, is a fan of thin triangles, and with points admitted everywhere none is under the
// quality asked for.
TEST(Triangulate, RefinementReachesTheQualityWhereAdmitted) {
  const Triangulated square = triangulate_yz({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, Refinement{20, {}});
  EXPECT_EQ(square.triangles, 2);
  EXPECT_NEAR(square.smallest_angle_deg, 45, 1e-9);
  std::vector<std::pair<double, double>> disc;
  for (int k = 0; k < 32; ++k) disc.emplace_back(10 * std::cos(k * M_PI / 16), 10 * std::sin(k * M_PI / 16));
  EXPECT_LT(triangulate_yz(disc, Refinement{}).smallest_angle_deg, 12);
  const Triangulated refined = triangulate_yz(disc, Refinement{20, {}});
  EXPECT_NEAR(refined.area, polygon_area(disc), 1e-9 * polygon_area(disc));
  EXPECT_GE(refined.smallest_angle_deg, 20);
}

// The refinement's index (ring_index.h) answers as a pass over the whole ring does, on a star-shaped ring
// of 400 sides, long along y (slabs across y) and turned to lie along x (slabs across x).
TEST(RingIndex, AnswersAsAPassOverTheWholeRing) {
  for (int turned = 0; turned < 2; ++turned) {
    std::vector<Eigen::Vector2d> Q;
    const int n = 400;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n, r = 10 + 4 * std::sin(7 * a) + 2 * std::cos(23 * a);
      const Eigen::Vector2d p(r * std::cos(a), 3 * r * std::sin(a));
      Q.push_back(turned ? Eigen::Vector2d(p.y(), -p.x()) : p);
    }
    const size_t boundary = Q.size();
    planar::RingIndex index(Q, boundary);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> across(-45, 45), near(0.05, 3);
    std::vector<int> sides;
    int inside = 0;
    for (int k = 0; k < 3000; ++k) {
      const Eigen::Vector2d x(across(random), across(random));
      const double d = near(random);
      ASSERT_EQ(index.inside(x), planar::inside_polygon(x, Q, boundary)) << x.transpose();
      inside += index.inside(x);
      index.sides_near(x, d, sides);
      for (size_t i = 0; i < boundary; ++i) {
        const Eigen::Vector2d &p = Q[i], &q = Q[(i + 1) % boundary];
        const double t = std::clamp((x - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
        if ((x - (p + t * (q - p))).norm() <= d) ASSERT_TRUE(std::binary_search(sides.begin(), sides.end(), int(i))) << i;
      }
      bool brute = false;
      for (const auto& q : Q) brute |= (q - x).norm() <= d;
      ASSERT_EQ(index.point_within(x, d), brute);
    }
    EXPECT_GT(inside, 300);  // the test sees both answers
    EXPECT_LT(inside, 2700);
    // Inner points added and taken back.
    Q.push_back(Eigen::Vector2d(0.5, 0.5));
    index.add_point(int(Q.size()) - 1);
    EXPECT_TRUE(index.point_within(Eigen::Vector2d(0.6, 0.5), 0.2));
    index.remove_point(int(Q.size()) - 1);
    Q.pop_back();
    EXPECT_FALSE(index.point_within(Eigen::Vector2d(0.6, 0.5), 0.2));
  }
}

}  // namespace
