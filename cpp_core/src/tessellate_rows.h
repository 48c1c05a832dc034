// The tessellation's state and sub-passes (private to cpp_core; tessellate.h mesh_rounding_surface is the pass).
//
// mesh_rounding_surface runs the sub-passes of one RowTessellation in this order:
//   1. place_levels       the profile's segment count and the inner rows' v levels (on the widest profile)
//   2. read_trim_lines    the trim lines as the first and last rows (unwrapped, closed for a loop) and
//                         their offsets from the surface's edges, which the inner rows follow
//   3. sample_inner_rows  the inner rows' u samples: both trim lines merged, thinned, gaps filled
//   4. plan_graded_rows   graded rows beside a trim line much finer than the first inner row is far
// then, up to kRefineRounds times, until no facet strays or no step can be split:
//   5. make_rows          every row's points (inner points new, end points on the end faces or shared)
//   6. zip_rows           neighbouring rows zipped into facets, taking the shorter diagonal
//   7. measure_facets     each facet's distance from the surface; the u ranges of those that stray
//   8. refine_samples     the inner rows' steps over those ranges halved
// and finally
//   9. commit             the inner points and the facets added to the edit; the stats
#pragma once
#include "meshround/mesh_edit.h"
#include "meshround/surface.h"
#include "meshround/tessellate.h"
#include "meshround/trim.h"

#include <array>
#include <utility>
#include <vector>

namespace meshround {

// Rounds of measuring and refining the inner rows' u samples at most.
constexpr int kRefineRounds = 8;
// A facet farther than this share of the tolerance from the surface has its u range refined.
constexpr double kRefineShare = 0.9;

struct RowPoint {
  int id;    // MeshEdit id for trim rows; index into `inner` (negative, -1 - i) for inner rows
  double u;  // unwrapped along the strip
  double v;
};

// Offsets of the trim points from the surface's edges, interpolated along u and faded across v.
class EdgeOffsets {
 public:
  EdgeOffsets() = default;
  EdgeOffsets(const RoundingSurface& surface, const std::vector<RowPoint>& first, const std::vector<RowPoint>& last,
              const MeshEdit& edit) {
    for (int side = 0; side < 2; ++side)
      for (const RowPoint& p : side ? last : first)
        rows_[side].push_back({p.u, edit.point(p.id) - surface.value(p.u, side)});
  }
  // The offset at (u, v): full at the trim lines, none from the middle of the profile on.
  Vec3 at(double u, double v) const { return fade(v) * along(0, u) + fade(1 - v) * along(1, u); }

 private:
  static double fade(double v) { return v >= 0.5 ? 0.0 : (1 - 2 * v) * (1 - 2 * v); }
  Vec3 along(int side, double u) const;  // rows are sorted by (unwrapped) u
  std::vector<std::pair<double, Vec3>> rows_[2];
};

// A graded row beside a trim line: its v and its own u samples.
struct GradedRow {
  double v;
  std::vector<double> U;
};

// A facet's u range (smallest, largest of its corners').
using URange = std::pair<double, double>;

// One round's tessellation: its sub-passes in order (see the top of this file) and what they share.
class RowTessellation {
 public:
  RowTessellation(const RoundingSurface& surface, const std::vector<ProfileStation>& stations, double tolerance,
                  const BandControls& controls, MeshEdit& edit, const SharedEnds& shared);
  void place_levels();
  void read_trim_lines(const TrimLines& trim);
  void sample_inner_rows();
  void plan_graded_rows();
  void make_rows();
  void zip_rows();
  std::vector<URange> measure_facets(int round);
  bool refine_samples(std::vector<URange>& bad);
  RoundMeshStats commit();

 private:
  // Steps along the round follow the local step across it (BandControls): facets keep their shape where a
  // variable radius shrinks.
  double h_min(double u) const { return controls.shortest_along(profile_step(surface, stations, nv, u)); }
  double h_max(double u) const { return controls.longest_along(profile_step(surface, stations, nv, u)); }
  std::vector<double> row_samples(const std::vector<double>& sorted, double scale) const;
  std::vector<double> samples_on_row(const std::vector<double>& samples, double v) const;
  std::vector<double> end_piece(int end, double v, std::vector<double>& mid) const;
  Vec3 end_offset(int end, double u, double v) const;
  void add_row(const std::vector<double>& row_u, double v);
  Vec3 position(const RowPoint& p) const { return p.id >= 0 ? edit.point(p.id) : inner[-1 - p.id]; }

  const RoundingSurface& surface;
  const std::vector<ProfileStation>& stations;
  const double tolerance;
  const BandControls& controls;
  MeshEdit& edit;
  const SharedEnds& shared;
  const bool debug;     // MESHROUND_DEBUG set: the rows and each refining round to stderr
  const double period;  // the surface's u range

  int nv = 0;                               // segments across the profile
  const ProfileStation* widest = nullptr;   // the widest uncapped profile: the v levels' and graded rows'
  std::vector<double> levels;               // v of the regular rows, 0 and 1 (the trim lines) included
  std::array<std::vector<RowPoint>, 2> trim_row;  // the trim lines as rows: side A (v = 0), side B (v = 1)
  EdgeOffsets offsets;
  std::vector<double> us;   // both trim lines' u, sorted
  double u_lo = 0, u_hi = 0;  // the inner rows' span
  std::vector<double> U;    // the regular inner rows' u samples
  std::vector<GradedRow> graded[2];  // side A: nearest the line first; side B: nearest the line last

  // Remade every refining round.
  std::vector<Vec3> inner;                        // the inner rows' points
  std::vector<std::vector<RowPoint>> rows;        // every row, side A's trim line first
  std::vector<std::array<RowPoint, 3>> tris;      // the facets
  RoundMeshStats stats;
};

}  // namespace meshround
