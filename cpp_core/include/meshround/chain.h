// Paper §3: the chain of sharp edges a seed selects, and the two base meshes on either side of it.
#pragma once
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "meshround/mesh.h"

namespace meshround {

// How a chain ends (open chains only).
enum class ChainEnd {
  Junction,  // three or more sharp edges meet: the end is capped by the other faces there
  Boundary,  // the mesh boundary
  Turn,      // the chain turns by more than the feature angle
  Fade,      // the edge stops being sharp
};

// An ordered polyline of sharp mesh edges. For a closed loop the first vertex is not repeated and the
// closing edge is (vertices.back(), vertices.front()).
struct SharpChain {
  std::vector<int> vertices;
  bool closed = false;
  ChainEnd start_end = ChainEnd::Fade, end_end = ChainEnd::Fade;
  // Per chain edge i (vertices[i], vertices[i+1]): its facet on side A and on side B.
  std::vector<int> facet_a, facet_b;
  std::vector<Vec3> points;       // vertex positions, in chain order
  std::vector<double> arc_length; // s at each vertex (0 at the start)
  double length = 0;              // total length (includes the closing edge of a loop)

  int num_edges() const { return int(facet_a.size()); }
  // Point and smoothed unit tangent at arc length s (wrapped for a loop, clamped otherwise).
  Vec3 point_at(double s) const;
  Vec3 tangent_at(double s) const;
  // Arc length of the chain point nearest to p, and the distance to it (exact; a bounding volume
  // hierarchy of the segments keeps this logarithmic, see index_segments). Of equally near segments,
  // the first.
  double project(const Vec3& p, double* distance) const;
  // Builds the segment index used by project() (without it, project() tries every segment).
  void index_segments();
  // The same, found by walking the chain from arc length s_hint while the distance falls: O(1) for a
  // point whose neighbour's projection is known (a flood over the mesh from the chain).
  double project_from(const Vec3& p, double s_hint, double* distance) const;

 private:
  friend SharpChain trace_chain(const MeshTopology&, const Vec3&, double, double, std::array<int, 2>);
  void finish_geometry(const MeshTopology& mesh);
  int segment_at(double s, double* local) const;
  std::vector<Vec3> vertex_tangents_;
  std::shared_ptr<const BoxTree> segments_;
};

// The sharp edge nearest to `seed` (within `search_radius`) and the whole chain through it.
// Throws RoundingError when no sharp edge is near the seed. A thin facet on the chain (height under
// search_radius / 6 and a quarter of its longest edge) holds part of the edge's fold: not a junction.
// `on_edge` (optional): the ends of a mesh edge the seed lies on (a chain traced before, picked again by an
// edge's middle): the search starts from the facets around it instead of looking at every facet.
SharpChain trace_chain(const MeshTopology& mesh, const Vec3& seed, double feature_angle_deg,
                       double search_radius, std::array<int, 2> on_edge = {-1, -1});

// The facets within `reach_distance` of the chain, split into its two sides. A base mesh is bounded
// by the chain, other sharp edges, the mesh boundary and the reach.
struct ChainProjection {
  double s = 0;         // arc length of the nearest chain point
  double distance = 0;  // distance to it
};

struct BaseMeshes {
  std::vector<int> facets[2];                  // side A = 0, side B = 1
  std::unordered_map<int, ChainProjection> projection;  // every vertex of the base facets
  std::unordered_map<int, int> side_of;        // facet -> side
  std::unordered_set<std::uint64_t> walls[2];  // edges where a side stops (sharp edge, boundary)
  std::unordered_set<std::uint64_t> reach_limit[2];  // edges where a side stops only for the reach
  double reach_distance = 0;                   // as collected: the band must lie within it
};

// `earlier_round`: vertices of rounds made before in the same call (round.h); a facet with all three
// among them is a wall, so that a base mesh stops where an earlier round begins (along its trim line).
BaseMeshes collect_base_meshes(const MeshTopology& mesh, const SharpChain& chain, double reach_distance,
                               double feature_angle_deg, const std::unordered_set<int>* earlier_round = nullptr);

}  // namespace meshround
