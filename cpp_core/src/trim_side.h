// The trim pass's state and sub-passes (private to cpp_core; trim.h trim_base_meshes is the pass).
//
// trim_base_meshes runs, for each side (A, then B), the sub-passes of one SideTrim in this order:
//   1. classify_vertices  each base vertex's signed distance from the band's edge; vertices near the
//                         contact line snapped onto it (trim_lines.cpp)
//   2. grade_line_edges   input edges from a vertex on the line to a kept one get graded points
//   3. find_dips          input edges in the band at both ends that run out of it between them get
//                         the two points where they cross the line
//   4. cut_facets         facets across the line keep their outer part, with the line refined in them
//   5. split_line_edges   input edges lying on the line get points every max_spacing
//   6. rebuild_kept       kept facets beside graded or split edges retriangulated with those points
// then takes out the capped ends' corners and closes the T-junctions a cut edge leaves in the facets
// outside the base meshes (trim.cpp).
#pragma once
#include "meshround/chain.h"
#include "meshround/mesh_edit.h"
#include "meshround/surface.h"
#include "meshround/trim.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace meshround {

// Signed distance of a point of one base mesh from that side's contact line, in the base surface:
// negative inside the band. `u` is the line parameter of the foot point.
struct ContactLineDistance {
  const RoundingSurface& surface;
  const SharpChain& chain;
  int side;  // 0: A (v = 0), 1: B (v = 1)

  double operator()(const Vec3& p, double u_hint, double* u_out, Vec3* away = nullptr) const;
};

constexpr double kFar = 1e30;  // |signed distance| of a vertex whose side is clear without projecting it

struct VertexSide {
  double d = 0;        // signed distance (0 = on the trim line after snapping); +-kFar: side known only
  double u = 0;
  bool exact = false;  // d is the true distance
};

// The part of an input edge between a trim line and the edge's kept end, with points graded along it.
struct KeptPiece {
  int trim_end;             // the trim vertex (a cut point, or an input vertex on the line)
  std::vector<int> points;  // inner points of the piece, from trim_end towards the kept end
};

// u -> to - from along the surface's boundary lines (the short way round a closed one).
double wrapped_delta(const RoundingSurface& s, double from, double to);

// What both sides' trims share: the call's inputs, the band's extent, the capped ends, the kept pieces.
struct TrimContext {
  const MeshTopology& mesh;
  const SharpChain& chain;
  const BaseMeshes& base;
  const RoundingSurface& surface;
  const std::vector<ProfileStation>& end_profiles;
  const TrimOptions& opt;
  MeshEdit& edit;
  // How far from the chain each contact line gets. Vertices well inside that range are in the band and
  // well beyond it outside: only their side matters, unless a cut edge needs their exact distance.
  double nearest[2] = {INFINITY, INFINITY}, farthest[2] = {0, 0};
  std::unordered_set<int> chain_vertices;
  // Capped ends cut by their end face (ends.h): there the band stops at the face's plane. `plane_slack`:
  // "on" that plane, for float32 coordinates -- of the mesh's magnitude, not the chain's: two rounds meeting
  // at a corner must agree whether a vertex there is on their lines (a mitre's foot 5e-5 from a mesh
  // vertex on the pocket's wall corner was on the first round's line and off the second's).
  const EndCut* cuts[2] = {nullptr, nullptr};
  double plane_slack = 0;
  std::unordered_map<std::uint64_t, KeptPiece> kept_piece;  // edge_key(trim_end, kept_end) -> the piece

  TrimContext(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base, const RoundingSurface& surface,
              const std::vector<ProfileStation>& end_profiles, const TrimOptions& opt, MeshEdit& edit);
  // How far p is past the capped ends' planes (the larger; -inf with none).
  double past_end(const Vec3& p) const;
  // The points on a kept piece, when a polygon runs along it from `from` to `to`.
  void add_piece_points(int from, int to, std::vector<int>& polygon) const;
};

// One side's trim: its sub-passes in order (see the top of this file) and what they share.
class SideTrim {
 public:
  SideTrim(TrimContext& ctx, int side, TrimLines& out);
  void classify_vertices();
  void grade_line_edges();
  void find_dips();
  void cut_facets();
  void split_line_edges();
  void rebuild_kept();

 private:
  // Measures (trim_lines.cpp).
  double behind_end(const Vec3& p) const;
  double distance(const Vec3& p, double u_hint, double* u_out, Vec3* away = nullptr) const;
  double u_on_line(const Vec3& q, double u_a, double u_b, double w0) const;
  bool at_corner(const Vec3& p, double* u_end) const;
  double corner_u(const Vec3& p, double u) const;
  bool reenters(const Vec3& from, const Vec3& to, double u) const;
  double line_bend(double u, double L) const;
  bool edge_reenters(int v, const Vec3& q, double u_v) const;
  VertexSide& exact(int v);
  bool closes_facet_on_line(int v) const;
  void snap_near_line(int v, VertexSide& s, const Vec3& away, bool on_end_plane);
  // Cutting (trim.cpp).
  void grade_piece(int trim_end, int kept_end, double u);
  int cut_point(int a, int b);
  bool kept_whole(int g);
  bool side_stands_for_line(int f, const Vec3& q) const;
  bool line_leaves_chord(int a, int b) const;
  double line_length(double u_a, double u_b) const;
  void refine_line_in_facet(int f, int from, double u_from, int to, double u_to, std::vector<int>& polygon);

  TrimContext& ctx;
  const MeshTopology& mesh;
  MeshEdit& edit;
  const TrimOptions& opt;
  const int side;
  TrimLines& out;
  const ContactLineDistance line_distance;
  const double hair;                     // a dip of the band's edge this deep is a hair (kHairShare x tolerance)
  std::unordered_set<int> plane_points;  // trim points on an end face's plane, not on the contact line
  std::unordered_map<int, VertexSide> vs;
  std::unordered_map<int, double> cut_u;  // cut point -> its line parameter
  std::unordered_set<int> cut, rebuild;   // facets across the line; kept facets to retriangulate
  std::unordered_map<std::uint64_t, std::vector<int>> split;  // edge (a < b) on the line -> its points, a to b
  std::unordered_map<std::uint64_t, std::array<int, 2>> dips;  // edge (a < b) in the band at both ends, out between: its cut points, a to b
};

}  // namespace meshround
