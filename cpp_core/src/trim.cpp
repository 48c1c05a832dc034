// The trim pass (trim.h) and its cutting sub-passes (trim_side.h): the facets across the contact lines cut,
// the edges from and along the lines graded, the kept facets beside them retriangulated.
#include "meshround/trim.h"
#include "meshround/cancel.h"
#include "call_checks.h"
#include "trim_caps.h"
#include "trim_side.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace meshround {
namespace {

// The kept piece of a long edge from the trim line gets points whose spacing grows from the trim line's by
// half again each step, but none in the outer kHingeRoom of the piece's part within the reach (grade_piece).
constexpr double kHingeRoom = 0.6;

// Facet g of the input as a polygon, with the points that the edit put on its edges (each edge's points
// in order from its first vertex to its second, as `points_on(p, q)` gives them).
template <class PointsOn>
std::vector<int> facet_with_edge_points(const MeshTopology& mesh, int g, PointsOn points_on) {
  std::vector<int> polygon;
  for (int k = 0; k < 3; ++k) {
    const int p = mesh.F(g, k), q = mesh.F(g, (k + 1) % 3);
    polygon.push_back(p);
    points_on(p, q, polygon);
  }
  return polygon;
}

// Facets outside the base meshes that share a cut edge get the cut point too (no T-junctions).
void close_t_junctions(const TrimContext& ctx) {
  const MeshTopology& mesh = ctx.mesh;
  MeshEdit& edit = ctx.edit;
  for (const auto& [key, id] : edit.edge_point) {
    poll_cancel();
    for (int g : mesh.edge_facets(int(key >> 32), int(key & 0xffffffffu))) {
      if (ctx.base.side_of.count(g) || edit.removed.count(g)) continue;
      edit.removed.insert(g);
      const std::vector<int> polygon = facet_with_edge_points(mesh, g, [&](int p, int q, std::vector<int>& poly) {
        auto it = edit.edge_point.find(edge_key(p, q));
        if (it == edit.edge_point.end()) return;
        ctx.add_piece_points(p, it->second, poly);
        poly.push_back(it->second);
        ctx.add_piece_points(it->second, q, poly);
      });
      triangulate_polygon(edit, polygon, mesh.facet_normal(g), edit.added);
    }
  }
}

}  // namespace

double wrapped_delta(const RoundingSurface& s, double from, double to) {
  double d = to - from;
  if (s.closed) {
    const double p = s.u_last - s.u_first;
    d -= std::round(d / p) * p;
  }
  return d;
}

TrimContext::TrimContext(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base, const RoundingSurface& surface,
                         const std::vector<ProfileStation>& end_profiles, const TrimOptions& opt, MeshEdit& edit)
    : mesh(mesh), chain(chain), base(base), surface(surface), end_profiles(end_profiles), opt(opt), edit(edit),
      chain_vertices(chain.vertices.begin(), chain.vertices.end()) {
  for (const ProfileStation& st : end_profiles)
    for (int k = 0; k < 2; ++k) {
      // (A capped end's contacts are moved onto its plane: the band's corner there, past the chain's end at
      // a mitre, farther from the chain than the contact lines are.)
      const Vec3 contact = st.cut.active ? st.cut.onto(st.contact[k]) : st.contact[k];
      const double d = (contact - chain.point_at(st.s)).norm();
      nearest[k] = std::min(nearest[k], d), farthest[k] = std::max(farthest[k], d);
    }
  const double magnitude = coordinate_magnitude(mesh.V);
  for (int end = 0; end < 2 && !chain.closed; ++end) {
    const ProfileStation& st = end ? end_profiles.back() : end_profiles.front();
    if (!st.cut.active) continue;
    cuts[end] = &st.cut;
    plane_slack = std::max(plane_slack, on_plane_slack(st.radius, std::max(magnitude, st.cut.point.cwiseAbs().maxCoeff())));
  }
}

double TrimContext::past_end(const Vec3& p) const {
  double past = -INFINITY;
  for (const EndCut* c : cuts)
    if (c) past = std::max(past, c->past(p));
  return past;
}

void TrimContext::add_piece_points(int from, int to, std::vector<int>& polygon) const {
  auto it = kept_piece.find(edge_key(from, to));
  if (it == kept_piece.end()) return;
  const auto& points = it->second.points;
  if (it->second.trim_end == from) polygon.insert(polygon.end(), points.begin(), points.end());
  else polygon.insert(polygon.end(), points.rbegin(), points.rend());
}

// The kept piece of a long edge from the trim line gets points whose spacing grows from the trim line's by
// half again each step: the facets on both sides of it can then grade from the fine trim line to their far
// corners instead of fanning out in slivers. None goes beyond the reach, but one where the piece leaves it:
// the facets beyond hinge on that point, and fan from it back to the nearer points within a narrow angle
// (the face's width seen from the hinge). That fan is only well shaped when the hinge's neighbour is far, so
// no graded point stays in the outer kHingeRoom of the piece's part within the reach.
void SideTrim::grade_piece(int trim_end, int kept_end, double u) {
  KeptPiece& piece = ctx.kept_piece[edge_key(trim_end, kept_end)];
  piece.trim_end = trim_end;
  const Vec3 x = edit.point(trim_end), y = edit.point(kept_end);
  const double length = (y - x).norm();
  auto admitted = [&](double at) { return !opt.shape.admit || opt.shape.admit(x + (y - x) * (at / length)); };
  std::vector<double> stops;  // distances from the trim end
  double at = opt.max_spacing(u), step = at;
  for (; length - at > 1.5 * step && admitted(at); at += step, step *= 1.5) stops.push_back(at);
  // The piece leaves the reach between the last stop and `at` (or its end, when the last step ran out
  // of length; then a hinge only where the part beyond is longer than the part within).
  const bool ran_out = !(length - at > 1.5 * step);
  if (!ran_out || !admitted(length)) {
    double in = stops.empty() ? 0 : stops.back(), out_at = ran_out ? length : at;
    for (int it = 0; it < 30; ++it) (admitted(0.5 * (in + out_at)) ? in : out_at) = 0.5 * (in + out_at);
    if (ran_out && length - in < in) in = -1;  // no room beyond: keep the graded stops as they are
    if (in >= 0) {
      while (!stops.empty() && stops.back() > (1 - kHingeRoom) * in) stops.pop_back();
      if (length - in > 0.5 * step) stops.push_back(in);
    }
  }
  for (double s : stops) piece.points.push_back(edit.add_point(x + (y - x) * (s / length)));
}

// The cut point on the edge a-b that crosses the line (made once; the kept piece beyond it graded).
int SideTrim::cut_point(int a, int b) {
  const std::uint64_t key = edge_key(a, b);
  auto it = edit.edge_point.find(key);
  if (it != edit.edge_point.end()) {
    if (!cut_u.count(it->second))  // the other side's trim line cut this edge already
      throw RoundingError(ErrorCode::ResultInvalid, "both contact lines cut the mesh edge at " +
                          format_point(0.5 * (edit.point(a) + edit.point(b))) +
                          ": the band is narrower than the facets there; try a larger radius or a finer mesh");
    return it->second;
  }
  if (vs[a].d > 0) std::swap(a, b);  // a inside, b outside
  const Vec3 pa = edit.point(a), pb = edit.point(b);
  // The capped end whose plane the edge leaves the band through, if any: of the planes the outer end
  // is past, the one crossed first (an edge may run from one end's plane to beyond the other's, or
  // past both: a CAD facet spanning the whole chain).
  const EndCut* beyond = nullptr;
  double first_crossing = INFINITY;
  for (const EndCut* c : ctx.cuts) {
    if (!c || c->past(pb) <= ctx.plane_slack) continue;
    const double fa = std::min(c->past(pa), 0.0), crossing = fa / (fa - c->past(pb));
    if (crossing < first_crossing) first_crossing = crossing, beyond = c;
  }
  // A vertex in the band on that plane: the plane's trace runs through the vertex itself. So too where
  // the edge runs in the plane to its far side of the chain's end (behind_end).
  const bool a_on_plane = beyond ? std::abs(beyond->past(pa)) <= ctx.plane_slack : std::abs(ctx.past_end(pa)) <= ctx.plane_slack;
  if ((beyond || behind_end(pb) > ctx.plane_slack) && a_on_plane) {
    plane_points.insert(a);
    return a;
  }
  double t0 = 0, t1 = 1, f0 = exact(a).d, f1 = exact(b).d, u = vs[a].u, t = 0.5;
  int side_kept = 0;
  for (int it2 = 0; it2 < 60; ++it2) {  // Illinois regula falsi
    t = (t0 * f1 - t1 * f0) / (f1 - f0);
    const double f = distance(pa + t * (pb - pa), u, &u);
    if (std::abs(f) < 1e-12 * std::max(1.0, ctx.surface.u_last) || t1 - t0 < 1e-14) break;
    if ((f < 0) == (f0 < 0)) {
      t0 = t, f0 = f;
      if (side_kept == -1) f1 *= 0.5;
      side_kept = -1;
    } else {
      t1 = t, f1 = f;
      if (side_kept == 1) f0 *= 0.5;
      side_kept = 1;
    }
  }
  // Cut on an end face's plane (the contact line is farther on): put onto the plane exactly.
  double u_line = u;
  const bool on_plane = beyond && line_distance(pa + t * (pb - pa), u, &u_line) < -ctx.plane_slack;
  if (on_plane) t = std::clamp(first_crossing, 0.0, 1.0);
  else u = u_on_line(pa + t * (pb - pa), vs[a].u, vs[b].u, 0.0);
  const int id = edit.add_point(pa + t * (pb - pa));
  edit.edge_point[key] = id;
  cut_u[id] = u;
  if (on_plane) plane_points.insert(id);
  else out.line[side].push_back({id, u});
  grade_piece(id, b, u);
  return id;
}

// An edge with both ends in the band can still run out of it between them, where the band's edge curves
// towards it: a CAD facet of a box's top face from one top edge to the other cuts across the inner corner
// of a rolled round's band (top edges of 2 rolled round a vertical 8: all its corners in the band, most of
// it outside, taken out whole -- a hole). Such an edge (sampled along; out by more than a hair) gets the two
// points where it crosses the line, which the facets on both sides take as cut points.
// The contact line's length from u_a to u_b (sampled).
double SideTrim::line_length(double u_a, double u_b) const {
  const double du = wrapped_delta(ctx.surface, u_a, u_b);
  double length = 0;
  Vec3 last = ctx.surface.value(u_a, side);
  for (int k = 1; k <= 32; ++k) {
    const Vec3 next = ctx.surface.value(ctx.surface.wrap(u_a + du * k / 32), side);
    length += (next - last).norm(), last = next;
  }
  return length;
}

constexpr int kDipSamples = 16;
constexpr double kDipDepthShare = 0.5;
void SideTrim::find_dips() {
  std::unordered_set<std::uint64_t> seen;
  for (int f : ctx.base.facets[side])
    for (int k = 0; k < 3; ++k) {
      int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (a > b) std::swap(a, b);
      poll_cancel();
      if (vs[a].d >= 0 || vs[b].d >= 0 || !seen.insert(edge_key(a, b)).second) continue;
      // The distance from the band's edge changes no faster than along the edge (about: half that here, for
      // the line's own bend), so an edge whose ends lie deeper in the band than it is long stays in.
      const Vec3 pa = edit.point(a), pb = edit.point(b);
      auto depth = [&](int v) {  // (measured here: a vertex deep in the band has only its side in vs)
        double u = vs[v].u;
        return vs[v].exact ? vs[v].d : distance(edit.point(v), u, &u);
      };
      const double da = depth(a), db = depth(b);
      if (!(da < 0 && db < 0) || (pb - pa).norm() <= kDipDepthShare * (-da - db) + 2 * hair) continue;
      // Both facets of the edge on this side: a dip's two points go into both polygons.
      const std::vector<int> facets = mesh.edge_facets(a, b);
      if (facets.size() != 2 || !std::all_of(facets.begin(), facets.end(), [&](int g) {
            const auto it = ctx.base.side_of.find(g);
            return it != ctx.base.side_of.end() && it->second == side;
          }))
        continue;
      // How far out the edge runs: the foot carried along it, and, where that reads out of the band, from the
      // chain's own nearest point too (each can slip to another stretch of the line round a turn of it: the
      // box's CAD mesh at a rolled corner of 5 / 7 under 8 read 11 mm where the edge runs 5.4 mm out, and its
      // dip was lost), the nearer taken. (A sample the carried foot reads in the band is not a dip's deepest:
      // the second measure, a search along the whole chain, is spent on the few that read out.)
      double best = -INFINITY, t_best = 0, u = vs[a].u, u_near = NAN;
      for (int i = 1; i < kDipSamples; ++i) {
        const double t = double(i) / kDipSamples;
        double d = distance(pa + t * (pb - pa), u, &u);
        if (d > std::max(best, hair)) d = std::min(d, distance(pa + t * (pb - pa), NAN, &u_near));
        if (d > best) best = d, t_best = t;
      }
      // (confirmed from the chain's own nearest point: a carried foot can slip to another stretch of the line)
      double u_check = NAN;
      if (!(best > hair) || !(distance(pa + t_best * (pb - pa), NAN, &u_check) > hair)) continue;
      // The crossing between t0 (in the band) and t1 (out), by bisection: where the distance is nought (not
      // a jump of a foot from one stretch of the line to another), and its line parameter.
      auto crossing = [&](double t0, double t1, double* u_at) {
        double uc = vs[t0 == 0.0 ? a : b].u;  // (the foot carried from that end's own)
        for (int it = 0; it < 60; ++it) {
          const double t = 0.5 * (t0 + t1);
          (distance(pa + t * (pb - pa), uc, &uc) < 0 ? t0 : t1) = t;
        }
        const double t = 0.5 * (t0 + t1);
        const bool on_line = std::abs(distance(pa + t * (pb - pa), NAN, u_at)) <= 1e-3 * hair;
        return on_line ? t : NAN;
      };
      double u1 = 0, u2 = 0;
      const double t1 = crossing(0.0, t_best, &u1), t2 = crossing(1.0, t_best, &u2);
      // The line between the two crossings runs round the part of the edge outside: at least as far as twice
      // that part's depth.
      if (std::isnan(t1) || std::isnan(t2) || !(t2 - t1 > 0) || line_length(u1, u2) < 2 * best) continue;
      std::array<int, 2> ids{};
      for (int i : {0, 1}) {
        ids[size_t(i)] = edit.add_point(pa + (i ? t2 : t1) * (pb - pa));
        cut_u[ids[size_t(i)]] = i ? u2 : u1;
        out.line[side].push_back({ids[size_t(i)], i ? u2 : u1});
      }
      dips[edge_key(a, b)] = ids;
    }
}

bool SideTrim::kept_whole(int g) {
  auto it = ctx.base.side_of.find(g);
  return it != ctx.base.side_of.end() && it->second == side &&
         std::all_of(&mesh.F(g, 0), &mesh.F(g, 0) + 3, [&](int v) { return vs[v].d >= 0; });
}

// Input edges from a vertex on the line to a kept one are graded as well when both their facets are cut or
// kept whole (all around such a vertex, so that no acute corner has points on one side only); kept facets
// with graded edges are retriangulated with the points (rebuild_kept).
void SideTrim::grade_line_edges() {
  for (int f : ctx.base.facets[side]) {
    int in = 0, beyond = 0;
    for (int k = 0; k < 3; ++k) in += vs[mesh.F(f, k)].d < 0, beyond += vs[mesh.F(f, k)].d > 0;
    if (in > 0 && beyond > 0) cut.insert(f);
  }
  for (int f : ctx.base.facets[side])
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (!((vs[a].d == 0 && vs[b].d > 0) || (vs[b].d == 0 && vs[a].d > 0)) || ctx.kept_piece.count(edge_key(a, b))) continue;
      const std::vector<int> pair = mesh.edge_facets(a, b);
      if (pair.size() != 2 || !std::all_of(pair.begin(), pair.end(), [&](int g) { return cut.count(g) || kept_whole(g); }))
        continue;
      vs[a].d == 0 ? grade_piece(a, b, vs[a].u) : grade_piece(b, a, vs[b].u);
      for (int g : pair)
        if (!cut.count(g)) rebuild.insert(g);
    }
}

// True when refine point q (in facet f's plane) is left out, a side of f standing for the line there: q lies
// outside one of f's sides within the tolerance, with its corners where the snaps put them: the line's points
// are spaced for a sag of a quarter of it (refine_line_in_facet), so without that point the line stays within it. (Within a quarter, kHairShare, a point 0.26 tolerances outside a
// flipped facet of a sharpened wall folded its polygon, made again at its own radius.) Or outside a side
// whose facet across is not cut (no corner in the band): nothing there follows the line, so the side stands
// for it (on a sharpened wall made again at its own radius the line dips 0.044 mm below a row of old contact
// vertices, onto the tilt of the wall's chords; the wall is where the row is). A line that runs well outside
// a thin CAD facet and back into a facet that is cut, by 0.7 mm and more on the S chain's, is taken as it is.
bool SideTrim::side_stands_for_line(int f, const Vec3& q) const {
  const Vec3 c[3] = {edit.point(mesh.F(f, 0)), edit.point(mesh.F(f, 1)), edit.point(mesh.F(f, 2))};
  const Vec3 n = (c[1] - c[0]).cross(c[2] - c[0]).normalized();
  auto uncut_across = [&](int k) {
    const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
    for (int g : mesh.edge_facets(a, b)) {
      if (g == f) continue;
      for (int j = 0; j < 3; ++j)
        if (const auto it = vs.find(mesh.F(g, j)); it == vs.end() || it->second.d < 0) return false;
    }
    return true;
  };
  for (int k = 0; k < 3; ++k) {
    const Vec3 edge = c[(k + 1) % 3] - c[k];
    const double beyond = -edge.cross(q - c[k]).dot(n) / edge.norm();  // > 0 outside this side
    if (beyond > 0 && (beyond <= opt.tolerance || uncut_across(k))) return true;
  }
  return false;
}

// a and b on the line, joined by an input edge: the line between them leaves that edge by more than its
// points are spaced for (a quarter of the tolerance, as refine_line_in_facet) -- the edge is a chord of a
// line that bends, as around a rolled corner's arc on a coarse mesh. Such an edge is not a piece of the line:
// the cut facets' own refinement carries the line there.
bool SideTrim::line_leaves_chord(int a, int b) const {
  const VertexSide &sa = vs.at(a), &sb = vs.at(b);
  const Vec3 q = ctx.surface.value(ctx.surface.wrap(sa.u + 0.5 * wrapped_delta(ctx.surface, sa.u, sb.u)), side);
  double t;
  return (closest_point_on_segment(q, edit.point(a), edit.point(b), &t) - q).norm() > 0.25 * opt.tolerance;
}

// Extra points of the trim line between its points `from` and `to` in cut facet f, where the contact line
// bends or runs long inside it, appended to `polygon`.
void SideTrim::refine_line_in_facet(int f, int from, double u_from, int to, double u_to, std::vector<int>& polygon) {
  const Vec3 n = mesh.facet_normal(f), p0 = mesh.corner(f, 0);
  const Vec3 x1 = edit.point(from), x2 = edit.point(to);
  const double du = wrapped_delta(ctx.surface, u_from, u_to);
  auto on_facet = [&](double u) { Vec3 q = ctx.surface.value(u, side); return Vec3(q - (q - p0).dot(n) * n); };
  const Vec3 mid = on_facet(u_from + 0.5 * du);
  double t;
  const double sag = (closest_point_on_segment(mid, x1, x2, &t) - mid).norm();
  double want = std::max({1.0, std::ceil((x2 - x1).norm() / opt.max_spacing(u_from + 0.5 * du)),
                          std::ceil(std::sqrt(sag / (0.25 * opt.tolerance)))});
  if (!(want <= 1e9)) want = INFINITY;  // (NaN too): refused by the budget below, never cast
  edit.check_budget(2.0 * (double(edit.new_points.size()) + want), "trim line points");
  const int segs = int(want);
  // The points are spaced evenly along the line, not in u: over a carried end's straight piece the
  // surface's u runs on while its points barely move (5 mm of u over the last 0.25 mm before a sphere
  // corner's plane), and a point spaced in u there lands a hair from the band's corner, leaving a sliver.
  const int fine = segs > 1 ? 8 * segs : 0;
  std::vector<double> length(fine + 1, 0.0);
  Vec3 last = fine > 0 ? on_facet(u_from) : Vec3::Zero();
  for (int k = 1; k <= fine; ++k) {  // (each sample evaluated once)
    const Vec3 next = on_facet(u_from + du * k / fine);
    length[k] = length[k - 1] + (next - last).norm(), last = next;
  }
  for (int s = 1, k = 0; s < segs; ++s) {
    const double at = length[fine] * s / segs;
    while (k + 1 < fine && length[k + 1] < at) ++k;
    const double share = length[k + 1] > length[k] ? (at - length[k]) / (length[k + 1] - length[k]) : 0.0;
    const double u = ctx.surface.wrap(u_from + du * (k + share) / fine);
    const Vec3 q = on_facet(u);
    // Where the line leaves a kept corner snapped onto it nearly along the facet's side, a point of it can
    // fall a hair outside the facet: it would fold the polygon back on that side. None there.
    if (side_stands_for_line(f, q)) continue;
    const int id = edit.add_point(q);
    out.line[side].push_back({id, u});
    polygon.push_back(id);
  }
}

// Facets with a corner in the band are taken out; those across the line keep their outer part: kept corners
// and cut points in order, the trim line between them refined, retriangulated in the facet's plane.
void SideTrim::cut_facets() {
  for (int f : ctx.base.facets[side]) {
    poll_cancel();
    int in = 0, outside = 0;
    for (int k = 0; k < 3; ++k) (vs[mesh.F(f, k)].d < 0 ? in : outside) += 1;
    if (in == 0) continue;
    edit.removed.insert(f);
    bool dipped = false;
    for (int k = 0; k < 3; ++k) dipped |= dips.count(edge_key(mesh.F(f, k), mesh.F(f, (k + 1) % 3))) > 0;
    if (!dipped && (outside == 0 || std::all_of(&mesh.F(f, 0), &mesh.F(f, 0) + 3, [&](int v) { return vs[v].d <= 0; }))) {
      ++out.facets_removed;
      continue;
    }
    ++out.facets_cut;
    struct Item { int vertex; double u; bool trim; };
    std::vector<Item> ring;
    std::vector<bool> band_before;  // a band corner was skipped just before this item
    bool skipped = false;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (vs[a].d >= 0) ring.push_back({a, vs[a].u, vs[a].d == 0}), band_before.push_back(skipped), skipped = false;
      else skipped = true;
      if ((vs[a].d < 0 && vs[b].d > 0) || (vs[a].d > 0 && vs[b].d < 0)) {
        const int x = cut_point(a, b);
        if (!ring.empty() && ring.back().vertex == x) continue;  // a band vertex on an end face's plane, again
        ring.push_back({x, cut_u.count(x) ? cut_u.at(x) : vs[x].u, true}), band_before.push_back(skipped), skipped = false;
      } else if (const auto dip = dips.find(edge_key(a, b)); dip != dips.end()) {  // out of the band and back: kept between
        const int first = dip->second[a < b ? 0 : 1], second = dip->second[a < b ? 1 : 0];
        ring.push_back({first, cut_u.at(first), true}), band_before.push_back(skipped), skipped = false;
        ring.push_back({second, cut_u.at(second), true}), band_before.push_back(false);
      }
    }
    if (ring.size() > 1 && ring.back().vertex == ring.front().vertex) ring.pop_back(), band_before.pop_back(), band_before[0] = true;
    // Only the band vertex on an end face's plane was cut off: the facet stays as it is.
    if (ring.size() == 3 && std::all_of(ring.begin(), ring.end(), [&](const Item& x) { return x.vertex < mesh.num_vertices(); })) {
      edit.removed.erase(f);
      --out.facets_cut;
      // ... unless an edge of it was graded from the trim line (a CAD mesh's long edge from the band's
      // corner): then it takes those points like any kept facet beside a graded piece.
      for (int k = 0; k < 3; ++k)
        if (ctx.kept_piece.count(edge_key(mesh.F(f, k), mesh.F(f, (k + 1) % 3)))) rebuild.insert(f);
      continue;
    }
    if (skipped && !band_before.empty()) band_before[0] = true;
    std::vector<int> polygon;
    for (size_t i = 0; i < ring.size(); ++i) {
      const Item& prev = ring[(i + ring.size() - 1) % ring.size()];
      if (!band_before[i]) ctx.add_piece_points(prev.vertex, ring[i].vertex, polygon);
      // (A piece on an end face's plane is straight: it needs no points.)
      if (band_before[i] && prev.trim && ring[i].trim && !plane_points.count(prev.vertex) && !plane_points.count(ring[i].vertex))
        refine_line_in_facet(f, prev.vertex, prev.u, ring[i].vertex, ring[i].u, polygon);
      polygon.push_back(ring[i].vertex);
    }
    triangulate_polygon(edit, polygon, mesh.facet_normal(f), edit.added, opt.shape);
  }
}

// Input edges that lie on the trim line (both ends on it, and the line along the edge between them) get points
// every max_spacing and the kept facet along them is split to match (rebuild_kept): the round's boundary row
// stays as dense as its inner rows.
void SideTrim::split_line_edges() {
  for (int f : ctx.base.facets[side])
    for (int k = 0; k < 3; ++k) {
      poll_cancel();
      int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (a > b) std::swap(a, b);
      const VertexSide &sa = vs[a], &sb = vs[b];
      if (sa.d != 0 || sb.d != 0 || line_leaves_chord(a, b)) continue;
      const Vec3 pa = edit.point(a), pb = edit.point(b);
      const int segs = int(std::ceil((pb - pa).norm() / opt.max_spacing(sa.u + 0.5 * wrapped_delta(ctx.surface, sa.u, sb.u))));
      if (segs < 2 || split.count(edge_key(a, b))) continue;
      std::vector<int>& ids = split[edge_key(a, b)];
      for (int i = 1; i < segs; ++i) {
        const Vec3 q = pa + (pb - pa) * (double(i) / segs);
        const double u = u_on_line(q, sa.u, sb.u, double(i) / segs);
        ids.push_back(edit.add_point(q));
        out.line[side].push_back({ids.back(), u});
      }
    }
  for (const auto& [key, ids] : split)
    for (int g : mesh.edge_facets(int(key >> 32), int(key & 0xffffffffu))) rebuild.insert(g);
}

// Kept facets beside graded pieces or split line edges, retriangulated with those points.
void SideTrim::rebuild_kept() {
  for (int g : rebuild) {
    poll_cancel();
    if (!edit.removed.insert(g).second) continue;  // in the band
    const std::vector<int> polygon = facet_with_edge_points(mesh, g, [&](int p, int q, std::vector<int>& poly) {
      auto it = split.find(edge_key(p, q));
      if (it == split.end()) ctx.add_piece_points(p, q, poly);
      else if (p < q) poly.insert(poly.end(), it->second.begin(), it->second.end());
      else poly.insert(poly.end(), it->second.rbegin(), it->second.rend());
    });
    triangulate_polygon(edit, polygon, mesh.facet_normal(g), edit.added, opt.shape);
  }
}

TrimLines trim_base_meshes(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base,
                           const RoundingSurface& surface, const std::vector<ProfileStation>& end_profiles,
                           const TrimOptions& opt, MeshEdit& edit) {
  TrimLines out;
  TrimContext ctx(mesh, chain, base, surface, end_profiles, opt, edit);
  for (int side = 0; side < 2; ++side) {
    SideTrim trim(ctx, side, out);
    trim.classify_vertices();
    trim.grade_line_edges();
    trim.find_dips();
    trim.cut_facets();
    trim.split_line_edges();
    trim.rebuild_kept();
  }
  // Capped ends: the corner of the end faces that the round replaces.
  if (!chain.closed) {
    if (chain.start_end == ChainEnd::Junction)
      remove_cap_corner(mesh, base, chain.vertices.front(), end_profiles.front(), edit, &out.facets_removed);
    if (chain.end_end == ChainEnd::Junction)
      remove_cap_corner(mesh, base, chain.vertices.back(), end_profiles.back(), edit, &out.facets_removed);
  }
  close_t_junctions(ctx);
  for (auto& line : out.line) {
    std::sort(line.begin(), line.end(), [](const TrimPoint& x, const TrimPoint& y) { return x.u < y.u; });
    line.erase(std::unique(line.begin(), line.end(), [](const TrimPoint& x, const TrimPoint& y) { return x.vertex == y.vertex; }),
               line.end());
  }
  return out;
}

}  // namespace meshround
