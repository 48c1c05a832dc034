#include "sphere_corner.h"

#include "delta.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <functional>
#include <vector>

#include "guard.h"
#include "meshround/cancel.h"
#include "meshround/mesh_edit.h"
#include "meshround/sew.h"

namespace meshround {

bool corner_ball(const Vec3& point, const std::vector<Vec3>& normals, double radius, bool convex, Vec3* centre,
                 std::vector<Vec3>* feet, double* miss) {
  const Eigen::Index n = Eigen::Index(normals.size());
  Eigen::MatrixX3d N(n, 3);
  Eigen::VectorXd rhs(n);
  for (Eigen::Index i = 0; i < n; ++i) N.row(i) = normals[size_t(i)].transpose(), rhs[i] = normals[size_t(i)].dot(point) + (convex ? -radius : radius);
  // The smallest singular value of the unit normals: near 0 when they lie about one plane or line.
  Eigen::JacobiSVD<Eigen::MatrixX3d> svd(N, Eigen::ComputeThinU | Eigen::ComputeThinV);
  if (n < 3 || svd.singularValues()[2] < 1e-3) return false;
  *centre = svd.solve(rhs);
  *miss = (N * *centre - rhs).cwiseAbs().maxCoeff();
  feet->clear();
  for (const Vec3& m : normals) feet->push_back(*centre + (convex ? radius : -radius) * m);
  return true;
}

namespace {

[[noreturn]] void not_blendable(const SphereCorner& c, const std::string& why) {
  throw RoundingError(ErrorCode::CornerNotBlendable, "the " + std::to_string(c.toward.size()) + " rounds at " + format_point(c.vertex) +
                      " cannot be blended: " + why);
}

// The facets between the rounds' end planes and the vertex, reached from the vertex.
std::unordered_set<int> corner_facets(const MeshTopology& mesh, const SphereCorner& c, int vertex) {
  const double slack = 1e-4 * c.radius;
  auto inside = [&](int v) {
    for (const Vec3& t : c.toward)
      if ((mesh.point(v) - c.centre).dot(t) < -slack) return false;
    return true;
  };
  std::unordered_set<int> region;
  std::vector<int> todo{vertex};
  std::unordered_set<int> seen{vertex};
  while (!todo.empty()) {
    const int v = todo.back();
    todo.pop_back();
    for (const int* f = mesh.facets_begin(v); f != mesh.facets_end(v); ++f) {
      if (region.count(*f) || !inside(mesh.F(*f, 0)) || !inside(mesh.F(*f, 1)) || !inside(mesh.F(*f, 2))) continue;
      region.insert(*f);
      for (int k = 0; k < 3; ++k)
        if (seen.insert(mesh.F(*f, k)).second) todo.push_back(mesh.F(*f, k));
    }
  }
  return region;
}

// The hole the region leaves, in the region's own orientation (the patch runs its edges the same way).
std::vector<int> hole_loop(const MeshTopology& mesh, const std::unordered_set<int>& region, const SphereCorner& c) {
  std::unordered_map<int, int> next;
  for (int f : region)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      bool inner = false;
      const std::vector<int> sides = mesh.edge_facets(a, b);
      for (int g : sides) inner |= g != f && region.count(g);
      if (inner) continue;
      if (sides.size() == 1)  // the rounds' own checks leave no new boundary: a hole of the input's
        throw RoundingError(ErrorCode::NonManifoldInput, "the mesh is open (a hole in it) next to the corner at " + format_point(c.vertex) +
                            ", at " + format_point(0.5 * (mesh.point(a) + mesh.point(b))) + "; fill the hole first");
      if (!next.emplace(a, b).second) not_blendable(c, "the corner's boundary touches itself at " + format_point(mesh.point(a)));
    }
  if (next.empty()) not_blendable(c, "no corner between the rounds' ends");
  std::vector<int> loop{next.begin()->first};
  while (true) {
    const int b = next.at(loop.back());
    if (b == loop.front()) break;
    if (loop.size() > next.size()) not_blendable(c, "the corner's boundary does not close");
    loop.push_back(b);
  }
  if (loop.size() != next.size()) not_blendable(c, "the corner between the rounds is not one hole");
  return loop;
}

constexpr int kMaxBisections = 40;

// Longest-edge bisection of the inner edges longer than `longest` (the hole's own sides stay: they are
// the rounds'), each new point put on the ball. Each pass marks every triangle's longest inner edge that
// is too long, and then, until nothing changes, the longest inner edge of every triangle with a marked
// edge (so a triangle is always cut from its longest inner edge first); every marked edge gets one
// middle, and each triangle is cut by its marked edges. The patch stays conforming and every pass halves
// the longest inner edges.
void refine_on_ball(MeshEdit& edit, std::vector<std::array<int, 3>>& tris, const std::unordered_set<std::uint64_t>& sides,
                    const SphereCorner& c, double longest) {
  auto length = [&](int a, int b) { return (edit.point(a) - edit.point(b)).norm(); };
  auto longest_inner = [&](const std::array<int, 3>& t) {  // its index j (edge t[j] -> t[j+1]), or -1
    int k = -1;
    for (int j = 0; j < 3; ++j) {
      const int a = t[size_t(j)], b = t[size_t(j + 1) % 3];
      if (!std::isfinite(length(a, b)))
        not_blendable(c, "the rounds' ends do not close a patch on the corner ball (a point of it is not a number)");
      if (!sides.count(edge_key(a, b)) && (k < 0 || length(a, b) > length(t[size_t(k)], t[size_t(k + 1) % 3]))) k = j;
    }
    return k;
  };
  for (int pass = 1;; ++pass) {
    poll_cancel();
    std::unordered_map<std::uint64_t, int> middle;  // marked edge -> its middle (-1 until made)
    for (const auto& t : tris) {
      const int k = longest_inner(t);
      if (k >= 0 && length(t[size_t(k)], t[size_t(k + 1) % 3]) > longest) middle[edge_key(t[size_t(k)], t[size_t(k + 1) % 3])] = -1;
    }
    if (middle.empty()) return;
    if (pass > kMaxBisections) not_blendable(c, "its patch does not refine to the tolerance");
    for (bool grew = true; grew;) {
      grew = false;
      for (const auto& t : tris) {
        bool marked = false;
        for (int j = 0; j < 3; ++j) marked |= middle.count(edge_key(t[size_t(j)], t[size_t(j + 1) % 3])) > 0;
        const int k = longest_inner(t);
        if (marked && k >= 0) grew |= middle.emplace(edge_key(t[size_t(k)], t[size_t(k + 1) % 3]), -1).second;
      }
    }
    auto middle_of = [&](int a, int b) {
      int& m = middle.at(edge_key(a, b));
      if (m < 0) {
        // (A side across the ball has no middle on it: the patch would not be a corner's.)
        const Vec3 mid = 0.5 * (edit.point(a) + edit.point(b)) - c.centre;
        if (mid.norm() <= 1e-3 * c.radius) not_blendable(c, "the rounds' ends lie on opposite sides of the corner ball");
        m = edit.add_point(c.centre + c.radius * mid.normalized());
      }
      return m;
    };
    std::vector<std::array<int, 3>> out;
    // Cuts triangle t (kept in its orientation) at its marked edges, the longest inner one first.
    std::function<void(const std::array<int, 3>&)> cut = [&](const std::array<int, 3>& t) {
      int k = -1;
      for (int j = 0; j < 3; ++j)
        if (middle.count(edge_key(t[size_t(j)], t[size_t(j + 1) % 3])) && (k < 0 || j == longest_inner(t))) k = j;
      if (k < 0) {
        out.push_back(t);
        return;
      }
      const int a = t[size_t(k)], b = t[size_t(k + 1) % 3], x = t[size_t(k + 2) % 3], m = middle_of(a, b);
      cut({a, m, x});
      cut({m, b, x});
    };
    for (const auto& t : tris) cut(t);
    tris.swap(out);
  }
}

// The patch as rows of points from the side `base` (the loop from feet[0] to feet[1]) to the apex feet[2],
// when the two other sides have one count of segments: row j runs on the great circle between the j-th
// points of those sides, with a count of segments going down from the base's to one; neighbouring rows
// are zipped into triangles. False (nothing made) when the two sides' counts differ.
bool rows_to_apex(MeshEdit& edit, const std::vector<int>& loop, const int at[3], const SphereCorner& c,
                  std::vector<std::array<int, 3>>& tris) {
  const int n = int(loop.size());
  auto side = [&](int from, int to) {  // loop ids from corner `from` to corner `to`, both included
    std::vector<int> out;
    for (int i = at[from];; i = (i + 1) % n) {
      out.push_back(loop[i]);
      if (i == at[to]) break;
    }
    return out;
  };
  const std::vector<int> base = side(0, 1), right = side(1, 2);
  std::vector<int> left = side(2, 0);
  std::reverse(left.begin(), left.end());  // feet[0] -> apex, like `right`
  const int K = int(right.size()) - 1;
  if (int(left.size()) - 1 != K || K < 1) return false;
  const int m0 = int(base.size()) - 1;
  std::vector<std::vector<int>> rows{base};
  for (int j = 1; j <= K; ++j) {
    const int m = j == K ? 0 : std::max(1, int(std::lround(m0 * double(K - j) / K)));
    const Vec3 a = (edit.point(left[j]) - c.centre).normalized(), b = (edit.point(right[j]) - c.centre).normalized();
    const double angle = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
    std::vector<int> row{left[j]};
    for (int i = 1; i < m; ++i) {  // slerp
      const double t = double(i) / m;
      const Vec3 d = angle > 1e-12 ? Vec3((std::sin((1 - t) * angle) * a + std::sin(t * angle) * b) / std::sin(angle)) : a;
      row.push_back(edit.add_point(c.centre + c.radius * d.normalized()));
    }
    if (m > 0) row.push_back(right[j]);
    rows.push_back(row);
  }
  for (int j = 0; j < K; ++j) {  // zip row j (lower) with row j + 1
    const std::vector<int>&lo = rows[j], &hi = rows[j + 1];
    const int nl = int(lo.size()) - 1, nh = int(hi.size()) - 1;
    int i = 0, k = 0;
    while (i < nl || k < nh) {
      const bool step_low = k == nh || (i < nl && double(i + 1) / nl <= double(k + 1) / std::max(nh, 1));
      if (step_low) tris.push_back({lo[i], lo[i + 1], hi[k]}), ++i;
      else tris.push_back({lo[i], hi[k + 1], hi[k]}), ++k;
    }
  }
  return true;
}

// The patch of four or more sides as a fan from the ball's point amid the loop. (A plane triangulation
// of the loop can join opposite feet by edges whose middles all fall on one point of the ball, so its
// bisection makes facets without area.) The patch lies within a hemisphere and bulges towards its
// middle, so every triangle of the fan is a proper one; the bisection refines them.
void fan_from_middle(MeshEdit& edit, const std::vector<int>& loop, const SphereCorner& c, std::vector<std::array<int, 3>>& tris) {
  Vec3 towards = Vec3::Zero();
  for (int v : loop) towards += (edit.point(v) - c.centre).normalized();
  const int middle = edit.add_point(c.centre + c.radius * towards.normalized());
  for (size_t i = 0; i < loop.size(); ++i) tris.push_back({loop[i], loop[(i + 1) % loop.size()], middle});
}

}  // namespace

void blend_sphere_corner(const Points& V, const Triangles& F, const SphereCorner& corner, double tolerance,
                         const SharpChain& chain, double reach, MeshDelta& delta) {
  const MeshTopology mesh(V, F);
  int vertex = -1;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if ((mesh.point(v) - corner.vertex).norm() <= 1e-9 * std::max(1.0, corner.vertex.cwiseAbs().maxCoeff())) vertex = v;
  if (vertex < 0) not_blendable(corner, "a round took its vertex");
  const std::unordered_set<int> region = corner_facets(mesh, corner, vertex);
  const std::vector<int> loop = hole_loop(mesh, region, corner);
  for (int v : loop)
    if (std::abs((mesh.point(v) - corner.centre).norm() - corner.radius) > tolerance + 1e-3 * corner.radius) {
      not_blendable(corner, "the rounds' ends do not all lie on the corner ball (at " + format_point(mesh.point(v)) + ")");
    }

  MeshEdit edit(mesh);
  edit.removed = region;
  Vec3 normal = Vec3::Zero();  // the loop's own (Newell): the triangulation keeps the loop's orientation
  std::unordered_set<std::uint64_t> sides;
  for (size_t i = 0; i < loop.size(); ++i) {
    const int a = loop[i], b = loop[(i + 1) % loop.size()];
    normal += (mesh.point(a) - corner.centre).cross(mesh.point(b) - corner.centre);
    sides.insert(edge_key(a, b));
  }
  // The patch's corners on the loop: the feet of the ball, in the loop's order.
  const int n = int(loop.size());
  std::vector<int> at;
  for (const Vec3& foot : corner.feet) {
    int best = 0;
    for (int i = 1; i < n; ++i)
      if ((mesh.point(loop[i]) - foot).norm() < (mesh.point(loop[best]) - foot).norm()) best = i;
    if ((mesh.point(loop[best]) - foot).norm() > 1e-3 * corner.radius + tolerance) not_blendable(corner, "no round ends at the ball's foot " + format_point(foot));
    at.push_back(best);
  }
  std::sort(at.begin(), at.end());
  if (std::adjacent_find(at.begin(), at.end()) != at.end()) not_blendable(corner, "two of the ball's feet fall on one point of the corner's boundary");
  std::vector<std::array<int, 3>> tris;
  bool rows = false;
  for (int turn = 0; turn < 3 && at.size() == 3 && !rows; ++turn) {  // an apex whose two sides have one count of segments
    const int order[3] = {at[size_t(turn)], at[size_t(turn + 1) % 3], at[size_t(turn + 2) % 3]};
    rows = rows_to_apex(edit, loop, order, corner, tris);
  }
  if (!rows && at.size() > 3) fan_from_middle(edit, loop, corner, tris);
  else if (!rows) triangulate_polygon(edit, loop, normal, tris);
  // A triangle of sides e strays about e^2 / (6 r) from the ball at its middle.
  refine_on_ball(edit, tris, sides, corner, std::sqrt(6 * corner.radius * tolerance));
  // Every triangle faces the way the loop runs (the rows are made without regard to it): seen from the
  // ball's centre, as the loop's own normal does.
  Vec3 middle = Vec3::Zero();
  for (int v : loop) middle += mesh.point(v) / double(loop.size());
  const bool outward = normal.dot(middle - corner.centre) > 0;
  for (auto& t : tris) {
    const Vec3 a = edit.point(t[0]), b = edit.point(t[1]), c = edit.point(t[2]);
    if (((b - a).cross(c - a).dot((a + b + c) / 3 - corner.centre) > 0) != outward) std::swap(t[1], t[2]);
  }
  edit.added = tris;
  check_result(edit, chain, reach, tolerance);
  delta = delta_from_edit(edit);
}

}  // namespace meshround
