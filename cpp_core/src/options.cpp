#include "meshround/options.h"

#include <algorithm>

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

}  // namespace meshround
