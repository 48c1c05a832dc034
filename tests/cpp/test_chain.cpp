// Chain tracing on a coarse mesher's fold: a thin facet along the sharp edge, tilted between the two
// faces, makes two more "sharp" edges at the chain's vertices. They are part of the edge's fold, not a
// junction: the chain runs on, and the facet behind the fold belongs to the base mesh.
#include <gtest/gtest.h>

#include <algorithm>

#include "meshround/chain.h"

using namespace meshround;

namespace {

// A 90 degree ridge along x (top face z = 0, y >= 0; wall y = 0, z <= 0), 20 long, open at its ends.
// Its first ridge edge R0-R1 carries a thin facet (R0, X, R1) on the wall side, X a hair below the ridge.
struct FoldedRidge {
  enum { R0, R1, R2, A0, A1, A2, B0, B1, B2, X };
  Points V;
  Triangles F;
  // without_far_wall: the wall under R1-R2 left out, so the wall behind the fold is reached only across it.
  explicit FoldedRidge(bool without_far_wall = false) : V(10, 3), F(10, 3) {
    V << 0, 0, 0, 10, 0, 0, 20, 0, 0,       // ridge
        0, 10, 0, 10, 10, 0, 20, 10, 0,     // top face
        0, 0, -10, 10, 0, -10, 20, 0, -10,  // wall
        5, 0.3, -0.3;                       // the fold's apex: 0.42 from the ridge
    F << R0, R1, A1, R0, A1, A0, R1, R2, A2, R1, A2, A1,  // top
        R0, X, R1,                                        // the thin fold facet
        R0, B0, X, X, B0, B1, X, B1, R1,                  // wall behind it
        R1, B1, B2, R1, B2, R2;                           // wall
    if (without_far_wall) F.conservativeResize(8, 3);
  }
};

}  // namespace

TEST(Chain, ThinFoldFacetIsNotAJunction) {
  const FoldedRidge r;
  const MeshTopology mesh(r.V, r.F);
  // The fold's own edges do count as sharp (45 degrees on either side)...
  ASSERT_TRUE(mesh.is_feature_edge(FoldedRidge::R1, FoldedRidge::X, 30));
  // ...yet the chain picked on the second ridge edge runs through R1 to the first one and on to the end.
  const SharpChain chain = trace_chain(mesh, Vec3(15, 0, 0), 30, 6.0);
  std::vector<int> v = chain.vertices;
  if (v.front() != FoldedRidge::R0) std::reverse(v.begin(), v.end());
  EXPECT_EQ(v, (std::vector<int>{FoldedRidge::R0, FoldedRidge::R1, FoldedRidge::R2}));
  EXPECT_EQ(chain.start_end, ChainEnd::Boundary);
  EXPECT_EQ(chain.end_end, ChainEnd::Boundary);
}

TEST(Chain, BaseMeshReachesBehindTheFold) {
  const FoldedRidge r(true);
  const MeshTopology mesh(r.V, r.F);
  SharpChain chain = trace_chain(mesh, Vec3(5, 0, 0), 30, 6.0);
  chain.index_segments();
  const BaseMeshes base = collect_base_meshes(mesh, chain, 6.0, 30);
  // Facet 5 (R0, B0, X) touches the ridge only through the fold's sharp edges: on the wall's side.
  ASSERT_TRUE(base.side_of.count(5));
  ASSERT_TRUE(base.side_of.count(4));
  EXPECT_EQ(base.side_of.at(5), base.side_of.at(4));
  EXPECT_NE(base.side_of.at(5), base.side_of.at(0));  // and not on the top face's side
}
