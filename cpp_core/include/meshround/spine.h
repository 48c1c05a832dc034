// Paper §4.1-4.3: ball centres and exact contact points.
//
// Instead of intersecting offset meshes and repairing the centres afterwards, each centre is solved
// directly: in the section plane through the chain point at arc length s, find c with
// dist(c, base A) = dist(c, base B) = r (Newton on the exact point-to-mesh distances). The closest
// points are the contacts, whether they lie on a facet, an edge or a vertex of a base mesh, and the
// profile through them is exact: the sphere touches both base meshes there.
#pragma once
#include <vector>

#include "meshround/chain.h"
#include "meshround/radius_law.h"

namespace meshround {

enum class ContactRegion { Facet = 0, Edge = 1, Vertex = 2 };

// Where a round runs into the face at a capped chain end (ends.h): its end profile is the section arc
// moved along `along` (the chain's direction out of the end) onto the plane through `point` with unit
// `normal` (pointing away from the round). Inactive: the section arc itself.
struct EndCut {
  bool active = false;
  Vec3 point = Vec3::Zero(), normal = Vec3::Zero(), along = Vec3::Zero();
  // Signed distance of p from the plane: > 0 past it, away from the round.
  double past(const Vec3& p) const { return (p - point).dot(normal); }
  // p moved along `along` onto the plane (an affine map: a rational arc stays one, with its weights).
  Vec3 onto(const Vec3& p) const { return p - along * (past(p) / along.dot(normal)); }
};

struct ProfileStation {
  double s = 0;                 // arc length along the chain = the surface's u parameter
  double radius = 0;
  Vec3 centre;                  // ball centre (a point of the spine)
  Vec3 contact[2];              // contact on side A, side B
  ContactRegion region[2]{};
  EndCut cut;                   // a capped end's station: its arc is the section's, moved onto the end face
  // A capped end's station set back from its end face (the face leans over the round): the previous
  // (next) station's ball carried along the straight chain end to the chain's end, its arc then moved onto
  // the face. The surface between the two is that straight extrusion, cut by the face (see loft_profiles).
  bool carried = false;
  double angle() const;         // opening angle of the profile arc (radians)
};

// A round made before in the same call, known exactly: the balls of `radius` centred on `spine` (its
// stations' centres, a polyline; exact where the chain is straight). A base mesh that runs over such a
// round is measured on the round itself, not on its facets (a rolled corner's second stage, stages.h).
struct ExactRound {
  std::vector<Vec3> spine;
  double radius = 0;
  // Its contact lines, point for point with the spine: the round is the balls' arc between them, and past
  // each its tangent plane there, the face it meets (a facet beside the contact line lies within r / 100
  // of the balls' envelope past it, which bends away from the face by d^2 / 2r). Empty: the whole envelope.
  std::vector<Vec3> contacts[2];
};

// Exact closest points on one base mesh.
class BaseDistance {
 public:
  // `rounds`: the earlier rounds of the call; a base facet lying on one of them (its corners on the round,
  // its middle within the round's chordal tolerance) is measured on that round's exact surface.
  BaseDistance(const MeshTopology& mesh, const std::vector<int>& facets, const std::vector<ExactRound>* rounds = nullptr);
  // Closest point of the base mesh to p; `facet` and `region` (closest_point_on_triangle's code) out.
  // Exact (a bounding volume hierarchy of the facets, searched branch and bound); of equally near
  // facets, the first in `facets`.
  Vec3 closest(const Vec3& p, int* facet = nullptr, int* region = nullptr) const;

 private:
  const MeshTopology& mesh_;
  const std::vector<int>& facets_;
  std::shared_ptr<const BoxTree> tree_;
  const std::vector<ExactRound>* rounds_ = nullptr;
  std::vector<int> on_round_;  // per base facet: the round it lies on, or -1
  // For base facet i on an earlier round: p's foot on that round's exact surface, when it lies over i.
  bool exact_foot(int i, const Vec3& p, Vec3* foot) const;
};

struct SpineContext {
  const MeshTopology& mesh;
  const SharpChain& chain;
  const BaseMeshes& base;
  const BaseDistance* distance[2];
};

// Why a ball of radius r does not fit at a station (fit_station), or Fits.
enum class StationMisfit {
  Fits,
  FlatEdge,     // the two facets at the chain are flat or folded back there: no wedge to start from
  NoBall,       // Newton found no ball touching both base meshes (the edge is flat there, or the faces part)
  Wall,         // a contact lies on a wall of its base mesh: the next sharp edge or the mesh boundary
  BeyondReach,  // a contact lies beyond the reach the base meshes were collected for
  Curvature,    // the chain's own curvature: a contact (or the centre) lies at or past the chain's centre of
                // curvature, so the line it traces along the chain folds back on itself
};
struct StationFit {
  StationMisfit misfit = StationMisfit::Fits;
  int side = -1;                    // the side (0 = A, 1 = B) that stops the ball; -1 for FlatEdge, NoBall
  Vec3 at = Vec3::Zero();           // where: the contact on the wall / past the reach, the point that folds
  std::uint64_t wall_edge = ~0ull;  // Wall: the wall edge touched (for a vertex contact, a wall edge at it)
};

// The ball of radius r at arc length s, and whether it fits (`fit`); never throws for a misfit. The one
// place the rules of a ball's room are checked: solve_station refuses by them, max_radius (max_radius.h)
// measures by them.
ProfileStation fit_station(const SpineContext& ctx, double s, double r, StationFit* fit);

// The ball of radius r at arc length s. Throws RoundingError (naming the place) when no ball of that
// radius fits between the base meshes there (fit_station's misfits: radius_too_large, beyond_reach).
ProfileStation solve_station(const SpineContext& ctx, double s, double r);

// The same for the radius `law` gives at s; a refusal names the control point nearest s, if any.
ProfileStation solve_station(const SpineContext& ctx, const RadiusLaw& law, double s);

// The curvature vector of the chain at arc length s as a ball of radius r sees it: from the chain point at
// s towards the centre C of the circle through the chain's vertices nearest s and r/2 of arc length either
// side (clamped at an open chain's ends), of length 1 / |C - point|; zero where the chain is straight or
// shorter than r.
Vec3 chain_curvature(const SharpChain& chain, double s, double r);

}  // namespace meshround
