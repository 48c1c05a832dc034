#include "call_checks.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace meshround {
namespace {

// What the mesh's coordinates can carry. Meshes come as float32 (STL, Mesh.Mesh): a coordinate of
// magnitude m holds ~7 digits, and the engine counts a point within 1e-6 m of a plane as on it
// (on_plane_slack). A chordal tolerance finer than that precision is not there to be met, and a radius
// below kMinRadiusPerPrecision times it cannot be made to its own default tolerance (r / 100): both
// are refused with radius_too_small, naming the smallest value that works.
constexpr double kCoordinatePrecision = 1e-6;     // relative to the mesh's largest |coordinate|, as on_plane_slack
constexpr double kMinTolerancePerPrecision = 1;   // tolerance >= the precision
constexpr double kMinRadiusPerPrecision = 100;    // radius >= 100 x the precision (its r / 100 >= the precision)

// The limits the mesh's precision sets (the options' own ranges are validate_options'); `magnitude` is
// the mesh's largest |coordinate|.
void check_precision(const RoundOptions& o, double magnitude) {
  double smallest_radius = o.radius;
  if (!o.radius_law.empty()) {
    smallest_radius = INFINITY;
    for (const RadiusControl& c : o.radius_law) smallest_radius = std::min(smallest_radius, c.radius);
  }
  const double precision = kCoordinatePrecision * magnitude;
  const std::string why = " mm is below what this mesh's coordinates can carry (float32-level precision " + format_number(precision) +
                          " mm at coordinates up to " + format_number(magnitude) + " mm)";
  const double min_radius = kMinRadiusPerPrecision * precision;
  if (smallest_radius < min_radius * (1 - 1e-6))  // a hair: the value the message names passes
    throw RoundingError(ErrorCode::RadiusTooSmall, "the radius " + format_number(smallest_radius) + why + "; the smallest radius that works is " +
                        format_number(min_radius) + " mm");
  const double min_tolerance = kMinTolerancePerPrecision * precision;
  if (o.effective_tolerance() < min_tolerance * (1 - 1e-6))
    throw RoundingError(ErrorCode::RadiusTooSmall, "the tolerance " + format_number(o.effective_tolerance()) + why +
                        "; the smallest tolerance that works is " + format_number(min_tolerance) + " mm");
}

}  // namespace

void check_call(const Points& V, const std::vector<Vec3>& seeds, const RoundOptions& opt) {
  validate_options(opt);
  check_precision(opt, coordinate_magnitude(V));
  if (seeds.empty()) throw RoundingError(ErrorCode::InvalidInput, "no seed given: pick a point on a sharp edge");
}

void check_facet_edges(const MeshTopology& mesh, const std::vector<int>& facets, const std::string& near) {
  for (int f : facets)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      int pair[2];
      const int count = mesh.edge_facet_pair(a, b, pair);
      const Vec3 mid = 0.5 * (mesh.point(a) + mesh.point(b));
      if (count > 2)
        throw RoundingError(ErrorCode::NonManifoldInput, "the edge at " + format_point(mid) + " near " + near +
                            " is non-manifold (more than two facets share it); repair the mesh there first");
      if (count == 2 && mesh.edge_direction(pair[0], a, b) == mesh.edge_direction(pair[1], a, b))
        throw RoundingError(ErrorCode::NonManifoldInput, "the facets at " + format_point(mid) + " near " + near +
                            " are oriented against each other (a flipped facet); repair the mesh there first");
    }
}

double coordinate_magnitude(const Points& V) {
  double m = 0;
  for (Eigen::Index i = 0; i < V.size(); ++i)
    if (std::isfinite(V.data()[i])) m = std::max(m, std::abs(V.data()[i]));
  return m;
}

}  // namespace meshround
