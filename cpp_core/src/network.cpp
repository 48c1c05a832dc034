#include "network.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "call_checks.h"
#include "meshround/radius_law.h"

namespace meshround {

bool constant_radius(const RoundOptions& own) {
  return std::all_of(own.radius_law.begin(), own.radius_law.end(), [&](const RadiusControl& c) { return c.radius == own.radius_law[0].radius; });
}

double one_radius(const RoundOptions& own) { return own.radius_law.empty() ? own.radius : own.radius_law[0].radius; }

const CornerEnd* corner_at(const NetworkPart& net, const Vec3& end_point) {
  for (const CornerEnd& c : net.corners)
    if ((c.point - end_point).norm() <= 1e-9 * std::max(1.0, end_point.cwiseAbs().maxCoeff())) return &c;
  return nullptr;
}

namespace {

// At a corner of four or more rounds, the largest distance a face may have from the one ball meant to
// touch them all, as a share of the tolerance (three faces always have such a ball).
constexpr double kCornerBallMissShare = 0.1;
// Rounds meeting at a corner have one radius there when their radii there differ by no more than this
// share of the tolerance.
constexpr double kSameCornerRadiusShare = 1e-3;
// A radius law into a corner holds its value over this many radii before the corner (its end's setback).
constexpr double kCornerLawHoldRadii = 2.0;
// Three rounds of one convexity with different radii: the two others roll on around the end of the one with
// the largest radius R (its pivot), as OCCT's fillet makes that corner (ChFi3d's three-edge corner: a torus
// where the two have one radius r, else a ball whose radius goes from one's to the other's with an S law);
// where two share the largest radius (8 / 8 / 5) one of them is the pivot and the ring the others' balls'
// centres run on round its axis, R - r, starts from nothing. A ring under this share of r is tight
// (RolledCorner::tight): there the profile stations are resolved finer (round.cpp sample_profiles). Measured
// on a box corner (fine, coarse and CAD meshes), against OCCT's fillet beyond / within 1 r of the corner:
// 7.5 / 7.5 / 8 0.0094-0.0127 / 0.0073-0.0104 r (0.0131 r beyond with the usual stations, then refused),
// 8 / 8 / 5 0.0087-0.0104 / 0.0087-0.0090 r (OCCT: a B-spline corner).
constexpr double kRolledRingShare = 0.125;
// ... and where the larger round's chain stands square to the face the other two share, within this many
// degrees: then their balls' centres run on a circle round its axis (a torus, as OCCT's fillet makes it).
// Off square (a drafted pocket's wall corner into its floor) that rolling was measured too: refused
// result_invalid on coarse meshes from a 1 deg draft, 0.014 r off OCCT's corner on a 1 mm mesh at 10 deg.
constexpr double kSquareCornerDeg = 0.25;

// +1 where chain c's edge at its end vertex v is convex (the solid's angle there is under 180 degrees),
// -1 where it is concave, 0 where that edge has not two facets; n: the two facets' normals.
int convexity_at(const MeshTopology& input, const SharpChain& c, int v, Vec3 n[2]) {
  const int next = c.vertices.front() == v ? c.vertices[1] : c.vertices[c.vertices.size() - 2];
  const std::vector<int> sides = input.edge_facets(v, next);
  if (sides.size() != 2) return 0;
  for (int k = 0; k < 2; ++k) n[k] = input.facet_normal(sides[k]);
  int third = 0;  // the corner of sides[0] off the edge: behind the other side's plane on a convex edge
  while (input.F(sides[0], third) == v || input.F(sides[0], third) == next) ++third;
  return (input.corner(sides[0], third) - input.point(v)).dot(n[1]) < 0 ? 1 : -1;
}

// The radius chain c's round has where it ends at vertex v: its own law's value there (options_per_chain),
// or the call's one radius. A round is cut at a corner by carrying its ball at the end's setback (up to
// about 2 r before the vertex: ends.h) on to the corner's plane, so a law must hold its value over that
// stretch: *changing is set when it does not.
double radius_at_end(const RoundOptions& own, const SharpChain& c, int v, bool* changing) {
  *changing = false;
  if (own.radius_law.empty()) return own.radius;
  const RadiusLaw law(own, c, own.reach * own.max_radius());
  const bool at_start = c.vertices.front() == v;
  const double end = at_start ? 0.0 : c.length, r = law.at(end);
  const double span = std::min(c.length, kCornerLawHoldRadii * law.max_radius());
  for (int i = 1; i <= 8; ++i)
    if (std::abs(law.at(at_start ? span * i / 8 : c.length - span * i / 8) - r) > kSameCornerRadiusShare * own.effective_tolerance()) *changing = true;
  return r;
}

// The refusal of a chain (picked at `picked`) whose radius law still changes within kCornerLawHoldRadii of the
// corner at `corner`; `where` says more of that corner.
RoundingError law_still_changing(const Vec3& picked, const Vec3& corner, const std::string& where) {
  return RoundingError(ErrorCode::CornerNotBlendable, "the radius of the chain picked at " + format_point(picked) + " still changes within " +
                       format_number(kCornerLawHoldRadii) + " r of the corner at " + format_point(corner) + where +
                       ": a radius law into a corner must hold its value over that stretch (put its last control point there)");
}

// Rounds that meet at a corner (mitre or sphere) meet in one curve only when they have one radius there:
// the radius they share at vertex v (chains `ids`, each with its own options), or a refusal naming the
// vertex and the radii. Laws are welcome as long as they agree at the corner.
double shared_corner_radius(const MeshTopology& input, const std::vector<SharpChain>& chains, const std::vector<RoundOptions>& own,
                            const std::vector<size_t>& ids, int v, const std::vector<Vec3>& picked) {
  std::vector<double> r;
  for (size_t id : ids) {
    bool changing = false;
    r.push_back(radius_at_end(own[id], chains[id], v, &changing));
    if (changing) throw law_still_changing(picked[id], input.point(v), "");
  }
  const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
  if (*hi - *lo > kSameCornerRadiusShare * own[ids[0]].effective_tolerance())
    throw RoundingError(ErrorCode::CornerNotBlendable, "the chains picked at and around " + format_point(picked[ids[0]]) + " meet at " +
                        format_point(input.point(v)) + " with radii " + format_number(*lo) + " and " + format_number(*hi) +
                        " there: rounds of different radii meeting at a corner are not blended yet (give them one radius at that corner)");
  return *hi;
}

// Three rounds of one convexity ending at vertex v (chains `ids`, each with its own options): the one (0, 1
// or 2) whose radius there is the largest (the first of two that share it) and larger than the smallest, or
// -1. The two others then roll on around its end as one round, as OCCT's fillet makes that corner (a torus
// where they have one radius, else a ball whose radius goes from one's to the other's round the end;
// require_square_corner); one radius meets in the corner's ball (ball_corner). A law still changing near the
// corner gives -1 here, and is refused there (shared_corner_radius).
int larger_radius_at(const std::vector<SharpChain>& chains, const std::vector<RoundOptions>& own, const std::vector<size_t>& ids, int v) {
  double r[3];
  for (int i = 0; i < 3; ++i) {
    bool changing = false;
    r[i] = radius_at_end(own[ids[size_t(i)]], chains[ids[size_t(i)]], v, &changing);
    if (changing) return -1;
  }
  const double same = kSameCornerRadiusShare * own[ids[0]].effective_tolerance();
  for (int i = 0; i < 3; ++i) {  // the largest, and larger than the smallest (one radius: the corner's ball)
    const double a = r[(i + 1) % 3], b = r[(i + 2) % 3];
    if (r[i] >= std::max(a, b) - same && r[i] > std::min(a, b) + same) return i;
  }
  return -1;
}

// The radii at vertex v of a rolled corner's two rounds that roll on around the odd one, where they differ
// (the round they make together then goes from one radius to the other round the odd round's end,
// round_in_stages); {0, 0} where they are one radius. Refuses (corner_not_blendable, naming the vertex)
// different radii of which one is a law still changing near the corner.
std::array<double, 2> pair_radii_at(const MeshTopology& input, const std::vector<SharpChain>& chains, const std::vector<RoundOptions>& own,
                                    const RolledCorner& c, int v, const std::vector<Vec3>& picked) {
  std::array<double, 2> r{};
  bool changing[2] = {false, false};
  for (int i : {0, 1}) r[size_t(i)] = radius_at_end(own[c.pair[size_t(i)]], chains[c.pair[size_t(i)]], v, &changing[i]);
  if (std::abs(r[0] - r[1]) <= kSameCornerRadiusShare * own[c.pair[0]].effective_tolerance()) return {0.0, 0.0};
  for (int i : {0, 1})
    if (changing[i])
      throw law_still_changing(picked[c.pair[size_t(i)]], input.point(v), ", where it rolls on around another round into one of another radius");
  return r;
}

// Whether the ring the pair's balls' centres run on round the odd round's axis at vertex v is tight: the odd
// radius less the pair's larger one under kRolledRingShare of that one (RolledCorner::tight).
bool ring_is_tight(const std::vector<SharpChain>& chains, const std::vector<RoundOptions>& own, const RolledCorner& c, int v) {
  bool changing = false;
  const double R = radius_at_end(own[c.odd], chains[c.odd], v, &changing);
  const double r = std::max(radius_at_end(own[c.pair[0]], chains[c.pair[0]], v, &changing),
                            radius_at_end(own[c.pair[1]], chains[c.pair[1]], v, &changing));
  return R - r < kRolledRingShare * r;
}

// Refuses (corner_not_blendable, naming the vertex) a corner where chain `odd` of `ids` -- the larger
// round, made first -- does not stand square to the face the other two share (kSquareCornerDeg).
void require_square_corner(const MeshTopology& input, const std::vector<SharpChain>& chains, const std::vector<size_t>& ids, int odd,
                           int v, const std::vector<Vec3>& picked) {
  Vec3 a[2], b[2];
  convexity_at(input, chains[ids[size_t((odd + 1) % 3)]], v, a);
  convexity_at(input, chains[ids[size_t((odd + 2) % 3)]], v, b);
  Vec3 shared = a[0];  // the side of the first that is nearest to a side of the second
  double best = -2;
  for (const Vec3& x : a)
    for (const Vec3& y : b)
      if (x.dot(y) > best) best = x.dot(y), shared = (x + y).normalized();
  const SharpChain& c = chains[ids[size_t(odd)]];
  const int next = c.vertices.front() == v ? c.vertices[1] : c.vertices[c.vertices.size() - 2];
  const Vec3 along = (input.point(next) - input.point(v)).normalized();
  const double off = std::acos(std::min(1.0, std::abs(along.dot(shared)))) * 180 / M_PI;
  if (off > kSquareCornerDeg)
    throw RoundingError(ErrorCode::CornerNotBlendable, "the chain picked at " + format_point(picked[ids[size_t(odd)]]) + " meets two of a smaller radius at " +
                        format_point(input.point(v)) + ", leaning " + format_number(off) + " deg off square to the face they share: they roll on "
                        "around its end only where it stands square to that face (a torus); other corners of different radii need a corner "
                        "patch, not made yet (give them one radius at that corner)");
}

// The faces at vertex v, each known by one of its facets' normals (`normals`, unit), made the
// area-weighted normals of their facets around v: each facet counts for the face nearest its normal,
// within `same` (a cosine). A sliver's normal, from vertices stored to a few 1e-6 mm, can be 1e-4 rad off
// its face, which puts the corner's ball 1e-4 r off the one the rounds' balls touch; the face's large
// facets hold its plane far better.
void face_normals_at(const MeshTopology& input, int v, double same, std::vector<Vec3>& normals) {
  std::vector<Vec3> sum(normals.size(), Vec3::Zero());
  for (const int* f = input.facets_begin(v); f != input.facets_end(v); ++f) {
    const Vec3 a = input.corner(*f, 0), b = input.corner(*f, 1), c = input.corner(*f, 2);
    const Vec3 area = (b - a).cross(c - a);
    if (!(area.norm() > 0)) continue;
    size_t best = 0;
    for (size_t j = 1; j < normals.size(); ++j)
      if (area.dot(normals[j]) > area.dot(normals[best])) best = j;
    if (area.normalized().dot(normals[best]) > same) sum[best] += area;
  }
  for (size_t j = 0; j < normals.size(); ++j)
    if (sum[j].norm() > 0) normals[j] = sum[j].normalized();
}

// Three or more picked chains ending at vertex v (chains `ids`): their faces there (each chain's two
// sides, paired up: as many faces as chains, around the vertex), the convexity all of them share, and
// the ball of `radius` touching all the faces -- for four or more, only where their offsets meet in one point.
SphereCorner ball_corner(const MeshTopology& input, const std::vector<SharpChain>& chains, const std::vector<size_t>& ids,
                         int v, double radius, const RoundOptions& opt, const Vec3& picked) {
  SphereCorner corner;
  corner.vertex = input.point(v);
  const size_t n = ids.size();
  auto refuse = [&](const std::string& why) {
    throw RoundingError(ErrorCode::CornerNotBlendable, "the " + std::to_string(n) + " chains picked at and around " + format_point(picked) +
                        " meet at " + format_point(corner.vertex) + ": " + why);
  };
  corner.radius = radius;
  std::vector<Vec3> normals;  // the faces at the vertex, one normal each
  const double same = std::cos(opt.feature_angle_deg * M_PI / 180);
  int convex = 0;
  for (size_t id : ids) {
    const SharpChain& c = chains[id];
    const bool at_start = c.vertices.front() == v;
    const int next = at_start ? c.vertices[1] : c.vertices[c.vertices.size() - 2];
    corner.toward.push_back((input.point(v) - input.point(next)).normalized());
    Vec3 sides[2];
    const int sign = convexity_at(input, c, v, sides);
    if (sign == 0) refuse("an edge there has not two facets");
    std::array<size_t, 2> faces{};
    for (int k = 0; k < 2; ++k) {
      const auto it = std::find_if(normals.begin(), normals.end(), [&](const Vec3& o) { return o.dot(sides[k]) > same; });
      faces[size_t(k)] = size_t(it - normals.begin());
      if (it == normals.end()) normals.push_back(sides[k]);
    }
    corner.sides.push_back(faces);
    convex += sign;
  }
  if (normals.size() != n) refuse(std::to_string(normals.size()) + " faces meet there, not " + std::to_string(n));
  face_normals_at(input, v, same, normals);
  if (size_t(std::abs(convex)) != n) refuse("convex and concave edges mixed at one corner are not blended yet");
  double miss = 0;
  if (!corner_ball(corner.vertex, normals, corner.radius, convex > 0, &corner.centre, &corner.feet, &miss))
    refuse("its faces do not meet in one point");
  // A ball that misses a face by more than a share of the tolerance is not the rolling ball's corner.
  const double tolerance = opt.effective_tolerance();
  if (miss > kCornerBallMissShare * tolerance)
    refuse("no ball of radius " + format_number(corner.radius) + " touches all " + std::to_string(n) + " faces there (one is " + format_number(miss) +
           " off it): that corner needs an n-sided patch, not made yet");
  for (const Vec3& t : corner.toward)
    if ((corner.vertex - corner.centre).dot(t) <= 0) refuse("the ball touching its faces lies beyond a chain's end");
  return corner;
}

// Where chain i of a sphere corner (its index in the corner's chains) ends: on the plane through the
// ball's centre and its feet on the chain's two faces (across the line the two faces meet in, as the
// ball has them), the round's end profile the great-circle arc between those feet. `into`: along the
// chain, away from the corner.
CornerEnd sphere_end(const SphereCorner& corner, size_t i, const Vec3& into) {
  CornerEnd end;
  end.point = corner.vertex;
  end.plane_point = corner.centre;
  end.sphere = true;
  end.feet = {corner.feet[corner.sides[i][0]], corner.feet[corner.sides[i][1]]};
  const Vec3 across = (end.feet[0] - corner.centre).cross(end.feet[1] - corner.centre);
  end.normal = across.dot(into) < 0 ? Vec3(-across.normalized()) : Vec3(across.normalized());
  return end;
}

}  // namespace

std::vector<int> plan_stages(const MeshTopology& input, const std::vector<SharpChain>& chains, const std::vector<Vec3>& picked,
                             const RoundOptions& opt, std::vector<RolledCorner>* rolled) {
  const size_t n = chains.size();
  std::map<int, std::vector<size_t>> ending;  // vertex -> the open chains ending there
  for (size_t k = 0; k < n; ++k)
    if (!chains[k].closed) {
      ending[chains[k].vertices.front()].push_back(k);
      if (chains[k].vertices.back() != chains[k].vertices.front()) ending[chains[k].vertices.back()].push_back(k);
    }
  std::vector<size_t> group(n);  // chains joined by mitres and sphere corners (union-find)
  for (size_t k = 0; k < n; ++k) group[k] = k;
  auto root = [&](size_t k) {
    while (group[k] != k) k = group[k] = group[group[k]];
    return k;
  };
  std::vector<int> want(n, -1);  // the stage a rolled corner asks of a chain (-1: none)
  std::vector<Vec3> asked_at(n);
  auto ask = [&](size_t k, int stage, const Vec3& at) {
    if (want[k] >= 0 && want[k] != stage)
      throw RoundingError(ErrorCode::CornerNotBlendable, "the chain picked at " + format_point(picked[k]) + " is rounded after the others at " +
                          format_point(stage ? at : asked_at[k]) + " but before them at " + format_point(stage ? asked_at[k] : at) +
                          ": such corners are not made together yet (round them in two calls)");
    want[k] = stage, asked_at[k] = at;
  };
  std::vector<RoundOptions> own;  // each chain's options, made the first time a law meets a corner of three
  for (const auto& [v, ids] : ending) {
    // A flipped or non-manifold facet at a corner would pass for another face meeting there: the input's
    // fault, named as such before the corner is judged.
    if (ids.size() >= 2)
      check_facet_edges(input, std::vector<int>(input.facets_begin(v), input.facets_end(v)), "the corner at " + format_point(input.point(v)));
    if (ids.size() == 3) {
      int sign[3];
      Vec3 normals[2];
      for (int i = 0; i < 3; ++i) sign[i] = convexity_at(input, chains[ids[i]], v, normals);
      const int sum = sign[0] + sign[1] + sign[2];
      if (!opt.radius_law.empty() && own.empty()) own = options_per_chain(opt, chains, picked);
      int odd = -1;
      if (sign[0] && sign[1] && sign[2] && std::abs(sum) == 1)  // two of one convexity, one of the other
        odd = sign[0] != sign[1] ? (sign[0] != sign[2] ? 0 : 1) : 2;
      else if (sign[0] && sign[1] && sign[2] && !own.empty()) {  // one convexity: the larger of two radii, if any
        odd = larger_radius_at(chains, own, ids, v);
        if (odd >= 0) require_square_corner(input, chains, ids, odd, v, picked);
      }
      if (odd >= 0) {
        RolledCorner c;
        c.vertex = input.point(v), c.odd = ids[size_t(odd)], c.odd_convex = sign[odd] > 0;
        c.pair = {ids[size_t((odd + 1) % 3)], ids[size_t((odd + 2) % 3)]};
        c.pair_convex = sign[(odd + 1) % 3] > 0;
        if (!own.empty() && !constant_radius(own[c.odd]))
          throw RoundingError(ErrorCode::CornerNotBlendable, "the chain picked at " + format_point(picked[c.odd]) + " meets the others at " +
                              format_point(c.vertex) + ", where it is rounded first and they roll on around its end: a variable radius "
                              "along it is not blended there yet (give it one radius; theirs may vary)");
        if (!own.empty()) c.pair_radius = pair_radii_at(input, chains, own, c, v, picked);
        if (!own.empty() && std::abs(sum) == 3) c.tight = ring_is_tight(chains, own, c, v);
        ask(c.odd, 0, c.vertex), ask(c.pair[0], 1, c.vertex), ask(c.pair[1], 1, c.vertex);
        rolled->push_back(c);
        continue;
      }
    }
    for (size_t i = 1; i < ids.size(); ++i) group[root(ids[i])] = root(ids[0]);
  }
  std::map<size_t, std::pair<int, size_t>> group_stage;  // group -> (stage, the chain that asked it)
  for (size_t k = 0; k < n; ++k) {
    if (want[k] < 0) continue;
    const auto [it, fresh] = group_stage.insert({root(k), {want[k], k}});
    if (!fresh && it->second.first != want[k]) {
      const size_t j = it->second.second;
      throw RoundingError(ErrorCode::CornerNotBlendable, "the chains picked at " + format_point(picked[k]) + " and " + format_point(picked[j]) +
                          " meet at corners, but one is rounded before and the other after its neighbours (at " + format_point(asked_at[k]) +
                          " and " + format_point(asked_at[j]) + "): such corners are not made together yet (round them in two calls)");
    }
  }
  std::vector<int> stage(n, 0);
  for (size_t k = 0; k < n; ++k) {
    const auto it = group_stage.find(root(k));
    if (it != group_stage.end()) stage[k] = it->second.first;
  }
  return stage;
}

// The corners where picked chains meet: a vertex where exactly two of them end is blended by a miter, as
// OCCT blends two rounds meeting where a third edge stays sharp: both rounds run on to the plane through
// the vertex bisecting the two chains and stop there, meeting along one curve (exact when their radii
// and faces match there; otherwise the second round's rows find no vertex of the first's to share and
// the call is refused, naming the corner). Where three or more end at a vertex, with one convexity, they
// meet in the ball touching all their faces (sphere_corner.h; four or more only where the faces' offsets
// meet in one point). Each chain may have a radius of its own or a law (its control points, options_per_chain)
// as long as the rounds meeting at a corner have one radius there. A chain running on through another's
// end, different radii at one corner, and four faces with no common ball are refused, naming the vertex.
std::vector<NetworkPart> find_corners(const MeshTopology& input, const std::vector<SharpChain>& chains, const std::vector<Vec3>& picked,
                                      const RoundOptions& opt, std::vector<std::pair<SphereCorner, size_t>>* spheres) {
  std::vector<NetworkPart> out(chains.size());
  const std::vector<RoundOptions> own = options_per_chain(opt, chains, picked);
  auto into = [](const SharpChain& c, bool at_start) {
    const size_t n = c.points.size();
    return at_start ? Vec3((c.points[1] - c.points[0]).normalized()) : Vec3((c.points[n - 2] - c.points[n - 1]).normalized());
  };
  std::map<int, std::pair<size_t, std::vector<size_t>>> balls;  // corner vertex -> its ball in `spheres`, the chains in its order
  for (size_t k = 0; k < chains.size(); ++k) {
    if (chains[k].closed) continue;
    for (bool at_start : {true, false}) {
      const int v = at_start ? chains[k].vertices.front() : chains[k].vertices.back();
      std::vector<std::pair<size_t, bool>> others;  // (chain, meets there at its start)
      for (size_t j = 0; j < chains.size(); ++j) {
        if (j == k || std::find(chains[j].vertices.begin(), chains[j].vertices.end(), v) == chains[j].vertices.end()) continue;
        const bool j_start = !chains[j].closed && chains[j].vertices.front() == v;
        if (chains[j].closed || (!j_start && chains[j].vertices.back() != v))
          throw RoundingError(ErrorCode::CornerNotBlendable, "the chain picked at " + format_point(picked[k]) + " ends at " + format_point(input.point(v)) +
                              " on the side of the chain picked at " + format_point(picked[j]) + ": a round running into another's side is not made yet");
        others.push_back({j, j_start});
      }
      if (others.empty()) continue;
      if (others.size() >= 2) {
        std::vector<size_t> ids{k};
        for (const auto& o : others) ids.push_back(o.first);
        const double radius = shared_corner_radius(input, chains, own, ids, v, picked);
        // One ball for the corner, made at its first chain: every round ending there ends on it.
        auto made = balls.find(v);
        if (made == balls.end()) {
          made = balls.emplace(v, std::make_pair(spheres->size(), ids)).first;
          spheres->push_back({ball_corner(input, chains, ids, v, radius, opt, picked[k]), k});
        }
        const auto& [index, order] = made->second;
        const size_t i = size_t(std::find(order.begin(), order.end(), k) - order.begin());
        out[k].corners.push_back(sphere_end((*spheres)[index].first, i, into(chains[k], at_start)));
        continue;
      }
      shared_corner_radius(input, chains, own, {k, others[0].first}, v, picked);
      const Vec3 d = into(chains[k], at_start) - into(chains[others[0].first], others[0].second);
      out[k].corners.push_back({input.point(v), d.normalized(), others[0].first < k});
    }
  }
  return out;
}

// Each chain's options: a radius law keeps the control points nearest to that chain (a point at a corner,
// as near to several chains, belongs to each of them); a chain without a control point is an error, as is
// a point far from every chain.
std::vector<RoundOptions> options_per_chain(const RoundOptions& opt, const std::vector<SharpChain>& chains,
                                            const std::vector<Vec3>& picked) {
  std::vector<RoundOptions> out(chains.size(), opt);
  if (opt.radius_law.empty() || chains.size() < 2) return out;
  for (RoundOptions& o : out) o.radius_law.clear(), o.tolerance = opt.effective_tolerance();  // one for all
  for (const RadiusControl& c : opt.radius_law) {
    std::vector<double> d(chains.size());
    for (size_t k = 0; k < chains.size(); ++k) chains[k].project(c.point, &d[k]);
    const double best_d = *std::min_element(d.begin(), d.end());
    // A point at a corner (as near to several chains) gives each of them its radius there.
    const double tie = 1e-9 * std::max(1.0, c.point.cwiseAbs().maxCoeff());
    for (size_t k = 0; k < chains.size(); ++k)
      if (d[k] <= best_d + tie) out[k].radius_law.push_back(c);  // RadiusLaw reports a point too far from its chain
  }
  for (size_t k = 0; k < chains.size(); ++k)
    if (out[k].radius_law.empty())
      throw RoundingError(ErrorCode::InvalidInput, "no radius control point lies on the chain picked at " + format_point(picked[k]) +
                          ": give each chain at least one (point, radius)");
  return out;
}

PickedChains pick_chains(const MeshTopology& input, const std::vector<Vec3>& seeds, const RoundOptions& opt) {
  PickedChains out;
  std::set<std::vector<int>> seen;
  for (const Vec3& seed : seeds) {
    if (!seed.allFinite()) throw RoundingError(ErrorCode::InvalidInput, "a seed has a NaN or infinite coordinate");
    SharpChain c = trace_chain(input, seed, opt.feature_angle_deg, opt.reach * opt.max_radius());
    std::vector<int> key = c.vertices;
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) continue;
    out.picked.push_back(seed);
    out.chains.push_back(std::move(c));
  }
  return out;
}

void plan_corners(const MeshTopology& input, const PickedChains& picked, const RoundOptions& opt, NetworkPlan& plan) {
  const std::vector<SharpChain>& chains = picked.chains;
  auto ending_at = [&](const Vec3& point, const std::vector<size_t>& among) {  // the chains with an end there
    std::vector<int> out;
    for (size_t k : among) {
      const SharpChain& c = chains[k];
      if (!c.closed && (input.point(c.vertices.front()) == point || input.point(c.vertices.back()) == point)) out.push_back(int(k));
    }
    return out;
  };
  try {
    std::vector<RolledCorner> rolled;
    const std::vector<int> stage = plan_stages(input, chains, picked.picked, opt, &rolled);
    for (const RolledCorner& c : rolled) plan.corners.push_back({c.vertex, "rolled", {int(c.odd), int(c.pair[0]), int(c.pair[1])}});
    std::vector<size_t> first;  // the chains find_corners sees: all of them, or those made first
    PickedChains made_first;
    for (size_t k = 0; k < chains.size(); ++k)
      if (rolled.empty() || stage[k] == 0) first.push_back(k), made_first.chains.push_back(chains[k]), made_first.picked.push_back(picked.picked[k]);
    options_per_chain(opt, made_first.chains, made_first.picked);
    std::vector<std::pair<SphereCorner, size_t>> spheres;
    const std::vector<NetworkPart> parts = find_corners(input, made_first.chains, made_first.picked, opt, &spheres);
    for (const auto& [corner, chain] : spheres) plan.corners.push_back({corner.vertex, "sphere", ending_at(corner.vertex, first)});
    for (const NetworkPart& part : parts)
      for (const CornerEnd& c : part.corners)
        if (!c.sphere && !c.other_made) plan.corners.push_back({c.point, "mitre", ending_at(c.point, first)});
  } catch (const RoundingError& e) {
    if (e.code != ErrorCode::CornerNotBlendable) throw;
    plan.refused = true;
    plan.refusal = e.what();
  }
}

std::function<bool(const Vec3&)> within_reach_of(const std::vector<SharpChain>& chains, const std::vector<RoundOptions>& options) {
  std::vector<double> reach;
  for (const RoundOptions& o : options) reach.push_back(o.reach * o.max_radius());
  // Each chain's segments indexed (the flat patches' smoothing asks this of every point it tries: a sharpened
  // chain of a few hundred points took 50 s under the sanitizers, segment by segment).
  auto indexed = std::make_shared<std::vector<SharpChain>>(chains);
  for (SharpChain& c : *indexed) c.index_segments();
  return [indexed, reach](const Vec3& p) {
    const std::vector<SharpChain>& chains = *indexed;
    for (size_t k = 0; k < chains.size(); ++k) {
      double d;
      chains[k].project(p, &d);
      if (d <= reach[k]) return true;
    }
    return false;
  };
}

}  // namespace meshround
