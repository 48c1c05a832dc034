// Changing the radius of an existing round (issue 15): the strip of facets that turns between two flat
// sides is recognised from a seed, its radius measured, and the sharp edge it replaced rebuilt by
// extending the two sides to their intersection line ("sharpen"); change_radius then rounds that edge
// again with round_edges' passes at the new radius (radius 0: the sharp edge only).
//
//   recognise_strip (strip.h) -> measure the radius (per vertex, on the ball tangent to both sides)
//     -> fold the strip onto the two sides (each vertex keeps its place along the corner line and its
//        share of the arc; facets across the corner line are split on it) -> re-mesh the end faces near
//        the corner -> check_result (guard.h) -> write_mesh  [-> round_edges at the new radius]
//
// Scope: the sides flat where they meet the strip (a plane each: the corner line is straight), or one side
// flat and the other curved along the round, meeting it at one angle (a wall curved in plan, vertical or
// drafted: the sharp edge rebuilt section by section, its corner line a polyline), or straight rounds
// mitred into each other where their walls meet at sharp edges (a pocket's rim whose wall corners stayed
// sharp: one sharp edge rebuilt per round, meeting at the rim's corners); the radius may vary
// along the strip (the measured law is reported). Other strips are refused with not_a_round, naming the
// place and the reason.
#pragma once
#include <string>
#include <vector>

#include "meshround/round.h"

namespace meshround {

struct SharpenOptions {
  double strip_turn_deg = 60.0;   // an edge turning by this much or more bounds a strip (a sharp edge); a
                                  // coarse round of 2 elements across a 90 degree corner turns by 45 per edge
  double flat_deg = 0.5;          // facets whose normals differ by less are coplanar (the flat sides)
  double axis_tilt_deg = 20.0;    // the round's facet normals, area-weighted, lie within this (rms) of perpendicular
                                  // to one axis (else a doubly curved or free-form region)
  double facet_tilt_deg = 45.0;   // one facet of a round may tilt this far from perpendicular to the corner line
                                  // (a coarse facet's chord across a cylinder tilts by ~25 degrees)
  double fit_tolerance = 0.01;    // share of r the measured radii may stray from their law (else not_a_round)
  double measure_clearance = 0.03;  // share of r a vertex must lie off both sides to be measured: nearer, an
                                    // offset of the side moves the tangent ball five times as much or more
                                    // (0.02 let a 1.4 mm mesh of a 4 mm round along an S measure 1.3 % low)
  double law_step = 0.5;          // the measured law's stations: about law_step * r apart along the strip
  double snap = 1e-3;             // a vertex this close (share of the arc) to the corner line is put on it
  long max_new_facets = 2000000;  // the work budget (as RoundOptions::max_new_facets)
};

// One strip found and sharpened.
struct StripReport {
  double found_radius = 0;             // mean measured radius (mm)
  double radius_min = 0, radius_max = 0;
  bool constant = true;                // the radii agree within fit_tolerance: a constant round
  std::vector<double> law_s, law_r;    // the measured law: arc length along the corner line, radius
  std::vector<Vec3> law_points;        // the corner line's point at each law_s
  double fit_residual = 0;             // largest |measured radius - law| over the strip's vertices (mm)
  double opening_deg = 0;              // angle the round turns through (between the sides' normals)
  bool convex = true;                  // the round cuts material off (false: it fills a concave corner)
  Vec3 corner[2];                      // the rebuilt sharp edge's end points
  std::vector<Vec3> corner_line;       // the rebuilt sharp edge (its two ends; a curved one: a point per station;
                                       // a mitred one: its ends and corners)
  int mitres = 0;                      // corners where the strip's rounds ran into each other (mitred, their walls
                                       // meeting at a sharp edge): the rebuilt edge is one sharp edge per round
  int strip_facets = 0, measured_vertices = 0, border_vertices[2] = {0, 0};
  int end_faces = 0, facets_split = 0, end_facets_remeshed = 0;
  int points_merged = 0;               // points on the rebuilt edge merged into a too-close neighbour
  int border_flips = 0;                // edges at the old contact lines flipped to take out a kink (a sliver's)
  std::string recognised;              // how the strip was told from its sides (for the report)
};

struct SharpenResult {
  Points vertices;
  Triangles triangles;
  std::vector<StripReport> strips;
};

// Sharpens the strip each seed picks (seeds on one strip count once), one after the other.
SharpenResult sharpen_rounds(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const SharpenOptions& options);

struct ChangeRadiusResult {
  RoundResult round;                 // as round_edges' (no chains when the radius is 0: the sharp edges)
  std::vector<StripReport> strips;   // per strip: what was found
  double seconds_sharpen = 0;
};

// Sharpen, then round the rebuilt edges with `round` (radius or law; radius 0 and no law: sharpen only).
ChangeRadiusResult change_radius(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const RoundOptions& round,
                                 const SharpenOptions& options = {});

}  // namespace meshround
