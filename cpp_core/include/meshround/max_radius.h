// The largest radius each picked chain can be rounded with, and what stops a larger one (issue 16).
//
// Measured from the geometry, not by rounding: at stations along the chain (its vertices, the middles of
// its edges, and at least kMinStations evenly), the ball of radius r is solved between the chain's two
// base meshes exactly as the rounding solves it (fit_station, spine.h: the one place the rules of a
// ball's room are checked), and the largest r that fits is found by bisecting that one ball -- a station
// is bisected only where the ball of the smallest room found so far does not fit, so a chain costs about
// one ball per station plus a few bisections. The base meshes are collected for the reach of the radius
// found (again, until the radius found is within 10% of the one they were collected for), so the answer
// is what round_edges with that reach factor sees.
//
// A ball does not fit when a contact lies on a wall of its side (the next sharp edge, the mesh boundary),
// beyond the reach, where the chain bends tighter than the ball (the contact line would fold back), when
// no ball touches both sides, or -- with several chains picked -- when its contact on a face shared with
// another picked chain (one sharing no vertex with it) reaches into that chain's band, the other chain's
// ball of the same radius solved there too (round_edges rounds them one after the other, the later one's
// base mesh stopping at the earlier round). An open chain's ends are planned as round_edges plans them (ends.h
// plan_ends, "end_setback"): its end faces, and its corners with the picked chains rounded in the same stage
// (with rolled corners, the chains made first; the others' ends run on around those rounds and are taken as
// end faces). Not measured here: the rounding's own output check.
#pragma once
#include <string>
#include <vector>

#include "meshround/chain.h"

namespace meshround {

// What stops a larger ball (names as scripts see them: room_limit_name).
enum class RoomLimit {
  None,             // "none": every ball up to the mesh's size fits (radius is that size)
  FaceEnd,          // "face_end": a contact runs off the end of its face, where the surface turns away (a convex edge)
  OppositeWall,     // "opposite_wall": a contact reaches a wall standing up across its face (a concave edge)
  Curvature,        // "curvature": the chain bends tighter than the ball, on the ball's side
  NeighbourChain,   // "neighbouring_chain": a contact reaches another picked chain
  Boundary,         // "boundary": a contact reaches the mesh boundary
  Reach,            // "reach": a contact lies beyond reach x r (a larger reach factor lets it go on)
  NoBall,           // "no_ball": no ball touches both faces (they part, or the edge is flat there)
  EndSetback,       // "end_setback": the round cannot run on to its end face or corner plane (the ball there
                    // does not fit, or the chain is too short for the setbacks: ends.h plan_ends)
};
const char* room_limit_name(RoomLimit why);

struct MaxRadiusOptions {
  double feature_angle_deg = 30.0;  // as RoundOptions
  double reach = 3.0;               // as RoundOptions: the base meshes are those round_edges collects
  double precision = 1e-4;          // relative width of the final bracket [fits, does not fit]
  int min_stations = 256;           // stations along the chain at least (evenly), besides its vertices and edge middles
  double search_radius = 0;         // for the seeds (find_chains); <= 0: 5% of the mesh's bounding-box diagonal
};

struct ChainRoom {
  double radius = 0;             // the largest radius whose ball fits at every station (to `precision`)
  double radius_refused = 0;     // the smallest radius found not to fit (radius * (1 + precision) or less)
  RoomLimit why = RoomLimit::None;
  Vec3 where = Vec3::Zero();     // the limiting feature: the wall's point the contact touches, the point that folds
  Vec3 chain_point = Vec3::Zero();  // the station where the room is smallest
  double curvature_radius = 0;   // Curvature: the chain's radius of curvature there
  int side = -1;                 // the side (0 = A, 1 = B) whose contact is stopped; -1: none / no ball
  int stations = 0, balls_solved = 0, collections = 0;  // the work done
  std::vector<Vec3> chain;       // the chain's polyline
  bool closed = false;
};

// One entry per distinct chain the seeds select, in seed order. Throws RoundingError for bad input as
// round_edges does (invalid_input, no_sharp_edge, non_manifold_input).
std::vector<ChainRoom> max_radius(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const MaxRadiusOptions& options);

}  // namespace meshround
