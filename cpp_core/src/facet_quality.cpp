#include "facet_quality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <unordered_map>

namespace meshround {

double smallest_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) { return smallest_angle(a, b, c) * 180 / M_PI; }

int count_thin_facets(const MeshTopology& mesh, const MeshEdit& edit, double* min_new, double* min_input) {
  int thin = 0;
  auto made = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const double angle = smallest_angle_deg(a, b, c);
    *min_new = std::min(*min_new, angle);
    return angle < kThinDeg;
  };
  for (const auto& f : edit.added) thin += made(edit.point(f[0]), edit.point(f[1]), edit.point(f[2]));
  for (int f : edit.removed) *min_input = std::min(*min_input, smallest_angle_deg(mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2)));
  for (const auto& snapped : edit.moved)
    for (const int* f = mesh.facets_begin(snapped.first); f != mesh.facets_end(snapped.first); ++f) {
      if (edit.removed.count(*f)) continue;
      const int a = mesh.F(*f, 0), b = mesh.F(*f, 1), c = mesh.F(*f, 2);
      thin += made(edit.point(a), edit.point(b), edit.point(c));
      *min_input = std::min(*min_input, smallest_angle_deg(mesh.corner(*f, 0), mesh.corner(*f, 1), mesh.corner(*f, 2)));
    }
  return thin;
}

void recount_new_facets(const Points& V, const Triangles& F, const MeshDelta& delta, int* thin_out, double* smallest_out) {
  std::unordered_map<int, Vec3> moved;
  for (size_t i = 0; i < delta.moved.size(); ++i) moved.emplace(delta.moved[i], delta.moved_to[i]);
  auto input_point = [&](int v) -> Vec3 { return V.row(v).transpose(); };
  auto point = [&](int v) -> Vec3 {
    if (v >= delta.input_vertices) return delta.new_points[size_t(v - delta.input_vertices)];
    const auto it = moved.find(v);
    return it != moved.end() ? it->second : input_point(v);
  };
  using Corners = std::array<std::array<double, 3>, 3>;
  auto corners = [](const std::array<Vec3, 3>& p) {  // from the smallest corner on, in the facet's order
    Corners c;
    for (int k = 0; k < 3; ++k) c[size_t(k)] = {p[size_t(k)].x(), p[size_t(k)].y(), p[size_t(k)].z()};
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    return c;
  };
  std::set<Corners> removed;
  for (int f : delta.removed) removed.insert(corners({input_point(F(f, 0)), input_point(F(f, 1)), input_point(F(f, 2))}));
  int thin = 0;
  double smallest = 180;
  auto count = [&](const std::array<Vec3, 3>& p) {
    const double a = smallest_angle_deg(p[0], p[1], p[2]);
    thin += a < kThinDeg, smallest = std::min(smallest, a);
  };
  for (const auto& f : delta.added) {
    const std::array<Vec3, 3> p{point(f[0]), point(f[1]), point(f[2])};
    if (!removed.count(corners(p))) count(p);
  }
  if (!moved.empty()) {  // kept input facets with a moved corner
    std::vector<char> is_removed(size_t(F.rows()), 0);
    for (int f : delta.removed) is_removed[size_t(f)] = 1;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      if (!is_removed[size_t(f)] && (moved.count(F(f, 0)) || moved.count(F(f, 1)) || moved.count(F(f, 2))))
        count({point(F(f, 0)), point(F(f, 1)), point(F(f, 2))});
  }
  *thin_out = thin, *smallest_out = smallest;
}

int count_cusp_facets(const MeshEdit& edit, const std::vector<CuspPoint>& cusps, double* angle_deg) {
  int count = 0;
  for (const auto& f : edit.added) {
    const Vec3 a = edit.point(f[0]), b = edit.point(f[1]), c = edit.point(f[2]);
    const double angle = smallest_angle_deg(a, b, c);
    if (angle >= kThinDeg) continue;
    for (const CuspPoint& cusp_point : cusps) {
      if (!(cusp_point.step > 0) || !(cusp_point.radius > 0)) continue;
      const double cusp = cusp_angle(cusp_point.step, cusp_point.radius) * 180 / M_PI;
      const double near = kCuspReach * cusp_point.step;
      if (std::min({(a - cusp_point.at).norm(), (b - cusp_point.at).norm(), (c - cusp_point.at).norm()}) > near || angle < kCuspAngleShare * cusp)
        continue;
      ++count, *angle_deg = std::min(*angle_deg, cusp);
      break;
    }
  }
  return count;
}

}  // namespace meshround
