// Paper §4.4: the radius along a chain, constant or given by control points.
//
// Control points are projected onto the chain (by arc length). Two points give OCCT's start->end law (the
// one FreeCAD's Part Fillet makes from a start and an end radius: a monotone cubic, steeper in the middle
// than at the ends); three or more a C1 monotone cubic (Fritsch-Carlson: no overshoot between
// neighbouring values); the radius is constant before the first and after the last point, periodic on a
// closed loop.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "meshround/chain.h"
#include "meshround/options.h"

namespace meshround {

class RadiusLaw {
 public:
  // Throws RoundingError for a radius <= 0, or a control point farther than `max_distance` from the chain.
  RadiusLaw(const RoundOptions& options, const SharpChain& chain, double max_distance);
  double at(double s) const;
  double min_radius() const;
  double max_radius() const;
  // "the radius control point at (x, y, z) (r = ...)" nearest to arc length s; "" for a constant radius.
  std::string nearest_control(double s) const;

 private:
  std::vector<std::pair<double, RadiusControl>> controls_;  // as given, with their arc lengths
  std::vector<double> s_, r_, slope_;
  double period_ = 0;  // > 0 on a closed loop
};

}  // namespace meshround
