// Corners of three rounds (after the rounds, before the result is returned): where three picked chains
// of one constant radius end at one vertex -- a box corner with its three edges rounded -- the exact
// rolling-ball blend is a patch of the ball that touches the three faces at once. Each round stops at
// the plane through that ball's centre across its chain (round.cpp, find_corners), so its end profile is
// a great-circle arc of the ball and the three arcs bound the patch. This pass removes what lies between
// them (the corner of the three faces and the rounds' end caps) and meshes the ball there.
#pragma once
#include "meshround/chain.h"
#include "meshround/mesh_delta.h"
#include "meshround/types.h"

namespace meshround {

struct SphereCorner {
  Vec3 vertex;      // where the three chains end
  Vec3 centre;      // the ball touching the three faces
  double radius = 0;
  Vec3 toward[3];   // unit, along each chain towards the vertex: the corner lies on that side of the planes
  Vec3 feet[3];     // where the ball touches the three faces: the corners of the patch
};

// The ball touching the three planes (point, outward unit normal) on the round's side: inside the solid
// for a convex corner (`convex`), outside for a concave one, and its feet on them. False when the planes
// meet at no single point.
bool corner_ball(const Vec3 points[3], const Vec3 normals[3], double radius, bool convex, Vec3* centre, Vec3 feet[3]);

// V / F: the mesh with the three rounds made; `delta`: the patch as an edit of it. Refuses (corner_not_blendable) when the corner is not one
// hole bounded by the three arcs, and (result_invalid) when the patch fails the output check (guard.h;
// `chain` and `reach` for its placement test).
void blend_sphere_corner(const Points& V, const Triangles& F, const SphereCorner& corner, double tolerance,
                         const SharpChain& chain, double reach, MeshDelta& delta);

}  // namespace meshround
