// MeshDelta: a rounding's result as an edit of its input mesh -- the facets it removes, the vertices it
// moves, the points and facets it adds. A caller that keeps the input in a structure of its own (FreeCAD's
// Mesh.Mesh) applies it to a copy: what that costs follows the band, not the mesh. apply_delta gives the
// same mesh as arrays, vertex for vertex and facet for facet.
#pragma once
#include <array>
#include <vector>

#include "meshround/types.h"

namespace meshround {

struct MeshDelta {
  int input_vertices = 0, input_facets = 0;
  std::vector<int> removed;               // input facets, ascending
  std::vector<int> freed;                 // input vertices that no kept input facet uses, ascending: the
                                          // band's inner vertices (and any the input's facets never used)
  std::vector<int> moved;                 // input vertices given a new position, ascending ...
  std::vector<Vec3> moved_to;             // ... and that position
  std::vector<Vec3> new_points;           // vertex ids input_vertices, input_vertices + 1, ...; all used
  std::vector<std::array<int, 3>> added;  // the facets made, in order (ids < input_vertices: input vertices)
};

// The one order of the result (a copy of the input with `removed` taken out -- which drops the freed
// vertices -- and then the points and facets added, as a Mesh.Mesh does it, gets the same):
//   vertices: the input vertices that are not freed, in their order (moved ones at their new position);
//             then the freed ones that added facets use, ascending; then new_points;
//   facets:   the input facets that are not removed, in their order; then added.
// Input vertices that are neither moved nor new keep their coordinates bit for bit.
void apply_delta(const Points& V, const Triangles& F, const MeshDelta& delta, Points& V_out, Triangles& F_out);

// Where each vertex and facet of apply_delta's result comes from: its id in the mesh the delta was
// applied to, or -1 for one the delta made.
struct StepOrigin {
  std::vector<int> vertex, facet;
};
void apply_delta(const Points& V, const Triangles& F, const MeshDelta& delta, Points& V_out, Triangles& F_out,
                 StepOrigin* origin);

}  // namespace meshround
