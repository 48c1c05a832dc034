// Paper §5.2: the round's own facets, made in the surface's (u, v) domain.
//
// Rows run along the spine at fixed v. The first and last rows are the trim lines themselves (so the
// round shares its boundary vertices with the trimmed mesh and no separate stitching is needed); the
// rows between are spaced in v for the chordal tolerance across the profile and sampled in u on the
// merged spacing of both trim lines, then refined wherever a facet is farther than the tolerance from
// the surface. Beside a trim line much finer than that, graded rows lead from its spacing to the
// round's. Neighbouring rows are zipped with the shorter diagonal.
#pragma once
#include <functional>
#include <vector>

#include "meshround/trim.h"

namespace meshround {

struct RoundMeshStats {
  int facets = 0;
  int rows = 0;             // rows across the profile, trim lines included
  double max_deviation = 0; // largest distance found from a new facet (centroid, edge midpoints) to the surface
};

// Where a round meets another at a corner (round.h), its end column is the other round's: the rows are
// the regular ones only (no graded rows, whose ends the other round would not have), and each inner row's
// end point at a shared end is the vertex `shared_end` finds there (-1: none; then the round is refused).
struct SharedEnds {
  bool at[2] = {false, false};                         // u_first, u_last
  std::function<int(const Vec3&)> vertex_at;          // an existing vertex at that point, or -1
  bool no_graded_rows = false;                         // set for every round with a corner end
  // A mitre end (u_first, u_last): its column is the exact end profile, without the trim lines' offsets
  // (each round's own), so that both rounds compute the same points in the mitre plane.
  bool exact_end[2] = {false, false};
};

RoundMeshStats mesh_rounding_surface(const RoundingSurface& surface, const std::vector<ProfileStation>& stations,
                                     const TrimLines& trim, double tolerance, MeshEdit& edit, const SharedEnds& shared = {});

// Spacing across the profile (and the largest step along it) for a tolerance: the v levels' count.
int profile_segments(const std::vector<ProfileStation>& stations, double tolerance);

// The step across the profile at u (local radius x opening angle / segments, interpolated between the
// stations); steps along the round and its trim lines are at most kMaxStepRatio times this.
double profile_step(const RoundingSurface& surface, const std::vector<ProfileStation>& stations, int segments, double u);
constexpr double kMaxStepRatio = 2.5;
// Graded rows beside a trim line (at most kGradedRows a side) while its short steps are under
// kGradedStep times the distance of the row beyond.
constexpr int kGradedRows = 4;
constexpr double kGradedStep = 0.6;

}  // namespace meshround
