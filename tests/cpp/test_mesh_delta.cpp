// The result as an edit of the input (mesh_delta.h): the delta describes the very mesh the arrays hold, in
// one order, whether it was made by one pass (from the pass's edit, at the band's cost) or by several
// (through the lineage of the last mesh); the input's kept vertices keep their bits.
#include <BRepPrimAPI_MakeBox.hxx>
#include <gtest/gtest.h>

#include <cstring>
#include <set>

#include "delta.h"
#include "meshround/round.h"
#include "meshround/sew.h"
#include "support.h"

using namespace meshround;
using namespace meshround::test;

namespace {

TriMesh box(double edge) { return mesh_shape(BRepPrimAPI_MakeBox(100, 60, 40).Shape(), edge); }

bool same_bits(const Points& a, Eigen::Index i, const Points& b, Eigen::Index j) {
  return std::memcmp(a.row(i).data(), b.row(j).data(), 3 * sizeof(double)) == 0;
}

// The delta's own account of the result, checked against the arrays independently of apply_delta: the kept
// input facets come first in their order with their vertices' bits, then the added ones.
void expect_describes(const TriMesh& in, const MeshDelta& d, const Points& V, const Triangles& F) {
  ASSERT_EQ(d.input_vertices, in.V.rows());
  ASSERT_EQ(d.input_facets, in.F.rows());
  ASSERT_TRUE(std::is_sorted(d.removed.begin(), d.removed.end()));
  ASSERT_TRUE(std::is_sorted(d.freed.begin(), d.freed.end()));
  ASSERT_EQ(F.rows(), in.F.rows() - Eigen::Index(d.removed.size()) + Eigen::Index(d.added.size()));
  const std::set<int> removed(d.removed.begin(), d.removed.end()), moved(d.moved.begin(), d.moved.end());
  Eigen::Index row = 0;
  std::set<int> used;
  for (Eigen::Index f = 0; f < in.F.rows(); ++f) {
    if (removed.count(int(f))) continue;
    for (int k = 0; k < 3; ++k) {
      const int v = in.F(f, k);
      used.insert(v);
      if (!moved.count(v)) EXPECT_TRUE(same_bits(in.V, v, V, F(row, k))) << "facet " << f;
    }
    ++row;
  }
  for (int v : d.freed) EXPECT_FALSE(used.count(v)) << "vertex " << v << " is freed but a kept facet uses it";
  for (const auto& a : d.added) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 want = a[k] < d.input_vertices ? Vec3(in.V.row(a[k]).transpose()) : d.new_points[size_t(a[k] - d.input_vertices)];
      const auto m = std::find(d.moved.begin(), d.moved.end(), a[k]);
      const Vec3 at = m != d.moved.end() ? d.moved_to[size_t(m - d.moved.begin())] : want;
      EXPECT_EQ(Vec3(V.row(F(row, k)).transpose()), at);
    }
    ++row;
  }
  // Vertices: the kept ones first in the input's order, then the freed ones used again, then the new.
  EXPECT_EQ(V.rows(), Eigen::Index(in.V.rows() - d.freed.size()) + [&] {
    std::set<int> reused;
    for (const auto& a : d.added)
      for (int v : a)
        if (v < d.input_vertices && std::binary_search(d.freed.begin(), d.freed.end(), v)) reused.insert(v);
    return Eigen::Index(reused.size());
  }() + Eigen::Index(d.new_points.size()));
}

TEST(MeshDelta, OneChainsDeltaIsTheMeshItsArraysHold) {
  const TriMesh in = box(2.0);
  RoundOptions opt;
  opt.radius = 5;
  const RoundResult res = round_edges(in.V, in.F, {Vec3(37, 60, 40)}, opt);
  const MeshDelta& d = res.delta;
  EXPECT_GT(d.removed.size(), 100u);
  EXPECT_GT(d.added.size(), 100u);
  EXPECT_FALSE(d.freed.empty());
  expect_describes(in, d, res.vertices, res.triangles);
  // Without arrays: the same delta, nothing else made.
  opt.write_arrays = false;
  const RoundResult lean = round_edges(in.V, in.F, {Vec3(37, 60, 40)}, opt);
  EXPECT_EQ(lean.vertices.rows(), 0);
  EXPECT_EQ(lean.delta.removed, d.removed);
  EXPECT_EQ(lean.delta.added, d.added);
  EXPECT_EQ(lean.delta.new_points, d.new_points);
}

TEST(MeshDelta, SeveralPassesGiveTheDeltaOfTheirLastMesh) {
  // Three chains and a sphere corner: four passes, each on the mesh the one before made.
  const TriMesh in = box(2.0);
  RoundOptions opt;
  opt.radius = 5;
  const RoundResult res = round_edges(in.V, in.F, {Vec3(50, 60, 40), Vec3(100, 30, 40), Vec3(100, 60, 20)}, opt);
  ASSERT_EQ(res.chains.size(), 3u);
  expect_describes(in, res.delta, res.vertices, res.triangles);
  const Topology t = topology({res.vertices, res.triangles});
  EXPECT_EQ(t.boundary + t.nonmanifold + t.misoriented, 0);
}

TEST(MeshDelta, LineageAndEditAgreeOnOnePass) {
  // delta_from_edit (the band's cost) and delta_from_lineage (the whole mesh's) of the same edit.
  const TriMesh in = box(5.0);
  const MeshTopology mesh(in.V, in.F);
  MeshEdit edit(mesh);
  // Remove the two facets of a top-face quad's diagonal and fan them from a new centre point; move a
  // vertex of another facet.
  int f0 = -1, f1 = -1;
  for (int f = 0; f < mesh.num_facets() && f1 < 0; ++f) {
    if (mesh.facet_normal(f).z() < 0.99) continue;
    for (int k = 0; k < 3 && f1 < 0; ++k) {
      const int g = mesh.neighbour(f, mesh.F(f, k), mesh.F(f, (k + 1) % 3));
      if (g >= 0 && mesh.facet_normal(g).z() > 0.99) f0 = f, f1 = g;
    }
  }
  ASSERT_GE(f1, 0);
  std::vector<int> ring;
  for (int f : {f0, f1})
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (mesh.neighbour(f, a, b) != f0 && mesh.neighbour(f, a, b) != f1) ring.push_back(a), ring.push_back(b);
    }
  Vec3 centre = Vec3::Zero();
  for (int k = 0; k < 3; ++k) centre += (mesh.corner(f0, k) + mesh.corner(f1, k)) / 6;
  const int c = edit.add_point(centre);
  edit.removed = {f0, f1};
  for (size_t i = 0; i < ring.size(); i += 2) edit.added.push_back({ring[i], ring[i + 1], c});
  edit.moved[mesh.F(f0, 0)] = mesh.corner(f0, 0) + Vec3(1e-3, 0, 0);
  const MeshDelta direct = delta_from_edit(edit);
  Points V;
  Triangles F;
  StepOrigin origin;
  write_mesh(edit, V, F, &origin);
  const MeshDelta traced = delta_from_lineage(in.V, in.F, V, F, follow({}, origin));
  EXPECT_EQ(direct.removed, traced.removed);
  EXPECT_EQ(direct.freed, traced.freed);
  EXPECT_EQ(direct.moved, traced.moved);
  EXPECT_EQ(direct.moved_to, traced.moved_to);
  EXPECT_EQ(direct.new_points, traced.new_points);
  EXPECT_EQ(direct.added, traced.added);
  expect_describes(in, direct, V, F);
}

TEST(MeshDelta, FreedVerticesUsedAgainComeAfterTheKeptOnes) {
  // A fan's centre vertex whose facets are all removed and made again: freed, then used by the new facets.
  const TriMesh in = box(5.0);
  const MeshTopology mesh(in.V, in.F);
  int centre = -1;
  for (int v = 0; v < mesh.num_vertices() && centre < 0; ++v) {
    bool flat = mesh.facets_end(v) - mesh.facets_begin(v) >= 4;
    for (const int* f = mesh.facets_begin(v); f != mesh.facets_end(v); ++f) flat &= mesh.facet_normal(*f).z() > 0.99;
    if (flat) centre = v;
  }
  ASSERT_GE(centre, 0);
  MeshEdit edit(mesh);
  for (const int* f = mesh.facets_begin(centre); f != mesh.facets_end(centre); ++f) {
    edit.removed.insert(*f);
    edit.added.push_back({mesh.F(*f, 0), mesh.F(*f, 1), mesh.F(*f, 2)});  // the same facet, made anew
  }
  const MeshDelta d = delta_from_edit(edit);
  ASSERT_EQ(d.freed, std::vector<int>{centre});
  Points V;
  Triangles F;
  apply_delta(in.V, in.F, d, V, F);
  ASSERT_EQ(V.rows(), in.V.rows());
  EXPECT_TRUE(same_bits(in.V, centre, V, V.rows() - 1));  // at the end, its bits kept
  expect_describes(in, d, V, F);
  const Topology t = topology({V, F});
  EXPECT_EQ(t.boundary + t.nonmanifold + t.misoriented, 0);
}

TEST(MeshDelta, ADeltaForAnotherMeshIsRefused) {
  const TriMesh in = box(20.0);
  MeshDelta d;
  d.input_vertices = int(in.V.rows()) + 1, d.input_facets = int(in.F.rows());
  Points V;
  Triangles F;
  EXPECT_THROW(apply_delta(in.V, in.F, d, V, F), RoundingError);
  d.input_vertices = int(in.V.rows());
  d.added.push_back({0, 1, int(in.V.rows())});  // a new point it does not have
  EXPECT_THROW(apply_delta(in.V, in.F, d, V, F), RoundingError);
}

}  // namespace
