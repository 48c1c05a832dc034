// The last pass over the new facets: flips and removals on flat ground only, never the round's vertices,
// never a facet with no corner where points are admitted.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "meshround/improve.h"

using namespace meshround;

namespace {

// An edit whose new facets are set directly; its input mesh is a stand-in far away.
struct Scene {
  Points V;
  Triangles F;
  MeshTopology input;
  MeshEdit edit;
  Scene() : V(stand_in_points()), F(stand_in_facets()), input(V, F), edit(input) {}
  static Points stand_in_points() {
    Points P(3, 3);
    P << 1000, 0, 0, 1001, 0, 0, 1000, 1, 0;
    return P;
  }
  static Triangles stand_in_facets() {
    Triangles T(1, 3);
    T << 0, 1, 2;
    return T;
  }
  int point(double x, double y, double z) { return edit.add_point(Vec3(x, y, z)); }
  double smallest_angle_deg() const {
    double q = INFINITY;
    for (const auto& t : edit.added) q = std::min(q, smallest_angle(edit.point(t[0]), edit.point(t[1]), edit.point(t[2])));
    return q * 180 / M_PI;
  }
  Vec3 vector_area() const {  // the same surface keeps it, whatever its triangles
    Vec3 a = Vec3::Zero();
    for (const auto& t : edit.added) a += 0.5 * (edit.point(t[1]) - edit.point(t[0])).cross(edit.point(t[2]) - edit.point(t[0]));
    return a;
  }
  bool has_edge(int a, int b) const {
    for (const auto& t : edit.added)
      for (int k = 0; k < 3; ++k)
        if (edge_key(t[k], t[(k + 1) % 3]) == edge_key(a, b)) return true;
    return false;
  }
};

const std::function<bool(const Vec3&)> everywhere = [](const Vec3&) { return true; };
const std::function<bool(const Vec3&)> nowhere = [](const Vec3&) { return false; };

// A flat kite split along its long diagonal (smallest angle 14.04 degrees); the short one gives 28.07.
struct Kite : Scene {
  int a, b, c, d;
  explicit Kite(double lift = 0) {
    a = point(0, 0, 0), b = point(4, -1, 0), c = point(8, 0, 0), d = point(4, 1, lift);
    edit.added = {{a, b, c}, {a, c, d}};
  }
};

TEST(ImproveNewFacets, FlipsTheSharedEdgeOfTwoCoplanarFacetsToTheBetterDiagonal) {
  Kite kite;
  const Vec3 area = kite.vector_area();
  const ImproveStats stats = improve_new_facets(kite.edit, {}, everywhere);
  EXPECT_EQ(stats.flips, 1);
  EXPECT_TRUE(kite.has_edge(kite.b, kite.d));
  EXPECT_FALSE(kite.has_edge(kite.a, kite.c));
  EXPECT_NEAR(kite.smallest_angle_deg(), 2 * std::atan(0.25) * 180 / M_PI, 1e-9);
  EXPECT_LT((kite.vector_area() - area).norm(), 1e-12);
}

TEST(ImproveNewFacets, LeavesFacetsThatAreNotCoplanar) {
  Kite kite(0.5);  // flipping would change the surface
  EXPECT_EQ(improve_new_facets(kite.edit, {}, everywhere).flips, 0);
  EXPECT_TRUE(kite.has_edge(kite.a, kite.c));
}

TEST(ImproveNewFacets, LeavesEdgesBetweenTheRoundsVerticesAndFacetsWhereNoPointMayGo) {
  Kite kite;
  EXPECT_EQ(improve_new_facets(kite.edit, {kite.a, kite.c}, everywhere).flips, 0);
  EXPECT_EQ(improve_new_facets(kite.edit, {}, nowhere).flips, 0);
  EXPECT_TRUE(kite.has_edge(kite.a, kite.c));
}

// Two flat faces (z = 0 and y = 0) meeting on the crease p-q along x; v sits on the crease near q, so
// both faces have a sliver at v. Without v each face is one triangle of 38.66 degrees.
struct Crease : Scene {
  int p, v, q, top, side;
  explicit Crease(double off_line = 0) {
    p = point(0, 0, 0), v = point(9, off_line, 0), q = point(10, 0, 0), top = point(5, 4, 0), side = point(5, 0, 4);
    edit.added = {{p, v, top}, {v, q, top}, {v, p, side}, {q, v, side}};
  }
};

TEST(ImproveNewFacets, RemovesAVertexOnAStraightCreaseWhenBothFacesGetBetter) {
  Crease crease;
  const Vec3 area = crease.vector_area();
  const ImproveStats stats = improve_new_facets(crease.edit, {}, everywhere);
  EXPECT_EQ(stats.vertices_removed, 1);
  ASSERT_EQ(crease.edit.added.size(), 2u);
  EXPECT_TRUE(crease.has_edge(crease.p, crease.q));
  EXPECT_NEAR(crease.smallest_angle_deg(), std::atan2(4.0, 5.0) * 180 / M_PI, 1e-9);
  EXPECT_LT((crease.vector_area() - area).norm(), 1e-12);
}

TEST(ImproveNewFacets, KeepsTheRoundsVerticesAndVerticesOffAStraightCrease) {
  Crease kept;
  EXPECT_EQ(improve_new_facets(kept.edit, {kept.v}, everywhere).vertices_removed, 0);
  EXPECT_EQ(kept.edit.added.size(), 4u);
  Crease bent(0.01);  // v off the line p-q: the crease bends there, removing v would straighten it
  EXPECT_EQ(improve_new_facets(bent.edit, {}, everywhere).vertices_removed, 0);
  EXPECT_EQ(bent.edit.added.size(), 4u);
}

TEST(ImproveNewFacets, SlidesACreaseVertexThatCannotGoToWhereItsFacetsAreBest) {
  Crease crease;
  const int w = crease.point(5, -3, -3);
  crease.edit.added.push_back({crease.p, crease.q, w});  // p-q taken: removing v would make it non-manifold
  const ImproveStats stats = improve_new_facets(crease.edit, {}, everywhere);
  EXPECT_EQ(stats.vertices_removed, 0);
  EXPECT_EQ(stats.vertices_slid, 1);
  const Vec3 at = crease.edit.point(crease.v);
  EXPECT_EQ(at.y(), 0.0);  // still on the crease, now clear of q
  EXPECT_EQ(at.z(), 0.0);
  EXPECT_LT(at.x(), 7.0);
  EXPECT_EQ(crease.edit.added.size(), 5u);
  EXPECT_NEAR(crease.smallest_angle_deg(), std::atan2(4.0, 5.0) * 180 / M_PI, 1e-9);
}

// A network's flat patch (remesh_flat_patches): a face 95 x 35 whose made facets fan from its far corner
// (0, 0) to a trim line of 39 points along y = 35, as an earlier round's trim leaves it for the next one to
// cut; points may go only within 10 of the line (the reach).
struct Fan {
  Points V;
  Triangles F;
  std::vector<int> ring;  // the outline, counter-clockwise seen from +z
  explicit Fan(bool inner_input_vertex = false) {
    std::vector<Vec3> P{{0, 0, 0}, {95, 0, 0}};
    for (int i = 0; i <= 38; ++i) P.push_back({95 - 2.5 * i, 35, 0});
    for (int v = 0; v < int(P.size()); ++v) ring.push_back(v);
    std::vector<std::array<int, 3>> T{{0, 1, 2}};
    for (int i = 2; i + 1 < int(P.size()); ++i) T.push_back({0, i, i + 1});
    if (inner_input_vertex) {  // a vertex inside the face: the fan's second facet split at its centroid
      P.push_back((P[0] + P[2] + P[3]) / 3);
      const int c = int(P.size()) - 1;
      const auto t = T[1];
      T[1] = {t[0], t[1], c}, T.push_back({t[1], t[2], c}), T.push_back({t[2], t[0], c});
    }
    V.resize(long(P.size()), 3);
    for (int v = 0; v < int(P.size()); ++v) V.row(v) = P[size_t(v)].transpose();
    F.resize(long(T.size()), 3);
    for (int f = 0; f < int(T.size()); ++f) F.row(f) << T[size_t(f)][0], T[size_t(f)][1], T[size_t(f)][2];
  }
};

const std::function<bool(const Vec3&)> near_the_line = [](const Vec3& p) { return p.y() >= 25; };

TEST(RemeshFlatPatches, MeshesAFanFromAFarCornerAgainWholeWithItsOutlineKept) {
  const Fan fan;
  const MeshTopology mesh(fan.V, fan.F);
  double before = INFINITY;
  for (int f = 0; f < mesh.num_facets(); ++f) before = std::min(before, smallest_angle(mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2)));
  ASSERT_LT(before * 180 / M_PI, 1.0);
  MeshEdit edit(mesh);
  const ImproveStats stats = remesh_flat_patches(edit, std::vector<char>(size_t(mesh.num_facets()), 1), [](int) { return true; }, near_the_line);
  ASSERT_EQ(stats.patches_remeshed, 1);
  EXPECT_EQ(edit.removed.size(), size_t(mesh.num_facets()));
  // Every side of the outline once, in its direction; every other edge twice, once each way; the area kept.
  std::map<std::pair<int, int>, int> directed;
  Vec3 area = Vec3::Zero();
  double after = INFINITY;
  for (const auto& t : edit.added) {
    const Vec3 a = edit.point(t[0]), b = edit.point(t[1]), c = edit.point(t[2]);
    area += 0.5 * (b - a).cross(c - a);
    after = std::min(after, smallest_angle(a, b, c));
    EXPECT_TRUE(near_the_line(a) || near_the_line(b) || near_the_line(c));  // no facet wholly beyond the reach
    EXPECT_TRUE(a.z() == 0 && b.z() == 0 && c.z() == 0);  // in the face's plane
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  auto uses = [&](int p, int q) { return directed.count(std::make_pair(p, q)) ? directed.at(std::make_pair(p, q)) : 0; };
  const size_t n = fan.ring.size();
  for (size_t i = 0; i < n; ++i) {
    const int p = fan.ring[i], q = fan.ring[(i + 1) % n];
    EXPECT_EQ(uses(p, q), 1) << p << "-" << q;
    EXPECT_EQ(uses(q, p), 0) << p << "-" << q;
  }
  for (const auto& [e, count] : directed) {
    const bool side = std::abs(e.first - e.second) == 1 || edge_key(e.first, e.second) == edge_key(0, int(n) - 1);
    if (!side) EXPECT_EQ(count + uses(e.second, e.first), 2) << e.first << "-" << e.second;
  }
  EXPECT_NEAR(area.z(), 95.0 * 35.0, 1e-6);
  EXPECT_GE(after * 180 / M_PI, 10.0);
}

TEST(RemeshFlatPatches, LeavesAPatchWithAVertexInsideThatMayNotGo) {
  const Fan fan(true);
  const MeshTopology mesh(fan.V, fan.F);
  MeshEdit edit(mesh);
  const int inner = mesh.num_vertices() - 1;
  auto may_go = [inner](int v) { return v != inner; };
  EXPECT_EQ(remesh_flat_patches(edit, std::vector<char>(size_t(mesh.num_facets()), 1), may_go, near_the_line).patches_remeshed, 0);
  EXPECT_TRUE(edit.added.empty() && edit.removed.empty());
  // The same vertex made by the call (it may go): the patch is meshed again.
  MeshEdit again(mesh);
  EXPECT_EQ(remesh_flat_patches(again, std::vector<char>(size_t(mesh.num_facets()), 1), [](int) { return true; }, near_the_line).patches_remeshed, 1);
}

TEST(RemeshFlatPatches, LeavesFacetsTheCallDidNotMake) {
  const Fan fan;
  const MeshTopology mesh(fan.V, fan.F);
  MeshEdit edit(mesh);
  EXPECT_EQ(remesh_flat_patches(edit, std::vector<char>(size_t(mesh.num_facets()), 0), [](int) { return true; }, near_the_line).patches_remeshed, 0);
}

}  // namespace
