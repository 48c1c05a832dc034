// RoundOptions: everything a rounding call can be told, with the defaults the paper uses.
#pragma once
#include <functional>
#include <vector>

#include "meshround/types.h"

namespace meshround {

// A radius control point: the radius wanted where the chain passes nearest to `point`.
struct RadiusControl {
  Vec3 point;
  double radius;
};

// The smallest reach factor: the base meshes must at least hold the ball's contacts.
constexpr double kMinReach = 1.0;

struct RoundOptions {
  double radius = 1.0;                 // ball radius (mm); used when `radius_law` is empty
  std::vector<RadiusControl> radius_law;  // variable radius: control points (optional); with several
                                          // chains, each point belongs to the chain nearest to it
  double tolerance = 0.0;              // chordal tolerance of the new facets; <= 0 means r_max / 100
  double feature_angle_deg = 30.0;     // an edge is sharp when its two facets turn by at least this
  double reach = 3.0;                  // base meshes are the facets within reach * r_max of the chain
  // Band element controls, as CAE pre-processors give them; each 0 = off, and the finer rule wins
  // (tessellate.h BandControls applies them):
  double max_element_angle_deg = 0;    // the round's elements span at most this angle of its profile (e.g.
                                       // 10: 9 elements across a 90 degree round); 0: the chordal tolerance alone
  double element_length = 0;           // element length along the round (mm); 0: the input's own next to the chain
  double max_aspect_ratio = 0;         // the round's elements' longest side / shortest side, at most (>= 1); 0: the
                                       // built-in bound (steps along 0.4 to kMaxStepRatio = 2.5 times the step across)
  // Work budget: a call that would make more new facets than this (profile stations count as facets)
  // is refused with work_limit before it runs away. 2,000,000 new facets is a few times the band of a
  // 1M-facet mesh's longest edges rounded at a tenth of their element size, and ~1 GB of work.
  long max_new_facets = 2000000;
  // Cancel poll (optional; default none): called often while the run goes (cancel.h), from the
  // running thread; once it returns true the run stops with RoundingError(ErrorCode::Cancelled), within
  // about 0.1 s of the request, the input untouched (it always is: the engine works on copies). True at
  // the first poll: the run is refused at once. It must be cheap and thread-safe, e.g. the load of a
  // std::atomic<bool> that another thread sets.
  std::function<bool()> cancelled;
  // The result's whole mesh as arrays (RoundResult::vertices / triangles; default true). False: only its
  // edit of the input (RoundResult::delta), for a caller that applies that to its own copy of the input.
  bool write_arrays = true;

  double max_radius() const;  // the radius, or the largest of the law's
  double effective_tolerance() const { return tolerance > 0 ? tolerance : max_radius() / 100.0; }
};

// The one place the options' ranges are checked: throws RoundingError (invalid_input) naming the first
// option out of range. round_edges and RadiusLaw call it; the workbench and the CLI check through it.
void validate_options(const RoundOptions& options);

}  // namespace meshround
