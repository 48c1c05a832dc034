#include "meshround/trim.h"
#include "meshround/cancel.h"
#include "call_checks.h"
#include "trim_caps.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace meshround {
namespace {

// Signed distance of a point of one base mesh from that side's contact line, in the base surface:
// negative inside the band. `u` is the line parameter of the foot point.
struct ContactLineDistance {
  const RoundingSurface& surface;
  const SharpChain& chain;
  int side;  // 0: A (v = 0), 1: B (v = 1)

  double operator()(const Vec3& p, double u_hint, double* u_out, Vec3* away = nullptr) const {
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
};

constexpr double kFar = 1e30;  // |signed distance| of a vertex whose side is clear without projecting it
constexpr double kSnapKeepsAngle = 10 * M_PI / 180;  // facets around a vertex snapped from afar keep this
constexpr double kNearShaped = 0.4;                   // x its shortest edge: snapped if its facets keep shape
// A trim line's point within kHairShare of the tolerance outside its facet is a hair outside (hair_outside).
constexpr double kHairShare = 0.25;

struct VertexSide {
  double d = 0;        // signed distance (0 = on the trim line after snapping); +-kFar: side known only
  double u = 0;
  bool exact = false;  // d is the true distance
};

// Where vertex v (at signed distance d from the contact line, `away` the line's outward direction there)
// can move onto the line without changing the mesh's surface by more than `flat_tol`: along `away` where
// its facets are (nearly) coplanar, along the crease where they lie in two planes (an end face's edge),
// nowhere at a corner of three or more. False when there is no such place.
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

// True if no facet around v turns over, or gets a smaller angle than min(kSnapKeepsAngle, its own), when v
// moves to q (its neighbours where earlier snaps put them).
bool snap_keeps_shape(const MeshTopology& mesh, const MeshEdit& edit, int v, const Vec3& q) {
  for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g) {
    Vec3 c[3];
    for (int k = 0; k < 3; ++k) c[k] = mesh.F(*g, k) == v ? q : edit.point(mesh.F(*g, k));
    const double before = smallest_angle(mesh.corner(*g, 0), mesh.corner(*g, 1), mesh.corner(*g, 2));
    if ((c[1] - c[0]).cross(c[2] - c[0]).dot(mesh.facet_normal(*g)) <= 0 ||
        smallest_angle(c[0], c[1], c[2]) < std::min(kSnapKeepsAngle, before))
      return false;
  }
  return true;
}

double wrapped_delta(const RoundingSurface& s, double from, double to) {
  double d = to - from;
  if (s.closed) {
    const double p = s.u_last - s.u_first;
    d -= std::round(d / p) * p;
  }
  return d;
}

// The part of an input edge between a trim line and the edge's kept end, with points graded along it.
struct KeptPiece {
  int trim_end;             // the trim vertex (a cut point, or an input vertex on the line)
  std::vector<int> points;  // inner points of the piece, from trim_end towards the kept end
};

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

}  // namespace

TrimLines trim_base_meshes(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base,
                           const RoundingSurface& surface, const std::vector<ProfileStation>& end_profiles,
                           const TrimOptions& opt, MeshEdit& edit) {
  TrimLines out;
  // How far from the chain each contact line gets. Vertices well inside that range are in the band and
  // well beyond it outside: only their side matters, unless a cut edge needs their exact distance.
  double nearest[2] = {INFINITY, INFINITY}, farthest[2] = {0, 0};
  for (const ProfileStation& st : end_profiles)
    for (int k = 0; k < 2; ++k) {
      // (A capped end's contacts are moved onto its plane: the band's corner there, past the chain's end at
      // a mitre, farther from the chain than the contact lines are.)
      const Vec3 contact = st.cut.active ? st.cut.onto(st.contact[k]) : st.contact[k];
      const double d = (contact - chain.point_at(st.s)).norm();
      nearest[k] = std::min(nearest[k], d), farthest[k] = std::max(farthest[k], d);
    }
  const std::unordered_set<int> chain_vertices(chain.vertices.begin(), chain.vertices.end());
  // Capped ends cut by their end face (ends.h): there the band stops at the face's plane. `plane_slack`:
  // "on" that plane, for float32 coordinates -- of the mesh's magnitude, not the chain's: two rounds meeting
  // at a corner must agree whether a vertex there is on their lines (a mitre's foot 5e-5 from a mesh
  // vertex on the pocket's wall corner was on the first round's line and off the second's).
  const EndCut* cuts[2] = {nullptr, nullptr};
  double plane_slack = 0;
  const double magnitude = coordinate_magnitude(mesh.V);
  for (int end = 0; end < 2 && !chain.closed; ++end) {
    const ProfileStation& st = end ? end_profiles.back() : end_profiles.front();
    if (!st.cut.active) continue;
    cuts[end] = &st.cut;
    plane_slack = std::max(plane_slack, on_plane_slack(st.radius, std::max(magnitude, st.cut.point.cwiseAbs().maxCoeff())));
  }
  auto past_end = [&](const Vec3& p) {
    double past = -INFINITY;
    for (const EndCut* c : cuts)
      if (c) past = std::max(past, c->past(p));
    return past;
  };
  std::unordered_map<std::uint64_t, KeptPiece> kept_piece;  // edge_key(trim_end, kept_end) -> the piece
  // The points on a kept piece, when a polygon runs along it from `from` to `to`.
  auto add_piece_points = [&](int from, int to, std::vector<int>& polygon) {
    auto it = kept_piece.find(edge_key(from, to));
    if (it == kept_piece.end()) return;
    const auto& points = it->second.points;
    if (it->second.trim_end == from) polygon.insert(polygon.end(), points.begin(), points.end());
    else polygon.insert(polygon.end(), points.rbegin(), points.rend());
  };
  for (int side = 0; side < 2; ++side) {
    const ContactLineDistance line_distance{surface, chain, side};
    // The band's edge: the contact line, and past a capped end its end face's plane. A point on the plane
    // is measured from the line alone, so that an edge lying in the plane is cut where the line crosses it.
    // On an end's plane, the band's corner runs from the chain's end to the round's corner on this side
    // (ends.h EndSegment): a point of the plane on the far side of the chain's end -- where this side's
    // face goes on around the end, as a pocket's top face around its rim -- is outside, however the
    // contact line measures it.
    auto behind_end = [&](const Vec3& p) {
      double behind = -INFINITY;
      for (int end = 0; end < 2; ++end) {
        if (!cuts[end] || std::abs(cuts[end]->past(p)) > plane_slack) continue;
        const Vec3 e = end ? chain.points.back() : chain.points.front();
        const Vec3 toward = (end ? end_profiles.back() : end_profiles.front()).contact[side] - e;
        if (toward.norm() > 0) behind = std::max(behind, -(p - e).dot(toward.normalized()));
      }
      return behind;
    };
    auto distance = [&](const Vec3& p, double u_hint, double* u_out, Vec3* away = nullptr) {
      const double d = line_distance(p, u_hint, u_out, away);
      const double past = past_end(p);
      if (past > plane_slack) return std::max(d, past);
      const double behind = behind_end(p);
      return behind > plane_slack ? std::max(d, behind) : d;
    };
    // The parameter of a point q on the contact line, searched from a few starts between u_a and u_b
    // (first at the share w): the one whose line point is nearest q. Near a capped end the line may
    // double back (a concave mitre's plane crosses it short of the chain's end), and a search can stop
    // at the end, where q is level with the line but not on it.
    auto u_on_line = [&](const Vec3& q, double u_a, double u_b, double w0) {
      double u = u_a, best = INFINITY;
      for (double w : {w0, 0.0, 1.0, 0.25, 0.75}) {
        double u_try = u_a + wrapped_delta(surface, u_a, u_b) * w;
        line_distance(q, u_try, &u_try);
        const double off = (surface.value(u_try, side) - q).norm();
        if (off < best) best = off, u = u_try;
        if (off <= plane_slack + 1e-9 * surface.u_last) break;
      }
      return u;
    };
    // The trim classifies facets by their corners' sides, so an edge between two kept corners must not run
    // into the band between them. Where the contact line curves tightly (the arc a rim's contact line makes
    // around a rolled corner) and the facets are long (a CAD mesh), a vertex snapped onto the line, or lying
    // just outside it, can have an edge to a kept vertex that leaves it nearly along the line on the band's
    // side and comes out again farther on: the kept facet beside that edge overlaps the band, the trim line's
    // points in the cut facet next to it fall beyond the edge, and that polygon folds over (0.11 mm on the
    // drafted pocket's CAD mesh at r = 2.5, the edge 7.9 mm long). `reenters`: the band's edge, sampled along
    // from -> to (densely near `from`, where such a dip begins), comes back into the band by more than a hair
    // after being out (or on it, at `from`). A dip within a hair is left to hair_outside (below).
    const double hair = kHairShare * opt.tolerance;
    auto reenters = [&](const Vec3& from, const Vec3& to, double u) {
      const double length = (to - from).norm();
      if (!(length > 0)) return false;
      std::vector<double> ts;
      for (int i = 1; i < 16; ++i) ts.push_back(i / 16.0);
      for (double t = 0.25; t * length > 0.25 * hair; t *= 0.5) ts.push_back(t);
      std::sort(ts.begin(), ts.end());
      bool out = distance(from, u, &u) > -hair;
      for (double t : ts) {
        const double d = distance(from + t * (to - from), u, &u);
        if (d > hair) out = true;
        else if (d < -hair && out) return true;
      }
      return false;
    };
    // True if an edge from vertex v, at q, to a vertex of this side's base beyond the line or on it enters the
    // band by more than a hair: an edge between two vertices on the line is taken as running along it (the
    // round's boundary row follows it), so on a curved line it must be short enough to stay within a hair
    // of the line (on the pocket's CAD mesh at r = 5 a chord 11 mm long left the line by 1.1 mm and the
    // round beside it 0.027 r off the exact one).
    // Neither can happen where the line is straight over the edges' length, nor to an edge that leaves the
    // line outwards more steeply than the line bends over its length: `line_bend` is how far the line
    // bends from its chords over +-L around u (a circle's sag over a half chord L is the deepest dip of a
    // segment of length L from a point on it), so that only the edges that may dip are sampled.
    auto line_bend = [&](double u, double L) {
      Vec3 C, Cu, Cv;
      surface.d1(u, side, C, Cu, Cv);
      const double h = 0.5 * L / std::max(Cu.norm(), 1e-300);
      Vec3 c[5];
      for (int k = 0; k < 5; ++k) c[k] = surface.value(surface.wrap(u + (k - 2) * h), side);
      double t;
      return std::max({(closest_point_on_segment(c[2], c[0], c[4], &t) - c[2]).norm(),
                       (closest_point_on_segment(c[1], c[0], c[2], &t) - c[1]).norm(),
                       (closest_point_on_segment(c[3], c[2], c[4], &t) - c[3]).norm()});
    };
    auto edge_reenters = [&](int v, const Vec3& q, double u_v) {
      double longest = 0;
      for (int w : mesh.vertex_neighbours(v)) longest = std::max(longest, (edit.point(w) - q).norm());
      const double bend = line_bend(u_v, longest);
      if (bend < 0.1 * hair) return false;
      Vec3 away;
      double u_q = u_v;
      distance(q, u_v, &u_q, &away);
      for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g) {
        const auto it = base.side_of.find(*g);
        if (it == base.side_of.end() || it->second != side) continue;
        for (int k = 0; k < 3; ++k) {
          const int w = mesh.F(*g, k);
          const Vec3 e = edit.point(w) - q;
          if (w == v || e.dot(away) >= 2 * (bend + hair)) continue;  // (e.dot(away) / |e|: the sine of its climb)
          double u = u_q;
          if (distance(edit.point(w), u, &u) >= -hair && reenters(q, edit.point(w), u_q)) return true;
        }
      }
      return false;
    };
    std::unordered_set<int> plane_points;  // trim points on an end face's plane, not on the contact line
    std::unordered_map<int, VertexSide> vs;
    std::unordered_map<int, double> cut_u;  // cut point -> its line parameter
    auto exact = [&](int v) -> VertexSide& {  // a vertex's true distance, when a cut needs it
      VertexSide& s = vs[v];
      if (!s.exact) {
        s.d = distance(edit.point(v), s.u, &s.u);
        // The chain is inside the band by definition, up to a capped end's plane (a sphere corner's plane
        // crosses the chain short of its end: the chain's vertices past it are outside).
        if (chain_vertices.count(v) && past_end(edit.point(v)) <= plane_slack) s.d = std::min(s.d, -1e-9);
        s.exact = true;
      }
      return s;
    };
    for (int f : base.facets[side])
      for (int k = 0; k < 3; ++k) {
        poll_cancel();
        const int v = mesh.F(f, k);
        if (vs.count(v)) continue;
        VertexSide s;
        Vec3 away;
        const ChainProjection& near = base.projection.at(v);
        const double from_chain = near.distance, s_chain = near.s;
        const double past = past_end(mesh.point(v));
        if (past > plane_slack) {  // past a capped end's face: outside the band
          vs[v] = {kFar, s_chain, false};
          continue;
        }
        const bool on_end_plane = past >= -plane_slack;
        if (!on_end_plane && (from_chain > 1.3 * farthest[side] || from_chain < 0.7 * nearest[side])) {  // clearly out / in
          vs[v] = {from_chain < 0.7 * nearest[side] ? -kFar : kFar, s_chain, false};
          continue;
        }
        s.exact = true;
        s.d = distance(mesh.point(v), s_chain, &s.u, &away);
        if (on_end_plane && std::abs(s.d) <= plane_slack) s.d = 0;  // the band's corner (ends.h: a vertex)
        if (chain_vertices.count(v)) s.d = std::min(s.d, -1e-9);  // (past a capped end's plane: kFar above)
        // A vertex very near the line moves onto it (when that does not change the surface): no slivers.
        // Near means within a fifth of its shortest edge; or within kNearShaped of it when its facets
        // keep their shape (a fine mesh's row of vertices just off the line would leave a strip of
        // slivers between itself and the line); or, for a vertex on an end face's edge, within 0.4 of the
        // line's spacing when its facets keep their shape (it would leave a sliver between the arc and
        // itself in the end face).
        else if (std::abs(s.d) > 0 && !edit.moved.count(v)) {
          double shortest = INFINITY;
          for (int w : mesh.vertex_neighbours(v))  // (facets on the chain go with the band: their shape is moot)
            if (!chain_vertices.count(w)) shortest = std::min(shortest, (mesh.point(w) - mesh.point(v)).norm());
          const double near_edges = 0.2 * shortest, near_line = 0.4 * opt.max_spacing(s.u);
          Vec3 q;
          bool on_crease = false;
          if (std::abs(s.d) < std::max(near_edges, near_line) &&
              snap_target(mesh, v, line_distance, s.d, s.u, away, 0.02 * opt.tolerance, &q, &on_crease)) {
            const double move = (q - mesh.point(v)).norm();
            const bool stays_on_end_plane = !on_end_plane || std::abs(past_end(q)) <= plane_slack;  // (e.g. along the end face's edge)
            if (stays_on_end_plane && (move < near_edges || ((on_crease ? move < near_line : move < kNearShaped * shortest) &&
                                      snap_keeps_shape(mesh, edit, v, q)))) {
              if (!edge_reenters(v, q, s.u)) {
                edit.moved[v] = q;
                s.d = 0;
                ++out.vertices_snapped;
              } else if (!on_crease && s.d > -near_line) {
                // On the line an edge of it would run into the band and out again (above): in flat ground the
                // vertex goes a little way past the line instead, into the band, where its edges leave the
                // band once -- as far in as a vertex that is not snapped may be (0.4 of the line's spacing),
                // within half its shortest edge; if that turns a facet over or still leaves an edge
                // re-entering, it stays where it is.
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
          }
        }
        vs[v] = s;
        if (s.d == 0) out.line[side].push_back({v, s.u});
      }

    // The kept piece of a long edge from the trim line gets points whose spacing grows from the trim
    // line's by half again each step: the facets on both sides of it can then grade from the fine trim
    // line to their far corners instead of fanning out in slivers. None goes beyond the reach, but one
    // where the piece leaves it: the facets beyond hinge on that point, and fan from it back to the
    // nearer points within a narrow angle (the face's width seen from the hinge). That fan is only well
    // shaped when the hinge's neighbour is far, so no graded point stays in the outer kHingeRoom of the
    // piece's part within the reach.
    constexpr double kHingeRoom = 0.6;
    auto grade_piece = [&](int trim_end, int kept_end, double u) {
      KeptPiece& piece = kept_piece[edge_key(trim_end, kept_end)];
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
        double in = stops.empty() ? 0 : stops.back(), out = ran_out ? length : at;
        for (int it = 0; it < 30; ++it) (admitted(0.5 * (in + out)) ? in : out) = 0.5 * (in + out);
        if (ran_out && length - in < in) in = -1;  // no room beyond: keep the graded stops as they are
        if (in >= 0) {
          while (!stops.empty() && stops.back() > (1 - kHingeRoom) * in) stops.pop_back();
          if (length - in > 0.5 * step) stops.push_back(in);
        }
      }
      for (double s : stops) piece.points.push_back(edit.add_point(x + (y - x) * (s / length)));
    };
    // Cut points on the edges that cross the line.
    auto cut_point = [&](int a, int b) -> int {
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
      for (const EndCut* c : cuts) {
        if (!c || c->past(pb) <= plane_slack) continue;
        const double fa = std::min(c->past(pa), 0.0), crossing = fa / (fa - c->past(pb));
        if (crossing < first_crossing) first_crossing = crossing, beyond = c;
      }
      // A vertex in the band on that plane: the plane's trace runs through the vertex itself. So too where
      // the edge runs in the plane to its far side of the chain's end (behind_end).
      const bool a_on_plane = beyond ? std::abs(beyond->past(pa)) <= plane_slack : std::abs(past_end(pa)) <= plane_slack;
      if ((beyond || behind_end(pb) > plane_slack) && a_on_plane) {
        plane_points.insert(a);
        return a;
      }
      double t0 = 0, t1 = 1, f0 = exact(a).d, f1 = exact(b).d, u = vs[a].u, t = 0.5;
      int side_kept = 0;
      for (int it2 = 0; it2 < 60; ++it2) {  // Illinois regula falsi
        t = (t0 * f1 - t1 * f0) / (f1 - f0);
        const double f = distance(pa + t * (pb - pa), u, &u);
        if (std::abs(f) < 1e-12 * std::max(1.0, surface.u_last) || t1 - t0 < 1e-14) break;
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
      const bool on_plane = beyond && line_distance(pa + t * (pb - pa), u, &u_line) < -plane_slack;
      if (on_plane) {
        t = std::clamp(first_crossing, 0.0, 1.0);
      }
      if (!on_plane) u = u_on_line(pa + t * (pb - pa), vs[a].u, vs[b].u, 0.0);
      const int id = edit.add_point(pa + t * (pb - pa));
      edit.edge_point[key] = id;
      cut_u[id] = u;
      if (on_plane) plane_points.insert(id);
      else out.line[side].push_back({id, u});
      grade_piece(id, b, u);
      return id;
    };

    // Input edges from a vertex on the line to a kept one are graded as well when both their facets are
    // cut or kept whole (all around such a vertex, so that no acute corner has points on one side
    // only); kept facets with graded edges are retriangulated with the points (below).
    std::unordered_set<int> cut_facets, rebuild;
    for (int f : base.facets[side]) {
      int in = 0, beyond = 0;
      for (int k = 0; k < 3; ++k) in += vs[mesh.F(f, k)].d < 0, beyond += vs[mesh.F(f, k)].d > 0;
      if (in > 0 && beyond > 0) cut_facets.insert(f);
    }
    auto kept_whole = [&](int g) {
      auto it = base.side_of.find(g);
      return it != base.side_of.end() && it->second == side &&
             std::all_of(&mesh.F(g, 0), &mesh.F(g, 0) + 3, [&](int v) { return vs[v].d >= 0; });
    };
    for (int f : base.facets[side])
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
        if (!((vs[a].d == 0 && vs[b].d > 0) || (vs[b].d == 0 && vs[a].d > 0)) || kept_piece.count(edge_key(a, b))) continue;
        const std::vector<int> pair = mesh.edge_facets(a, b);
        if (pair.size() != 2 || !std::all_of(pair.begin(), pair.end(), [&](int g) { return cut_facets.count(g) || kept_whole(g); }))
          continue;
        vs[a].d == 0 ? grade_piece(a, b, vs[a].u) : grade_piece(b, a, vs[b].u);
        for (int g : pair)
          if (!cut_facets.count(g)) rebuild.insert(g);
      }
    // q (in facet f's plane) a hair outside one of f's sides -- within kHairShare of the tolerance (the sag
    // the line's points are spaced for, below), with its corners where the snaps put them. (A line that runs
    // well outside a thin CAD facet and back, by 0.7 mm and more on the S chain's, is taken as it is.)
    auto hair_outside = [&](int f, const Vec3& q) {
      const Vec3 c[3] = {edit.point(mesh.F(f, 0)), edit.point(mesh.F(f, 1)), edit.point(mesh.F(f, 2))};
      const Vec3 n = (c[1] - c[0]).cross(c[2] - c[0]).normalized();
      for (int k = 0; k < 3; ++k) {
        const Vec3 side = c[(k + 1) % 3] - c[k];
        const double out = -side.cross(q - c[k]).dot(n) / side.norm();  // > 0 outside this side
        if (out > 0 && out <= kHairShare * opt.tolerance) return true;
      }
      return false;
    };
    for (int f : base.facets[side]) {
      poll_cancel();
      int in = 0, outside = 0;
      for (int k = 0; k < 3; ++k) (vs[mesh.F(f, k)].d < 0 ? in : outside) += 1;
      if (in == 0) continue;
      edit.removed.insert(f);
      if (outside == 0 || std::all_of(&mesh.F(f, 0), &mesh.F(f, 0) + 3, [&](int v) { return vs[v].d <= 0; })) {
        ++out.facets_removed;
        continue;
      }
      ++out.facets_cut;
      // The outer part: kept corners and cut points in order, the trim line between them refined.
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
          if (kept_piece.count(edge_key(mesh.F(f, k), mesh.F(f, (k + 1) % 3)))) rebuild.insert(f);
        continue;
      }
      if (skipped && !band_before.empty()) band_before[0] = true;
      const Vec3 n = mesh.facet_normal(f), p0 = mesh.corner(f, 0);
      std::vector<int> polygon;
      for (size_t i = 0; i < ring.size(); ++i) {
        const Item& prev = ring[(i + ring.size() - 1) % ring.size()];
        if (!band_before[i]) add_piece_points(prev.vertex, ring[i].vertex, polygon);
        // (A piece on an end face's plane is straight: it needs no points.)
        if (band_before[i] && prev.trim && ring[i].trim && !plane_points.count(prev.vertex) && !plane_points.count(ring[i].vertex)) {
          // Extra points where the contact line bends or runs long inside this facet.
          const Vec3 x1 = edit.point(prev.vertex), x2 = edit.point(ring[i].vertex);
          const double du = wrapped_delta(surface, prev.u, ring[i].u);
          auto on_facet = [&](double u) { Vec3 q = surface.value(u, side); return Vec3(q - (q - p0).dot(n) * n); };
          const Vec3 mid = on_facet(prev.u + 0.5 * du);
          double t;
          const double sag = (closest_point_on_segment(mid, x1, x2, &t) - mid).norm();
          double want = std::max({1.0, std::ceil((x2 - x1).norm() / opt.max_spacing(prev.u + 0.5 * du)),
                                  std::ceil(std::sqrt(sag / (0.25 * opt.tolerance)))});
          if (!(want <= 1e9)) want = INFINITY;  // (NaN too): refused by the budget below, never cast
          edit.check_budget(2.0 * (double(edit.new_points.size()) + want), "trim line points");
          const int segs = int(want);
          for (int s = 1; s < segs; ++s) {
            const double u = surface.wrap(prev.u + du * s / segs);
            const Vec3 q = on_facet(u);
            // Where the line leaves a kept corner snapped onto it nearly along the facet's side, a point of it
            // can fall a hair outside the facet: it would fold the polygon back on that side. None there.
            if (hair_outside(f, q)) continue;
            const int id = edit.add_point(q);
            out.line[side].push_back({id, u});
            polygon.push_back(id);
          }
        }
        polygon.push_back(ring[i].vertex);
      }
      triangulate_polygon(edit, polygon, n, edit.added, opt.shape);
    }

    // Input edges that lie on the trim line (both ends on it) get points every max_spacing and the kept
    // facet along them is split to match: the round's boundary row stays as dense as its inner rows.
    // Kept facets with graded pieces are retriangulated here too.
    std::unordered_map<std::uint64_t, std::vector<int>> split;  // edge (a < b) -> its points, a to b
    for (int f : base.facets[side])
      for (int k = 0; k < 3; ++k) {
        poll_cancel();
        int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
        if (a > b) std::swap(a, b);
        const VertexSide &sa = vs[a], &sb = vs[b];
        if (sa.d != 0 || sb.d != 0) continue;
        const Vec3 pa = edit.point(a), pb = edit.point(b);
        const int segs = int(std::ceil((pb - pa).norm() / opt.max_spacing(sa.u + 0.5 * wrapped_delta(surface, sa.u, sb.u))));
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
    for (int g : rebuild) {
      poll_cancel();
      if (!edit.removed.insert(g).second) continue;  // in the band
      const std::vector<int> polygon = facet_with_edge_points(mesh, g, [&](int p, int q, std::vector<int>& poly) {
        auto it = split.find(edge_key(p, q));
        if (it == split.end()) add_piece_points(p, q, poly);
        else if (p < q) poly.insert(poly.end(), it->second.begin(), it->second.end());
        else poly.insert(poly.end(), it->second.rbegin(), it->second.rend());
      });
      triangulate_polygon(edit, polygon, mesh.facet_normal(g), edit.added, opt.shape);
    }
  }

  // Capped ends: the corner of the end faces that the round replaces.
  if (!chain.closed) {
    if (chain.start_end == ChainEnd::Junction)
      remove_cap_corner(mesh, base, chain.vertices.front(), end_profiles.front(), edit, &out.facets_removed);
    if (chain.end_end == ChainEnd::Junction)
      remove_cap_corner(mesh, base, chain.vertices.back(), end_profiles.back(), edit, &out.facets_removed);
  }
  // Facets outside the base meshes that share a cut edge get the cut point too (no T-junctions).
  for (const auto& [key, id] : edit.edge_point) {
    poll_cancel();
    for (int g : mesh.edge_facets(int(key >> 32), int(key & 0xffffffffu))) {
      if (base.side_of.count(g) || edit.removed.count(g)) continue;
      edit.removed.insert(g);
      const std::vector<int> polygon = facet_with_edge_points(mesh, g, [&](int p, int q, std::vector<int>& poly) {
        auto it = edit.edge_point.find(edge_key(p, q));
        if (it == edit.edge_point.end()) return;
        add_piece_points(p, it->second, poly);
        poly.push_back(it->second);
        add_piece_points(it->second, q, poly);
      });
      triangulate_polygon(edit, polygon, mesh.facet_normal(g), edit.added);
    }
  }
  for (auto& line : out.line) {
    std::sort(line.begin(), line.end(), [](const TrimPoint& x, const TrimPoint& y) { return x.u < y.u; });
    line.erase(std::unique(line.begin(), line.end(), [](const TrimPoint& x, const TrimPoint& y) { return x.vertex == y.vertex; }),
               line.end());
  }
  return out;
}

}  // namespace meshround
