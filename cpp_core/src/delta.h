// Making MeshDeltas (private to cpp_core): from one pass's MeshEdit at the cost of the band, and from a
// chain of passes (several chains, an end split, sphere corners), each of which made a whole mesh from the
// one before, through the lineage of that last mesh.
#pragma once
#include <utility>

#include "meshround/mesh_delta.h"
#include "meshround/mesh_edit.h"

namespace meshround {

// The delta of facets removed from `in`, input vertices moved, points made (ids in.num_vertices() + k,
// those no added facet uses left out) and facets added; `removed` in any order. Work: the band's.
MeshDelta make_delta(const MeshTopology& in, std::vector<int> removed, const std::vector<std::pair<int, Vec3>>& moved,
                     const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& added);
MeshDelta delta_from_edit(const MeshEdit& edit);

// The input vertex / facet that each vertex / facet of a mesh made by passes is, or -1 for a made one.
// Empty: the input itself.
struct Lineage {
  std::vector<int> vertex, facet;
};
// The lineage after one more pass whose result came from the mesh of `before` as `step` says.
Lineage follow(const Lineage& before, const StepOrigin& step);
// The delta from the input (V0, F0) to the mesh (V, F) of that lineage. Work: the whole mesh's.
MeshDelta delta_from_lineage(const Points& V0, const Triangles& F0, const Points& V, const Triangles& F, const Lineage& lineage);
// The delta as an edit of `in` (for the output check, guard.h, of a result made in several passes).
MeshEdit edit_of(const MeshTopology& in, const MeshDelta& d);
// Two passes' deltas as one: `first` made (V1, F1) from (V0, F0), `first_origin` says how; `then` edits (V1, F1).
MeshDelta delta_through(const Points& V0, const Triangles& F0, const Points& V1, const Triangles& F1, const StepOrigin& first_origin,
                        const MeshDelta& then);

}  // namespace meshround
