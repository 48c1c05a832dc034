// Thin facets (private to cpp_core): the report counts the new facets with an angle under kThinDeg, per
// chain as a round is made (against the input facets it replaces) and again over a finished network,
// whose later passes replace facets that earlier ones made.
#pragma once
#include "meshround/mesh_edit.h"
#include "meshround/types.h"

namespace meshround {

constexpr double kThinDeg = 10;  // a new facet with a smaller angle is thin (the report's "slivers")

double smallest_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c);

// Facets made (or kept with a vertex snapped onto a trim line) against the input facets they replace:
// how many are under kThinDeg; their smallest angle and the replaced input facets' (degrees) out.
int count_thin_facets(const MeshTopology& mesh, const MeshEdit& edit, double* min_new, double* min_input);

// The thin facets (and the smallest angle) among (out_V, out_F)'s facets that are not (V, F)'s, into
// `thin` and `smallest`. Only facets with a corner in the box [lo, hi] are looked at: the caller's box
// holds every made facet.
void recount_new_facets(const Points& V, const Triangles& F, const Points& out_V, const Triangles& out_F, const Vec3& lo,
                        const Vec3& hi, int* thin, double* smallest);

}  // namespace meshround
