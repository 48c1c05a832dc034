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

#include "meshround/options.h"
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

// The band element controls (RoundOptions) as the tessellation and the trim use them: the one place
// their rules live.
struct BandControls {
  double max_angle = 0;       // radians of the profile per element across; 0: the chordal tolerance alone
  double element_length = 0; // step along the round (mm); 0: the trim lines' own (the input's next to the chain)
  double max_aspect = 0;      // steps along at most this times the step across, and the step across at most
                              // this times element_length when that is given; 0: kMaxStepRatio along only
  static BandControls of(const RoundOptions& options);
  // The longest step along the round where the step across is `across`.
  double longest_along(double across) const;
  // The shortest step along the inner rows keep between samples (closer samples are thinned out).
  double shortest_along(double across) const;
};

RoundMeshStats mesh_rounding_surface(const RoundingSurface& surface, const std::vector<ProfileStation>& stations,
                                     const TrimLines& trim, double tolerance, const BandControls& controls, MeshEdit& edit,
                                     const SharedEnds& shared = {});

// Elements across the profile for a tolerance and the controls: the v levels' count.
int profile_segments(const std::vector<ProfileStation>& stations, double tolerance, const BandControls& controls);

// The step across the profile at u (local radius x opening angle / segments, interpolated between the
// stations); steps along the round and its trim lines are at most BandControls::longest_along of this.
double profile_step(const RoundingSurface& surface, const std::vector<ProfileStation>& stations, int segments, double u);
// The built-in bounds of the steps along: between kMinStepRatio and kMaxStepRatio times the step across.
constexpr double kMaxStepRatio = 2.5;
constexpr double kMinStepRatio = 0.4;
// Graded rows beside a trim line (at most kGradedRows a side) while its short steps are under
// kGradedStep times the distance of the row beyond.
constexpr int kGradedRows = 4;
constexpr double kGradedStep = 0.6;

}  // namespace meshround
