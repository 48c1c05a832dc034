// Capped chain ends: the face a round runs into where its chain ends at a junction (private to cpp_core).
//
// Where three or more sharp edges meet at a chain's end, the faces there other than the chain's two
// sides are its end face: a box's side face at a convex corner, a pocket's next wall where a rim edge
// runs into it (the top face goes on past the end), a drafted or 45-degree wall. Like OCCT's fillet of
// that one edge, the round runs on to the end face's plane and stops there: its end profile is the
// section arc moved along the chain onto that plane (EndCut), the base meshes are trimmed up to the
// plane, and the gap between the end profile and the end face is filled in the plane by the sewing pass.
#pragma once
#include <functional>

#include "meshround/mesh_delta.h"
#include "meshround/mesh_edit.h"
#include "meshround/spine.h"
#include "meshround/surface.h"
#include "network.h"

namespace meshround {

// The end face's plane at the chain's first (at_start) or last vertex; inactive when the end is not a
// junction, when the faces there are not one plane, or when that plane runs nearly along the chain.
EndCut end_face_cut(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base, bool at_start);

// How far back from the end the last ball must sit so that its whole profile, carried along the chain,
// reaches the plane (none of it starts past the plane): 0 for a plane square to the chain's end.
// `inside`: a ball `to_end` short of the end (the chain's end is straight: balls there are translates).
// `open`: the plane of a mesh edge the chain runs off (open_end_cut), where the ball stands further back.
double end_cut_setback(const ProfileStation& inside, double to_end, const EndCut& cut, bool open = false);

// How a chain's round ends: each open end's cut -- its end face's plane (end_face_cut), or the plane of a
// corner with another picked chain (network.h) -- and how far before it the balls stop (the setback; the
// last ball is carried on along the chain onto the plane). Refuses a ball there that does not fit
// (radius_too_large), and setbacks that leave too little of the chain for its balls (radius_too_large too:
// a smaller radius has shorter setbacks). An end that runs off the mesh's edge is checked there (open_end_cut).
// The one rule round_edges rounds by and max_radius measures by.
struct EndPlan {
  EndCut cut[2];
  double setback[2] = {0, 0};
};
EndPlan plan_ends(const SpineContext& ctx, const RadiusLaw& law, const NetworkPart& net, double tolerance);

// A chain that runs off the mesh's edge (ChainEnd::Boundary) ends, as OCCT's fillet of the open shell does,
// on the plane of the mesh's edge there: the plane through the chain's end vertex spanned by its two
// boundary edges (a crop square to the chain or slanted across it; the plane across the chain where those
// edges are nearly one line). Its end profile is cut by that plane and becomes part of the mesh's edge.
// Inactive for other ends. The one rule plan_ends and the output check (guard.h) use. plan_ends refuses such
// an end, once a ball fits there, where the mesh's edge is not in that plane within `tolerance` out to the end
// profile's contacts (a ragged or bent crop) or the plane runs nearly along the chain (corner_not_blendable
// naming the end), or where the boundary there is a hole's (non_manifold_input).
EndCut open_end_cut(const MeshTopology& mesh, const SharpChain& chain, bool at_start);
// That refusal (open_ends.cpp), for the end `at_start` whose open_end_cut is `cut`.
void check_open_end(const MeshTopology& mesh, const SharpChain& chain, const RadiusLaw& law, double tolerance, bool at_start,
                    const EndCut& cut);

// Vertex v lies on a hole of the mesh, not on its edge: its boundary loop closes within 8 r and spans less than
// half the mesh's box. The one rule a hole is named by: at an open chain end (non_manifold_input) and where a
// ball would reach it (spine.h solve_station, radius_too_large: a pin hole limits the radius as a wall does).
bool on_hole(const MeshTopology& mesh, int v, double r);

constexpr double kMinCrossing = 0.3;  // |cos| between a chain and the normal of the plane that ends it, at least

// Where a side's base mesh goes on past a capped end's plane (a pocket's top face around its corner),
// the band's corner there must run along mesh edges: the segment from the chain's end vertex to the
// round's corner on that side (both on the plane) is made of edges. The corner becomes a vertex
// (splitting the facet or edge it lies in) and each facet the segment crosses is split along the plane;
// a vertex of a flat neighbourhood a hair off the plane is moved onto it instead (no slivers). Input
// vertices keep their indices (new ones follow); facets off the segment are the input's.
struct EndSegment {
  EndCut cut;
  int end_vertex = -1;     // the chain's vertex at that end
  // Where the segment starts on the chain: the end vertex when the plane passes through it; else (a sphere
  // corner's plane, across the chain short of its end) the point on chain edge (edge[0], edge[1]).
  Vec3 start;
  int edge[2] = {-1, -1};
  Vec3 corner;             // where the round's side meets the plane (the surface's corner)
  std::vector<int> facets; // the side's base facets near the segment
  // The round's end profile leaves the segment tangentially at the corner (a cusp: the end cap between them
  // comes to a point there). A point is put on the segment this far from the corner, the round's step across
  // there, so that the cap's facet at the cusp has its angle there at half the profile's first step (the
  // least the tolerance allows) and no smaller one elsewhere; none where the segment is under
  // kCuspPointRoom steps long.
  double cusp_step = 0;
  double radius = 0;       // the round's radius at that end
};
constexpr double kCuspPointRoom = 2.5;
// The segments a chain's round needs (none where no base mesh goes on past an end's plane). `step`: the
// round's step across its profile at u (tessellate.h profile_step).
std::vector<EndSegment> end_segments(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base,
                                     const std::vector<ProfileStation>& stations, const RoundingSurface& surface,
                                     const std::function<double(double)>& step);
// The split as a delta of `mesh` (mesh_delta.h); returns false (delta untouched) when there is nothing to split.
// A vertex on the plane within `weld` of a segment's corner is that corner.
bool split_along_end_segments(const MeshTopology& mesh, const std::vector<EndSegment>& segments, double weld, MeshDelta& delta);

}  // namespace meshround
