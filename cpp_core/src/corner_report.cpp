#include "corner_report.h"

#include "meshround/surface.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace meshround {

namespace {

// How near a surface or plane a vertex must be to count as on a seam: a share of the radius (the seams'
// own points are exact to the engine's precision, far inside this), and float32 coordinates' precision.
constexpr double kOnSurfaceShare = 0.05;
constexpr double kOnPlaneShare = 1e-4;
// A point counts as on a round's arc within this angle (degrees) beyond its contacts.
constexpr double kArcSlackDeg = 0.5;

// The point of a polyline nearest p: segment i and parameter t on it. The first and last segments run on
// beyond the line's ends: a round's end carried on to a corner plane (round.cpp end_cut_profiles) goes on
// straight along the chain past its last ball.
std::pair<size_t, double> nearest_on(const std::vector<Vec3>& line, const Vec3& p) {
  std::pair<size_t, double> best{0, 0.0};
  double best_d2 = INFINITY;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec3 a = line[i], d = line[i + 1] - a;
    const double lo = i == 0 ? -INFINITY : 0.0, hi = i + 2 == line.size() ? INFINITY : 1.0;
    const double t = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), lo, hi) : 0.0;
    const double d2 = (a + t * d - p).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = {i, t};
  }
  return best;
}

Vec3 at(const std::vector<Vec3>& line, std::pair<size_t, double> where) {
  const auto [i, t] = where;
  return i + 1 < line.size() ? Vec3((1 - t) * line[i] + t * line[i + 1]) : line.back();  // (t may lie past an end)
}

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / M_PI;
}

// A point on round k: its ball's centre (the spine's nearest point), the exact surface's misfit there, and
// whether it lies on the ball's arc between the two contacts (the flat faces beyond are near the ball too).
struct OnRound {
  Vec3 centre;
  double misfit = INFINITY;
  bool on_arc = false;
};

// The ball's radius there is its own (the distance from its centre to its contacts, between the two
// nearest balls): a round of one radius or of a law alike.
OnRound on_round(const RoundedChain& round, const Vec3& p) {
  OnRound o;
  const auto where = nearest_on(round.spine, p);
  o.centre = at(round.spine, where);
  const auto [i, t] = where;
  const size_t j = std::min(i + 1, round.spine.size() - 1);
  const double w = std::clamp(t, 0.0, 1.0);
  const double radius = (1 - w) * (round.contacts[0][i] - round.spine[i]).norm() + w * (round.contacts[0][j] - round.spine[j]).norm();
  o.misfit = std::abs((p - o.centre).norm() - radius);
  const Vec3 a = at(round.contacts[0], where) - o.centre, b = at(round.contacts[1], where) - o.centre, d = p - o.centre;
  o.on_arc = angle_deg(a, d) + angle_deg(d, b) <= angle_deg(a, b) + kArcSlackDeg;
  return o;
}

Vec3 facet_normal(const Points& V, const Triangles& F, int f) {
  const Vec3 a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
  return (b - a).cross(c - a).normalized();
}

// The turn across each seam edge (both ends flagged in `seam`), measured between its two facets, into
// c.seam_turn_deg; `at_edge(middle)` is called at every seam edge's middle.
template <class AtEdge>
void seam_edges(const Points& V, const Triangles& F, const std::vector<char>& seam, AtEdge at_edge, CornerReport& c) {
  std::map<std::pair<int, int>, std::vector<int>> edges;  // seam edge -> its facets
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (seam[size_t(a)] && seam[size_t(b)]) edges[{std::min(a, b), std::max(a, b)}].push_back(int(f));
    }
  for (const auto& [edge, facets] : edges) {
    at_edge(Vec3(0.5 * (V.row(edge.first) + V.row(edge.second))));
    if (facets.size() == 2) c.seam_turn_deg = std::max(c.seam_turn_deg, angle_deg(facet_normal(V, F, facets[0]), facet_normal(V, F, facets[1])));
  }
}

// One corner's seams: `on_seam(p)` picks the seam vertices, `exact(p)` gives the normals of the exact
// surfaces meeting there and `misfit(p)` the larger distance from them, taken at the seam vertices and
// at the middles of the seam edges (the chords between them). The turn across each seam edge is measured
// between its two facets.
template <class OnSeam, class Exact, class Misfit>
void measure_seams(const Points& V, const Triangles& F, OnSeam on_seam, Exact exact, Misfit misfit, CornerReport& c) {
  std::vector<char> seam(size_t(V.rows()), 0);
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (on_seam(Vec3(V.row(v)))) {
      seam[size_t(v)] = 1, ++c.seam_vertices;
      const auto [n0, n1] = exact(Vec3(V.row(v)));
      c.normal_jump_deg = std::max(c.normal_jump_deg, angle_deg(n0, n1));
      c.deviation = std::max(c.deviation, misfit(Vec3(V.row(v))));
    }
  seam_edges(V, F, seam, [&](const Vec3& middle) { c.deviation = std::max(c.deviation, misfit(middle)); }, c);
}

CornerReport mitre_report(const Points& V, const Triangles& F, const CornerEnd& end, int i, int j,
                          const std::vector<RoundedChain>& rounds, const std::vector<double>& radii) {
  CornerReport c;
  c.vertex = end.point, c.kind = "mitre", c.chains = {i, j}, c.radius = std::max(radii[i], radii[j]);
  const double r = c.radius, slack = kOnPlaneShare * std::max(r, end.point.cwiseAbs().maxCoeff() * 1e-2);
  auto on_both = [&](const Vec3& p, OnRound* oi, OnRound* oj) {
    *oi = on_round(rounds[size_t(i)], p), *oj = on_round(rounds[size_t(j)], p);
    return oi->on_arc && oj->on_arc && oi->misfit <= kOnSurfaceShare * radii[size_t(i)] && oj->misfit <= kOnSurfaceShare * radii[size_t(j)];
  };
  auto on_seam = [&](const Vec3& p) {
    OnRound oi, oj;
    return std::abs((p - end.point).dot(end.normal)) <= slack && (p - end.point).norm() <= 4 * r && on_both(p, &oi, &oj);
  };
  auto exact = [&](const Vec3& p) {
    OnRound oi, oj;
    on_both(p, &oi, &oj);
    return std::pair<Vec3, Vec3>{p - oi.centre, p - oj.centre};
  };
  auto misfit = [&](const Vec3& p) {
    return std::max(on_round(rounds[size_t(i)], p).misfit, on_round(rounds[size_t(j)], p).misfit);
  };
  measure_seams(V, F, on_seam, exact, misfit, c);
  return c;
}

CornerReport sphere_report(const Points& V, const Triangles& F, const SphereCorner& ball, const std::vector<int>& ids,
                           const std::vector<RoundedChain>& rounds) {
  CornerReport c;
  c.vertex = ball.vertex, c.kind = "sphere", c.chains = ids, c.radius = ball.radius;
  const TopoDS_Face face = sphere_patch_face(ball.centre, ball.radius, ball.feet, ball.vertex - ball.centre);
  if (!face.IsNull()) c.brep = face_to_brep(face);
  const double r = ball.radius, slack = kOnPlaneShare * std::max(r, ball.vertex.cwiseAbs().maxCoeff() * 1e-2);
  auto on_ball = [&](const Vec3& p) { return std::abs((p - ball.centre).norm() - r) <= kOnSurfaceShare * r; };
  auto in_patch = [&](const Vec3& p) {
    return on_ball(p) && std::all_of(ball.toward.begin(), ball.toward.end(), [&](const Vec3& t) { return (p - ball.centre).dot(t) >= -slack; });
  };
  auto plane_of = [&](const Vec3& p) {  // the round whose end plane p lies on, or -1
    for (size_t m = 0; m < ball.toward.size(); ++m)
      if (std::abs((p - ball.centre).dot(ball.toward[m])) <= slack) return int(m);
    return -1;
  };
  auto on_seam = [&](const Vec3& p) { return in_patch(p) && plane_of(p) >= 0; };
  auto exact = [&](const Vec3& p) {
    const int k = ids[size_t(plane_of(p))];
    return std::pair<Vec3, Vec3>{p - ball.centre, p - on_round(rounds[size_t(k)], p).centre};
  };
  auto misfit = [&](const Vec3& p) {
    const int m = plane_of(p);
    const double to_ball = std::abs((p - ball.centre).norm() - r);
    return m < 0 ? to_ball : std::max(to_ball, on_round(rounds[size_t(ids[size_t(m)])], p).misfit);
  };
  measure_seams(V, F, on_seam, exact, misfit, c);
  // The patch's own facets: their vertices and centroids against the ball.
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Vec3 a = V.row(F(f, 0)), b = V.row(F(f, 1)), d = V.row(F(f, 2));
    if (!in_patch(a) || !in_patch(b) || !in_patch(d)) continue;
    for (const Vec3& p : {a, b, d, Vec3((a + b + d) / 3)}) c.deviation = std::max(c.deviation, std::abs((p - ball.centre).norm() - r));
  }
  return c;
}

}  // namespace

std::vector<CornerReport> report_corners(const Points& V, const Triangles& F, const std::vector<NetworkPart>& network,
                                         const std::vector<std::pair<SphereCorner, size_t>>& spheres,
                                         const std::vector<RoundedChain>& rounds, const std::vector<double>& radii) {
  std::vector<CornerReport> out;
  // Mitres: the two chains with a (non-sphere) corner end at the same point.
  std::vector<std::pair<const CornerEnd*, int>> ends;
  for (size_t k = 0; k < network.size(); ++k)
    for (const CornerEnd& e : network[k].corners)
      if (!e.sphere) ends.push_back({&e, int(k)});
  std::vector<char> done(ends.size(), 0);
  for (size_t a = 0; a < ends.size(); ++a)
    for (size_t b = a + 1; b < ends.size() && !done[a]; ++b)
      if (!done[b] && (ends[a].first->point - ends[b].first->point).norm() <= 1e-9 * std::max(1.0, ends[a].first->point.cwiseAbs().maxCoeff())) {
        out.push_back(mitre_report(V, F, *ends[a].first, ends[a].second, ends[b].second, rounds, radii));
        done[a] = done[b] = 1;
      }
  for (const auto& [ball, k] : spheres) {
    std::vector<int> ids;
    for (size_t j = 0; j < network.size(); ++j)
      for (const CornerEnd& e : network[j].corners)
        if (e.sphere && (e.point - ball.vertex).norm() <= 1e-9 * std::max(1.0, ball.vertex.cwiseAbs().maxCoeff())) ids.push_back(int(j));
    if (ids.size() == ball.toward.size()) out.push_back(sphere_report(V, F, ball, ids, rounds));
  }
  return out;
}

CornerReport report_rolled_corner(const Points& V, const Triangles& F, const RolledCorner& corner, const RoundedChain& odd,
                                  const RoundedChain& rolled, double odd_radius, int odd_index, int rolled_index) {
  CornerReport c;
  c.vertex = corner.vertex, c.kind = "rolled", c.chains = {odd_index, rolled_index}, c.radius = odd_radius;
  const double r = odd_radius, s = corner.odd_convex ? 1 : -1, t = corner.pair_convex ? 1 : -1;
  double near = 4 * r;  // the neighbourhood: 4 x the larger of the two rounds' radii
  for (size_t i = 0; i < rolled.spine.size(); ++i) near = std::max(near, 4 * (rolled.spine[i] - rolled.contacts[0][i]).norm());
  // The rolled round's balls near the vertex that lean on the odd round (their contact on it): the angle
  // between the two outward normals at the contact, s (p - odd centre) and t (p - rolled centre), s and t
  // +1 where the odd and the rolled round are convex (their balls in the solid), -1 where concave.
  int side = -1;
  for (size_t i = 0; i < rolled.spine.size(); ++i)
    for (int k = 0; k < 2; ++k) {
      const Vec3 p = rolled.contacts[k][i];
      if ((p - corner.vertex).norm() > near) continue;
      const OnRound o = on_round(odd, p);
      if (!o.on_arc || o.misfit > kOnSurfaceShare * r) continue;
      side = k;
      c.normal_jump_deg = std::max(c.normal_jump_deg, angle_deg(s * (p - o.centre), t * (p - rolled.spine[i])));
    }
  if (side < 0) return c;
  // The mesh's seam: its vertices on the odd round along that contact line, their distance (and the seam
  // edges' middles') from the odd round's exact surface, and the turn across the seam edges.
  std::vector<char> seam(size_t(V.rows()), 0);
  auto misfit = [&](const Vec3& p) { return on_round(odd, p).misfit; };
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const Vec3 p = V.row(v);
    if ((p - corner.vertex).norm() > near) continue;
    const OnRound o = on_round(odd, p);
    if (o.on_arc && o.misfit <= kOnSurfaceShare * r && (at(rolled.contacts[side], nearest_on(rolled.contacts[side], p)) - p).norm() <= kOnSurfaceShare * r)
      seam[size_t(v)] = 1, ++c.seam_vertices, c.deviation = std::max(c.deviation, o.misfit);
  }
  seam_edges(V, F, seam, [&](const Vec3& middle) { c.deviation = std::max(c.deviation, misfit(middle)); }, c);
  return c;
}

}  // namespace meshround
