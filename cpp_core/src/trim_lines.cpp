// The trim's measures and its first sub-pass (trim_side.h): where each base vertex lies against the band's
// edge, and the vertices near the contact line snapped onto it.
#include "trim_side.h"
#include "guard.h"

#include "meshround/cancel.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace meshround {

double ContactLineDistance::operator()(const Vec3& p, double u_hint, double* u_out, Vec3* away) const {
  const double v = side;
  double u = std::isnan(u_hint) ? chain.project(p, nullptr) : u_hint;
  Vec3 C, Cu, Cv;
  for (int it = 0; it < 30; ++it) {
    surface.d1(u, v, C, Cu, Cv);
    const double step = (p - C).dot(Cu) / std::max(Cu.squaredNorm(), 1e-300);
    const double next = surface.wrap(u + step);
    const bool done = std::abs(next - u) < 1e-13 * std::max(1.0, chain.length);
    u = next;
    if (done) break;
  }
  surface.d1(u, v, C, Cu, Cv);
  // Across the line, in the base surface: the profile's own tangent there, which points into the band
  // at side A (start of the arc) and out of it at side B (end of the arc).
  Vec3 tau = Cv - Cv.dot(Cu) / std::max(Cu.squaredNorm(), 1e-300) * Cu;
  tau.normalize();
  if (side == 0) tau = -tau;
  if (u_out) *u_out = u;
  if (away) *away = tau;
  return (p - C).dot(tau);
}

namespace {

constexpr double kSnapKeepsAngle = 10 * M_PI / 180;  // facets around a vertex snapped from afar keep this
constexpr double kNearShaped = 0.4;                   // x its shortest edge: snapped if its facets keep shape
constexpr double kHairShare = 0.25;                   // x the tolerance: a dip of the band's edge this deep is a hair

// The direction a vertex on the mesh boundary may move in without moving the boundary: along its two
// boundary edges where they run on straight (zero where they turn, or where more meet). Zero for a vertex
// inside the mesh, with *on_boundary false.
Vec3 along_boundary(const MeshTopology& mesh, int v, bool* on_boundary) {
  std::vector<Vec3> out;
  for (int w : mesh.vertex_neighbours(v))
    if (mesh.edge_facet_count(v, w) == 1) out.push_back((mesh.point(w) - mesh.point(v)).normalized());
  *on_boundary = !out.empty();
  if (out.size() != 2 || out[0].dot(out[1]) > -1 + 1e-6) return Vec3::Zero();
  return out[0];
}

// Where vertex v (at signed distance d from the contact line, `away` the line's outward direction there)
// can move onto the line without changing the mesh's surface by more than `flat_tol`: along `away` where
// its facets are (nearly) coplanar, along the crease where they lie in two planes (an end face's edge) or
// along the mesh boundary it lies on (which stays where it was), nowhere at a corner of three or more or
// where the boundary turns. False when there is no such place.
bool snap_target(const MeshTopology& mesh, int v, const ContactLineDistance& distance, double d, double u,
                 const Vec3& away, double flat_tol, Vec3* q, bool* on_crease) {
  const Vec3 p = mesh.point(v);
  const int* begin = mesh.facets_begin(v);
  const Vec3 n1 = mesh.facet_normal(*begin);
  Vec3 crease = Vec3::Zero();
  double widest = 0;
  for (const int* g = begin; g != mesh.facets_end(v); ++g) {
    const Vec3 c = n1.cross(mesh.facet_normal(*g));
    if (c.norm() > widest) widest = c.norm(), crease = c.normalized();
  }
  *on_crease = widest >= std::sin(20 * M_PI / 180);
  bool on_boundary = false;
  const Vec3 boundary = along_boundary(mesh, v, &on_boundary);
  if (on_boundary) {
    if (boundary.isZero() || (*on_crease && std::abs(boundary.dot(crease)) < 1 - 1e-6)) return false;
    *on_crease = true, crease = boundary;
  }
  if (!*on_crease) {  // a smooth region: across the line, if that stays on it
    *q = p - d * away;
    for (const int* g = begin; g != mesh.facets_end(v); ++g)
      if (std::abs((*q - p).dot(mesh.facet_normal(*g))) > flat_tol) return false;
    return true;
  }
  for (const int* g = begin; g != mesh.facets_end(v); ++g)
    if (std::abs(mesh.facet_normal(*g).dot(crease)) > 1e-3) return false;  // a corner, or a curved side
  double t = 0;
  Vec3 tau = away;
  for (int it = 0; it < 4; ++it) {  // Newton along the crease
    const double slope = crease.dot(tau);
    if (std::abs(slope) < 0.2) return false;  // the crease runs nearly along the line
    t -= d / slope;
    d = distance(p + t * crease, u, &u, &tau);
  }
  *q = p + t * crease;
  return std::abs(d) <= 1e-6 * (1 + std::abs(t));
}

// True if no facet around v gets a smaller angle than min(kSnapKeepsAngle, its own) when v moves to q (its
// neighbours where earlier snaps put them; a facet turning over is snap_flattens', asked of every snap). The
// angle is not asked of a facet with another corner inside the band (`in_band`): the line cuts it and only
// its piece outside is kept, triangulated anew.
// (A CAD mesh's sliver 60 mm long beside a crease, one corner 0.07 mm outside the line and one inside:
// snapping the outer corner along the crease onto the line thinned the sliver, so it stayed, and the strip
// between it and the line was left a sliver of no area.)
bool snap_keeps_shape(const MeshTopology& mesh, const MeshEdit& edit, int v, const Vec3& q, const std::function<bool(int)>& in_band) {
  for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g) {
    Vec3 c[3];
    bool cut = false;
    for (int k = 0; k < 3; ++k) {
      c[k] = mesh.F(*g, k) == v ? q : edit.point(mesh.F(*g, k));
      cut |= mesh.F(*g, k) != v && in_band(mesh.F(*g, k));
    }
    const double before = smallest_angle(mesh.corner(*g, 0), mesh.corner(*g, 1), mesh.corner(*g, 2));
    if (!cut && smallest_angle(c[0], c[1], c[2]) < std::min(kSnapKeepsAngle, before)) return false;
  }
  return true;
}

// True if a facet around v would turn over or be left without area (the output check's kDegenerateDeg) with
// v at q: a sliver along the line whose three corners would all be on it (a round's contact row rounded again
// at the round's own radius: a MeshPart facet along the contact edge, its middle corner 3e-4 or 0.015 mm off
// that edge, all three snapped onto the line).
bool snap_flattens(const MeshTopology& mesh, const MeshEdit& edit, int v, const Vec3& q) {
  for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g) {
    Vec3 c[3];
    for (int k = 0; k < 3; ++k) c[k] = mesh.F(*g, k) == v ? q : edit.point(mesh.F(*g, k));
    if ((c[1] - c[0]).cross(c[2] - c[0]).dot(mesh.facet_normal(*g)) <= 0 || smallest_angle(c[0], c[1], c[2]) * 180 / M_PI < kDegenerateDeg)
      return true;
  }
  return false;
}

}  // namespace

SideTrim::SideTrim(TrimContext& ctx, int side, TrimLines& out)
    : ctx(ctx), mesh(ctx.mesh), edit(ctx.edit), opt(ctx.opt), side(side), out(out),
      line_distance{ctx.surface, ctx.chain, side}, hair(kHairShare * ctx.opt.tolerance) {}

// On an end's plane, the band's corner runs from the chain's end to the round's corner on this side (ends.h
// EndSegment): a point of the plane on the far side of the chain's end -- where this side's face goes on
// around the end, as a pocket's top face around its rim -- is outside, however the contact line measures it.
double SideTrim::behind_end(const Vec3& p) const {
  double behind = -INFINITY;
  for (int end = 0; end < 2; ++end) {
    if (!ctx.cuts[end] || std::abs(ctx.cuts[end]->past(p)) > ctx.plane_slack) continue;
    const Vec3 e = end ? ctx.chain.points.back() : ctx.chain.points.front();
    const Vec3 toward = (end ? ctx.end_profiles.back() : ctx.end_profiles.front()).contact[side] - e;
    if (toward.norm() > 0) behind = std::max(behind, -(p - e).dot(toward.normalized()));
  }
  return behind;
}

// The band's edge: the contact line, and past a capped end its end face's plane. A point on the plane is
// measured from the line alone, so that an edge lying in the plane is cut where the line crosses it.
double SideTrim::distance(const Vec3& p, double u_hint, double* u_out, Vec3* away) const {
  const double d = line_distance(p, u_hint, u_out, away);
  const double past = ctx.past_end(p);
  if (past > ctx.plane_slack) return std::max(d, past);
  const double behind = behind_end(p);
  return behind > ctx.plane_slack ? std::max(d, behind) : d;
}

// The parameter of a point q on the contact line, searched from a few starts between u_a and u_b (first at
// the share w0): the one whose line point is nearest q. Near a capped end the line may double back (a
// concave mitre's plane crosses it short of the chain's end), and a search can stop at the end, where q is
// level with the line but not on it.
double SideTrim::u_on_line(const Vec3& q, double u_a, double u_b, double w0) const {
  double u = u_a, best = INFINITY;
  for (double w : {w0, 0.0, 1.0, 0.25, 0.75}) {
    double u_try = u_a + wrapped_delta(ctx.surface, u_a, u_b) * w;
    line_distance(q, u_try, &u_try);
    const double off = (ctx.surface.value(u_try, side) - q).norm();
    if (off < best) best = off, u = u_try;
    if (off <= ctx.plane_slack + 1e-9 * ctx.surface.u_last) break;
  }
  return u;
}

// The trim classifies facets by their corners' sides, so an edge between two kept corners must not run into
// the band between them. Where the contact line curves tightly (the arc a rim's contact line makes around a
// rolled corner) and the facets are long (a CAD mesh), a vertex snapped onto the line, or lying just outside
// it, can have an edge to a kept vertex that leaves it nearly along the line on the band's side and comes
// out again farther on: the kept facet beside that edge overlaps the band, the trim line's points in the cut
// facet next to it fall beyond the edge, and that polygon folds over (0.11 mm on the drafted pocket's CAD
// mesh at r = 2.5, the edge 7.9 mm long). True if the band's edge, sampled along from -> to (densely near
// `from`, where such a dip begins), comes back into the band by more than a hair after being out (or on it,
// at `from`). A dip within a hair is left to side_stands_for_line (trim.cpp).
bool SideTrim::reenters(const Vec3& from, const Vec3& to, double u) const {
  const double length = (to - from).norm();
  if (!(length > 0)) return false;
  std::vector<double> ts;
  for (int i = 1; i < 16; ++i) ts.push_back(i / 16.0);
  for (double t = 0.25; t * length > 0.25 * hair; t *= 0.5) ts.push_back(t);
  std::sort(ts.begin(), ts.end());
  bool outside = distance(from, u, &u) > -hair;
  for (double t : ts) {
    const double d = distance(from + t * (to - from), u, &u);
    if (d > hair) outside = true;
    else if (d < -hair && outside) return true;
  }
  return false;
}

// How far the line bends from its chords over +-L around u (a circle's sag over a half chord L is the
// deepest dip of a segment of length L from a point on it).
double SideTrim::line_bend(double u, double L) const {
  Vec3 C, Cu, Cv;
  ctx.surface.d1(u, side, C, Cu, Cv);
  const double h = 0.5 * L / std::max(Cu.norm(), 1e-300);
  Vec3 c[5];
  for (int k = 0; k < 5; ++k) c[k] = ctx.surface.value(ctx.surface.wrap(u + (k - 2) * h), side);
  double t;
  return std::max({(closest_point_on_segment(c[2], c[0], c[4], &t) - c[2]).norm(),
                   (closest_point_on_segment(c[1], c[0], c[2], &t) - c[1]).norm(),
                   (closest_point_on_segment(c[3], c[2], c[4], &t) - c[3]).norm()});
}

// True if an edge from vertex v, at q, to a vertex of this side's base beyond the line or on it enters the
// band by more than a hair (reenters): an edge between two vertices on the line is taken as running along it
// (the round's boundary row follows it), so on a curved line it must be short enough to stay within a hair
// of the line (on the pocket's CAD mesh at r = 5 a chord 11 mm long left the line by 1.1 mm and the round
// beside it 0.027 r off the exact one). Neither can happen where the line is straight over the edges'
// length, nor to an edge that leaves the line outwards more steeply than the line bends over its length
// (line_bend): only the edges that may dip are sampled.
bool SideTrim::edge_reenters(int v, const Vec3& q, double u_v) const {
  double longest = 0;
  for (int w : mesh.vertex_neighbours(v)) longest = std::max(longest, (edit.point(w) - q).norm());
  const double bend = line_bend(u_v, longest);
  if (bend < 0.1 * hair) return false;
  Vec3 away;
  double u_q = u_v;
  distance(q, u_v, &u_q, &away);
  for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g) {
    const auto it = ctx.base.side_of.find(*g);
    if (it == ctx.base.side_of.end() || it->second != side) continue;
    for (int k = 0; k < 3; ++k) {
      const int w = mesh.F(*g, k);
      const Vec3 e = edit.point(w) - q;
      if (w == v || e.dot(away) >= 2 * (bend + hair)) continue;  // (e.dot(away) / |e|: the sine of its climb)
      double u = u_q;
      if (distance(edit.point(w), u, &u) >= -hair && reenters(q, edit.point(w), u_q)) return true;
    }
  }
  return false;
}

// A vertex's true distance, when a cut needs it.
VertexSide& SideTrim::exact(int v) {
  VertexSide& s = vs[v];
  if (!s.exact) {
    s.d = distance(edit.point(v), s.u, &s.u);
    // The chain is inside the band by definition, up to a capped end's plane (a sphere corner's plane
    // crosses the chain short of its end: the chain's vertices past it are outside).
    if (ctx.chain_vertices.count(v) && ctx.past_end(edit.point(v)) <= ctx.plane_slack) s.d = std::min(s.d, -1e-9);
    s.exact = true;
  }
  return s;
}

// Whether p, on a capped end's plane, is the band's corner there: within a corner weld of the surface's
// corner (ends.cpp insert_corner takes a vertex that near for it); *u_end: that end's parameter.
bool SideTrim::at_corner(const Vec3& p, double* u_end) const {
  for (int end = 0; end < 2; ++end) {
    if (!ctx.cuts[end] || std::abs(ctx.cuts[end]->past(p)) > ctx.plane_slack) continue;
    *u_end = end ? ctx.surface.u_last : ctx.surface.u_first;
    if ((ctx.surface.value(*u_end, side) - p).norm() <= std::max(ctx.plane_slack, kCornerWeldShare * opt.tolerance)) return true;
  }
  return false;
}

// The parameter of the band's corner p on a capped end's plane (the end profile's contact): the end's own.
// Over a carried end's straight piece the contact line creeps up to the plane (0.07 mm over its last
// 0.66 of u at a drafted pocket's wall corner), so the line's search from a vertex snapped there along the
// end face's edge can stop short of the end; the inner rows span the trim lines' parameters and would stop
// there too, below the plane, and the gap to the end face be sewn with tilted facets.
double SideTrim::corner_u(const Vec3& p, double u) const {
  double u_end;
  return at_corner(p, &u_end) ? u_end : u;
}

void SideTrim::classify_vertices() {
  for (int f : ctx.base.facets[side])
    for (int k = 0; k < 3; ++k) {
      poll_cancel();
      const int v = mesh.F(f, k);
      if (vs.count(v)) continue;
      VertexSide s;
      Vec3 away;
      const ChainProjection& near = ctx.base.projection.at(v);
      const double from_chain = near.distance, s_chain = near.s;
      const double past = ctx.past_end(mesh.point(v));
      if (past > ctx.plane_slack) {  // past a capped end's face: outside the band
        vs[v] = {kFar, s_chain, false};
        continue;
      }
      const bool on_end_plane = past >= -ctx.plane_slack;
      if (!on_end_plane && (from_chain > 1.3 * ctx.farthest[side] || from_chain < 0.7 * ctx.nearest[side])) {  // clearly out / in
        vs[v] = {from_chain < 0.7 * ctx.nearest[side] ? -kFar : kFar, s_chain, false};
        continue;
      }
      s.exact = true;
      s.d = distance(mesh.point(v), s_chain, &s.u, &away);
      // The band's corner (ends.h: a vertex; within a corner weld of the surface's, insert_corner's pick).
      double u_end;
      if (on_end_plane && (std::abs(s.d) <= ctx.plane_slack || at_corner(mesh.point(v), &u_end))) s.d = 0;
      if (ctx.chain_vertices.count(v)) s.d = std::min(s.d, -1e-9);  // (past a capped end's plane: kFar above)
      else if (std::abs(s.d) > 0 && !edit.moved.count(v)) {
        snap_near_line(v, s, away, on_end_plane);
        // Not moved but within a weld of the line (a sliver beside it would flatten): on the line where it is.
        // (A round made again at its own radius: its contact line runs 2e-5 mm from the old contact vertices,
        // and the cut facets' points 3e-5 mm from them made facets of no area.)
        if (std::abs(s.d) <= kWeldShare * opt.tolerance) s.d = 0;
      }
      if (on_end_plane && s.d == 0) s.u = corner_u(edit.point(v), s.u);
      vs[v] = s;
      if (s.d == 0) out.line[side].push_back({v, s.u});
    }
}

// True if a facet around v has its two other corners on the line already: v snapped too, all three would be
// on it, a facet of next to no area that is neither in the band nor out (the rim around rounded wall corners,
// sharpened on its 1.4 mm mesh and made 2.1 mm: two old contact vertices 0.1 mm inside the new line and one
// 0.11 mm outside between them, each snapped, left a facet of 0.013 deg along the line, and a hole beside it).
bool SideTrim::closes_facet_on_line(int v) const {
  for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g) {
    int on = 0;
    for (int k = 0; k < 3; ++k) {
      const int w = mesh.F(*g, k);
      const auto it = vs.find(w);
      on += w != v && it != vs.end() && it->second.d == 0;
    }
    if (on == 2) return true;
  }
  return false;
}

// A vertex very near the line moves onto it (when that does not change the surface): no slivers. Near means
// within a fifth of its shortest edge; or within kNearShaped of it when its facets keep their shape (a fine
// mesh's row of vertices just off the line would leave a strip of slivers between itself and the line); or,
// for a vertex on an end face's edge, within 0.4 of the line's spacing when its facets keep their shape (it
// would leave a sliver between the arc and itself in the end face).
void SideTrim::snap_near_line(int v, VertexSide& s, const Vec3& away, bool on_end_plane) {
  double shortest = INFINITY;
  for (int w : mesh.vertex_neighbours(v))  // (facets on the chain go with the band: their shape is moot)
    if (!ctx.chain_vertices.count(w)) shortest = std::min(shortest, (mesh.point(w) - mesh.point(v)).norm());
  const double near_edges = 0.2 * shortest, near_line = 0.4 * opt.max_spacing(s.u);
  Vec3 q;
  bool on_crease = false;
  if (!(std::abs(s.d) < std::max(near_edges, near_line) &&
        snap_target(mesh, v, line_distance, s.d, s.u, away, 0.02 * opt.tolerance, &q, &on_crease)))
    return;
  const double move = (q - mesh.point(v)).norm();
  // (For a snap along a crease only: everywhere, it let snaps through that left degenerate pieces of cut
  // facets on CAD meshes of the L channel and the drafted shoulder.)
  auto in_band = [&](int w) {
    double u = s.u;
    return on_crease && distance(edit.point(w), s.u, &u) < -hair;
  };
  // Along a crease two vertices may have one target, where the line crosses the crease between them: the
  // nearer goes there (the farther one snapped first, from inside the band, left the nearer a hair outside
  // the line, and the strip between them a sliver of no area: a CAD mesh's rows along a round that was
  // sharpened, 60 mm long, 0.07 mm off the line).
  if (on_crease)
    for (int w : mesh.vertex_neighbours(v)) {
      const Vec3 vw = mesh.point(w) - mesh.point(v), vq = q - mesh.point(v);
      if (!edit.moved.count(w) && (mesh.point(w) - q).norm() < move && vw.cross(vq).norm() <= 1e-3 * vw.norm() * vq.norm()) return;
    }
  // Nor where a neighbour already is, or was snapped to (two vertices on an end face's edge, each snapped
  // along its own crease to the band's corner: 3e-6 mm apart on a gmsh mesh of the L bracket at r = 6, and
  // the strip between them a facet of no area).
  for (int w : mesh.vertex_neighbours(v))
    if ((edit.point(w) - q).norm() <= kWeldShare * opt.tolerance) return;
  const bool stays_on_end_plane = !on_end_plane || std::abs(ctx.past_end(q)) <= ctx.plane_slack;  // (e.g. along the end face's edge)
  if (!(stays_on_end_plane && (move < near_edges || ((on_crease ? move < near_line : move < kNearShaped * shortest) &&
                                                     snap_keeps_shape(mesh, edit, v, q, in_band)))))
    return;
  if (snap_flattens(mesh, edit, v, q) || closes_facet_on_line(v)) return;
  if (!edge_reenters(v, q, s.u)) {
    edit.moved[v] = q;
    s.d = 0;
    ++out.vertices_snapped;
  } else if (!on_crease && s.d > -near_line) {
    // On the line an edge of it would run into the band and out again (edge_reenters): in flat ground the
    // vertex goes a little way past the line instead, into the band, where its edges leave the band once --
    // as far in as a vertex that is not snapped may be (0.4 of the line's spacing), within half its shortest
    // edge; if that turns a facet over or still leaves an edge re-entering, it stays where it is.
    const double depth = std::min(near_line, 0.5 * shortest);
    const Vec3 p = mesh.point(v), q_in = q - depth * away;
    double u_in = s.u;
    bool fits = distance(q_in, s.u, &u_in) < -hair;
    for (const int* g = mesh.facets_begin(v); fits && g != mesh.facets_end(v); ++g) {
      Vec3 c[3];
      for (int j = 0; j < 3; ++j) c[j] = mesh.F(*g, j) == v ? q_in : edit.point(mesh.F(*g, j));
      const Vec3 n = mesh.facet_normal(*g);
      fits = std::abs((q_in - p).dot(n)) <= 0.02 * opt.tolerance && (c[1] - c[0]).cross(c[2] - c[0]).dot(n) > 0;
    }
    if (fits && !edge_reenters(v, q_in, u_in)) {
      edit.moved[v] = q_in;
      s.d = distance(q_in, u_in, &s.u);
    }
  }
}

}  // namespace meshround
