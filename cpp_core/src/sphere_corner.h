// Corners of three or more rounds (after the rounds, before the result is returned): where n picked
// chains of one constant radius end at one vertex -- a box corner with its three edges rounded, a
// pyramid's apex with its four -- the exact rolling-ball blend is a patch of the ball that touches the n
// faces at once (three faces always have one; four or more only when their offsets meet in one point,
// as at a regular pyramid's apex). Each round stops at the plane through that ball's centre across its
// chain (round.cpp, find_corners), so its end profile is a great-circle arc of the ball and the n arcs
// bound the patch. This pass removes what lies between them (the corner of the faces and the rounds' end
// caps) and meshes the ball there.
#pragma once
#include "meshround/chain.h"
#include "meshround/mesh_delta.h"
#include "meshround/types.h"

#include <array>
#include <vector>

namespace meshround {

struct SphereCorner {
  Vec3 vertex;               // where the chains end
  Vec3 centre;               // the ball touching the faces
  double radius = 0;
  std::vector<Vec3> toward;  // unit, along each chain towards the vertex: the corner lies on that side of the planes
  std::vector<Vec3> feet;    // where the ball touches the faces: the corners of the patch
  std::vector<std::array<size_t, 2>> sides;  // each chain's two faces (indices into feet), in the order of toward
};

// The ball touching the n >= 3 planes through `point` (outward unit normals) on the round's side: inside
// the solid for a convex corner (`convex`), outside for a concave one, and its feet on them (the least-
// squares centre when n > 3). `miss`: the largest distance of a face from that ball's surface (0 for
// three planes). False when the planes meet at no single point.
bool corner_ball(const Vec3& point, const std::vector<Vec3>& normals, double radius, bool convex, Vec3* centre,
                 std::vector<Vec3>* feet, double* miss);

// V / F: the mesh with the rounds made; `delta`: the patch as an edit of it. Refuses (corner_not_blendable) when the corner is not one
// hole bounded by the rounds' arcs, and (result_invalid) when the patch fails the output check (guard.h;
// `chain` and `reach` for its placement test).
void blend_sphere_corner(const Points& V, const Triangles& F, const SphereCorner& corner, double tolerance,
                         const SharpChain& chain, double reach, MeshDelta& delta);

}  // namespace meshround
