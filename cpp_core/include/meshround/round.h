// round_edges(): the passes of the paper in order, for every chain the seeds select.
//
//   trace_chain -> collect_base_meshes -> solve_station (adaptive) -> loft_profiles
//     -> end faces (ends.h: the end profiles onto the end faces' planes, the base mesh split at the band's
//        corner where it goes on past one) -> trim_base_meshes -> mesh_rounding_surface -> sew_round
//     -> improve_new_facets -> check_result (guard.h) -> the result as an edit of the input (mesh_delta.h)
//
// Chains are rounded one after the other, each on the result of the previous one. Where two of them end
// at one vertex, their rounds are mitred (network.h find_corners): both stop at the plane bisecting
// the chains there, the second taking the first's vertices for its end; where three of one convexity
// end there, the ball touching their faces is the corner (sphere_corner.h); where three of mixed
// convexity do, the odd one is made first and the other two are traced again on its result, rolling on
// around its end as one round (network.h RolledCorner, stages.h). Other corners are refused
// (corner_not_blendable, naming the vertex). A radius law is split among the chains, each control point
// going to the chain nearest to it.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "meshround/chain.h"
#include "meshround/element_quality.h"
#include "meshround/mesh_delta.h"
#include "meshround/options.h"

namespace meshround {

struct ChainReport {
  bool closed = false;
  double length = 0;
  int stations = 0;               // profiles lofted
  int facets_removed = 0, facets_cut = 0, facets_added = 0;
  int vertices_snapped = 0;
  int contacts_on_edges = 0, contacts_on_vertices = 0;  // profiles whose contact is not inside a facet
  double surface_deviation = 0;   // largest distance found between the lofted surface and the exact rolling ball
  double mesh_deviation = 0;      // largest distance found between new facets and the surface
  int profile_rows = 0;
  int gap_facets = 0, open_gaps = 0;
  int edges_flipped = 0, vertices_removed = 0, vertices_slid = 0;  // by the last pass, on flat ground (improve.h)
  int thin_facets = 0;         // new facets with an angle under 10 degrees
  // Of those, the ones at an end cap's cusp: where the round runs into a face that its side goes on past (a
  // pocket rim edge into the next wall), its end profile leaves the side tangentially, and the cap between them
  // comes to a point. A facet there has its angle at half the profile's step (cusp_angle_deg), the most the
  // chordal tolerance allows (acos(1 - t / r): 8.1 deg at t = r / 100); OCCT's mesh of its own fillet, at that
  // deflection, has 1.4 deg there.
  int cusp_facets = 0;
  double cusp_angle_deg = 0;
  // When there are thin facets and the input facets they replace have none: the smallest reach factor
  // (of 1.25, 1.5, 2, 3 times the one asked for) at which this chain rounds with none, and its smallest
  // new angle there; 0 when none of those does, or when the round made over 10,000 new facets (not probed). Large CAD facets cut by a small round leave too little
  // room within the reach for well-shaped facets out to their far corners.
  double reach_for_room = 0, min_angle_at_reach_for_room = 0;
};

struct RoundedChain {
  std::vector<Vec3> chain;                 // the sharp-edge polyline
  std::vector<Vec3> spine;                 // ball centres
  std::vector<Vec3> contacts[2];           // contact points, side A and B
  std::string brep;                        // the rounding face, OCCT BRep text
  ChainReport report;
};

// One corner of a network of rounds (where picked chains end at one vertex), measured on the finished mesh
// against the exact rounds and corner ball (corner_report.h).
struct CornerReport {
  Vec3 vertex;                // where the chains meet
  std::string kind;           // "mitre": two rounds meeting on the plane halving the chains' angle, a crease as in
                              // OCCT's fillet; "sphere": three or more rounds and the ball touching all their faces;
                              // "rolled": convex and concave mixed -- the odd round first, the other two as one
                              // round rolling on around its end (a torus where the faces are square)
  std::vector<int> chains;    // the rounds meeting there (RoundResult::chains); rolled: the odd one, the rolled one
  double radius = 0;
  int seam_vertices = 0;      // the mesh vertices on the seams (the mitre curve; the patch's three arcs; where the
                              // rolled round leans on the odd one)
  double deviation = 0;       // mm: the seams' (and a sphere patch's facets') largest distance from the exact surfaces
  double normal_jump_deg = 0; // largest angle between the exact normals of the surfaces meeting at a seam vertex:
                              // 0 where they join tangentially (G1: a sphere patch), a mitre's crease otherwise
  double seam_turn_deg = 0;   // largest turn between the two facets across a seam edge (the mesh's own view of it)
  std::string brep;           // "sphere": the patch of the ball as an OCCT face (BRep text), bounded by the rounds'
                              // end arcs, as exact as their faces (RoundedChain::brep); empty for the others
};

struct RoundReport {
  int facets_removed = 0, facets_added = 0;
  double max_deviation = 0;          // max over chains of the measured facet-to-surface distance
  double min_new_angle_deg = 180;    // smallest angle of any new facet (or kept one with a snapped vertex)
  double min_input_angle_deg = 180;  // smallest angle of the input facets that were cut or snapped
  bool input_forces_small_angles = false;
  int thin_facets = 0;                 // new facets under 10 degrees, over all chains
  int thin_facets_short_of_room = 0;   // of those, the ones on chains with a reach_for_room
  int cusp_facets = 0;                 // of those, the ones at an end cap's cusp (ChainReport), and their
  double cusp_angle_deg = 0;           // smallest angle there
  double reach_for_room = 0;           // the largest over chains (ChainReport)
  std::vector<CornerReport> corners;      // one per corner of the network, if any
  ElementQuality band;                    // the new facets' quality as CAE checks it (element_quality.h)
  std::map<std::string, double> seconds;  // per pass, summed over chains
  double seconds_total = 0;
};

struct RoundResult {
  Points vertices;      // the rounded mesh (empty unless RoundOptions::write_arrays), in apply_delta's order
  Triangles triangles;
  MeshDelta delta;      // the same as an edit of the input (mesh_delta.h)
  std::vector<RoundedChain> chains;
  RoundReport report;
};

RoundResult round_edges(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const RoundOptions& options);

// What round_edges will make of the chains the seeds select, before it makes anything (the task panel shows
// it as the user picks): the chains as it takes them, and where they meet, each corner's blend.
struct PlannedCorner {
  Vec3 vertex;
  std::string kind;         // as CornerReport::kind: "mitre", "sphere" or "rolled"
  std::vector<int> chains;  // the chains meeting there (indices into NetworkPlan::chains)
};
struct NetworkPlan {
  std::vector<SharpChain> chains;       // one per distinct chain, in the order round_edges rounds them
  std::vector<PlannedCorner> corners;   // the corners found before the first refused one
  bool refused = false;                 // a corner round_edges would refuse (corner_not_blendable) ...
  std::string refusal;                  // ... and its message, naming the vertex
};
// Errors as round_edges for the options and seeds; corner refusals go into the plan. A rolled corner's
// second-stage chains are traced on the first stage's result, so the plan lists the chains as picked.
NetworkPlan plan_network(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const RoundOptions& options);

// The chains the seeds select (for highlighting a pick); one per distinct chain. A seed farther than
// search_radius from every sharp edge is an error; <= 0 means 5% of the mesh's bounding-box diagonal.
std::vector<SharpChain> find_chains(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds,
                                    double feature_angle_deg, double search_radius = 0);
// The same on a mesh's topology built already (the options are not checked here).
std::vector<SharpChain> find_chains(const MeshTopology& mesh, const std::vector<Vec3>& seeds, double feature_angle_deg,
                                    double search_radius = 0);

}  // namespace meshround
