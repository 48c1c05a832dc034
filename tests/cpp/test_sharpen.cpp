// change_radius / sharpen_rounds (sharpen.h) on meshes of OCCT-filleted solids, against OCCT.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <gtest/gtest.h>

#include "meshround/sharpen.h"
#include "support.h"

using namespace meshround;
using namespace meshround::test;

namespace {

struct Solid {
  const char* name;
  TopoDS_Shape sharp;
  std::function<bool(const Vec3&, const Vec3&)> chain;
  Vec3 on_round;  // a point on the round at r0 (for the seed)
  double r0;
  bool convex;
};

// The top back edge of a 100 x 60 x 40 box, rounded at r0 = 5: the round's middle at x = 37.
Solid box_edge() {
  const double r = 5, c = r / std::sqrt(2.0);
  return {"box", BRepPrimAPI_MakeBox(100, 60, 40).Shape(),
          [](const Vec3& p, const Vec3& q) { return std::abs(p.y() - 60) + std::abs(q.y() - 60) + std::abs(p.z() - 40) + std::abs(q.z() - 40) < 1e-9; },
          Vec3(37, 60 - r + c, 40 - r + c), r, true};
}

// The inner edge of an L-section (concave), rounded at r0 = 4.
Solid lchannel() {
  BRepBuilderAPI_MakePolygon poly;
  for (auto [y, z] : {std::pair{0., 0.}, {60., 0.}, {60., 10.}, {10., 10.}, {10., 50.}, {0., 50.}}) poly.Add(gp_Pnt(0, y, z));
  poly.Close();
  const double r = 4, c = r / std::sqrt(2.0);
  return {"lchannel", BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(poly.Wire()).Face(), gp_Vec(100, 0, 0)).Shape(),
          [](const Vec3& p, const Vec3& q) { return std::abs(p.y() - 10) + std::abs(q.y() - 10) + std::abs(p.z() - 10) + std::abs(q.z() - 10) < 1e-9; },
          Vec3(37, 10 + r - c, 10 + r - c), r, false};
}

// The filleted solid's CAD tessellation: every vertex on its faces, long slivers along the round.
TriMesh rounded_mesh(const Solid& s) { return mesh_shape(reference_fillet(s.sharp, pick_edges(s.sharp, s.chain), s.r0), 0.0); }

std::vector<Vec3> vertices(const TriMesh& m) {
  std::vector<Vec3> out;
  for (int i = 0; i < m.V.rows(); ++i) out.push_back(m.V.row(i).transpose());
  return out;
}

void expect_sharpened(const Solid& s) {
  SCOPED_TRACE(s.name);
  const TriMesh in = rounded_mesh(s);
  const SharpenResult res = sharpen_rounds(in.V, in.F, {s.on_round}, {});
  ASSERT_EQ(res.strips.size(), 1u);
  const StripReport& st = res.strips[0];
  EXPECT_NEAR(st.found_radius, s.r0, 1e-3 * s.r0);
  EXPECT_TRUE(st.constant);
  EXPECT_EQ(st.convex, s.convex);
  EXPECT_EQ(st.end_faces, 2);
  EXPECT_NEAR(st.opening_deg, 90.0, 1e-6);
  // Every vertex on the sharp solid's faces: the sharp edge and its end corners rebuilt exactly.
  const TriMesh out{res.vertices, res.triangles};
  EXPECT_LE(max_distance_to_shape(vertices(out), s.sharp), 1e-5 * s.r0);
  const Topology t = topology(out);
  EXPECT_EQ(t.boundary, 0);
  EXPECT_EQ(t.nonmanifold, 0);
  EXPECT_EQ(t.misoriented, 0);
  EXPECT_EQ(t.degenerate, 0);
}

// The box of box_edge() with its edge rounded at r0, meshed as a prism: the section (the arc in `arc`
// segments) at stations `step` apart along x, the two end caps fanned from their centroid.
TriMesh rounded_box_prism(double r0, int arc, double step) {
  std::vector<Eigen::Vector2d> sec{{0, 0}, {60, 0}};
  for (int k = 0; k <= arc; ++k) {
    const double a = 0.5 * M_PI * k / arc;
    sec.push_back({60 - r0 + r0 * std::cos(a), 40 - r0 + r0 * std::sin(a)});
  }
  sec.push_back({0, 40});
  const int n = int(sec.size()), stations = int(std::lround(100 / step)) + 1;
  TriMesh m;
  m.V.resize(n * stations + 2, 3);
  for (int i = 0; i < stations; ++i)
    for (int k = 0; k < n; ++k) m.V.row(i * n + k) << 100.0 * i / (stations - 1), sec[k].x(), sec[k].y();
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : sec) c += p / n;
  m.V.row(n * stations) << 0, c.x(), c.y();
  m.V.row(n * stations + 1) << 100, c.x(), c.y();
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i + 1 < stations; ++i)
    for (int k = 0; k < n; ++k) {  // the section runs counter-clockwise seen from +x: outward facets
      const int a = i * n + k, b = i * n + (k + 1) % n, a2 = a + n, b2 = b + n;
      f.push_back({a, b, b2}), f.push_back({a, b2, a2});
    }
  for (int k = 0; k < n; ++k) {
    f.push_back({n * stations, (k + 1) % n, k});
    f.push_back({n * stations + 1, (stations - 1) * n + k, (stations - 1) * n + (k + 1) % n});
  }
  m.F.resize(int(f.size()), 3);
  for (size_t i = 0; i < f.size(); ++i) m.F.row(int(i)) << f[i][0], f[i][1], f[i][2];
  return m;
}

void expect_new_radius(const Solid& s, const TriMesh& in, double r1) {
  SCOPED_TRACE(std::string(s.name) + " to r = " + std::to_string(r1));
  RoundOptions opt;
  opt.radius = r1;
  const ChangeRadiusResult res = change_radius(in.V, in.F, {s.on_round}, opt);
  const TriMesh out{res.round.vertices, res.round.triangles};
  const TopoDS_Shape ref = reference_fillet(s.sharp, pick_edges(s.sharp, s.chain), r1);
  ASSERT_EQ(res.round.chains.size(), 1u);
  const Vec3 a = res.round.chains[0].chain.front(), b = res.round.chains[0].chain.back();
  std::vector<Vec3> near;
  for (const Vec3& p : mesh_samples(out)) {
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    if ((a + t * (b - a) - p).norm() < 2 * r1) near.push_back(p);
  }
  EXPECT_LE(max_distance_to_shape(near, ref), r1 / 100);
  EXPECT_LE(max_distance_to_mesh(fillet_face_samples(ref, s.sharp, 24), out), r1 / 100);
  const Topology t = topology(out);
  EXPECT_EQ(t.boundary + t.nonmanifold + t.misoriented + t.degenerate, 0);
}

}  // namespace

TEST(Sharpen, ConvexBoxRoundFoundAndSharpened) { expect_sharpened(box_edge()); }
TEST(Sharpen, ConcaveChannelRoundFoundAndSharpened) { expect_sharpened(lchannel()); }

// (The CAD tessellations above have facets running the round's whole length: sharpened, they leave
// slivers along the rebuilt edge that round_edges reads as a fold of the edge and refuses. A prism mesh
// of the rounded box, coarse (3 facets across the round) and fine (8), rounds.)
TEST(ChangeRadius, LargerAndSmallerMatchOcctFilletOfTheSharpSolid) {
  for (int arc : {3, 8}) {
    const TriMesh in = rounded_box_prism(5.0, arc, 2.0);
    for (double r1 : {8.0, 3.0}) expect_new_radius(box_edge(), in, r1);
  }
}

TEST(ChangeRadius, RefusesWhatIsNotARound) {
  const Solid s = box_edge();
  const TriMesh in = rounded_mesh(s);
  try {
    sharpen_rounds(in.V, in.F, {Vec3(50, 30, 40)}, {});  // the flat top face
    FAIL() << "no error";
  } catch (const RoundingError& e) {
    EXPECT_EQ(e.code, ErrorCode::NotARound);
    EXPECT_NE(std::string(e.what()).find("flat face"), std::string::npos) << e.what();
  }
  // The sharp solid's mesh has no round at all: its edge is two flat faces meeting.
  const TriMesh sharp = mesh_shape(s.sharp, 4.0);
  try {
    sharpen_rounds(sharp.V, sharp.F, {Vec3(37, 60, 40)}, {});
    FAIL() << "no error";
  } catch (const RoundingError& e) {
    EXPECT_EQ(e.code, ErrorCode::NotARound);
  }
  EXPECT_THROW(sharpen_rounds(in.V, in.F, {}, {}), RoundingError);
  SharpenOptions bad;
  bad.flat_deg = -1;
  EXPECT_THROW(sharpen_rounds(in.V, in.F, {s.on_round}, bad), RoundingError);
}
