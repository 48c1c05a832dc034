#include "facet_quality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

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

void recount_new_facets(const Points& V, const Triangles& F, const Points& out_V, const Triangles& out_F, const Vec3& lo,
                        const Vec3& hi, int* thin_out, double* smallest_out) {
  auto near = [&](const Points& P, const Triangles& T, Eigen::Index f) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = P.row(T(f, k)).transpose();
      if (!(p.array() < lo.array()).any() && !(p.array() > hi.array()).any()) return true;
    }
    return false;
  };
  auto corners = [](const Points& P, const Triangles& T, Eigen::Index f) {
    std::array<std::array<double, 3>, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = {P(T(f, k), 0), P(T(f, k), 1), P(T(f, k), 2)};
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    return c;
  };
  std::set<std::array<std::array<double, 3>, 3>> input;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if (near(V, F, f)) input.insert(corners(V, F, f));
  int thin = 0;
  double smallest = 180;
  for (Eigen::Index f = 0; f < out_F.rows(); ++f) {
    if (!near(out_V, out_F, f) || input.count(corners(out_V, out_F, f))) continue;
    const double a = smallest_angle_deg(out_V.row(out_F(f, 0)).transpose(), out_V.row(out_F(f, 1)).transpose(), out_V.row(out_F(f, 2)).transpose());
    thin += a < kThinDeg, smallest = std::min(smallest, a);
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
