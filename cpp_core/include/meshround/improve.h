// The last pass before the mesh is written: better shaped new facets where that changes no geometry.
//
// The trim and the end caps triangulate one polygon at a time, with points they had to place before
// the polygons were known (graded points along an edge shared by two faces, hinge points where an edge
// leaves the reach). Across polygons some of those choices turn out poor: two pieces of one flat face
// split along the worse diagonal of their quad, a graded point that the facets around it would be
// better without. This pass looks across polygons, on flat ground only, so the surface stays exactly
// what it was:
// - flips: the shared edge of two coplanar new facets is flipped when the other diagonal gives a larger
//   smallest angle (Lawson);
// - removals: a new vertex inside a flat patch of new facets, or on a straight crease between two flat
//   patches, is removed and the hole triangulated again (each patch on its own) when the smallest angle
//   around it gets larger; one that cannot go slides along its crease to where its facets are best.
// Vertices of the round and its trim lines never move or go; every facet made keeps a corner where
// `admit` allows points (within the reach), so nothing new appears beyond it.
#pragma once
#include <functional>
#include <unordered_set>

#include "meshround/mesh_edit.h"

namespace meshround {

struct ImproveStats {
  int flips = 0;             // edges flipped
  int vertices_removed = 0;  // new vertices taken out
  int vertices_slid = 0;     // new vertices moved along their crease
};

// `keep`: vertices that must stay (the round's). Removed facets are dropped from edit.added.
ImproveStats improve_new_facets(MeshEdit& edit, const std::unordered_set<int>& keep,
                                const std::function<bool(const Vec3&)>& admit);

}  // namespace meshround
