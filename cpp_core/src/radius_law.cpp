#include "meshround/radius_law.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace meshround {

constexpr double kStartEndSlope = 3.0 / 7.0;  // see the two-point law below

RadiusLaw::RadiusLaw(const RoundOptions& options, const SharpChain& chain, double max_distance) {
  validate_options(options);
  if (options.radius_law.empty()) {
    s_ = {0.0}, r_ = {options.radius}, slope_ = {0.0};
    return;
  }
  std::vector<std::pair<double, double>> pts;
  for (const RadiusControl& c : options.radius_law) {
    double d;
    const double s = chain.project(c.point, &d);
    if (!(d <= max_distance))
      throw RoundingError(ErrorCode::InvalidInput, "the radius control point at " + format_point(c.point) + " is " + format_number(d) +
                          " mm from the chain, farther than the reach (" + format_number(max_distance) + " mm)");
    pts.push_back({s, c.radius});
    controls_.push_back({s, c});
  }
  std::sort(pts.begin(), pts.end());
  for (const auto& [s, r] : pts) {
    if (!s_.empty() && s - s_.back() < 1e-9 * std::max(1.0, chain.length)) {
      if (std::abs(r - r_.back()) > 1e-12) throw RoundingError(ErrorCode::InvalidInput, "two radius control points project to the same place on the chain");
      continue;
    }
    s_.push_back(s), r_.push_back(r);
  }
  if (chain.closed && s_.size() > 1) {
    period_ = chain.length;
    // Wrap one point on each side so the law is periodic.
    s_.insert(s_.begin(), s_.back() - period_);
    r_.insert(r_.begin(), r_.back());
    s_.push_back(s_[1] + period_);
    r_.push_back(r_[1]);
  }
  const int n = int(s_.size());
  slope_.assign(n, 0.0);
  if (n == 2 && !chain.closed) {
    // OCCT's start -> end law (BRepFilletAPI_MakeFillet::Add(R1, R2, E)): a cubic whose slope at both
    // ends is 3/7 of the mean slope, r = R1 + (R2 - R1) (3/7 t + 4/7 (3 t^2 - 2 t^3)); measured on OCCT
    // 7.6's fillets of straight edges, to 1e-5 mm whatever the edge's length and radii.
    slope_[0] = slope_[1] = kStartEndSlope * (r_[1] - r_[0]) / (s_[1] - s_[0]);
  } else if (n >= 3) {  // Fritsch-Carlson monotone slopes
    std::vector<double> d(n - 1);
    for (int i = 0; i + 1 < n; ++i) d[i] = (r_[i + 1] - r_[i]) / (s_[i + 1] - s_[i]);
    for (int i = 1; i + 1 < n; ++i) slope_[i] = d[i - 1] * d[i] <= 0 ? 0.0 : 3 * (s_[i + 1] - s_[i - 1]) /
        ((2 * s_[i + 1] - s_[i] - s_[i - 1]) / d[i - 1] + (s_[i + 1] + s_[i] - 2 * s_[i - 1]) / d[i]);
    if (!chain.closed) slope_[0] = slope_[n - 1] = 0.0;
  }
}

double RadiusLaw::at(double s) const {
  const int n = int(s_.size());
  if (n == 1) return r_[0];
  if (period_ > 0) s = s_[1] + std::fmod(std::fmod(s - s_[1], period_) + period_, period_);
  if (s <= s_.front()) return r_.front();
  if (s >= s_.back()) return r_.back();
  const int i = int(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin()) - 1;
  const double h = s_[i + 1] - s_[i], t = (s - s_[i]) / h;
  // Cubic Hermite with the slopes above.
  const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t), h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
  return h00 * r_[i] + h10 * h * slope_[i] + h01 * r_[i + 1] + h11 * h * slope_[i + 1];
}

std::string RadiusLaw::nearest_control(double s) const {
  if (controls_.empty()) return "";
  const auto& c = *std::min_element(controls_.begin(), controls_.end(), [&](const auto& x, const auto& y) {
    return std::abs(x.first - s) < std::abs(y.first - s);
  });
  return "the radius control point at " + format_point(c.second.point) + " (r = " + format_number(c.second.radius) + ")";
}

double RadiusLaw::min_radius() const { return *std::min_element(r_.begin(), r_.end()); }
double RadiusLaw::max_radius() const { return *std::max_element(r_.begin(), r_.end()); }

}  // namespace meshround
