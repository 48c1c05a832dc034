// MeshTopology: the adjacency view of (V, F) that all passes share, built once in O(n).
// Orientation of the input does not matter anywhere: facet normals are compared after aligning them
// across the shared edge.
#pragma once
#include <array>
#include <cmath>
#include <memory>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "meshround/types.h"

namespace meshround {

inline std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

class MeshTopology {
 public:
  // V: (n, 3), F: (m, 3). Throws RoundingError for an empty mesh, NaN/inf coordinates or bad indices.
  MeshTopology(const Points& V, const Triangles& F);

  const Points& V;
  const Triangles& F;

  int num_vertices() const { return int(V.rows()); }
  int num_facets() const { return int(F.rows()); }
  Vec3 point(int v) const { return V.row(v).transpose(); }
  Vec3 corner(int f, int k) const { return V.row(F(f, k)).transpose(); }

  // Facets around vertex v (unordered).
  const int* facets_begin(int v) const { return vf_.data() + vf_start_[v]; }
  const int* facets_end(int v) const { return vf_.data() + vf_start_[v + 1]; }

  // Facets that share the edge (a, b): 1 on a boundary, 2 inside, more where the mesh is non-manifold.
  std::vector<int> edge_facets(int a, int b) const;
  int edge_facet_count(int a, int b) const;  // the same, counted only (no allocation)
  int edge_facet_pair(int a, int b, int pair[2]) const;  // the count; the first two facets in `pair`
  // The other facet on edge (a, b) of facet f, or -1 when the edge is a boundary or non-manifold.
  int neighbour(int f, int a, int b) const;
  // Vertices joined to v by an edge.
  std::vector<int> vertex_neighbours(int v) const;
  // Vertices that no facet uses, ascending (usually none).
  const std::vector<int>& unused_vertices() const { return unused_; }

  Vec3 facet_normal(int f) const;  // unit normal (zero for a degenerate facet)
  // A repeated vertex or (numerically) no area.
  bool facet_degenerate(int f) const;
  bool facet_has_edge(int f, int a, int b) const;
  // +1 when facet f runs a -> b, -1 when it runs b -> a.
  int edge_direction(int f, int a, int b) const;
  // Angle (degrees) between the two facets of an edge, normals aligned across it; 0 = flat.
  // Returns 180 for a boundary or non-manifold edge (treated as a feature everywhere).
  double dihedral_deg(int a, int b) const;
  // The same between the normals n0, n1 given for the edge's facets f0, f1 (aligned across it here).
  double dihedral_deg(int f0, int f1, const Vec3& n0, Vec3 n1, int a, int b) const;
  // A sharp edge: dihedral >= the feature angle, also when a sliver facet's own normal (tilted by a tiny
  // offset of its vertices) is replaced by its neighbours' on the same face. Boundary and non-manifold
  // edges are features.
  bool is_feature_edge(int a, int b, double feature_angle_deg) const;
  // Normal of facet f for feature detection across its edge (a, b): its own, or for a sliver the
  // area-weighted normal of it and its other neighbours within the feature angle.
  Vec3 feature_normal(int f, int a, int b, double feature_angle_deg) const;

 private:
  std::vector<int> vf_start_, vf_;
  std::vector<int> unused_;
};

// Closest point on triangle (a, b, c) to p. `region` tells where it lies: 0 inside, 1..3 on edge
// (ab, bc, ca), 4..6 on vertex (a, b, c) -- the paper's facet / edge / vertex contact regions.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, int* region);
Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b, double* t);
// Smallest interior angle of triangle (a, b, c), in radians (0 for a degenerate one).
double smallest_angle(const Vec3& a, const Vec3& b, const Vec3& c);
// How far off a plane (or a line) a point may lie and still count as on it: a hair of the distances
// involved, plus what float32 coordinates (STL, Mesh.Mesh) of this magnitude can hold.
inline double on_plane_slack(double span, double magnitude) { return 1e-9 * span + 1e-6 * magnitude; }
// x lies on the plane through `origin` with unit normal `unit_normal`, within on_plane_slack.
inline bool on_plane(const Vec3& x, const Vec3& origin, const Vec3& unit_normal) {
  return std::abs((x - origin).dot(unit_normal)) <= on_plane_slack((x - origin).norm(), x.cwiseAbs().maxCoeff());
}

// The private search index of facets and chain segments (cpp_core/src/box_tree.h).
class BoxTree;

}  // namespace meshround
