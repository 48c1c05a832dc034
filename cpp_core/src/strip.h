// Private to the sharpen pass (sharpen.h): the strip of facets a seed picks on an existing round, its two
// flat sides, its ends, and the radius measured at each of its vertices.
//
// How a strip is told from its sides (recognise_strip):
//  1. the seed's facet must be curved: some neighbour across a smooth edge (turning by less than
//     strip_turn_deg) differs from it by flat_deg or more (a facet whose smooth neighbours are all
//     coplanar with it lies on a flat face);
//  2. the curved facets are flooded from it across smooth edges; the flat facets next to that flood are
//     the sides' candidates, split in two by which way their normal turns from the seed's about the axis
//     (the direction the flood's normals are all perpendicular to: smallest eigenvector of their spread);
//     each side's candidates must share one normal (one plane);
//  3. the strip is the flood of facets from the seed whose normal is neither side's and is perpendicular
//     to the corner line (the two sides' normals' cross product) within axis_tilt_deg; its boundary edges
//     are border A (a side-A facet across), border B, or an end (a facet of an end face, or the mesh
//     boundary). Anything else across a smooth edge is not a round.
//  4. the radius at a vertex is that of the ball tangent to both side planes whose circle, in the section
//     normal to the corner line, passes through the vertex (a quadratic; the root with the vertex between
//     the two contacts).
#pragma once
#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "meshround/mesh.h"
#include "meshround/sharpen.h"

namespace meshround {

enum class StripRole { Inner = 0, BorderA = 1, BorderB = 2, End = 3 };

struct StripEnd {
  bool face = false;          // an end face (else the strip ends at the mesh boundary)
  std::vector<int> facets;    // the end face's facets across the strip's end edges
  Vec3 normal = Vec3::Zero(); // the end face's plane: normal . x = offset
  double offset = 0;
};

// The two sides' planes and their corner line -- of the whole strip when both sides are flat, else of one
// station (a strip vertex's section: the flat side's plane and the curved side's tangent plane there).
struct StripFrame {
  Vec3 normal[2];                           // side planes (A, B): normal . x = offset
  double offset[2] = {0, 0};
  double side[2] = {0, 0};                  // +-1: the side of each plane the round (and its ball) lies on
  Vec3 axis, corner;                        // the corner line: corner + s axis
  Vec3 centre_dir;                          // the ball's centre in a section: its corner point + r centre_dir
  int piece = -1;                           // a mitred strip's: its round (RoundStrip::pieces)

  double s_of(const Vec3& p) const { return axis.dot(p - corner); }
  // p's component normal to the corner line, relative to it (a point of p's section).
  Vec3 across(const Vec3& p) const { const Vec3 d = p - corner; return d - axis * axis.dot(d); }
};

// The strip's own frame (StripFrame base) is the seed's station; `curved`: side B curves along the round
// (a wall curved in plan) and each vertex has its station's frame, the corner line is the polyline `line`.
struct RoundStrip : StripFrame {
  std::vector<int> facets;
  std::unordered_set<int> facet_set;
  std::unordered_map<int, StripRole> role;  // every vertex of the strip
  std::unordered_map<int, int> end_of;      // End vertices: which end (0: low s, 1: high s)
  double s_lo = 0, s_hi = 0;                // the strip's extent along the corner line
  StripEnd ends[2];
  std::unordered_map<int, double> radius;   // measured radius at each Inner / End vertex
  int border_count[2] = {0, 0};
  std::string recognised;

  bool curved = false;
  std::unordered_map<int, StripFrame> frames;  // curved: each strip vertex's station
  std::vector<Vec3> line;                      // curved: the corner line's points at the stations, in order ...
  std::vector<double> line_s;                  // ... and their arc length
  std::vector<StripFrame> stations;            // ... and frame
  StripFrame end_frame[2];                     // curved: the frame at each end
  bool closed = false;                         // curved: all around a loop (no end); the line closes on itself
  double loop_length = 0;                      // closed: the line's length, the closing segment included

  // Mitred (strip_mitre.cpp): rounds on one plane A and each on its own plane B, run into each other at
  // creases on the planes bisecting two walls. Each is a straight piece of the corner line; the stations
  // are the pieces' starts (a mitre's corner), `line` the polygon through them.
  bool mitred = false;
  struct Piece {
    StripFrame frame;  // its corner at the piece's start
    double s0 = 0, length = 0;
    std::vector<StripEnd> mitres;  // the planes bisecting its wall and the next one's, at its mitred ends
    double lo = -INFINITY, hi = INFINITY;  // where its rebuilt edge may run, along its axis from its start (to a mitre's corner)
  };
  // A point's foot on its round's corner line: the rebuilt edge's point in its section (a mitred strip's kept
  // between its mitres' corners: a crease point's foot is the corner).
  Vec3 foot(const StripFrame& f, const Vec3& p) const {
    double s = f.s_of(p);
    if (mitred && f.piece >= 0) s = std::clamp(s, pieces[size_t(f.piece)].lo, pieces[size_t(f.piece)].hi);
    return f.corner + f.axis * s;
  }
  std::vector<Piece> pieces;
  struct Crease {
    StripEnd plane;               // the plane bisecting the two walls, which its vertices slide onto
    int pieces[2] = {-1, -1};     // the two rounds it joins
  };
  std::unordered_map<int, Crease> mitre_of;  // a vertex on a crease

  const StripFrame& frame(int v) const { return curved ? frames.at(v) : *this; }
  // Position along the corner line (its arc length for a curved strip: that of the nearest station; in
  // [0, loop_length) for a closed one).
  double param(const Vec3& p) const;
  // The corner line's point at position s (a curved strip's: on its polyline, extended at the ends; a
  // closed one's wrapped).
  Vec3 point_at(double s) const;
};

// Throws RoundingError(not_a_round) naming the place and the reason when the seed is not on a round
// between two flat sides; non_manifold_input for a non-manifold or inconsistently oriented strip.
RoundStrip recognise_strip(const MeshTopology& mesh, const Vec3& seed, const SharpenOptions& options);

// The measured law (StripReport's radius fields), checked: not_a_round when the radii stray from it.
void measure_law(const MeshTopology& mesh, const RoundStrip& strip, const SharpenOptions& options, StripReport& report);

}  // namespace meshround
