#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "meshround/mesh_edit.h"

namespace meshround {
namespace {

double min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto ang = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, v = r - p;
    const double d = u.norm() * v.norm();
    return d > 0 ? std::acos(std::clamp(u.dot(v) / d, -1.0, 1.0)) : 0.0;
  };
  return std::min({ang(a, b, c), ang(b, c, a), ang(c, a, b)});
}

bool inside_triangle_2d(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        const Eigen::Vector2d& c) {
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
    return (x - o).x() * (y - o).y() - (x - o).y() * (y - o).x();
  };
  // Points on the ear's sides count as inside: a vertex on the diagonal c-a would be cut off.
  const double eps = -1e-12 * ((b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm());
  const double d1 = cross(a, b, p), d2 = cross(b, c, p), d3 = cross(c, a, p);
  return d1 >= eps && d2 >= eps && d3 >= eps;
}

}  // namespace

void triangulate_polygon(const MeshEdit& edit, const std::vector<int>& polygon, const Vec3& normal,
                         std::vector<std::array<int, 3>>& out) {
  std::vector<int> ring = polygon;
  // Drop repeated consecutive ids (a trim point that coincides with a corner).
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) return;
  const Vec3 n = normal.normalized();
  const Vec3 e1 = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized(), e2 = n.cross(e1);
  std::vector<Vec3> P;
  std::vector<Eigen::Vector2d> Q;
  for (int v : ring) {
    P.push_back(edit.point(v));
    Q.emplace_back(P.back().dot(e1), P.back().dot(e2));
  }
  // Work counter-clockwise in the plane; remember to flip back.
  double area = 0;
  for (size_t i = 0; i < Q.size(); ++i) {
    const auto &a = Q[i], &b = Q[(i + 1) % Q.size()];
    area += a.x() * b.y() - a.y() * b.x();
  }
  const bool flipped = area < 0;
  std::vector<int> idx(ring.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = int(i);
  if (flipped) std::reverse(idx.begin(), idx.end());
  auto emit = [&](int a, int b, int c) {
    if (flipped) out.push_back({ring[c], ring[b], ring[a]});
    else out.push_back({ring[a], ring[b], ring[c]});
  };
  while (idx.size() > 3) {
    int best = -1;
    double best_q = -1;
    const int m = int(idx.size());
    for (int i = 0; i < m; ++i) {
      const int a = idx[(i + m - 1) % m], b = idx[i], c = idx[(i + 1) % m];
      const auto &qa = Q[a], &qb = Q[b], &qc = Q[c];
      const double turn = (qb - qa).x() * (qc - qb).y() - (qb - qa).y() * (qc - qb).x();
      if (turn <= 1e-9 * (qb - qa).norm() * (qc - qb).norm()) continue;  // reflex or flat corner: not an ear
      bool empty = true;
      for (int j = 0; j < m && empty; ++j) {
        const int w = idx[j];
        if (w == a || w == b || w == c) continue;
        empty = !inside_triangle_2d(Q[w], qa, qb, qc);
      }
      if (!empty) continue;
      const double q = min_angle(P[a], P[b], P[c]);
      if (q > best_q) best_q = q, best = i;
    }
    if (best < 0) {
      // Numerically degenerate polygon: cut the flattest corner so the loop still closes.
      if (getenv("MESHROUND_DEBUG")) {
        fprintf(stderr, "ear clipping stuck on %d points:\n", m);
        for (int j = 0; j < m; ++j) fprintf(stderr, "  %d (%g %g %g)\n", ring[idx[j]], P[idx[j]].x(), P[idx[j]].y(), P[idx[j]].z());
      }
      best = 0;
    }
    emit(idx[(best + m - 1) % m], idx[best], idx[(best + 1) % m]);
    idx.erase(idx.begin() + best);
  }
  emit(idx[0], idx[1], idx[2]);
}

}  // namespace meshround
