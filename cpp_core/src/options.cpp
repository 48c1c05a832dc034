#include "meshround/options.h"

#include <algorithm>
#include <cmath>

#include "meshround/cancel.h"
#include "meshround/types.h"

namespace meshround {

const char* const kCancelledMessage = "the rounding was cancelled";

namespace detail {
thread_local const std::function<bool()>* cancel_poll = nullptr;
thread_local unsigned cancel_ticks = 0;
void throw_cancelled() { throw RoundingError(ErrorCode::Cancelled, kCancelledMessage); }
}  // namespace detail

double RoundOptions::max_radius() const {
  double r = radius_law.empty() ? radius : 0.0;
  for (const RadiusControl& c : radius_law) r = std::max(r, c.radius);
  return r;
}

void validate_options(const RoundOptions& o) {
  auto invalid = [](const std::string& what) { throw RoundingError(ErrorCode::InvalidInput, what); };
  if (o.radius_law.empty()) {
    if (!(o.radius > 0) || !std::isfinite(o.radius))
      invalid("the radius must be a positive number (got " + format_number(o.radius) + ")");
  }
  for (const RadiusControl& c : o.radius_law) {
    if (!c.point.allFinite()) invalid("a radius control point has a NaN or infinite coordinate");
    if (!(c.radius > 0) || !std::isfinite(c.radius))
      invalid("the radius control point at " + format_point(c.point) + " has radius " + format_number(c.radius) +
              "; radii must be positive");
  }
  if (!(o.tolerance >= 0) || !std::isfinite(o.tolerance))
    invalid("the tolerance must be a number >= 0 (got " + format_number(o.tolerance) + "; 0 means r / 100)");
  if (!(o.feature_angle_deg > 0 && o.feature_angle_deg < 180))
    invalid("the feature angle must lie between 0 and 180 degrees (got " + format_number(o.feature_angle_deg) + ")");
  if (!(o.reach >= kMinReach) || !std::isfinite(o.reach))
    invalid("the reach factor must be at least " + format_number(kMinReach) + " (got " + format_number(o.reach) + ")");
  if (!(o.max_element_angle_deg >= 0 && o.max_element_angle_deg <= 90))
    invalid("the largest element angle must lie between 0 (off) and 90 degrees (got " + format_number(o.max_element_angle_deg) + ")");
  if (!(o.element_length >= 0) || !std::isfinite(o.element_length))
    invalid("the element length must be a number >= 0 (got " + format_number(o.element_length) + "; 0 means the input's own)");
  if (!(o.max_aspect_ratio == 0 || (o.max_aspect_ratio >= 1 && std::isfinite(o.max_aspect_ratio))))
    invalid("the largest aspect ratio must be at least 1, or 0 for the built-in bound (got " + format_number(o.max_aspect_ratio) + ")");
  if (!(o.max_new_facets > 0)) invalid("the work budget (max_new_facets) must be positive");
}

}  // namespace meshround
