#include "strip.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>

#include "meshround/cancel.h"
#include "meshround/mesh_edit.h"
#include "strip_facets.h"

namespace meshround {
using namespace strip_detail;
namespace {

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

// The share of the flood's area that may tilt by more than facet_tilt_deg from perpendicular to its axis.
constexpr double kTiltedShare = 0.02;

// The axis the flood's normals turn about: the direction they are all (nearly) perpendicular to, in the
// mean (tilt_deg rms) and facet by facet (all but kTiltedShare of the area within facet_tilt_deg). The
// flood (breadth first from the seed) failing that while its first kLocalFacets pass is a round whose
// axis turns along it: a chain curved in plan, or rounds going on into others through corner blends.
// (The facet test: a CAD mesh of a round along a wall curved in plan floods the wall too -- its facets are
// curved ones -- and the wall's area, its normals all level, passed the mean test about the vertical, though
// the round's facets next to the top face tilt by up to 90 degrees from level.)
Vec3 turning_axis(Facets& fx, const std::vector<int>& facets, const Vec3& where, const SharpenOptions& o, bool* turns = nullptr) {
  const double tilt2 = std::pow(std::sin(o.axis_tilt_deg * kDeg), 2), facet_tilt = std::sin(o.facet_tilt_deg * kDeg);
  double total = 0;
  const auto eig = normal_spread(fx, facets.begin(), facets.end(), &total);
  const Eigen::Vector3d lam = eig.eigenvalues();  // ascending
  double tilted = 0;
  for (int f : facets)
    if (std::abs(fx.normal(f).dot(eig.eigenvectors().col(0).normalized())) > facet_tilt) tilted += fx.area(f);
  if (!(total > 0) || lam(0) > tilt2 * total || tilted > kTiltedShare * total) {
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


// A mesher's cap at the round's end (a facet with an angle of 150 deg or more, on neither side), flat with no
// facet around it but the strip's: the round's own, its corners on the round (MeshPart ends a round's rows a
// hair short of its end face and joins the last row to the end arc by such caps: a box's 5 mm round meshed at
// 5 mm, its last row 0.16 mm in, caps turned 28 deg off the end face, was refused as ending on a face "not
// flat"; the L channel's at 1.2 mm, 0.02 mm in, caps turned 55 deg, as running on smoothly). A cap of the end
// face itself lies flat with the end face's facets.
bool end_cap(Facets& fx, int g, const SharpenOptions& o, const RoundStrip& strip) {
  if (!fx.cap(g)) return false;
  for (int k = 0; k < 3; ++k) {
    const int h = fx.across(g, k);
    if (h >= 0 && !strip.facet_set.count(h) && angle_deg(fx.normal(g), fx.normal(h)) <= 2 * o.flat_deg) return false;
  }
  return true;
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
  std::unordered_set<int> end_caps;
  flood_from(mesh, fx, f0, o, strip, end_edges, [&](int f, int k, int g) {
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
    if (g >= 0 && fx.smooth(f, g) && on_strip(g)) return true;
    const int side = g >= 0 ? side_of(g) : -1;
    if (side >= 0 && fx.smooth(f, g)) {
      for (int v : {a, b}) strip.role[v] = side ? StripRole::BorderB : StripRole::BorderA;
    } else if (side < 0 && g >= 0 && end_cap(fx, g, o, strip)) {
      end_caps.insert(g);
      return true;
    } else if (g < 0 || !fx.smooth(f, g) || end_caps.count(f)) {  // (an end cap's end face turns less)
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

// Where the strip meets the mesh boundary, that must be one of its ends: a path of open edges from one
// side's border across to the other's. A loop of them, or a path from a side back to the same side, is a
// hole in the round (its vertices would be folded onto an end face the round does not reach).
void refuse_holes(const MeshTopology& mesh, const std::vector<std::pair<int, int>>& end_edges, const RoundStrip& strip) {
  std::unordered_map<int, std::vector<int>> open;  // vertex -> its neighbours along open edges
  for (const auto& [f, k] : end_edges) {
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
    if (mesh.edge_facet_count(a, b) != 1) continue;
    open[a].push_back(b), open[b].push_back(a);
  }
  std::unordered_set<int> seen;
  for (const auto& [v0, unused] : open) {
    (void)unused;
    if (!seen.insert(v0).second) continue;
    std::vector<int> part{v0};
    size_t degrees = 0;
    for (size_t i = 0; i < part.size(); ++i) {
      degrees += open.at(part[i]).size();
      for (int w : open.at(part[i]))
        if (seen.insert(w).second) part.push_back(w);
    }
    int sides = 0;  // bit 1: side A's border reached, bit 2: side B's
    for (int v : part)
      if (open.at(v).size() == 1) {
        auto role = strip.role.find(v);
        if (role != strip.role.end() && (role->second == StripRole::BorderA || role->second == StripRole::BorderB)) sides |= int(role->second);
      }
    if (strip.closed || degrees / 2 >= part.size() || sides != 3)
      throw RoundingError(ErrorCode::NonManifoldInput, "the mesh is open (a hole in the round, not an end of it) where the rounding goes, at " +
                          format_point(mesh.point(v0)) + "; nothing was changed");
  }
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
    // A side's own facet across an end edge (a sliver of the mesher's where the round meets its end face):
    // not the end face's.
    const StripFrame& side = strip.curved ? strip.end_frame[end] : static_cast<const StripFrame&>(strip);
    if (angle_deg(fx.normal(g), side.normal[0]) <= 2 * o.flat_deg || angle_deg(fx.normal(g), side.normal[1]) <= 2 * o.flat_deg) continue;
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


}  // namespace

RoundStrip recognise_strip(const MeshTopology& mesh, const Vec3& seed, const SharpenOptions& o) {
  const int f0 = nearest_facet(mesh, seed);
  Facets fx(mesh, o);
  if (fx.flat(f0)) not_a_round("the seed's facet lies on a flat face", seed);
  std::vector<int> curved, beside;
  flood_curved(fx, f0, o.max_new_facets, curved, beside);
  RoundStrip strip;
  bool turns = false, curved_side = false, mitred = false;
  std::vector<std::pair<int, int>> end_edges;
  Vec3 axis0 = Vec3::Zero();
  try {
    axis0 = turning_axis(fx, curved, seed, o, &turns);
  } catch (const RoundingError&) {  // (a CAD mesh of mitred rounds: too few facets to see one turning locally)
    if (!(mitred = recognise_mitred(mesh, fx, f0, curved, beside, o, seed, strip, end_edges))) throw;
  }
  if (!mitred && !turns) side_normals(fx, beside, fx.normal(f0), axis0, o, seed, strip, &curved_side);
  if (mitred) {
  } else if (turns || curved_side) {
    if (!recognise_mitred(mesh, fx, f0, curved, beside, o, seed, strip, end_edges))
      recognise_curved(mesh, fx, f0, curved, beside, o, seed, strip, end_edges);
  } else {
    strip.axis = strip.normal[0].cross(strip.normal[1]);
    if (strip.axis.norm() < 1e-6) not_a_round("its two sides are parallel (no sharp edge to rebuild)", seed);
    strip.axis.normalize();
    flood_strip(mesh, fx, f0, o, seed, strip, end_edges);
    side_planes(mesh, seed, strip);
  }
  refuse_holes(mesh, end_edges, strip);
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
  if (strip.mitred)
    strip.recognised = "curved facets flooded from the seed (" + std::to_string(curved.size()) + "), flanked by one flat side and " +
                       std::to_string(strip.pieces.size()) + " flat walls meeting at sharp edges; strip = " + std::to_string(strip.facets.size()) +
                       " facets of " + std::to_string(strip.pieces.size()) + " rounds " + (strip.closed ? "all around a loop, " : "") +
                       "mitred into each other on the planes bisecting their walls (" + std::to_string(strip.mitre_of.size()) + " crease vertices)";
  else if (strip.curved)
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
    // A side curved along the round is known at its stations by their tangent planes, which its facets
    // leave by their chords' sag in plan between two stations (length x turn / 8): a radius measured
    // there may stray by that much more (a 2.8 mm mesh of the S plate's 4 mm round along its 20 mm arc:
    // 0.05 mm, 1.2 % of r).
    std::vector<double> sag;  // between station i and i + 1
    if (strip.curved)
      for (size_t i = 0; i + 1 < strip.stations.size(); ++i) {
        const double turn = std::acos(std::min(1.0, std::abs(strip.stations[i].axis.dot(strip.stations[i + 1].axis))));
        sag.push_back((strip.line_s[i + 1] - strip.line_s[i]) * turn / 8);
      }
    auto allowance = [&](double s) {  // the largest sag within two stations (a wall that starts to curve)
      if (sag.empty()) return 0.0;
      const long j = long(std::upper_bound(strip.line_s.begin(), strip.line_s.end(), s) - strip.line_s.begin());
      double most = 0;
      for (long i = std::max(0L, j - 3); i <= std::min(long(sag.size()) - 1, j + 1); ++i) most = std::max(most, sag[size_t(i)]);
      return most;
    };
    rep.fit_residual = 0;
    double worst_excess = 0, worst_off = 0, worst_sag = 0;
    Vec3 worst = strip.corner;
    for (const auto& [s, rv] : sr) {
      const double off = std::abs(rv - law_at(s));
      rep.fit_residual = std::max(rep.fit_residual, off);
      if (off - allowance(s) > worst_excess) worst_excess = off - allowance(s), worst_off = off, worst_sag = allowance(s), worst = strip.point_at(s);
    }
    if (worst_excess > tol)
      throw RoundingError(ErrorCode::NotARound, "the strip along " + format_point(worst) + " is not a round: the radius is not defined there "
                          "(the balls tangent to both sides through its vertices range over " + format_number(rep.radius_min) + " .. " +
                          format_number(rep.radius_max) + " mm and stray by " + format_number(worst_off) + " mm from any law along it, over " +
                          format_number(100 * o.fit_tolerance) + "% of r" +
                          (worst_sag > 0 ? " and the curved side's chord sag there, " + format_number(worst_sag) + " mm" : std::string()) + ")");
  }
  for (double s : rep.law_s) rep.law_points.push_back(strip.point_at(s));
}

double RoundStrip::param(const Vec3& p) const {
  if (!curved) return s_of(p);
  if (mitred) {  // along the nearest piece (an open strip's first and last run on past their ends)
    double best = INFINITY, s = 0;
    for (size_t i = 0; i < pieces.size(); ++i) {
      const Piece& piece = pieces[i];
      double along = piece.frame.s_of(p);
      if (closed || i > 0) along = std::max(along, 0.0);
      if (closed || i + 1 < pieces.size()) along = std::min(along, piece.length);
      const double off = (piece.frame.corner + along * piece.frame.axis - p).squaredNorm();
      if (off < best) best = off, s = piece.s0 + along;
    }
    return closed ? s - loop_length * std::floor(s / loop_length) : s;
  }
  size_t best = 0;
  for (size_t i = 1; i < line.size(); ++i)
    if ((line[i] - p).squaredNorm() < (line[best] - p).squaredNorm()) best = i;
  const double s = line_s[best] + stations[best].axis.dot(p - line[best]);
  return closed ? s - loop_length * std::floor(s / loop_length) : s;
}

Vec3 RoundStrip::point_at(double s) const {
  if (!curved) return corner + s * axis;
  if (closed) {
    s -= loop_length * std::floor(s / loop_length);
    if (s >= line_s.back()) {  // on the closing segment
      const double w = (s - line_s.back()) / std::max(loop_length - line_s.back(), 1e-300);
      return (1 - w) * line.back() + w * line.front();
    }
  }
  if (s <= line_s.front()) return line.front() + (s - line_s.front()) * stations.front().axis;
  if (s >= line_s.back()) return line.back() + (s - line_s.back()) * stations.back().axis;
  const size_t j = std::upper_bound(line_s.begin(), line_s.end(), s) - line_s.begin();
  const double w = (s - line_s[j - 1]) / (line_s[j] - line_s[j - 1]);
  return (1 - w) * line[j - 1] + w * line[j];
}

}  // namespace meshround
