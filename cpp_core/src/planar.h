// Planar helpers shared by the polygon triangulation passes (private to cpp_core). Points are 2-D
// coordinates of a flat polygon in its own plane; rings are counter-clockwise.
#pragma once
#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace meshround::planar {

// Apexes of isosceles triangles tried on a side, best shaped first: height over the side's length, and
// the base angle in degrees.
inline constexpr std::array<std::pair<double, double>, 4> kApexHeights{{{0.866, 60}, {0.289, 30}, {0.182, 20}, {0.106, 12}}};

// Twice the signed area of (o, x, y): > 0 when they turn left.
inline double cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
  return (x - o).x() * (y - o).y() - (x - o).y() * (y - o).x();
}

// p inside the ear (a, b, c) or within a hair of it: a vertex (nearly) on the diagonal c-a would be cut off
// or leave a zero-area triangle behind.
inline bool blocks_ear(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double hair = 1e-7 * std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return cross2(a, b, p) >= -hair * (b - a).norm() && cross2(b, c, p) >= -hair * (c - b).norm() &&
         cross2(c, a, p) >= -hair * (a - c).norm();
}

// Even-odd test against the polygon Q[0, boundary).
inline bool inside_polygon(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& Q, size_t boundary) {
  bool in = false;
  for (size_t i = 0, j = boundary - 1; i < boundary; j = i++)
    if ((Q[i].y() > p.y()) != (Q[j].y() > p.y()) &&
        p.x() < (Q[j].x() - Q[i].x()) * (p.y() - Q[i].y()) / (Q[j].y() - Q[i].y()) + Q[i].x())
      in = !in;
  return in;
}

// True if segments p-q and r-s cross at a point inside both.
inline bool segments_cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r, const Eigen::Vector2d& s) {
  return cross2(p, q, r) * cross2(p, q, s) < 0 && cross2(r, s, p) * cross2(r, s, q) < 0;
}

// True if triangle (a, b, c) (ids into Q, counter-clockwise) lies inside the ring (ids into Q): no ring
// vertex in it and no ring edge crossing its sides.
inline bool triangle_in_ring(const std::vector<Eigen::Vector2d>& Q, const std::vector<int>& ring, int a, int b, int c) {
  if (cross2(Q[a], Q[b], Q[c]) <= 0) return false;
  const int m = int(ring.size());
  for (int k = 0; k < m; ++k) {
    const int w = ring[k], w1 = ring[(k + 1) % m];
    if (w != a && w != b && w != c && blocks_ear(Q[w], Q[a], Q[b], Q[c])) return false;
    for (auto [p, q] : {std::pair{a, b}, {b, c}, {c, a}})
      if (segments_cross(Q[w], Q[w1], Q[p], Q[q])) return false;
  }
  return true;
}

}  // namespace meshround::planar
