#include "strip.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>

#include "meshround/cancel.h"
#include "meshround/mesh_edit.h"

namespace meshround {
namespace {

constexpr double kDeg = M_PI / 180.0;

[[noreturn]] void not_a_round(const std::string& why, const Vec3& where) {
  throw RoundingError(ErrorCode::NotARound, "the strip picked at " + format_point(where) + " is not a round between two flat sides: " + why);
}

double angle_deg(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(a.dot(b), -1.0, 1.0)) / kDeg; }

// The facets' normals and smooth neighbours, looked up once per facet.
class Facets {
 public:
  Facets(const MeshTopology& mesh, const SharpenOptions& o) : mesh_(mesh), o_(o) {}
  const Vec3& normal(int f) {
    auto it = normal_.find(f);
    if (it == normal_.end()) it = normal_.emplace(f, mesh_.facet_normal(f)).first;
    return it->second;
  }
  // The neighbour across edge k of f (-1: boundary), refusing a non-manifold or flipped neighbour.
  int across(int f, int k) {
    const int a = mesh_.F(f, k), b = mesh_.F(f, (k + 1) % 3);
    int pair[2];
    const int count = mesh_.edge_facet_pair(a, b, pair);
    if (count == 1) return -1;
    const Vec3 mid = 0.5 * (mesh_.point(a) + mesh_.point(b));
    if (count > 2) throw RoundingError(ErrorCode::NonManifoldInput, "the edge at " + format_point(mid) + " on the strip is non-manifold");
    const int g = pair[0] == f ? pair[1] : pair[0];
    if (mesh_.edge_direction(f, a, b) == mesh_.edge_direction(g, a, b))
      throw RoundingError(ErrorCode::NonManifoldInput, "the facets at " + format_point(mid) + " are oriented against each other (a flipped facet)");
    return g;
  }
  bool smooth(int f, int g) { return angle_deg(normal(f), normal(g)) < o_.strip_turn_deg; }
  // Flat: every smooth neighbour coplanar with it.
  bool flat(int f) {
    for (int k = 0; k < 3; ++k) {
      const int g = across(f, k);
      if (g >= 0 && smooth(f, g) && angle_deg(normal(f), normal(g)) >= o_.flat_deg) return false;
    }
    return true;
  }
  Vec3 centroid(int f) const { return (mesh_.corner(f, 0) + mesh_.corner(f, 1) + mesh_.corner(f, 2)) / 3; }
  double area(int f) const { return 0.5 * (mesh_.corner(f, 1) - mesh_.corner(f, 0)).cross(mesh_.corner(f, 2) - mesh_.corner(f, 0)).norm(); }

 private:
  const MeshTopology& mesh_;
  const SharpenOptions& o_;
  std::unordered_map<int, Vec3> normal_;
};

int nearest_facet(const MeshTopology& mesh, const Vec3& seed) {
  int best = -1;
  double best_d = INFINITY;
  CancelPoll poll(1 << 14);
  for (int f = 0; f < mesh.num_facets(); ++f) {
    poll.tick();
    int region;
    const double d = (closest_point_on_triangle(seed, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2), &region) - seed).squaredNorm();
    if (d < best_d) best_d = d, best = f;
  }
  return best;
}

// Step 2: the curved facets flooded from f0, and the flat facets beside them (the sides' candidates).
void flood_curved(Facets& fx, int f0, long budget, std::vector<int>& curved, std::vector<int>& beside) {
  std::unordered_set<int> seen{f0};
  std::deque<int> queue{f0};
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop_front();
    curved.push_back(f);
    if (long(curved.size()) > budget) check_work_budget(double(curved.size()), budget, "strip recognition");
    for (int k = 0; k < 3; ++k) {
      const int g = fx.across(f, k);
      if (g < 0 || !fx.smooth(f, g) || !seen.insert(g).second) continue;
      if (fx.flat(g)) beside.push_back(g);
      else queue.push_back(g);
    }
  }
}

// The facets' normals' area-weighted spread: its eigenvalues (ascending) and vectors; `total` the area.
Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> normal_spread(Facets& fx, std::vector<int>::const_iterator begin,
                                                             std::vector<int>::const_iterator end, double* total) {
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  *total = 0;
  for (auto f = begin; f != end; ++f) {
    const double w = fx.area(*f);
    spread += w * fx.normal(*f) * fx.normal(*f).transpose();
    *total += w;
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(spread);
}

// The facets flooded first from the seed (breadth first: its neighbourhood, a few elements each way) that
// tell a round turning along its length from a free-form region.
constexpr size_t kLocalFacets = 60;

// The axis the flood's normals turn about: the direction they are all (nearly) perpendicular to. The
// flood (breadth first from the seed) failing that while its first kLocalFacets pass is a round whose
// axis turns along it: a chain curved in plan, or rounds going on into others through corner blends.
Vec3 turning_axis(Facets& fx, const std::vector<int>& facets, const Vec3& where, double tilt_deg, bool* turns = nullptr) {
  const double tilt2 = std::pow(std::sin(tilt_deg * kDeg), 2);
  double total = 0;
  const auto eig = normal_spread(fx, facets.begin(), facets.end(), &total);
  const Eigen::Vector3d lam = eig.eigenvalues();  // ascending
  if (!(total > 0) || lam(0) > tilt2 * total) {
    double local_total = 0;
    const auto near = normal_spread(fx, facets.begin(), facets.begin() + std::min(facets.size(), kLocalFacets), &local_total);
    const bool local = facets.size() > kLocalFacets && local_total > 0 && near.eigenvalues()(0) <= tilt2 * local_total &&
                       near.eigenvalues()(1) >= 1e-8 * local_total;
    if (local && turns) return *turns = true, near.eigenvectors().col(0).normalized();
    if (local)
      not_a_round("it is a round whose axis turns along its length (a chain curved in plan, as an S-shaped edge or a circular "
                  "pocket's rim, or rounds running on into each other through corner blends, as around a pocket's rim); "
                  "only a straight round between two flat sides can be changed", where);
    not_a_round("its facets' normals do not turn about one axis (a free-form or doubly curved region)", where);
  }
  if (lam(1) < 1e-8 * total) not_a_round("its facets' normals do not turn (a flat region)", where);
  return eig.eigenvectors().col(0).normalized();
}

// A side whose candidates do not share one plane: the two of them farthest apart in angle named. (A side
// that curves along the round -- a wall curved in plan -- is seen here: its flat-looking facets, one
// tessellation column each, turn with the wall.)
[[noreturn]] void refuse_side(Facets& fx, const std::vector<int>& members, int side, const SharpenOptions& o, const Vec3& where) {
  (void)o;
  auto farthest = [&](const Vec3& from) {  // the member whose normal is farthest from `from` (linear work)
    int best = members.front();
    for (int f : members)
      if (angle_deg(fx.normal(f), from) > angle_deg(fx.normal(best), from)) best = f;
    return best;
  };
  Vec3 mean = Vec3::Zero();
  for (int f : members) mean += fx.area(f) * fx.normal(f);
  const int a = farthest(mean.normalized()), b = farthest(fx.normal(a));
  const double spread = angle_deg(fx.normal(a), fx.normal(b));
  char turn[32];
  std::snprintf(turn, sizeof turn, "%.1f", spread);
  not_a_round(std::string("the faces along its ") + (side ? "second" : "first") + " side are not one plane (near " + format_point(fx.centroid(a)) +
              " and " + format_point(fx.centroid(b)) + " they turn by " + turn + " degrees: a side curved along the round, as a "
              "wall curved in plan, or more than one face); only a round between two flat sides can be changed", where);
}

// Step 2's end: each side's plane normal from its candidates (one normal per side, else refused).
void side_normals(Facets& fx, const std::vector<int>& beside, const Vec3& n0, const Vec3& axis, const SharpenOptions& o,
                  const Vec3& where, RoundStrip& strip, bool* curved_side = nullptr) {
  Vec3 sum[2] = {Vec3::Zero(), Vec3::Zero()};
  std::vector<int> members[2];
  const double tilt = std::sin(o.facet_tilt_deg * kDeg);
  for (int f : beside) {
    const Vec3& n = fx.normal(f);
    if (std::abs(n.dot(axis)) > tilt) continue;  // an end face's, not a side's
    const int side = n0.cross(n).dot(axis) < 0 ? 0 : 1;
    sum[side] += fx.area(f) * n, members[side].push_back(f);
  }
  for (int side = 0; side < 2; ++side) {
    if (members[side].empty()) not_a_round(std::string("no flat face was found on its ") + (side ? "second" : "first") + " side", where);
    strip.normal[side] = sum[side].normalized();
    double offset = 0;
    for (int f : members[side]) {
      if (angle_deg(fx.normal(f), strip.normal[side]) > 2 * o.flat_deg) {
        if (curved_side) return void(*curved_side = true);
        refuse_side(fx, members[side], side, o, where);
      }
      offset += strip.normal[side].dot(fx.centroid(f));
    }
    strip.offset[side] = offset / double(members[side].size());
  }
}

// How far off a side plane a vertex may lie and still be on it (float32 coordinates, see on_plane_slack).
double plane_slack(const MeshTopology& mesh, int f) {
  double magnitude = 0;
  for (int k = 0; k < 3; ++k) magnitude = std::max(magnitude, mesh.corner(f, k).cwiseAbs().maxCoeff());
  return 2 * on_plane_slack(0, magnitude);
}

}  // namespace

namespace {

// The breadth-first flood of a strip's facets from f0 (each one's vertices Inner until told otherwise):
// visit(f, k, g) decides for edge k of strip facet f, whose neighbour g (-1: the mesh boundary) is not in
// the strip yet, whether g joins it (true), else records what the edge is.
template <class Visit>
void flood_from(const MeshTopology& mesh, Facets& fx, int f0, const SharpenOptions& o, RoundStrip& strip, Visit visit) {
  strip.facet_set.insert(f0);
  std::deque<int> queue{f0};
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop_front();
    strip.facets.push_back(f);
    if (long(strip.facets.size()) > o.max_new_facets) check_work_budget(double(strip.facets.size()), o.max_new_facets, "strip recognition");
    for (int k = 0; k < 3; ++k) {
      for (int v : {mesh.F(f, k), mesh.F(f, (k + 1) % 3)}) strip.role.emplace(v, StripRole::Inner);
      const int g = fx.across(f, k);
      if (g >= 0 && strip.facet_set.count(g)) continue;
      if (visit(f, k, g)) strip.facet_set.insert(g), queue.push_back(g);
    }
  }
}

// Step 3: the strip's facets, and the role of each of its vertices from the facets across its boundary.
void flood_strip(const MeshTopology& mesh, Facets& fx, int f0, const SharpenOptions& o, const Vec3& where, RoundStrip& strip,
                 std::vector<std::pair<int, int>>& end_edges) {
  const double tilt = std::sin(o.facet_tilt_deg * kDeg);
  auto side_of = [&](int g) {  // 0, 1: a side's facet (its normal and its corners on that side's plane); -1: neither
    for (int side = 0; side < 2; ++side) {
      if (angle_deg(fx.normal(g), strip.normal[side]) >= 2 * o.flat_deg) continue;
      bool on = true;
      for (int k = 0; k < 3; ++k) on &= std::abs(strip.normal[side].dot(mesh.corner(g, k)) - strip.offset[side]) <= plane_slack(mesh, g);
      if (on) return side;
    }
    return -1;
  };
  auto on_strip = [&](int g) { return side_of(g) < 0 && std::abs(fx.normal(g).dot(strip.axis)) <= tilt; };
  if (side_of(f0) >= 0) not_a_round("the seed's facet lies on a flat face beside a round, not on the round", where);
  if (!on_strip(f0)) not_a_round("the seed's facet turns like neither side's nor the round's", where);
  flood_from(mesh, fx, f0, o, strip, [&](int f, int k, int g) {
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
    if (g >= 0 && fx.smooth(f, g) && on_strip(g)) return true;
    const int side = g >= 0 ? side_of(g) : -1;
    if (side >= 0 && fx.smooth(f, g)) {
      for (int v : {a, b}) strip.role[v] = side ? StripRole::BorderB : StripRole::BorderA;
    } else if (g < 0 || !fx.smooth(f, g)) {
      end_edges.push_back({f, k});
    } else {
      not_a_round("it runs on smoothly, at " + format_point(0.5 * (mesh.point(a) + mesh.point(b))) + " (a facet turned " +
                  format_number(std::asin(std::min(1.0, std::abs(fx.normal(g).dot(strip.axis)))) / kDeg) + " deg off the corner line's normal plane)" +
                  ", into a face that is neither of its flat sides (another round, a corner blend or a free-form face)", where);
    }
    return false;
  });
  // A border's vertices are the border's even where an end edge also touches them.
}

// Step 3's end: the side planes through their borders (checked flat there), the corner line, the side of
// each plane the round lies on, and the direction of the ball's centre from the corner.
void side_planes(const MeshTopology& mesh, const Vec3& where, RoundStrip& strip) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const auto& [v, role] : strip.role) lo = lo.cwiseMin(mesh.point(v)), hi = hi.cwiseMax(mesh.point(v));
  const double span = (hi - lo).norm(), slack = 2 * on_plane_slack(span, std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()));
  for (int side = 0; side < 2; ++side) {
    const StripRole border = side ? StripRole::BorderB : StripRole::BorderA;
    double sum = 0;
    int n = 0;
    for (const auto& [v, role] : strip.role)
      if (role == border) sum += strip.normal[side].dot(mesh.point(v)), ++n;
    if (n < 2) not_a_round(std::string("its ") + (side ? "second" : "first") + " border has fewer than two vertices", where);
    strip.border_count[side] = n;
    strip.offset[side] = sum / n;
    for (const auto& [v, role] : strip.role)
      if (role == border && std::abs(strip.normal[side].dot(mesh.point(v)) - strip.offset[side]) > slack)
        not_a_round("its border at " + format_point(mesh.point(v)) + " is not straight on a flat side (the side is curved there)", where);
  }
  Eigen::Matrix3d M;
  M.row(0) = strip.normal[0].transpose(), M.row(1) = strip.normal[1].transpose(), M.row(2) = strip.axis.transpose();
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
  if (std::abs(lu.determinant()) < 1e-6) not_a_round("its two sides are parallel (no sharp edge to rebuild)", where);
  strip.corner = lu.solve(Eigen::Vector3d(strip.offset[0], strip.offset[1], strip.axis.dot(where)));
  for (int side = 0; side < 2; ++side) {
    double sum = 0;
    for (const auto& [v, role] : strip.role)
      if (role == StripRole::Inner || role == StripRole::End) sum += strip.normal[side].dot(mesh.point(v)) - strip.offset[side];
    if (std::abs(sum) <= slack) not_a_round("it has no vertex off its sides (one element across: the radius is not defined)", where);
    strip.side[side] = sum > 0 ? 1.0 : -1.0;
  }
  strip.centre_dir = lu.solve(Eigen::Vector3d(strip.side[0], strip.side[1], 0));
  strip.s_lo = INFINITY, strip.s_hi = -INFINITY;
  for (const auto& [v, role] : strip.role) strip.s_lo = std::min(strip.s_lo, strip.s_of(mesh.point(v))), strip.s_hi = std::max(strip.s_hi, strip.s_of(mesh.point(v)));
}

// The ends: the end faces across the end edges (each one plane), or the mesh boundary.
void strip_ends(const MeshTopology& mesh, Facets& fx, const std::vector<std::pair<int, int>>& end_edges, const SharpenOptions& o,
                const Vec3& where, RoundStrip& strip) {
  const double mid = 0.5 * (strip.s_lo + strip.s_hi);
  Vec3 sum[2] = {Vec3::Zero(), Vec3::Zero()};
  for (const auto& [f, k] : end_edges) {
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
    const int end = strip.param(0.5 * (mesh.point(a) + mesh.point(b))) < mid ? 0 : 1;
    for (int v : {a, b})
      if (strip.role[v] == StripRole::Inner || strip.role[v] == StripRole::End) strip.role[v] = StripRole::End, strip.end_of[v] = end;
    const int g = fx.across(f, k);
    if (g < 0) continue;
    strip.ends[end].face = true;
    strip.ends[end].facets.push_back(g);
    sum[end] += fx.area(g) * fx.normal(g);
  }
  for (int end = 0; end < 2; ++end) {
    StripEnd& e = strip.ends[end];
    if (!e.face) continue;
    e.normal = sum[end].normalized();
    for (int g : e.facets)
      if (angle_deg(fx.normal(g), e.normal) > 2 * o.flat_deg)
        not_a_round("it ends on a face that is not flat (near " + format_point(fx.centroid(g)) + ")", where);
    if (std::abs(e.normal.dot(strip.curved ? strip.end_frame[end].axis : strip.axis)) < 0.2) not_a_round("its end face runs nearly along it (near " + format_point(fx.centroid(e.facets[0])) + ")", where);
    double off = 0;
    int n = 0;
    for (const auto& [v, end_v] : strip.end_of)
      if (end_v == end) off += e.normal.dot(mesh.point(v)), ++n;
    e.offset = n ? off / n : e.normal.dot(fx.centroid(e.facets[0]));
  }
}

// Step 4: the radius of the ball tangent to both planes whose section circle passes through p.
bool vertex_radius(const StripFrame& strip, const Vec3& p, double* r) {
  const Vec3 P = strip.across(p), m = strip.centre_dir;
  const double k = m.squaredNorm() - 1, b = P.dot(m), c = P.squaredNorm();
  if (k <= 1e-12) return false;
  const double disc = b * b - k * c;
  if (disc < -1e-9 * b * b) return false;
  const double root = std::sqrt(std::max(disc, 0.0));
  for (double x : {(b + root) / k, (b - root) / k})  // the larger first
    if (x > 0 && (P - x * m).dot(m) <= 1e-9 * x * m.squaredNorm()) return *r = x, true;
  return false;
}

// A strip whose side B curves along the round (a wall curved in plan, vertical or drafted; side A flat):
// side A is the largest plane beside the flood, side B the facets meeting A's normal at the angle most of
// the area beyond the round has (the opening, one angle all along: a wall ruled across the round); the
// strip is what turns between them. Each station (border B vertex; ordered along the border, nearest next)
// gets its frame: plane A and side B's tangent plane there (normal to the axis and to side B's line in the
// station's section, fitted to the side-B vertices nearly in it), their corner line and the ball's centre
// direction; each strip vertex takes the frame of its nearest station, its corner point moved into its
// own section. The corner line is the stations' corner points: the sharp edge rebuilt section by section,
// exact where side B is ruled across the round but for taking a station's tangent plane half a border
// spacing h away: within about (h/2)^2 / 2R, R side B's radius along the round. A closed loop (a round
// all around a circular pocket) is refused (not done yet).
constexpr double kStationTurnDeg = 15;  // largest turn of the corner line between two stations
constexpr double kJoinDeg = 80;         // see recognise_curved's flood

void recognise_curved(const MeshTopology& mesh, Facets& fx, int f0, const std::vector<int>& flood, const std::vector<int>& beside,
                      const SharpenOptions& o, const Vec3& where, RoundStrip& strip, std::vector<std::pair<int, int>>& end_edges) {
  const double fd2 = 2 * o.flat_deg;
  // Side A: the largest group of coplanar candidates.
  std::vector<std::pair<Vec3, double>> groups;  // (normal, area)
  for (int f : beside) {
    bool known = false;
    for (auto& [n, a] : groups)
      if (angle_deg(fx.normal(f), n) <= fd2) a += fx.area(f), known = true;
    if (!known) groups.push_back({fx.normal(f), fx.area(f)});
  }
  if (groups.empty()) not_a_round("no flat face was found on either side", where);
  const Vec3 nA = std::max_element(groups.begin(), groups.end(), [](auto& x, auto& y) { return x.second < y.second; })->first;
  Vec3 sumA = Vec3::Zero();
  for (int f : beside)
    if (angle_deg(fx.normal(f), nA) <= fd2) sumA += fx.area(f) * fx.normal(f);
  strip.normal[0] = sumA.normalized();
  {  // sharper: the plane fitted to the group's vertices (a facet's normal carries its float32 rounding)
    std::unordered_set<int> on;
    for (int f : beside)
      if (angle_deg(fx.normal(f), strip.normal[0]) <= fd2)
        for (int k = 0; k < 3; ++k) on.insert(mesh.F(f, k));
    Vec3 c = Vec3::Zero();
    for (int v : on) c += mesh.point(v) / double(on.size());
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    for (int v : on) C += (mesh.point(v) - c) * (mesh.point(v) - c).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
    Vec3 fit = eig.eigenvectors().col(0).normalized();
    if (fit.dot(strip.normal[0]) < 0) fit = -fit;
    if (on.size() >= 4 && eig.eigenvalues()(1) > 0 && angle_deg(fit, strip.normal[0]) < fd2) strip.normal[0] = fit;
    strip.offset[0] = strip.normal[0].dot(c);  // (through the plane's own vertices, not the border's: a
                                               // sliver at an end may put a round's vertex on the border)
  }
  // The opening: the largest angle to side A that a tenth of the area of the fullest angle has, in bins
  // of 2 flat_deg (side B's facets: one angle all along; the round's spread over the angles between).
  std::unordered_map<int, double> bins;
  for (const std::vector<int>* list : {&flood, &beside})
    for (int f : *list) bins[int(std::floor(angle_deg(fx.normal(f), strip.normal[0]) / fd2))] += fx.area(f);
  double fullest = 0;
  for (const auto& [b, a] : bins)
    if (b * fd2 > 4 * fd2) fullest = std::max(fullest, a);
  int top_bin = -1;
  for (const auto& [b, a] : bins)
    if (b * fd2 > 4 * fd2 && a >= 0.1 * fullest && b > top_bin) top_bin = b;
  if (top_bin < 0) not_a_round("no second side was found beside it", where);
  double opening = 0, opening_area = 0;  // the area-weighted mean angle in that bin and its neighbours
  for (const std::vector<int>* list : {&flood, &beside})
    for (int f : *list) {
      const double a = angle_deg(fx.normal(f), strip.normal[0]);
      if (std::abs(a - (top_bin + 0.5) * fd2) <= 1.5 * fd2) opening += fx.area(f) * a, opening_area += fx.area(f);
    }
  opening /= opening_area;
  if (opening < 4 * fd2 || opening > 180 - 4 * fd2) not_a_round("its sides do not meet at an angle (no sharp edge to rebuild)", where);
  auto side_of = [&](int g) {
    const double a = angle_deg(fx.normal(g), strip.normal[0]);
    if (a < fd2) return 0;
    if (a > opening - fd2) return 1;
    return -1;
  };
  if (side_of(f0) >= 0) not_a_round("the seed's facet lies on a side beside a round, not on the round", where);
  // The strip, its borders and ends (as flood_strip, the sides told by their angle to side A).
  std::vector<std::pair<int, int>> border_b;  // (border B vertex, the side-B facet across the border there)
  std::vector<std::pair<int, int>> border_edges;  // (strip facet, edge) of each border B edge
  flood_from(mesh, fx, f0, o, strip, [&](int f, int k, int g) {
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
    const int side = g >= 0 ? side_of(g) : -1;
    // (a facet turning like neither side joins while it turns by less than kJoinDeg: a mesher's folded
    // sliver on a seam between two round faces turns by a little over strip_turn_deg)
    if (g >= 0 && side < 0 && angle_deg(fx.normal(f), fx.normal(g)) < std::max(o.strip_turn_deg, kJoinDeg)) return true;
    if (side >= 0 && fx.smooth(f, g)) {
      for (int v : {a, b}) strip.role[v] = side ? StripRole::BorderB : StripRole::BorderA;
      if (side) border_b.push_back({a, g}), border_b.push_back({b, g}), border_edges.push_back({f, k});
    } else {
      end_edges.push_back({f, k});
    }
    return false;
  });
  if (end_edges.empty()) not_a_round("it runs all around a closed loop (a circular pocket's or boss's rim: not done yet)", where);
  // Plane A's border.
  int n = 0;
  for (const auto& [v, role] : strip.role)
    if (role == StripRole::BorderA) ++n;
  if (n < 2) not_a_round("its flat side's border has fewer than two vertices", where);
  strip.border_count[0] = n;
  // Side B's tangent plane at each border B vertex: its normal from the side-B facets around it that turn
  // with the one across the border there (not an end face's), weighted by their angles at the vertex.
  std::unordered_map<int, Vec3> anchor;
  for (const auto& [v, g] : border_b) anchor.emplace(v, fx.normal(g));
  if (anchor.size() < 2) not_a_round("its curved side's border has fewer than two vertices", where);
  strip.border_count[1] = int(anchor.size());
  std::vector<StripFrame> station;
  std::vector<int> station_vertex;  // the border B vertex of each
  for (const auto& [b, an] : anchor) {
    Vec3 nB = Vec3::Zero();
    for (const int* g = mesh.facets_begin(b); g != mesh.facets_end(b); ++g) {
      if (strip.facet_set.count(*g) || side_of(*g) != 1 || angle_deg(fx.normal(*g), an) > kStationTurnDeg) continue;
      int k = 0;
      while (mesh.F(*g, k) != b) ++k;
      const Vec3 u = mesh.point(mesh.F(*g, (k + 1) % 3)) - mesh.point(b), w = mesh.point(mesh.F(*g, (k + 2) % 3)) - mesh.point(b);
      nB += std::atan2(u.cross(w).norm(), u.dot(w)) * fx.normal(*g);  // weighted by the facet's angle at b
    }
    if (nB.norm() < 1e-12) continue;
    nB.normalize();
    // Sharper (the facets of a tessellated curved wall tilt by their chords): side B's line in b's own
    // section, through b and the side-B vertices within three rings of it that lie nearly in that section
    // (|along| < 0.35 of the ring's mean edge), projected into it; nB is normal to it and to the axis.
    {
      const Vec3 t = strip.normal[0].cross(nB).normalized();
      std::unordered_set<int> ring{b};
      for (int pass = 0; pass < 3; ++pass) {
        std::vector<int> grow(ring.begin(), ring.end());
        for (int v : grow)
          for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g)
            if (!strip.facet_set.count(*g) && side_of(*g) == 1 && angle_deg(fx.normal(*g), nB) <= kStationTurnDeg)
              for (int k = 0; k < 3; ++k) ring.insert(mesh.F(*g, k));
      }
      double h = 0;
      int nh = 0;
      for (const int* g = mesh.facets_begin(b); g != mesh.facets_end(b); ++g)
        for (int k = 0; k < 3; ++k) h += (mesh.corner(*g, k) - mesh.corner(*g, (k + 1) % 3)).norm(), ++nh;
      h /= std::max(nh, 1);
      Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
      int used = 0;
      for (int v : ring) {
        const Vec3 d = mesh.point(v) - mesh.point(b);
        if (v == b || std::abs(t.dot(d)) > 0.35 * h || d.norm() < 0.2 * h) continue;
        const Vec3 q = d - t * t.dot(d);
        C += q * q.transpose() / q.squaredNorm(), ++used;
      }
      if (used >= 1) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
        const Vec3 down = eig.eigenvectors().col(2).normalized();
        Vec3 fit = down.cross(t).normalized();
        if (fit.dot(nB) < 0) fit = -fit;
        if (angle_deg(fit, nB) < 5) nB = fit;
      }
    }
    StripFrame F;
    F.normal[0] = strip.normal[0], F.offset[0] = strip.offset[0];
    F.normal[1] = nB, F.offset[1] = F.normal[1].dot(mesh.point(b));
    F.axis = F.normal[0].cross(F.normal[1]);
    if (F.axis.norm() < 1e-6) not_a_round("its two sides are parallel at " + format_point(mesh.point(b)), where);
    F.axis.normalize();
    Eigen::Matrix3d M;
    M.row(0) = F.normal[0].transpose(), M.row(1) = F.normal[1].transpose(), M.row(2) = F.axis.transpose();
    F.corner = M.fullPivLu().solve(Eigen::Vector3d(F.offset[0], F.offset[1], F.axis.dot(mesh.point(b))));
    station.push_back(F), station_vertex.push_back(b);
  }
  // In order along the corner line: from the station farthest from their middle, each next the nearest.
  {
    Vec3 middle = Vec3::Zero();
    for (const StripFrame& F : station) middle += F.corner / double(station.size());
    size_t first = 0;
    for (size_t i = 1; i < station.size(); ++i)
      if ((station[i].corner - middle).squaredNorm() > (station[first].corner - middle).squaredNorm()) first = i;
    std::swap(station[0], station[first]), std::swap(station_vertex[0], station_vertex[first]);
    for (size_t i = 1; i < station.size(); ++i) {
      size_t best = i;
      for (size_t j = i + 1; j < station.size(); ++j)
        if ((station[j].corner - station[i - 1].corner).squaredNorm() < (station[best].corner - station[i - 1].corner).squaredNorm()) best = j;
      std::swap(station[i], station[best]), std::swap(station_vertex[i], station_vertex[best]);
    }
  }
  // The run of stations through the seed's whose corner line turns by kStationTurnDeg at most from one to
  // the next; stations beyond it at an end (an end face's facets across a sliver) are dropped.
  {
    std::vector<double> turn(station.size(), 0);
    for (size_t i = 1; i < station.size(); ++i)
      turn[i] = std::acos(std::min(1.0, std::abs(station[i].axis.dot(station[i - 1].axis)))) / kDeg;
    size_t seed_at = 0;
    for (size_t i = 1; i < station.size(); ++i)
      if ((station[i].corner - where).squaredNorm() < (station[seed_at].corner - where).squaredNorm()) seed_at = i;
    size_t lo = seed_at, hi = seed_at;
    while (lo > 0 && turn[lo] <= kStationTurnDeg) --lo;
    while (hi + 1 < station.size() && turn[hi + 1] <= kStationTurnDeg) ++hi;
    // Dropped at an end: stations within twice the round's width (corner to border) of the run's last
    // one, the end face's (a mesher's slivers there); beyond, the corner line goes on around a corner.
    auto beyond = [&](size_t from, size_t to, size_t end) {
      const double width = (station[end].corner - mesh.point(station_vertex[end])).norm();
      for (size_t j = from; j < to; ++j)
        if ((station[j].corner - station[end].corner).norm() > 2 * width) return true;
      return false;
    };
    const bool past_lo = beyond(0, lo, lo), past_hi = beyond(hi + 1, station.size(), hi);
    if (past_lo || past_hi) {
      const size_t at = past_lo ? lo : hi + 1;
      not_a_round("its corner line turns by " + format_number(turn[at]) + " deg at " + format_point(station[at].corner) +
                  " (a corner of its curved side, or a corner blend where rounds meet, as around a pocket's rim: not done yet)", where);
    }
    station = std::vector<StripFrame>(station.begin() + long(lo), station.begin() + long(hi) + 1);
    // The border edges at a dropped station are the strip's end there (across them: an end face's
    // facets, reached through a mesher's sliver); their vertices are the strip's.
    const std::unordered_set<int> kept(station_vertex.begin() + long(lo), station_vertex.begin() + long(hi) + 1);
    for (const auto& [f, k] : border_edges) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (kept.count(a) && kept.count(b)) continue;
      end_edges.push_back({f, k});
      for (int v : {a, b})
        if (!kept.count(v)) strip.role[v] = StripRole::Inner;
    }
    strip.border_count[1] = int(kept.size());
    if (station.size() < 2) not_a_round("its curved side's border has fewer than two stations", where);
  }
  for (size_t i = 0; i < station.size(); ++i) {
    StripFrame& F = station[i];
    const Vec3 along = i > 0 ? station[i - 1].axis : Vec3(station[std::min<size_t>(1, station.size() - 1)].corner - F.corner);
    if (F.axis.dot(along) < 0) F.axis = -F.axis;
  }
  // The strip vertices' stations (nearest corner point), the side of each plane the round lies on.
  std::unordered_map<int, size_t> at;
  for (const auto& [v, role] : strip.role) {
    size_t best = 0;
    for (size_t i = 1; i < station.size(); ++i)
      if ((station[i].corner - mesh.point(v)).squaredNorm() < (station[best].corner - mesh.point(v)).squaredNorm()) best = i;
    at[v] = best;
  }
  const double slack = 1e-6 * (station.front().corner - station.back().corner).norm() + 1e-9;
  for (int side = 0; side < 2; ++side) {
    double total = 0;
    for (const auto& [v, role] : strip.role)
      if (role == StripRole::Inner || role == StripRole::End)
        total += station[at[v]].normal[side].dot(mesh.point(v)) - station[at[v]].offset[side];
    if (std::abs(total) <= slack) not_a_round("it has no vertex off its sides (one element across: the radius is not defined)", where);
    strip.side[side] = total > 0 ? 1.0 : -1.0;
  }
  double s = 0;
  for (size_t i = 0; i < station.size(); ++i) {
    StripFrame& F = station[i];
    F.side[0] = strip.side[0], F.side[1] = strip.side[1];
    Eigen::Matrix3d M;
    M.row(0) = F.normal[0].transpose(), M.row(1) = F.normal[1].transpose(), M.row(2) = F.axis.transpose();
    F.centre_dir = M.fullPivLu().solve(Eigen::Vector3d(F.side[0], F.side[1], 0));
    if (i > 0) s += (F.corner - station[i - 1].corner).norm();
    strip.line.push_back(F.corner), strip.line_s.push_back(s);
  }
  // A vertex's frame: its nearest station's, the corner point moved into the vertex's own section.
  for (const auto& [v, role] : strip.role) {
    const Vec3 p = mesh.point(v);
    StripFrame F = station[at[v]];
    F.corner += F.axis * F.axis.dot(p - F.corner);  // its own section's corner point
    strip.frames.emplace(v, F);
  }
  strip.curved = true;
  // The strip's own frame: the seed's station's; the line's frames; the ends' (the first and last station).
  size_t seed_at = 0;
  for (size_t i = 1; i < station.size(); ++i)
    if ((station[i].corner - where).squaredNorm() < (station[seed_at].corner - where).squaredNorm()) seed_at = i;
  static_cast<StripFrame&>(strip) = station[seed_at];
  strip.stations = std::move(station);
  strip.end_frame[0] = strip.stations.front(), strip.end_frame[1] = strip.stations.back();
  strip.s_lo = INFINITY, strip.s_hi = -INFINITY;
  for (const auto& [v, role] : strip.role) strip.s_lo = std::min(strip.s_lo, strip.param(mesh.point(v))), strip.s_hi = std::max(strip.s_hi, strip.param(mesh.point(v)));
}

}  // namespace

RoundStrip recognise_strip(const MeshTopology& mesh, const Vec3& seed, const SharpenOptions& o) {
  const int f0 = nearest_facet(mesh, seed);
  Facets fx(mesh, o);
  if (fx.flat(f0)) not_a_round("the seed's facet lies on a flat face", seed);
  std::vector<int> curved, beside;
  flood_curved(fx, f0, o.max_new_facets, curved, beside);
  RoundStrip strip;
  bool turns = false, curved_side = false;
  const Vec3 axis0 = turning_axis(fx, curved, seed, o.axis_tilt_deg, &turns);
  if (!turns) side_normals(fx, beside, fx.normal(f0), axis0, o, seed, strip, &curved_side);
  std::vector<std::pair<int, int>> end_edges;
  if (turns || curved_side) {
    recognise_curved(mesh, fx, f0, curved, beside, o, seed, strip, end_edges);
  } else {
    strip.axis = strip.normal[0].cross(strip.normal[1]);
    if (strip.axis.norm() < 1e-6) not_a_round("its two sides are parallel (no sharp edge to rebuild)", seed);
    strip.axis.normalize();
    flood_strip(mesh, fx, f0, o, seed, strip, end_edges);
    side_planes(mesh, seed, strip);
  }
  strip_ends(mesh, fx, end_edges, o, seed, strip);
  if (strip.curved) {
    // A vertex a hair outside a side's plane (its station's tangent plane, within measure_clearance of its
    // distance from the corner: a curved side's tangent plane is taken at the nearest station) lies on
    // that side's border: it stays where it is.
    for (auto& [v, role] : strip.role) {
      if (role != StripRole::Inner) continue;
      const StripFrame& F = strip.frame(v);
      const Vec3 p = mesh.point(v);
      double r;
      if (vertex_radius(F, p, &r)) continue;
      const double reach = o.measure_clearance * F.across(p).norm();
      for (int side = 0; side < 2; ++side)
        if (std::abs(F.normal[side].dot(p) - F.offset[side]) <= reach) role = side ? StripRole::BorderB : StripRole::BorderA;
    }
  }
  for (const auto& [v, role] : strip.role) {
    if (role != StripRole::Inner && role != StripRole::End) continue;
    double r;
    if (!vertex_radius(strip.frame(v), mesh.point(v), &r))
      not_a_round("no ball tangent to both sides passes through its vertex at " + format_point(mesh.point(v)), seed);
    strip.radius[v] = r;
  }
  if (strip.radius.empty()) not_a_round("it has no vertex between its borders (one element across: the radius is not defined)", seed);
  if (strip.curved)
    strip.recognised = "curved facets flooded from the seed (" + std::to_string(curved.size()) + "), flanked by a flat side and a side "
                       "curved along the round (" + format_number(angle_deg(strip.normal[0], strip.normal[1])) + " deg apart); strip = " +
                       std::to_string(strip.facets.size()) + " facets turning about the corner line between them, " +
                       std::to_string(strip.line.size()) + " stations along it";
  else
    strip.recognised = "curved facets flooded from the seed (" + std::to_string(curved.size()) + "), flanked by two flat sides (" +
                       format_number(angle_deg(strip.normal[0], strip.normal[1])) + " deg apart); strip = " +
                       std::to_string(strip.facets.size()) + " facets turning about the corner line between them";
  return strip;
}

void measure_law(const MeshTopology& mesh, const RoundStrip& strip, const SharpenOptions& o, StripReport& rep) {
  std::vector<std::pair<double, double>> sr;  // (s, r) of every measured vertex
  double sum = 0;
  rep.radius_min = INFINITY, rep.radius_max = 0;
  // Vertices nearer a side than measure_clearance * r measure the radius ill-conditioned (a float32 hair
  // off the plane moves the tangent ball a lot): left out while others are there.
  auto clear = [&](int v, double r) {
    const Vec3 p = mesh.point(v);
    const StripFrame& f = strip.frame(v);
    return std::min(std::abs(f.normal[0].dot(p) - f.offset[0]), std::abs(f.normal[1].dot(p) - f.offset[1])) >= o.measure_clearance * r;
  };
  bool any_clear = false;
  for (const auto& [v, r] : strip.radius) any_clear |= clear(v, r);
  for (const auto& [v, r] : strip.radius) {
    if (any_clear && !clear(v, r)) continue;
    sr.push_back({strip.param(mesh.point(v)), r});
    sum += r;
    rep.radius_min = std::min(rep.radius_min, r), rep.radius_max = std::max(rep.radius_max, r);
  }
  rep.found_radius = sum / double(sr.size());
  rep.measured_vertices = int(sr.size());
  const double r = rep.found_radius, tol = o.fit_tolerance * r;
  rep.constant = rep.radius_max - rep.radius_min <= tol;
  rep.law_s.clear(), rep.law_r.clear(), rep.law_points.clear();
  if (rep.constant) {
    rep.fit_residual = std::max(rep.radius_max - r, r - rep.radius_min);
    for (double s : {strip.s_lo, strip.s_hi}) rep.law_s.push_back(s), rep.law_r.push_back(r);
  } else {  // stations every ~law_step * r: the hat-weighted mean radius of the vertices around each
    const double L = strip.s_hi - strip.s_lo;
    const int n = std::max(2, int(std::ceil(L / std::max(o.law_step * r, 1e-9))) + 1);
    const double h = L / (n - 1);
    std::vector<double> wsum(n, 0), rsum(n, 0);
    for (const auto& [s, rv] : sr) {
      const double x = std::clamp((s - strip.s_lo) / h, 0.0, double(n - 1));
      const int i = std::min(int(x), n - 2);
      const double w = x - i;
      wsum[i] += 1 - w, rsum[i] += (1 - w) * rv, wsum[i + 1] += w, rsum[i + 1] += w * rv;
    }
    for (int i = 0; i < n; ++i)
      if (wsum[i] > 1e-6) rep.law_s.push_back(strip.s_lo + i * h), rep.law_r.push_back(rsum[i] / wsum[i]);
    auto law_at = [&](double s) {
      const size_t j = std::upper_bound(rep.law_s.begin(), rep.law_s.end(), s) - rep.law_s.begin();
      if (j == 0) return rep.law_r.front();
      if (j == rep.law_s.size()) return rep.law_r.back();
      const double w = (s - rep.law_s[j - 1]) / (rep.law_s[j] - rep.law_s[j - 1]);
      return (1 - w) * rep.law_r[j - 1] + w * rep.law_r[j];
    };
    rep.fit_residual = 0;
    Vec3 worst = strip.corner;
    for (const auto& [s, rv] : sr)
      if (std::abs(rv - law_at(s)) > rep.fit_residual) rep.fit_residual = std::abs(rv - law_at(s)), worst = strip.point_at(s);
    if (rep.fit_residual > tol)
      throw RoundingError(ErrorCode::NotARound, "the strip along " + format_point(worst) + " is not a round: the radius is not defined there "
                          "(the balls tangent to both sides through its vertices range over " + format_number(rep.radius_min) + " .. " +
                          format_number(rep.radius_max) + " mm and stray by " + format_number(rep.fit_residual) + " mm from any law along it, over " +
                          format_number(100 * o.fit_tolerance) + "% of r)");
  }
  for (double s : rep.law_s) rep.law_points.push_back(strip.point_at(s));
}

double RoundStrip::param(const Vec3& p) const {
  if (!curved) return s_of(p);
  size_t best = 0;
  for (size_t i = 1; i < line.size(); ++i)
    if ((line[i] - p).squaredNorm() < (line[best] - p).squaredNorm()) best = i;
  return line_s[best] + stations[best].axis.dot(p - line[best]);
}

Vec3 RoundStrip::point_at(double s) const {
  if (!curved) return corner + s * axis;
  if (s <= line_s.front()) return line.front() + (s - line_s.front()) * stations.front().axis;
  if (s >= line_s.back()) return line.back() + (s - line_s.back()) * stations.back().axis;
  const size_t j = std::upper_bound(line_s.begin(), line_s.end(), s) - line_s.begin();
  const double w = (s - line_s[j - 1]) / (line_s[j] - line_s[j - 1]);
  return (1 - w) * line[j - 1] + w * line[j];
}

}  // namespace meshround
