// The output check: a clean edit passes; a hole, a non-manifold edge, a flipped facet, a degenerate facet
// and a vertex beyond the faces it rounds are each refused with result_invalid.
#include <gtest/gtest.h>

#include <BRepPrimAPI_MakeBox.hxx>

#include "../../cpp_core/src/guard.h"
#include "support.h"

using namespace meshround;
using namespace meshround::test;

namespace {

struct Scene {
  TriMesh m = mesh_shape(BRepPrimAPI_MakeBox(100, 60, 40).Shape(), 4.0);
  MeshTopology mesh{m.V, m.F};
  SharpChain chain = trace_chain(mesh, Vec3(37, 60, 40), 30, 15);
  MeshEdit edit{mesh};
  int facet = -1;  // a facet of the top face beside the chain
  Scene() {
    for (int f = 0; f < mesh.num_facets() && facet < 0; ++f) {
      const Vec3 c = (mesh.corner(f, 0) + mesh.corner(f, 1) + mesh.corner(f, 2)) / 3;
      if (std::abs(c.z() - 40) < 1e-9 && c.y() > 56 && std::abs(c.x() - 50) < 4) facet = f;
    }
  }
  int corner(int k) const { return mesh.F(facet, k); }
  // The facet replaced by a fan around a new point at p.
  void fan_around(const Vec3& p) {
    edit.removed.insert(facet);
    const int c = edit.add_point(p);
    for (int k = 0; k < 3; ++k) edit.added.push_back({corner(k), corner((k + 1) % 3), c});
  }
  Vec3 centroid() const { return (mesh.corner(facet, 0) + mesh.corner(facet, 1) + mesh.corner(facet, 2)) / 3; }
  std::string refusal() {
    try {
      check_result(edit, chain, 15, 0.05);
    } catch (const RoundingError& e) {
      EXPECT_EQ(e.code, ErrorCode::ResultInvalid);
      return e.what();
    }
    return "";
  }
};

TEST(OutputCheck, PassesAFacetSplitInItsPlane) {
  Scene s;
  ASSERT_GE(s.facet, 0);
  s.fan_around(s.centroid());
  EXPECT_EQ(s.refusal(), "");
}

TEST(OutputCheck, RefusesAHole) {
  Scene s;
  s.edit.removed.insert(s.facet);
  EXPECT_NE(s.refusal().find("new boundary edge"), std::string::npos);
}

TEST(OutputCheck, RefusesANonManifoldEdge) {
  Scene s;
  s.edit.added.push_back({s.corner(0), s.corner(1), s.corner(2)});  // the facet twice: three on each edge
  EXPECT_NE(s.refusal().find("non-manifold"), std::string::npos);
}

TEST(OutputCheck, RefusesAFlippedFacet) {
  Scene s;
  s.edit.removed.insert(s.facet);
  s.edit.added.push_back({s.corner(0), s.corner(2), s.corner(1)});
  EXPECT_NE(s.refusal().find("facing the other way"), std::string::npos);
}

TEST(OutputCheck, RefusesADegenerateFacet) {
  Scene s;
  s.fan_around(s.mesh.corner(s.facet, 0) + 1e-9 * (s.mesh.corner(s.facet, 1) - s.mesh.corner(s.facet, 0)));
  EXPECT_NE(s.refusal().find("degenerate"), std::string::npos);
}

TEST(OutputCheck, RefusesAVertexBeyondTheFacesItRounds) {
  Scene s;
  s.fan_around(s.centroid() + Vec3(0, 0, 0.5));
  EXPECT_NE(s.refusal().find("beyond the faces it rounds"), std::string::npos);
}

TEST(OutputCheck, RefusesAVertexThatIsNotANumber) {
  // A NaN point passes every comparison of the placement checks: refused on its own.
  Scene s;
  s.fan_around(Vec3(NAN, NAN, NAN));
  EXPECT_NE(s.refusal().find("not a number"), std::string::npos);
}

TEST(OutputCheck, NamesANewHoleNextToAHoleOfTheInputAsTheInputs) {
  // The input lacks one facet beside the chain; the edit takes away its neighbour: the new boundary lies
  // next to the input's own, so the refusal is the input's (non_manifold_input), naming that place.
  Scene s;
  TriMesh holed = s.m;
  holed.F.row(s.facet) = holed.F.row(holed.F.rows() - 1);
  holed.F.conservativeResize(holed.F.rows() - 1, 3);
  const MeshTopology mesh(holed.V, holed.F);  // (the chain as traced on the whole mesh: the same vertices)
  int neighbour = -1;
  for (int f = 0; f < mesh.num_facets() && neighbour < 0; ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.edge_facet_count(mesh.F(f, k), mesh.F(f, (k + 1) % 3)) == 1 && std::abs(mesh.corner(f, 0).z() - 40) < 1e-9) neighbour = f;
  ASSERT_GE(neighbour, 0);
  MeshEdit edit{mesh};
  edit.removed.insert(neighbour);
  try {
    check_result(edit, s.chain, 15, 0.05);
    FAIL() << "a hole passed the check";
  } catch (const RoundingError& e) {
    EXPECT_EQ(e.code, ErrorCode::NonManifoldInput) << e.what();
    EXPECT_NE(std::string(e.what()).find("a hole in it"), std::string::npos) << e.what();
  }
}

TEST(OutputCheck, RefusesAVertexOfTheMeshBoundaryMovedOffItAndPassesOneSlidAlongIt) {
  // The input lacks one facet beside the chain. A vertex of that hole's rim moved into the hole notches the
  // mesh's edge: refused, though no edge is new (the same vertex ids), as the input's fault (the band ran into
  // its hole: non_manifold_input naming it). Slid along a rim edge, it stays on it.
  Scene s;
  TriMesh holed = s.m;
  const int a = s.corner(0), b = s.corner(1);
  holed.F.row(s.facet) = holed.F.row(holed.F.rows() - 1);
  holed.F.conservativeResize(holed.F.rows() - 1, 3);
  const MeshTopology mesh(holed.V, holed.F);
  ASSERT_EQ(mesh.edge_facet_count(a, b), 1);
  const Vec3 pa = mesh.point(a), pb = mesh.point(b), c = s.centroid();
  for (const bool along : {false, true}) {
    MeshEdit edit{mesh};
    edit.moved[a] = along ? Vec3(pa + 0.1 * (pb - pa)) : Vec3(pa + 0.2 * (c - pa));
    std::string refusal;
    ErrorCode code = ErrorCode::InvalidInput;
    try {
      check_result(edit, s.chain, 15, 0.05);
    } catch (const RoundingError& e) {
      refusal = e.what(), code = e.code;
    }
    if (along) {
      EXPECT_EQ(refusal, "");
    } else {
      EXPECT_EQ(code, ErrorCode::NonManifoldInput) << refusal;
      EXPECT_NE(refusal.find("the mesh is open (a hole in it, or its edge) where the rounding goes, at ("), std::string::npos) << refusal;
    }
  }
}

TEST(OutputCheck, RefusesANewFacetThroughAKeptFacetAwayFromTheBand) {
  // A kept facet that shares no vertex with the edit (a wall across a thin part, a loose piece) still
  // counts: the fan dipped under the top face runs through a small upright facet standing there.
  Scene s;
  ASSERT_GE(s.facet, 0);
  const Vec3 c = s.centroid();
  TriMesh with_wall = s.m;
  const int n = int(with_wall.V.rows()), m = int(with_wall.F.rows());
  with_wall.V.conservativeResize(n + 3, 3);
  with_wall.V.row(n) = (c + Vec3(-1, 0, -0.9)).transpose();
  with_wall.V.row(n + 1) = (c + Vec3(1, 0, -0.9)).transpose();
  with_wall.V.row(n + 2) = (c + Vec3(0, 0, -0.1)).transpose();
  with_wall.F.conservativeResize(m + 1, 3);
  with_wall.F.row(m) << n, n + 1, n + 2;
  const MeshTopology mesh(with_wall.V, with_wall.F);
  auto edit_with_dip = [&](double dip) {
    MeshEdit edit{mesh};
    edit.removed.insert(s.facet);
    const int apex = edit.add_point(c - Vec3(0, 0, dip));
    for (int k = 0; k < 3; ++k) edit.added.push_back({s.corner(k), s.corner((k + 1) % 3), apex});
    return edit;
  };
  EXPECT_NO_THROW(check_result(edit_with_dip(0.05), s.chain, 15, 0.05));  // above the wall's top: clear
  try {
    check_result(edit_with_dip(0.5), s.chain, 15, 0.05);
    FAIL() << "a facet through a kept facet passed the check";
  } catch (const RoundingError& e) {
    EXPECT_EQ(e.code, ErrorCode::ResultInvalid);
    EXPECT_NE(std::string(e.what()).find("cross each other"), std::string::npos) << e.what();
  }
}

TEST(OutputCheck, RefusesAFacetFoldedBackOntoItsNeighbourByAHair) {
  // The facet replaced by a fan around a point 0.001 mm under the top face: inside the facet that is a sound
  // (hardly) bent fan; past one of its sides, over the kept neighbour there, the fan folds back onto that
  // neighbour -- too flat for the piercing test to see, so the two are tested as coplanar (guard.cpp
  // kFoldShare).
  Scene s;
  ASSERT_GE(s.facet, 0);
  int a = -1, b = -1, c = -1;
  for (int k = 0; k < 3 && a < 0; ++k) {
    const int p = s.corner(k), q = s.corner((k + 1) % 3);
    for (int g : s.mesh.edge_facets(p, q))
      if (g != s.facet && s.mesh.facet_normal(g).z() > 0.99) a = p, b = q, c = s.corner((k + 2) % 3);
  }
  ASSERT_GE(a, 0);
  const Vec3 dip(0, 0, 1e-3);
  Scene inside;
  inside.fan_around(inside.centroid() - dip);
  EXPECT_EQ(inside.refusal(), "");
  const Vec3 mid = 0.5 * (s.mesh.point(a) + s.mesh.point(b));
  s.fan_around(mid + 0.3 * (mid - s.mesh.point(c)) - dip);
  EXPECT_NE(s.refusal().find("cross each other"), std::string::npos);
}

TEST(OutputCheck, RefusesASmallFacetFoldedOntoALargerOneMadeBeforeIt) {
  // The facet re-made as a large one (a, b, u), then a small one (a, u, x) folded back onto it (x just past
  // its side a-u, 0.002 mm over the face), and a low tent over the rest (a fan around w, 0.03 mm up). The
  // small one lies on the large one's plane, but the large one's far corner b is well off the small one's
  // (tilted by 0.002 mm over its 0.07 mm height): tested only that way round, the pair was let through.
  Scene s;
  ASSERT_GE(s.facet, 0);
  const int a = s.corner(0), b = s.corner(1), c = s.corner(2);
  const Vec3 pa = s.mesh.point(a), pb = s.mesh.point(b), pc = s.mesh.point(c);
  const Vec3 pu = 0.8 * pc + 0.1 * pa + 0.1 * pb, side = 0.5 * (pa + pu);
  s.edit.removed.insert(s.facet);
  const int u = s.edit.add_point(pu), x = s.edit.add_point(side + 0.03 * (pb - side) + Vec3(0, 0, 2e-3));
  const int w = s.edit.add_point((pa + pb + pc + pu) / 4 + Vec3(0, 0, 0.03));
  for (const std::array<int, 3>& f : std::vector<std::array<int, 3>>{{a, b, u}, {a, u, x}, {w, b, c}, {w, c, a}, {w, a, x}, {w, x, u}, {w, u, b}})
    s.edit.added.push_back(f);
  EXPECT_NE(s.refusal().find("cross each other"), std::string::npos) << s.refusal();
}

}  // namespace
