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

#include "meshround/mesh_delta.h"
#include "meshround/mesh_edit.h"

namespace meshround {

struct ImproveStats {
  int flips = 0;             // edges flipped
  int vertices_removed = 0;  // new vertices taken out
  int vertices_slid = 0;     // new vertices moved along their crease
  int patches_remeshed = 0;  // flat patches meshed again whole (remesh_flat_patches)
};

// `keep`: vertices that must stay (the round's). Removed facets are dropped from edit.added.
ImproveStats improve_new_facets(MeshEdit& edit, const std::unordered_set<int>& keep,
                                const std::function<bool(const Vec3&)>& admit);

// After a network's rounds: each chain's trim cut the facets the ones before it made, and a piece of an
// earlier trim that spans from a far corner of a large face to the band of the next round is cut again
// where the later round admits no point near that corner (a CAD face's fan from its far corner to both
// trim lines). Each flat patch of the made facets (`made`: per facet of edit.input; connected across
// edges, on one plane, its outline one simple loop, or two -- an annulus, cut in two across) that has a
// facet under kThinDeg is meshed again whole, as the trim meshes a cut facet: its outline kept, its inner
// vertices (each one that `may_go`) dropped, points added inside where `admit` allows. The new facets
// replace the patch when their smallest angle is larger, no more of them are under kThinDeg, each has a
// corner where `admit` allows, and they add no edge the mesh has outside the patch.
ImproveStats remesh_flat_patches(MeshEdit& edit, const std::vector<char>& made, const std::function<bool(int)>& may_go,
                                 const std::function<bool(const Vec3&)>& admit);
// The same over a call's result: `delta` is what the call made of `input` (its added facets the made ones, its
// new points the vertices that may go); it becomes the result with the patches meshed again. False (delta
// as it was) when no patch was. It costs what the band costs: the made facets and the kept ones around them
// are meshed as a mesh of their own.
bool remesh_flat_patches(const MeshTopology& input, MeshDelta& delta, const std::function<bool(const Vec3&)>& admit);

}  // namespace meshround
