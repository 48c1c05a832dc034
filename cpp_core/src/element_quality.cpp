#include "meshround/element_quality.h"

#include <algorithm>
#include <cmath>

namespace meshround {
namespace {

double angle_deg(const Vec3& a, const Vec3& b) {
  const double na = a.norm(), nb = b.norm();
  if (na == 0 || nb == 0) return 0;
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

}  // namespace

ElementQuality element_quality(const Points& V, const std::vector<std::array<int, 4>>& elements) {
  ElementQuality q;
  if (elements.empty()) return q;
  q.min_angle_deg = 180, q.min_side = INFINITY;
  for (const auto& e : elements) {
    const int n = e[3] < 0 ? 3 : 4;
    Vec3 p[4];
    for (int i = 0; i < n; ++i) p[i] = V.row(e[i]).transpose();
    double shortest = INFINITY, longest = 0;
    for (int i = 0; i < n; ++i) {
      const Vec3 &prev = p[(i + n - 1) % n], &here = p[i], &next = p[(i + 1) % n];
      const double side = (next - here).norm();
      shortest = std::min(shortest, side), longest = std::max(longest, side);
      const double a = angle_deg(prev - here, next - here);
      q.min_angle_deg = std::min(q.min_angle_deg, a), q.max_angle_deg = std::max(q.max_angle_deg, a);
    }
    q.min_side = std::min(q.min_side, shortest);
    q.max_aspect_ratio = std::max(q.max_aspect_ratio, shortest > 0 ? longest / shortest : INFINITY);
    ++q.elements;
    if (n == 4) {
      ++q.quads;
      const double on02 = angle_deg((p[1] - p[0]).cross(p[2] - p[0]), (p[2] - p[0]).cross(p[3] - p[0]));
      const double on13 = angle_deg((p[2] - p[1]).cross(p[3] - p[1]), (p[3] - p[1]).cross(p[0] - p[1]));
      q.max_warpage_deg = std::max({q.max_warpage_deg, on02, on13});
    }
  }
  return q;
}

ElementQuality added_facets_quality(const Points& V, const MeshDelta& delta) {
  // Only the points the added facets use are placed: input ids keep V's point unless moved.
  auto point = [&](int id) -> Vec3 {
    if (id >= delta.input_vertices) return delta.new_points[id - delta.input_vertices];
    const auto it = std::lower_bound(delta.moved.begin(), delta.moved.end(), id);
    return it != delta.moved.end() && *it == id ? delta.moved_to[it - delta.moved.begin()] : Vec3(V.row(id).transpose());
  };
  Points P(3 * delta.added.size(), 3);
  std::vector<std::array<int, 4>> elements;
  elements.reserve(delta.added.size());
  for (const auto& f : delta.added) {
    const int at = int(3 * elements.size());
    for (int i = 0; i < 3; ++i) P.row(at + i) = point(f[i]).transpose();
    elements.push_back({at, at + 1, at + 2, -1});
  }
  return element_quality(P, elements);
}

}  // namespace meshround
