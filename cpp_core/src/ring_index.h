// The refinement's search index over a polygon being refined (private to cpp_core): its sides and its points
// (the ring's, then the inner points as they go in) sorted into slabs across the ring's longer extent, so that
// "is this point inside", "which sides lie near it" and "is a point near it" look at a slab or a few, not at
// the whole ring. A trim polygon of a facet thousands of times the band has thousands of sides and gets
// thousands of points: a pass over all of them per candidate point made its refinement quadratic.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

namespace meshround::planar {

class RingIndex {
 public:
  // Q[0, boundary) is the ring; points after it are inner points, added with add_point.
  RingIndex(const std::vector<Eigen::Vector2d>& Q, size_t boundary) : Q_(Q), boundary_(boundary) {
    Eigen::Vector2d lo = Q[0], hi = Q[0];
    for (size_t i = 0; i < boundary; ++i) lo = lo.cwiseMin(Q[i]), hi = hi.cwiseMax(Q[i]);
    axis_ = (hi - lo).x() >= (hi - lo).y() ? 0 : 1;
    lo_ = lo[axis_];
    const double extent = hi[axis_] - lo[axis_];
    const int count = int(std::clamp(double(boundary) / 2, 1.0, double(kMaxSlabs)));
    width_ = extent > 0 ? extent / count : 1.0;
    sides_.resize(size_t(count)), points_.resize(size_t(count));
    for (size_t i = 0; i < boundary; ++i) {
      const int a = slab_of(Q[i][axis_]), b = slab_of(Q[(i + 1) % boundary][axis_]);
      if (std::abs(b - a) >= kWideSlabs) {
        wide_.push_back(int(i));
        continue;
      }
      for (int s = std::min(a, b); s <= std::max(a, b); ++s) sides_[size_t(s)].push_back(int(i));
    }
    for (size_t i = 0; i < Q.size(); ++i) add_point(int(i));
  }

  // Even-odd test, as planar::inside_polygon, with the ray across the slabs (along the other axis): only
  // the sides of p's slab can cross it.
  bool inside(const Eigen::Vector2d& p) const {
    const int u = axis_, w = 1 - axis_;
    bool in = false;
    auto cross = [&](int i) {
      const Eigen::Vector2d &a = Q_[size_t(i)], &b = Q_[(size_t(i) + 1) % boundary_];
      if ((a[u] > p[u]) != (b[u] > p[u]) && p[w] < (b[w] - a[w]) * (p[u] - a[u]) / (b[u] - a[u]) + a[w]) in = !in;
    };
    if (p[u] < lo_ || !(p[u] <= lo_ + width_ * double(sides_.size()))) return false;  // (beyond every side; NaN too)
    for (int i : sides_[size_t(slab_of(p[u]))]) cross(i);
    for (int i : wide_) cross(i);
    return in;
  }

  // The sides with a point within `distance` of p along the slab axis (a superset of those within
  // `distance` of p), in increasing order, into `out`.
  void sides_near(const Eigen::Vector2d& p, double distance, std::vector<int>& out) const {
    out.clear();
    const int a = slab_of(p[axis_] - distance), b = slab_of(p[axis_] + distance);
    if (b - a >= kWideSlabs) {
      for (int i = 0; i < int(boundary_); ++i) out.push_back(i);
      return;
    }
    for (int s = a; s <= b; ++s) out.insert(out.end(), sides_[size_t(s)].begin(), sides_[size_t(s)].end());
    out.insert(out.end(), wide_.begin(), wide_.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

  // Some point (ring or inner) within `distance` of p.
  bool point_within(const Eigen::Vector2d& p, double distance) const {
    const int a = slab_of(p[axis_] - distance), b = slab_of(p[axis_] + distance);
    auto near = [&](int v) { return (Q_[size_t(v)] - p).norm() <= distance; };
    if (b - a >= kWideSlabs) return std::any_of(Q_.begin(), Q_.end(), [&](const Eigen::Vector2d& q) { return (q - p).norm() <= distance; });
    for (int s = a; s <= b; ++s)
      if (std::any_of(points_[size_t(s)].begin(), points_[size_t(s)].end(), near)) return true;
    return false;
  }

  void add_point(int v) { points_[size_t(slab_of(Q_[size_t(v)][axis_]))].push_back(v); }
  // Takes back the last point added (v, the last of Q).
  void remove_point(int v) { points_[size_t(slab_of(Q_[size_t(v)][axis_]))].pop_back(); }

 private:
  static constexpr int kMaxSlabs = 1 << 14;
  static constexpr int kWideSlabs = 64;  // a side over more slabs is kept apart; a query over more looks at all
  int slab_of(double x) const {
    const double s = std::floor((x - lo_) / width_);
    return int(std::clamp(std::isnan(s) ? 0.0 : s, 0.0, double(sides_.size() - 1)));
  }
  const std::vector<Eigen::Vector2d>& Q_;
  size_t boundary_;
  int axis_ = 0;
  double lo_ = 0, width_ = 1;
  std::vector<std::vector<int>> sides_, points_;
  std::vector<int> wide_;
};

}  // namespace meshround::planar
