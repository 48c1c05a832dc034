// The corner line of a curved strip (strip_line.h).
#include "strip_line.h"

#include <Eigen/Dense>

namespace meshround::strip_detail {

// close_loop's bounds (strip_line.h).
constexpr double kLoopGap = 3;
constexpr double kLoopTurnDeg = 25;  // a loop's largest turn between two stations in a row (1.4 mm elements
                                     // around a pocket's wall corner of R 6 turn it by up to 19 deg; a
                                     // mitred corner by 90)
void close_loop(const std::vector<StripFrame>& station, const Vec3& where, bool walked) {
  const size_t n = station.size();
  if (n < 6) not_a_round("it runs all around a loop of " + std::to_string(n) + " stations only (too few to follow it)", where);
  std::vector<double> gap(n);
  for (size_t i = 0; i < n; ++i) gap[i] = (station[(i + 1) % n].corner - station[i].corner).norm();
  std::vector<double> sorted = gap;
  std::nth_element(sorted.begin(), sorted.begin() + long(n / 2), sorted.end());
  for (size_t i = 0; i < n; ++i) {
    const StripFrame &a = station[i], &b = station[(i + 1) % n];
    if (!walked && gap[i] > kLoopGap * sorted[n / 2])
      not_a_round("its corner line, all around a loop, is not followed evenly at " + format_point(a.corner), where);
    const double turn = std::acos(std::min(1.0, std::abs(a.axis.dot(b.axis)))) / kDeg;
    if (turn > kLoopTurnDeg)
      not_a_round("its corner line turns by " + format_number(turn) + " deg at " + format_point(b.corner) +
                  " (a corner of its curved side, or a corner blend where rounds meet, as around a pocket's rim: not done yet)", where);
  }
}

Vec3 frame_solve(const Vec3& n0, const Vec3& n1, const Vec3& axis, const Vec3& rhs) {
  Eigen::Matrix3d M;
  M.row(0) = n0.transpose(), M.row(1) = n1.transpose(), M.row(2) = axis.transpose();
  return M.fullPivLu().solve(rhs);
}

// smooth_tilts' window and its outliers (strip_line.h).
constexpr int kSmoothStations = 5;
constexpr double kSmoothOutlier = 3;
constexpr double kSmoothFloorDeg = 0.05;
void smooth_tilts(std::vector<StripFrame>& station, const std::vector<Vec3>& border, bool closed) {
  const int n = int(station.size()), k = kSmoothStations;
  if (n < 2 * k + 1) return;
  const CornerCurve line(station, closed);  // (its arc lengths: read before any station is changed)
  auto tilt_of = [&](const StripFrame& F) { return std::asin(std::clamp(F.normal[1].dot(F.normal[0]), -1.0, 1.0)); };
  std::vector<double> tilt(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    int lo = i - k, hi = i + k;  // an open line's window shifts inward at its ends
    if (!closed) lo = std::clamp(lo, 0, n - 1 - 2 * k), hi = lo + 2 * k;
    std::vector<std::pair<double, double>> pts;  // (arc length from station i, tilt)
    for (int j = lo; j <= hi; ++j) pts.push_back({line.S(j) - line.S(i), tilt_of(station[size_t(((j % n) + n) % n)])});
    // The inliers: within kSmoothOutlier robust deviations (1.4826 median absolute deviations, at least
    // kSmoothFloorDeg) of the window's median tilt; a run of a few bad stations stays out.
    std::vector<double> v;
    for (const auto& [t, x] : pts) v.push_back(x);
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    const double median = v[v.size() / 2];
    for (double& x : v) x = std::abs(x - median);
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    const double within = std::max(kSmoothOutlier * 1.4826 * v[v.size() / 2], kSmoothFloorDeg * kDeg);
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Eigen::Vector2d B = Eigen::Vector2d::Zero();
    int used = 0;
    for (const auto& [t, x] : pts)
      if (std::abs(x - median) <= within) {
        const Eigen::Vector2d row(1.0, t);
        A += row * row.transpose(), B += row * x, ++used;
      }
    tilt[size_t(i)] = median;
    if (used >= 3 && std::abs(A.determinant()) > 1e-12 * A.squaredNorm()) tilt[size_t(i)] = A.fullPivLu().solve(B)(0);
  }
  for (int i = 0; i < n; ++i) {
    StripFrame& F = station[size_t(i)];
    const Vec3 level = F.normal[1] - F.normal[0] * F.normal[0].dot(F.normal[1]);  // side B's normal in plane A
    if (level.norm() < 1e-9) continue;
    const Vec3 nB = std::cos(tilt[size_t(i)]) * level.normalized() + std::sin(tilt[size_t(i)]) * F.normal[0];
    // (about b's foot on the plane: the plane runs through b, or through the wall beside b when b sits a hair
    // up the round, wall_normal_in_section)
    const Vec3 b = border[size_t(i)] - F.normal[1] * (F.normal[1].dot(border[size_t(i)]) - F.offset[1]);
    const Vec3 c = frame_solve(F.normal[0], nB, F.axis, Vec3(F.offset[0], nB.dot(b), F.axis.dot(b)));
    if ((c - F.corner).norm() > 0.2 * (F.corner - b).norm()) continue;  // not a scatter: keep it as measured
    F.normal[1] = nB, F.offset[1] = nB.dot(b), F.corner = c;
  }
}

void order_along(std::vector<StripFrame>& station, std::vector<int>& vertex) {
  Vec3 middle = Vec3::Zero();
  for (const StripFrame& F : station) middle += F.corner / double(station.size());
  size_t first = 0;
  for (size_t i = 1; i < station.size(); ++i)
    if ((station[i].corner - middle).squaredNorm() > (station[first].corner - middle).squaredNorm()) first = i;
  std::swap(station[0], station[first]), std::swap(vertex[0], vertex[first]);
  for (size_t i = 1; i < station.size(); ++i) {
    size_t best = i;
    for (size_t j = i + 1; j < station.size(); ++j)
      if ((station[j].corner - station[i - 1].corner).squaredNorm() < (station[best].corner - station[i - 1].corner).squaredNorm()) best = j;
    std::swap(station[i], station[best]), std::swap(vertex[i], vertex[best]);
  }
}

bool order_around(const MeshTopology& mesh, const std::vector<std::pair<int, int>>& border_edges, std::vector<StripFrame>& station,
                  std::vector<int>& vertex) {
  std::unordered_map<int, std::vector<int>> next;
  for (const auto& [f, k] : border_edges) {
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
    next[a].push_back(b), next[b].push_back(a);
  }
  for (const auto& [v, around] : next)
    if (around.size() != 2) return false;
  std::unordered_map<int, size_t> place;  // border vertex -> its place along the loop
  for (int prev = -1, v = vertex.front(); place.emplace(v, place.size()).second;) {
    const auto it = next.find(v);
    if (it == next.end()) return false;
    const int go = it->second[0] != prev ? it->second[0] : it->second[1];
    prev = v, v = go;
  }
  if (place.size() != next.size()) return false;
  std::vector<size_t> order(station.size());
  for (size_t i = 0; i < order.size(); ++i) {
    if (!place.count(vertex[i])) return false;
    order[i] = i;
  }
  std::sort(order.begin(), order.end(), [&](size_t i, size_t j) { return place.at(vertex[i]) < place.at(vertex[j]); });
  std::vector<StripFrame> s2;
  std::vector<int> v2;
  for (size_t i : order) s2.push_back(station[i]), v2.push_back(vertex[i]);
  station.swap(s2), vertex.swap(v2);
  return true;
}

}  // namespace meshround::strip_detail
