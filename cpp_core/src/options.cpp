#include "meshround/options.h"

#include <algorithm>

namespace meshround {

double RoundOptions::max_radius() const {
  double r = radius_law.empty() ? radius : 0.0;
  for (const RadiusControl& c : radius_law) r = std::max(r, c.radius);
  return r;
}

}  // namespace meshround
