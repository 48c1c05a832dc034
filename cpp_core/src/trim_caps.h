// The trim pass's end caps (private to cpp_core): at a chain's capped end, the corner of the end faces
// that the round replaces (trim.h trim_base_meshes removes it after trimming the base meshes).
#pragma once
#include "meshround/chain.h"
#include "meshround/mesh_edit.h"
#include "meshround/spine.h"

namespace meshround {

// A facet of an end face lies in the end's plane when its corners are within this share of the radius of it
// (the cap's corner is removed from such facets only; plan_ends leaves an end square where the end face's
// facets at the chain's end do not all lie in its plane).
constexpr double kOnCapPlaneShare = 1e-3;

// Facets of the end faces that the round cuts into at a capped chain end (a convex end), or that have a
// vertex on the faces' traces within the band (a concave end: the round adds to the end face, and such a
// vertex would sit right next to the arc).
void remove_cap_corner(const MeshTopology& mesh, const BaseMeshes& base, int corner, const ProfileStation& st,
                       MeshEdit& edit, int* removed);

}  // namespace meshround
