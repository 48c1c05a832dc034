// MeshEdit: the edits the passes make to the input mesh, kept apart from it until the end so that the
// input is never touched and a failure leaves nothing half done.
#pragma once
#include <array>
#include <functional>
#include <limits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "meshround/mesh.h"

namespace meshround {

// Throws RoundingError(WorkLimit) when `facets` > `budget`, naming the pass that would make them.
void check_work_budget(double facets, long budget, const char* pass);

struct MeshEdit {
  explicit MeshEdit(const MeshTopology& in) : input(in) {}

  const MeshTopology& input;
  std::vector<Vec3> new_points;            // vertex ids num_vertices(), num_vertices() + 1, ...
  std::unordered_map<int, Vec3> moved;     // input vertices snapped onto a trim line
  std::unordered_set<int> removed;         // input facets removed or replaced by pieces
  std::vector<std::array<int, 3>> added;   // new facets (pieces of cut facets, the round, end caps)
  std::unordered_map<std::uint64_t, int> edge_point;  // input edge -> the trim vertex inserted on it
  long max_new_facets = std::numeric_limits<long>::max();  // the work budget (RoundOptions::max_new_facets)

  // Refuses with work_limit when `facets` new facets would overrun the budget; `pass` names where.
  void check_budget(double facets, const char* pass) const { check_work_budget(facets, max_new_facets, pass); }
  // Each new point costs about two new facets (a triangulated patch has two facets per inner vertex),
  // so the points made anywhere (trim refinement, rows, end caps) are counted against the budget here.
  int add_point(const Vec3& p) {
    if (2.0 * double(new_points.size() + 1) > double(max_new_facets)) check_budget(2.0 * double(new_points.size() + 1), "new points");
    new_points.push_back(p);
    return input.num_vertices() + int(new_points.size()) - 1;
  }
  Vec3 point(int v) const {
    if (v >= input.num_vertices()) return new_points[v - input.num_vertices()];
    auto it = moved.find(v);
    return it != moved.end() ? it->second : input.point(v);
  }
};

// Inner points for a better triangulation of a flat polygon (none by default).
struct Refinement {
  double quality_deg = 0;                  // > 0: add points while a triangle has a smaller angle
  std::function<bool(const Vec3&)> admit;  // optional: where points may go
  double flat_tolerance = 0;               // a polygon this close to a plane still gets points (in that
                                           // plane): an end face meeting a variable round's tilted end
  double smoothing_gain_deg = 0.01;        // an inner point moves only if that raises the smallest angle
                                           // around it by more than this
  size_t max_split_ring = 500;             // a polygon with more sides is refined whole, without first
                                           // splitting off the parts refinement cannot shape (that try is
                                           // quadratic in the sides: a trim line across a facet thousands of
                                           // times the band has over ten thousand)
};

// Triangulates a simple polygon (vertex ids, in order) in the plane with normal `normal`: ear clipping
// that always cuts the best-shaped ear, then flips to the best triangulation; with `refine`, points are
// added inside (never on its sides) where that improves the worst triangle. Triangles keep the
// polygon's orientation.
void triangulate_polygon(MeshEdit& edit, const std::vector<int>& polygon, const Vec3& normal,
                         std::vector<std::array<int, 3>>& out, const Refinement& refine = {});

}  // namespace meshround
