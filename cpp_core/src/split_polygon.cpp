#include "split_polygon.h"

#include <algorithm>
#include <cmath>

#include "planar.h"

namespace meshround {
namespace {

using namespace planar;

// The base angle (degrees) of the best-shaped isosceles triangle on side a -> b whose apex lies inside the
// ring and where the caller admits points; 0 if none from 60 down to 12 degrees does.
double free_apex_angle(const std::vector<Eigen::Vector2d>& ring, int a, int b, const Refinement& refine,
                       const ToSpace& to_3d) {
  const Eigen::Vector2d s0 = ring[a], s1 = ring[b];
  for (auto [height, degrees] : kApexHeights) {
    const Eigen::Vector2d x = 0.5 * (s0 + s1) + height * Eigen::Vector2d(-(s1 - s0).y(), (s1 - s0).x());
    if (inside_polygon(x, ring, ring.size()) && (!refine.admit || refine.admit(to_3d(x)))) return degrees;
  }
  return 0;
}

// The ring's vertex that makes the best triangle on side i -> i+1 (a triangle inside the ring, with no other
// vertex in it), or -1.
int best_vertex_apex(const std::vector<Vec3>& P, const std::vector<Eigen::Vector2d>& Q, const std::vector<int>& ring, int i,
                     double* quality) {
  const int m = int(ring.size()), a = ring[i], b = ring[(i + 1) % m];
  // Best shaped first (ties in ring order): the first inside the ring is the answer, and the costly
  // inside test runs on a few vertices, not on all.
  std::vector<std::pair<double, int>> apexes;
  for (int v : ring) {
    const double q = v != a && v != b ? smallest_angle(P[a], P[b], P[v]) : 0.0;
    if (q > 0) apexes.push_back({q, v});  // (no NaN in the sort)
  }
  std::stable_sort(apexes.begin(), apexes.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  *quality = 0;
  for (const auto& [q, v] : apexes)
    if (triangle_in_ring(Q, ring, a, b, v)) return *quality = q, v;
  return -1;
}

// Splits off the triangles of sides that no inner point can mend: sides (shared with untouched facets,
// so never split) whose every well-shaped apex lies outside the polygon or where points are not admitted,
// such as a long side beyond the reach. The longest such side first gets its best vertex as apex, and the
// ring is cut there. Left to refinement these sides are fanned from a far corner and the flips undo a
// good apex found later. Returns the rings left to triangulate; `fixed` gets the triangles split off.
std::vector<std::vector<int>> split_off_unmendable_sides(const std::vector<Vec3>& P, const std::vector<Eigen::Vector2d>& Q,
                                                         size_t boundary, const Refinement& refine,
                                                         const ToSpace& to_3d,
                                                         std::vector<std::array<int, 3>>& fixed) {
  std::vector<std::vector<int>> todo(1), done;
  for (size_t i = 0; i < boundary; ++i) todo[0].push_back(int(i));
  while (!todo.empty()) {
    std::vector<int> ring = std::move(todo.back());
    todo.pop_back();
    if (ring.size() == 3) {
      fixed.push_back({ring[0], ring[1], ring[2]});
      continue;
    }
    std::vector<Eigen::Vector2d> ring_q;
    for (int v : ring) ring_q.push_back(Q[v]);
    const int m = int(ring.size());
    int side = -1, apex = -1;
    // The longest side that qualifies (ties in ring order): sides tried longest first.
    std::vector<std::pair<double, int>> sides;
    for (int i = 0; i < m; ++i) {
      const double length = (ring_q[(i + 1) % m] - ring_q[i]).norm();
      if (length > 0) sides.push_back({length, i});  // (no NaN in the sort)
    }
    std::stable_sort(sides.begin(), sides.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    for (const auto& [length, i] : sides) {
      const double free = free_apex_angle(ring_q, i, (i + 1) % m, refine, to_3d);
      if (free >= refine.quality_deg) continue;
      double q;
      const int v = best_vertex_apex(P, Q, ring, i, &q);
      if (v >= 0 && q * 180 / M_PI > free) {
        side = i, apex = v;
        break;
      }
    }
    if (side < 0) {
      done.push_back(std::move(ring));
      continue;
    }
    fixed.push_back({ring[side], ring[(side + 1) % m], apex});
    const int j = int(std::find(ring.begin(), ring.end(), apex) - ring.begin());
    std::vector<int> after, before;  // side's end -> apex, and apex -> side's start, along the ring
    for (int k = (side + 1) % m;; k = (k + 1) % m) {
      after.push_back(ring[k]);
      if (k == j) break;
    }
    for (int k = j;; k = (k + 1) % m) {
      before.push_back(ring[k]);
      if (k == side) break;
    }
    for (auto* piece : {&after, &before})
      if (piece->size() >= 3) todo.push_back(std::move(*piece));
  }
  return done;
}

// Cuts off, with a fan, each corner of the ring where points are not admitted (beyond the reach) and
// whose angle is wide enough for two good triangles: points on 1-3 rays that split the angle evenly
// become the ring's new vertices there, at the distance where the fan's triangles and the ears it leaves
// beside it are best shaped. Refinement alone cannot reach such a corner: no point may go near it, so it
// would be fanned to points across the polygon.
void cut_off_far_corners(std::vector<Vec3>& P, std::vector<Eigen::Vector2d>& Q, std::vector<int>& ring,
                         const Refinement& refine, const ToSpace& to_3d,
                         std::vector<std::array<int, 3>>& fixed) {
  const double quality = refine.quality_deg * M_PI / 180;
  for (size_t i = 0; i < ring.size() && ring.size() >= 4; ++i) {
    const int m = int(ring.size()), a = ring[(i + m - 1) % m], c = ring[i], b = ring[(i + 1) % m];
    if (!refine.admit || refine.admit(P[c]) || cross2(Q[a], Q[c], Q[b]) <= 0) continue;
    const Eigen::Vector2d ub = (Q[b] - Q[c]).normalized(), ua = (Q[a] - Q[c]).normalized();
    const double angle = std::acos(std::clamp(ua.dot(ub), -1.0, 1.0));
    if (angle < 2 * quality) continue;
    std::vector<Eigen::Vector2d> ring_q;
    for (int v : ring) ring_q.push_back(Q[v]);
    const int b_next = ring[(i + 2) % m], a_prev = ring[(i + m - 2) % m];
    const double sides = std::min((Q[a] - Q[c]).norm(), (Q[b] - Q[c]).norm());
    auto fan_of = [&](int first, int rays) {  // b, X_1 .. X_rays, a: the fan's rim, around c
      std::vector<int> fan{b};
      for (int j = 0; j < rays; ++j) fan.push_back(first + j);
      fan.push_back(a);
      return fan;
    };
    // The fan (rays, distance) whose triangles, and the ears it leaves at a and b, are best shaped.
    double best_score = 0;
    std::vector<Eigen::Vector2d> best_points;
    for (int rays = 1; rays <= 3 && angle / (rays + 1) >= 0.5 * quality; ++rays) {
      std::vector<Eigen::Vector2d> dirs;
      for (int j = 1; j <= rays; ++j) {
        const double t = double(j) / (rays + 1);
        dirs.push_back((std::sin((1 - t) * angle) * ub + std::sin(t * angle) * ua) / std::sin(angle));
      }
      for (double d = sides; d > 0.05 * sides; d *= 0.95) {
        const int first = int(Q.size());
        for (const auto& u : dirs) Q.push_back(Q[c] + d * u), P.push_back(to_3d(Q.back()));
        const std::vector<int> fan = fan_of(first, rays);
        bool good = true;
        for (int j = 0; j < rays && good; ++j) good = inside_polygon(Q[first + j], ring_q, ring.size()) && refine.admit(P[first + j]);
        for (size_t j = 0; j + 1 < fan.size() && good; ++j) good = triangle_in_ring(Q, ring, c, fan[j], fan[j + 1]);
        if (good) {
          double score = INFINITY;
          for (size_t j = 0; j + 1 < fan.size(); ++j) score = std::min(score, smallest_angle(P[c], P[fan[j]], P[fan[j + 1]]));
          if (cross2(Q[first], Q[b], Q[b_next]) > 0) score = std::min(score, smallest_angle(P[first], P[b], P[b_next]));
          if (cross2(Q[a_prev], Q[a], Q[first + rays - 1]) > 0) score = std::min(score, smallest_angle(P[a_prev], P[a], P[first + rays - 1]));
          if (score > best_score) best_score = score, best_points.assign(Q.begin() + first, Q.end());
        }
        Q.resize(first), P.resize(first);
      }
    }
    if (best_points.empty()) continue;
    const int first = int(Q.size()), rays = int(best_points.size());
    for (const auto& x : best_points) Q.push_back(x), P.push_back(to_3d(x));
    const std::vector<int> fan = fan_of(first, rays);
    for (size_t j = 0; j + 1 < fan.size(); ++j) fixed.push_back({c, fan[j], fan[j + 1]});
    std::vector<int> cut(ring.begin(), ring.begin() + i);  // ..., a, X_rays .. X_1, b, ...
    for (int j = rays - 1; j >= 0; --j) cut.push_back(first + j);
    cut.insert(cut.end(), ring.begin() + i + 1, ring.end());
    ring = std::move(cut);
  }
}

}  // namespace

std::vector<std::vector<int>> split_for_refinement(std::vector<Vec3>& P, std::vector<Eigen::Vector2d>& Q, size_t boundary,
                                                   const Refinement& refine, const ToSpace& to_3d,
                                                   std::vector<std::array<int, 3>>& fixed) {
  std::vector<std::vector<int>> rings = split_off_unmendable_sides(P, Q, boundary, refine, to_3d, fixed);
  for (auto& ring : rings) cut_off_far_corners(P, Q, ring, refine, to_3d, fixed);
  return rings;
}

}  // namespace meshround
