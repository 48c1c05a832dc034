// The strip recognition for a round with one side curved along it (strip.h, strip_facets.h).
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "facet_quality.h"
#include "strip_facets.h"
#include "strip_line.h"

namespace meshround::strip_detail {

// A strip whose side B curves along the round (a wall curved in plan, vertical or drafted; side A flat):
// side A is the largest plane beside the flood, side B the facets meeting A's normal at the angle most of
// the area beyond the round has (the opening, one angle all along: a wall ruled across the round); the
// strip is what turns between them. Each station (border B vertex; ordered along the border, nearest next)
// gets its frame: plane A and side B's tangent plane there (normal to the axis and to side B's line in the
// station's section, fitted to the side-B vertices nearly in it), their corner line and the ball's centre
// direction; each strip vertex takes the frame of its nearest station, its corner point moved into its
// own section on a smooth curve through the stations' corners (CornerCurve), the stations' tilts smoothed
// along the line first (smooth_tilts). The corner line is the stations' corner points: the sharp edge
// rebuilt section by section, exact at the stations where side B is ruled across the round (the edge is
// their polygon). A round all around a loop (a circular pocket's or boss's rim: no end) is one too, its
// corner line a closed polygon.
constexpr double kStationTurnDeg = 15;  // largest turn of the corner line between two stations
constexpr double kShapedDeg = 10;       // a side-B facet with a smaller angle is a sliver (its normal not trusted)
constexpr double kFineShare = 0.25;     // x the round's height: a mesh this fine has its wall fitted off a sliver border
constexpr double kJoinDeg = 80;         // see recognise_curved's flood

// What recognise_curved learns of a strip, pass by pass (each pass below fills its part; the strip itself,
// RoundStrip, gets plane A, its roles, borders and, last, its stations and frames).
struct CurvedPasses {
  double fd2 = 0;      // twice the flat angle: facets within it of a plane's normal lie on the plane (deg)
  double opening = 0;  // side B's angle to plane A, area-weighted over side B's facets (deg)
  double spread = 0;   // their spread about it (deg)
  std::vector<std::pair<int, int>> border_b;      // (border B vertex, the side-B facet across the border there)
  std::vector<std::pair<int, int>> border_edges;  // (strip facet, edge) of each border B edge
  bool closed = false;                            // a round all around a loop (a circular pocket's or boss's rim)
  std::vector<StripFrame> station;                // one per border B vertex, in order along the corner line
  std::vector<int> station_vertex;                // the border B vertex of each
  bool walked = false;                            // a loop's stations ordered along its border (order_around)

  // A facet's side by its angle to plane A: 0 on side A, 1 on side B, -1 neither (the round, an end face).
  int side_of(Facets& fx, const RoundStrip& strip, int g) const {
    const double a = angle_deg(fx.normal(g), strip.normal[0]);
    if (a < fd2) return 0;
    if (a > opening - std::max(fd2, 2 * spread)) return 1;
    return -1;
  }
  // A facet turning clearly like neither side (twice side_of's margins off them): the round's own (a wall's
  // chord, tilted by 1.5 deg, is near the wall's angle though side_of may not take it).
  bool round_like(Facets& fx, const RoundStrip& strip, int g) const {
    const double a = angle_deg(fx.normal(g), strip.normal[0]);
    return a >= 2 * fd2 && a <= opening - 2 * std::max(fd2, 2 * spread);
  }
};

// Plane A (strip.normal[0], offset[0]): the largest group of coplanar facets beside the flood, its plane
// fitted to the group's vertices.
void fit_side_a(const MeshTopology& mesh, Facets& fx, const std::vector<int>& beside, double fd2, const Vec3& where, RoundStrip& strip) {
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
}

// The opening (pass.opening, pass.spread): the largest angle to side A that a tenth of the area of the
// fullest angle has, in bins of 2 flat_deg (side B's facets: one angle all along; the round's spread over the
// angles between).
void measure_opening(Facets& fx, const std::vector<int>& flood, const std::vector<int>& beside, const RoundStrip& strip,
                     const Vec3& where, CurvedPasses& pass) {
  const double fd2 = pass.fd2;
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
  // The opening is the area-weighted mean angle from kWallSpreadBins below that bin to 1.5 above it, and
  // side B's facets those within twice their spread about it (fd2 at least) or beyond: a coarse mesh of a
  // curved wall (1.4 mm facets around a wall corner of R 6) tilts its facets by up to 3 degrees either way.
  // Caps are left out (strip_facets.h: their normals say little).
  constexpr double kWallSpreadBins = 5;
  double opening = 0, opening_area = 0, opening_sq = 0;
  for (const std::vector<int>* list : {&flood, &beside})
    for (int f : *list) {
      const double a = angle_deg(fx.normal(f), strip.normal[0]), off = a - (top_bin + 0.5) * fd2;
      if (!fx.cap(f) && off >= -kWallSpreadBins * fd2 && off <= 1.5 * fd2)
        opening += fx.area(f) * a, opening_sq += fx.area(f) * a * a, opening_area += fx.area(f);
    }
  opening /= opening_area;
  const double spread = std::sqrt(std::max(0.0, opening_sq / opening_area - opening * opening));
  if (opening < 4 * fd2 || opening > 180 - 4 * fd2) not_a_round("its sides do not meet at an angle (no sharp edge to rebuild)", where);
  pass.opening = opening, pass.spread = spread;
}

// The strip's flood (as flood_strip, the sides told by their angle to side A): its facets and roles, border B's
// vertices and edges (pass.border_b, border_edges), the end edges, and plane A's border count.
void flood_curved(const MeshTopology& mesh, Facets& fx, int f0, const SharpenOptions& o, const Vec3& where, RoundStrip& strip,
                  std::vector<std::pair<int, int>>& end_edges, CurvedPasses& pass) {
  auto side_of = [&](int g) { return pass.side_of(fx, strip, g); };
  auto& border_b = pass.border_b;
  auto& border_edges = pass.border_edges;
  // Cap g met by the strip at its apex (edge (a, b) of strip facet f is not g's longest side), with a facet
  // across its longest side that turns by less than strip_turn_deg from f: g lies between the round and a
  // side, or inside the round (a mesher's folded sliver where the S plate's torus meets its cylinder, on its
  // 3.5 mm mesh: its normal 88 deg off the round's, taken for the wall's and an end face mid-strip).
  auto cap_between = [&](int g, int f, int a, int b) {
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if ((mesh.corner(g, j) - mesh.corner(g, (j + 1) % 3)).squaredNorm() > (mesh.corner(g, k) - mesh.corner(g, (k + 1) % 3)).squaredNorm()) k = j;
    const int p = mesh.F(g, k), q = mesh.F(g, (k + 1) % 3);
    if ((p == a && q == b) || (p == b && q == a)) return false;
    const int h = fx.across(g, k);
    if (h < 0 || fx.cap(h) || !fx.smooth(f, h)) return false;
    if (side_of(h) >= 0) return !strip.facet_set.count(h);
    // Inside the round: the facets across its longest side and its other short side are clearly the round's
    // too (not a cap of an end face, its longest side on the end's seam with the round, nor one between the
    // round and a tilted chord of the wall).
    for (int j = 0; j < 3; ++j) {
      const int u = mesh.F(g, j), w = mesh.F(g, (j + 1) % 3);
      if (j == k || (u == a && w == b) || (u == b && w == a)) continue;
      const int e = fx.across(g, j);
      return e >= 0 && !fx.cap(e) && pass.round_like(fx, strip, e) && pass.round_like(fx, strip, h) && fx.smooth(f, e);
    }
    return false;
  };
  flood_from(mesh, fx, f0, o, strip, end_edges, [&](int f, int k, int g) {
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
    const int side = g >= 0 ? side_of(g) : -1;
    // (a facet turning like neither side joins while it turns by less than kJoinDeg: a mesher's folded
    // sliver on a seam between two round faces turns by a little over strip_turn_deg; from a cap -- a
    // seam's facet with its corners nearly in a line, between a round's straight part and its torus around
    // a wall corner, its normal 130 degrees off its neighbours' -- the turn is measured from the strip's
    // facets beside the cap instead)
    // A cap between the round and a side joins the strip whatever its normal, which says nothing: a mesher's
    // caps along the contact line, their longest side on it and the apex 0.009 mm up the round, face up to
    // 124 deg from side A. Taken as side B, the border ran through the apex and its station's wall plane
    // leaned by the cap's normal (the corner line 2 mm off in plan); turning by more than strip_turn_deg from
    // the round beside it, one was taken for an end face mid-strip. (A cap on an end face's seam with the
    // round has the end face across its longest side, turning by 90 deg from the round: left to the rules
    // below.)
    if (g >= 0 && fx.cap(g) && cap_between(g, f, a, b)) return true;
    if (g >= 0 && side < 0) {
      const double join = std::max(o.strip_turn_deg, kJoinDeg);
      if (angle_deg(fx.normal(f), fx.normal(g)) < join) return true;
      if (fx.cap(f))
        for (int j = 0; j < 3; ++j) {
          const int h = fx.across(f, j);
          if (h >= 0 && h != g && strip.facet_set.count(h) && !fx.cap(h) && angle_deg(fx.normal(h), fx.normal(g)) < join) return true;
        }
    }
    if (side >= 0 && fx.smooth(f, g)) {
      for (int v : {a, b}) strip.role[v] = side ? StripRole::BorderB : StripRole::BorderA;
      if (side) border_b.push_back({a, g}), border_b.push_back({b, g}), border_edges.push_back({f, k});
    } else {
      end_edges.push_back({f, k});
    }
    return false;
  });
  pass.closed = end_edges.empty();
  // Plane A's border.
  int n = 0;
  for (const auto& [v, role] : strip.role)
    if (role == StripRole::BorderA) ++n;
  if (n < 2) not_a_round("its flat side's border has fewer than two vertices", where);
  strip.border_count[0] = n;
}

// Side B's tangent plane at border B vertex b, its normal `nB` from the facets around b made sharper (the
// facets of a tessellated curved wall tilt by their chords): side B's line in b's own section, through the
// side-B vertices within three rings of b that lie nearly in that section (|along| < 0.35 of the ring's mean
// edge), projected into it; nB is normal to it and to the axis, and the plane passes through *on_plane.
// The line is fitted to those vertices clear of the border when they spread over a fifth of that edge: a
// border vertex may sit a hair up the round (a mesher's rows of slivers along the contact line, 0.66 and
// 5.6 deg up the S plate's 4 mm round on a 1 mm mesh, 0.02 mm off the wall), and a plane through it tilts.
// Else it runs from b through the others.
Vec3 wall_normal_in_section(const MeshTopology& mesh, Facets& fx, const RoundStrip& strip, const CurvedPasses& pass,
                            const std::unordered_set<int>& border, int b, bool on_sliver, Vec3 nB, Vec3* on_plane) {
  auto side_of = [&](int g) { return pass.side_of(fx, strip, g); };
  const Vec3 t = strip.normal[0].cross(nB).normalized(), pb = mesh.point(b);
  *on_plane = pb;
  std::unordered_set<int> ring{b};
  for (int step = 0; step < 3; ++step) {
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
  std::vector<Vec3> section;  // the ring's vertices in b's section, relative to b, projected into it
  for (int v : ring) {
    const Vec3 d = mesh.point(v) - pb;
    if (v != b && std::abs(t.dot(d)) <= 0.35 * h && d.norm() >= 0.2 * h) section.push_back(d - t * t.dot(d));
  }
  // Those clear of the border, within `along` of the section (out to a mean edge where too few are nearer).
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  Vec3 mean = Vec3::Zero();
  double spread = 0;
  // (only on a fine mesh, edges under a quarter of the round's height: there the wall's curve in plan leaves a
  // window of an edge each way within a hair of its tangent plane; on a coarse one b is on the wall)
  const double height = std::abs(strip.normal[0].dot(pb) - strip.offset[0]);
  for (double along : {0.35 * h, h}) {
    if (!on_sliver || h > kFineShare * height) break;
    std::vector<Vec3> clear;
    for (int v : ring) {
      const Vec3 d = mesh.point(v) - pb;
      if (!border.count(v) && std::abs(t.dot(d)) <= along) clear.push_back(d - t * t.dot(d));
    }
    C.setZero(), mean.setZero(), spread = 0;
    for (const Vec3& q : clear) mean += q / double(clear.size());
    for (const Vec3& q : clear) C += (q - mean) * (q - mean).transpose(), spread = std::max(spread, (q - mean).norm());
    if (clear.size() >= 2 && spread >= 0.2 * h) break;
  }
  if (spread < 0.2 * h) {
    C.setZero(), mean.setZero();
    for (const Vec3& q : section) C += q * q.transpose() / q.squaredNorm();
    if (section.empty()) return nB;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
  const Vec3 down = eig.eigenvectors().col(2).normalized();
  Vec3 fit = down.cross(t).normalized();
  if (fit.dot(nB) < 0) fit = -fit;
  if (angle_deg(fit, nB) >= 5) return nB;
  *on_plane = pb + mean;
  return fit;
}

// A station per border B vertex (pass.station, station_vertex): plane A and side B's tangent plane there, their
// corner line's direction (the axis) and corner point in the vertex's section. Side B's normal at a vertex is
// the side-B facets' around it that turn with the one across the border there (not an end face's), weighted
// by their angles at the vertex.
void make_stations(const MeshTopology& mesh, Facets& fx, const Vec3& where, RoundStrip& strip, CurvedPasses& pass) {
  auto side_of = [&](int g) { return pass.side_of(fx, strip, g); };
  const bool closed = pass.closed;
  auto& station = pass.station;
  auto& station_vertex = pass.station_vertex;
  const auto& border_b = pass.border_b;
  std::unordered_map<int, Vec3> anchor;
  for (const auto& [v, g] : border_b) {
    if (anchor.count(v)) continue;
    // (across a cap, a loop's wall normal is its largest side-B facet's at v: a cap's says little of the
    // wall; an open strip's end face may be that facet)
    int wall = g;
    if (closed && fx.cap(g))
      for (const int* h = mesh.facets_begin(v); h != mesh.facets_end(v); ++h)
        if (!strip.facet_set.count(*h) && !fx.cap(*h) && side_of(*h) == 1 && (wall == g || fx.area(*h) > fx.area(wall))) wall = *h;
    anchor.emplace(v, fx.normal(wall));
  }
  if (anchor.size() < 2) not_a_round("its curved side's border has fewer than two vertices", where);
  std::unordered_set<int> border;
  for (const auto& [v, g] : border_b) border.insert(v);
  strip.border_count[1] = int(anchor.size());
  for (const auto& [b, an] : anchor) {
    // Where b's side-B facets are all slivers (a mesher's row of slivers along the contact line: b sits a hair
    // up the round), their normals turn with their vertices' float32 places (a 3.8 deg facet on the S plate's
    // 1 mm mesh, 1.4 deg off the wall in plan): its neighbours' side-B facets that are not slivers serve,
    // weighted by area, and the wall's line in b's section is fitted off the border (wall_normal_in_section).
    Vec3 nB = Vec3::Zero();
    int walls = 0, shaped_walls = 0;
    auto shaped = [&](int g) { return smallest_angle_deg(mesh.corner(g, 0), mesh.corner(g, 1), mesh.corner(g, 2)) >= kShapedDeg; };
    const Vec3 wall_normal = an;  // (a lambda may not capture a structured binding before C++20: clang refuses it)
    auto wall = [&](int g) {
      return !strip.facet_set.count(g) && side_of(g) == 1 && !(closed && fx.cap(g)) && angle_deg(fx.normal(g), wall_normal) <= kStationTurnDeg;
    };
    for (const int* g = mesh.facets_begin(b); g != mesh.facets_end(b); ++g) {
      if (!wall(*g)) continue;
      int k = 0;
      while (mesh.F(*g, k) != b) ++k;
      const Vec3 u = mesh.point(mesh.F(*g, (k + 1) % 3)) - mesh.point(b), w = mesh.point(mesh.F(*g, (k + 2) % 3)) - mesh.point(b);
      nB += std::atan2(u.cross(w).norm(), u.dot(w)) * fx.normal(*g);  // weighted by the facet's angle at b
      ++walls, shaped_walls += shaped(*g);
    }
    const bool on_sliver = walls > 0 && shaped_walls == 0;
    if (on_sliver) {
      Vec3 around = Vec3::Zero();
      for (int w : mesh.vertex_neighbours(b))
        for (const int* g = mesh.facets_begin(w); g != mesh.facets_end(w); ++g)
          if (wall(*g) && shaped(*g)) around += fx.area(*g) * fx.normal(*g);
      if (around.norm() > 1e-12) nB = around;
    }
    if (nB.norm() < 1e-12) continue;
    nB.normalize();
    Vec3 on_wall;
    nB = wall_normal_in_section(mesh, fx, strip, pass, border, b, on_sliver, nB, &on_wall);
    StripFrame F;
    F.normal[0] = strip.normal[0], F.offset[0] = strip.offset[0];
    F.normal[1] = nB, F.offset[1] = F.normal[1].dot(on_wall);
    F.axis = F.normal[0].cross(F.normal[1]);
    if (F.axis.norm() < 1e-6) not_a_round("its two sides are parallel at " + format_point(mesh.point(b)), where);
    F.axis.normalize();
    F.corner = frame_solve(F.normal[0], F.normal[1], F.axis, Vec3(F.offset[0], F.offset[1], F.axis.dot(mesh.point(b))));
    station.push_back(F), station_vertex.push_back(b);
  }
}

// An open strip's run of stations through the seed's whose corner line turns by kStationTurnDeg at most from
// one to the next (pass.station, `run_vertex`: their border B vertices); stations beyond it at an end (an end
// face's facets across a sliver) are dropped, their border edges made end edges.
void keep_seed_run(const MeshTopology& mesh, const Vec3& where, RoundStrip& strip, std::vector<std::pair<int, int>>& end_edges,
                   CurvedPasses& pass, std::vector<int>& run_vertex) {
  auto& station = pass.station;
  const auto& station_vertex = pass.station_vertex;
  const auto& border_edges = pass.border_edges;
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
  run_vertex.assign(station_vertex.begin() + long(lo), station_vertex.begin() + long(hi) + 1);
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

// The stations in order along the corner line; a loop's closing up evenly; an open strip's run through the
// seed's station (keep_seed_run); the tilts smoothed; the axes all one way along the line.
void order_stations(const MeshTopology& mesh, const Vec3& where, RoundStrip& strip, std::vector<std::pair<int, int>>& end_edges,
                    CurvedPasses& pass) {
  const bool closed = pass.closed;
  auto& station = pass.station;
  auto& station_vertex = pass.station_vertex;
  const bool walked = pass.walked = closed && order_around(mesh, pass.border_edges, station, station_vertex);
  if (!walked) order_along(station, station_vertex);
  // A loop: its corner line must close up evenly (no station skipped by the ordering) and turn by
  // kLoopTurnDeg at most from each station to the next, the last to the first included.
  if (closed) close_loop(station, where, walked);
  std::vector<int> run_vertex = station_vertex;  // the border B vertex of each station kept
  if (!closed) keep_seed_run(mesh, where, strip, end_edges, pass, run_vertex);
  {
    std::vector<Vec3> border;
    for (const int v : run_vertex) border.push_back(mesh.point(v));
    smooth_tilts(station, border, closed);
    if (!walked) order_along(station, run_vertex);  // a corrected corner may change places with its neighbour
    if (closed) close_loop(station, where, walked);
  }
  for (size_t i = 0; i < station.size(); ++i) {
    StripFrame& F = station[i];
    const Vec3 along = i > 0 ? station[i - 1].axis : Vec3(station[std::min<size_t>(1, station.size() - 1)].corner - F.corner);
    if (F.axis.dot(along) < 0) F.axis = -F.axis;
  }
}

// The side of each plane the round lies on (strip.side), from the strip's inner and end vertices; `at`: each
// strip vertex's station (the nearest corner point).
void find_sides(const MeshTopology& mesh, const std::vector<StripFrame>& station, const Vec3& where, RoundStrip& strip,
                std::unordered_map<int, size_t>& at) {
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
}

// The strip's corner line from the stations, each vertex's frame (its nearest station's, moved into its own
// section), the strip's own frame, its ends' and its parameter range.
void frame_vertices(const MeshTopology& mesh, std::vector<StripFrame> station, const std::unordered_map<int, size_t>& at,
                    bool closed, const Vec3& where, RoundStrip& strip) {
  double s = 0;
  for (size_t i = 0; i < station.size(); ++i) {
    StripFrame& F = station[i];
    F.side[0] = strip.side[0], F.side[1] = strip.side[1];
    F.centre_dir = frame_solve(F.normal[0], F.normal[1], F.axis, Vec3(F.side[0], F.side[1], 0));
    if (i > 0) s += (F.corner - station[i - 1].corner).norm();
    strip.line.push_back(F.corner), strip.line_s.push_back(s);
  }
  strip.closed = closed;
  strip.loop_length = closed ? s + (station.front().corner - station.back().corner).norm() : 0.0;
  // A vertex's frame: its nearest station's, moved into the vertex's own section on the corner line's curve
  // (CornerCurve), side B's plane turned about A's normal with the line.
  const CornerCurve curve(station, closed);
  for (const auto& [v, role] : strip.role) {
    const Vec3 p = mesh.point(v);
    StripFrame F = station[at.at(v)];
    double u = curve.S(long(at.at(v))) + F.axis.dot(p - F.corner);
    Vec3 d, c;
    for (int step = 0; step < 3; ++step) {  // the curve's point whose normal plane holds p
      c = curve.at(u, &d);
      u += (p - c).dot(d) / std::max(d.squaredNorm(), 1e-300);
    }
    c = curve.at(u, &d);
    const Vec3 axis = d.dot(F.axis) < 0 ? Vec3(-d.normalized()) : Vec3(d.normalized());
    const double turn = std::atan2(F.axis.cross(axis).dot(F.normal[0]), F.axis.dot(axis));
    F.normal[1] = Eigen::AngleAxisd(turn, F.normal[0]) * F.normal[1];
    F.axis = (F.normal[0].cross(F.normal[1])).normalized();
    if (F.axis.dot(axis) < 0) F.axis = -F.axis;
    F.corner = c + F.axis * F.axis.dot(p - c);  // in p's own section
    F.offset[1] = F.normal[1].dot(F.corner);
    F.centre_dir = frame_solve(F.normal[0], F.normal[1], F.axis, Vec3(F.side[0], F.side[1], 0));
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
  if (closed) strip.s_lo = 0, strip.s_hi = strip.loop_length;
}

void recognise_curved(const MeshTopology& mesh, Facets& fx, int f0, const std::vector<int>& flood, const std::vector<int>& beside,
                      const SharpenOptions& o, const Vec3& where, RoundStrip& strip, std::vector<std::pair<int, int>>& end_edges) {
  CurvedPasses pass;
  pass.fd2 = 2 * o.flat_deg;
  fit_side_a(mesh, fx, beside, pass.fd2, where, strip);
  measure_opening(fx, flood, beside, strip, where, pass);
  if (pass.side_of(fx, strip, f0) >= 0) not_a_round("the seed's facet lies on a side beside a round, not on the round", where);
  flood_curved(mesh, fx, f0, o, where, strip, end_edges, pass);
  make_stations(mesh, fx, where, strip, pass);
  order_stations(mesh, where, strip, end_edges, pass);
  std::unordered_map<int, size_t> at;
  find_sides(mesh, pass.station, where, strip, at);
  frame_vertices(mesh, std::move(pass.station), at, pass.closed, where, strip);
}

}  // namespace meshround::strip_detail
