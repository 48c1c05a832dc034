// Thin facets (private to cpp_core): the report counts the new facets with an angle under kThinDeg, per
// chain as a round is made (against the input facets it replaces) and again over a finished network,
// whose later passes replace facets that earlier ones made.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "meshround/mesh_delta.h"
#include "meshround/mesh_edit.h"
#include "meshround/types.h"

namespace meshround {

constexpr double kThinDeg = 10;  // a new facet with a smaller angle is thin (the report's "slivers")

double smallest_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c);

// Facets made (or kept with a vertex snapped onto a trim line) against the input facets they replace:
// how many are under kThinDeg; their smallest angle and the replaced input facets' (degrees) out.
int count_thin_facets(const MeshTopology& mesh, const MeshEdit& edit, double* min_new, double* min_input);

// The thin facets (and the smallest angle) among the facets of `delta` applied to (V, F) that are not (V, F)'s
// -- the made facets but those that put back an input facet the delta removed, and the kept facets with a moved
// corner -- into `thin` and `smallest`. From the delta alone: what it costs follows the band, not the mesh.
void recount_new_facets(const Points& V, const Triangles& F, const MeshDelta& delta, int* thin, double* smallest);

// A cusp of a round's end cap (ends.h EndSegment): where the round's end profile leaves a face's trace
// tangentially, `step` the profile's step across there and `radius` the round's.
struct CuspPoint {
  Vec3 at;
  double step = 0, radius = 0;
};
// A facet's angle at a cusp (radians): half the angle of the profile's first step there.
inline double cusp_angle(double step, double radius) { return std::asin(std::min(1.0, 0.5 * step / radius)); }
// Of the made facets under kThinDeg, those at a cusp: a corner within kCuspReach steps of it and an angle no
// smaller than kCuspAngleShare x the cusp's, half the profile's step (the most the tolerance allows there is
// acos(1 - t / r): no mesh of the exact round within it does much better at a tangential end). The cusps'
// angle (degrees; the smallest, where there are several) into *angle_deg.
constexpr double kCuspReach = 2.5;  // (the cap is a wedge narrower than its step for two steps from the cusp)
constexpr double kCuspAngleShare = 0.9;
int count_cusp_facets(const MeshEdit& edit, const std::vector<CuspPoint>& cusps, double* angle_deg);

}  // namespace meshround
