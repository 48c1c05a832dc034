#include "ends.h"

#include "facet_quality.h"
#include "trim_caps.h"

#include "delta.h"
#include "guard.h"

#include "meshround/surface.h"

#include <algorithm>
#include <array>
#include <exception>
#include <cmath>
#include <unordered_map>

namespace meshround {
namespace {

constexpr double kCoplanarDeg = 2;       // the end face's facets at the vertex agree within this
// x r added to a nonzero setback, the last ball clear of the end's plane: kSetbackSlack at an end face or a
// corner; kOpenSetbackSlack at the plane of a mesh edge the chain runs off (open_end_cut), half the round's
// row across at the default tolerance r / 100 (0.2 r): where a slanted crop is nearest the last ball, the
// facets between its profile and the end profile are then not slivers (down to 3.5 deg on a CAD mesh at
// 0.02 r).
constexpr double kSetbackSlack = 0.02, kOpenSetbackSlack = 0.1;

// The share of a chain its two ends' setbacks may take: the rest, the balls' own stretch, must hold
// its profile stations. At a sphere corner the rounds' ends are measured on balls that stand clear of the
// other rounds only up to half a chain (longer setbacks are refused, naming the chain).
constexpr double kMaxSetbackShare = 0.9, kMaxSetbackShareAtSphere = 0.5;
// At a sphere corner the end's ball is measured this share of the radius before the corner's plane: on
// the plane its contacts are the corner ball's feet, where the rounds made before end (their facets are
// walls to this round's base meshes).
constexpr double kSphereMeasureInset = 1e-3;

}  // namespace

EndCut end_face_cut(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base, bool at_start) {
  EndCut cut;
  if (chain.closed || (at_start ? chain.start_end : chain.end_end) != ChainEnd::Junction) return cut;
  const int v = at_start ? chain.vertices.front() : chain.vertices.back();
  // The end face: the facets at v on neither side of the chain.
  Vec3 sum = Vec3::Zero();
  std::vector<Vec3> normals;
  for (const int* f = mesh.facets_begin(v); f != mesh.facets_end(v); ++f) {
    if (base.side_of.count(*f)) continue;
    const Vec3 n = mesh.facet_normal(*f);
    const Vec3 a = mesh.corner(*f, 0), b = mesh.corner(*f, 1), c = mesh.corner(*f, 2);
    sum += (b - a).cross(c - a);
    normals.push_back(n);
  }
  if (normals.empty() || sum.norm() == 0) return cut;
  const Vec3 n = sum.normalized();
  for (const Vec3& m : normals)
    if (m.dot(n) < std::cos(kCoplanarDeg * M_PI / 180)) return cut;  // two or more faces: left square
  const double s_end = at_start ? 0.0 : chain.length;
  const Vec3 out = at_start ? Vec3(-chain.tangent_at(s_end)) : chain.tangent_at(s_end);
  if (std::abs(out.dot(n)) < kMinCrossing) return cut;
  cut.active = true;
  cut.point = mesh.point(v);
  cut.normal = out.dot(n) > 0 ? n : Vec3(-n);
  cut.along = out;
  return cut;
}

double end_cut_setback(const ProfileStation& inside, double to_end, const EndCut& cut, bool open) {
  if (!cut.active) return 0;
  Vec3 poles[3];
  double w[3];
  ProfileStation square = inside;
  square.cut = EndCut{};
  profile_arc(square, poles, w);
  double setback = 0;  // the poles carried to the end (to_end along the chain), then past the plane
  for (const Vec3& p : poles) setback = std::max(setback, cut.past(p) / cut.along.dot(cut.normal) + to_end);
  return setback > 1e-9 * inside.radius ? setback + (open ? kOpenSetbackSlack : kSetbackSlack) * inside.radius : 0.0;
}

namespace {

// The mesh being split: triangles that may be replaced, and points that may be added or moved.
struct SplitMesh {
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> tris;
  std::vector<char> gone;
  std::unordered_map<std::uint64_t, int> edge_point;  // split edge -> its new point
  std::unordered_map<int, std::vector<int>> pieces;   // a replaced triangle -> what replaced it

  int add(const Vec3& p) { points.push_back(p); return int(points.size()) - 1; }
  void replace(int t, std::initializer_list<std::array<int, 3>> parts) {
    gone[t] = 1;
    for (const auto& f : parts) pieces[t].push_back(int(tris.size())), tris.push_back(f), gone.push_back(0);
  }
  // The triangles that stand for t now: t itself, or what replaced it (and them), into `out`.
  void live(int t, std::vector<int>& out) const {
    if (!gone[size_t(t)]) {
      out.push_back(t);
      return;
    }
    const auto it = pieces.find(t);
    if (it != pieces.end())
      for (int u : it->second) live(u, out);
  }
  int point_on_edge(int a, int b, const Vec3& p) {
    auto [it, fresh] = edge_point.try_emplace(edge_key(a, b), -1);
    if (fresh) it->second = add(p);
    return it->second;
  }
};

constexpr double kSnapKeepsAngle = 10 * M_PI / 180;  // a vertex snapped onto the plane keeps its facets' angles above this
constexpr double kSnapShare = 0.25;  // x its shortest edge: a vertex that near the plane moves onto it
constexpr double kSlideOffPlane = 1e-4;   // x the chain edge's length: how far a vertex slid along the chain may leave
                                          // its facets' planes
constexpr double kSlideKeepsAngle = 0.5;  // x min(kSnapKeepsAngle, its own): the smallest angle kept by the facets of a vertex
                                          // slid along the chain or moved onto the band's corner
constexpr double kCuspKeepsShare = 0.75;  // x its smallest angle: a facet split by a cusp point keeps this (or the cusp's)
constexpr double kSideShare = 0.01;  // x a side's length: how near its ends a corner is that end vertex's
constexpr double kSideSplitShare = 0.15;  // x a side's length: a corner that near a flat side (not near its ends)
                                          // may split that side (insert_corner)

// Whether input vertex v may move to `to`: no facet around it (its own, as split so far, or a piece made
// with it) turns over, gets a smallest angle under `angle_share` x min(kSnapKeepsAngle, its own), or leaves
// its plane by more than `off_plane`.
bool move_keeps_shape(const SplitMesh& m, const MeshTopology& mesh, int v, const Vec3& to, double angle_share, double off_plane) {
  std::vector<int> around;
  for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g) m.live(*g, around);
  for (size_t t = size_t(mesh.num_facets()); t < m.tris.size(); ++t)  // (pieces not of v's own facets)
    if (!m.gone[t] && std::find(m.tris[t].begin(), m.tris[t].end(), v) != m.tris[t].end()) around.push_back(int(t));
  for (int t : around) {
    const auto& g = m.tris[size_t(t)];
    if (std::find(g.begin(), g.end(), v) == g.end()) continue;
    Vec3 c[3], c0[3];
    for (int k = 0; k < 3; ++k) c0[k] = m.points[g[k]], c[k] = g[k] == v ? to : c0[k];
    const Vec3 n_before = (c0[1] - c0[0]).cross(c0[2] - c0[0]);
    if ((c[1] - c[0]).cross(c[2] - c[0]).dot(n_before) <= 0 ||
        smallest_angle(c[0], c[1], c[2]) < angle_share * std::min(kSnapKeepsAngle, smallest_angle(c0[0], c0[1], c0[2])) ||
        std::abs(n_before.normalized().dot(to - m.points[v])) > off_plane)
      return false;
  }
  return true;
}

// The corner as a vertex: the nearest vertex when it is one, or when it is a vertex of a flat neighbourhood
// within kSnapShare of its shortest edge from it (moved there), or within a weld of it on the plane (left where
// it is); else the facet or edge split at it.
int insert_corner(SplitMesh& m, const MeshTopology& mesh, std::vector<int>& facets, const EndSegment& seg, double slack,
                  double weld) {
  const Vec3& q = seg.corner;
  int near = -1;
  double near_d = INFINITY;
  for (int t : facets)
    for (int v : m.tris[t])
      if (!m.gone[t] && (m.points[v] - q).norm() < near_d) near_d = (m.points[v] - q).norm(), near = v;
  if (near >= 0 && near < mesh.num_vertices() && near_d > slack) {
    double shortest = INFINITY;
    bool flat = true;
    const Vec3 n0 = mesh.facet_normal(*mesh.facets_begin(near));
    for (const int* g = mesh.facets_begin(near); g != mesh.facets_end(near); ++g) flat &= mesh.facet_normal(*g).dot(n0) > 1 - 1e-6;
    for (int w : mesh.vertex_neighbours(near)) shortest = std::min(shortest, (m.points[w] - m.points[near]).norm());
    // (Only where its facets keep half their smallest angles: on a sharpened rim the corner lay on an edge in
    // the mitre's plane, and a crease vertex 0.02 mm off the plane moved onto it flattened the facet on that
    // edge. Not all of them: a sharpened CAD rim's crease vertex 0.03 mm from the corner, among slivers, was
    // left beside it, and the trim's facets between it and the contact line had no area.)
    if (flat && std::abs((q - m.points[near]).dot(n0)) <= slack && near_d <= kSnapShare * shortest &&
        move_keeps_shape(m, mesh, near, q, kSlideKeepsAngle, INFINITY)) {
      m.points[near] = q;
      return near;
    }
  }
  // (A box's top corner made again at its own radius: the band's corner fell 0.0004 mm from the old one's
  // corner vertex among slivers, which no move keeps, and the split left one more.)
  if (near >= 0 && near_d <= weld && std::abs(seg.cut.past(m.points[near])) <= slack) return near;
  int best = -1, region = 0;
  double best_d = INFINITY;
  for (int t : facets) {
    if (m.gone[t]) continue;
    int reg;
    const auto& f = m.tris[t];
    const double d = (closest_point_on_triangle(q, m.points[f[0]], m.points[f[1]], m.points[f[2]], &reg) - q).norm();
    if (d < best_d) best_d = d, best = t, region = reg;
  }
  if (best < 0) return -1;
  const auto f = m.tris[best];
  for (int k = 0; k < 3; ++k)
    if ((m.points[f[k]] - q).norm() <= slack) return f[k];
  // Within a hair of a side the corner is split into that side. Else of the facet split at the corner (three
  // pieces) and the splits of a side within kSideSplitShare of its length whose facet across lies in one
  // plane with this one (two pieces in each), the one whose pieces' smallest angle is largest: a corner a
  // hair inside a facet beside a side leaves a sliver between itself and the side (a gmsh mesh of a drafted
  // pocket had its floor's corner 0.017 mm from a 1.08 mm side; that sliver straddled the end plane and
  // folded once trimmed), while near a vertex the side's pieces are the worse.
  auto across = [&](int a, int b, int c) {  // the third corner of the other facet on side a-b, if coplanar
    const Vec3 n = (m.points[b] - m.points[a]).cross(m.points[c] - m.points[a]).normalized();
    for (size_t t = 0; t < m.tris.size(); ++t) {
      if (m.gone[t]) continue;
      const auto& g = m.tris[t];
      for (int j = 0; j < 3; ++j)
        if (g[j] == b && g[(j + 1) % 3] == a) {
          const Vec3 ng = (m.points[g[1]] - m.points[g[0]]).cross(m.points[g[2]] - m.points[g[0]]).normalized();
          return ng.dot(n) > 1 - 1e-6 ? g[(j + 2) % 3] : -1;
        }
    }
    return -1;
  };
  if (region == 0 || region > 3) {  // (inside the facet, or nearest one of its corners)
    const Vec3 &A = m.points[f[0]], &B = m.points[f[1]], &C = m.points[f[2]];
    double best_angle = std::min({smallest_angle(A, B, q), smallest_angle(B, C, q), smallest_angle(C, A, q)});
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3], c = f[(k + 2) % 3];
      double t;
      const double off = (closest_point_on_segment(q, m.points[a], m.points[b], &t) - q).norm();
      if (off <= slack) {
        region = k + 1;
        break;
      }
      const bool beside = t > kSideShare && t < 1 - kSideShare;  // (near an end the corner is that vertex's)
      if (!beside || off > kSideSplitShare * (m.points[b] - m.points[a]).norm()) continue;
      const int y = across(a, b, c);
      if (y < 0) continue;
      const Vec3 &pa = m.points[a], &pb = m.points[b], &pc = m.points[c], &py = m.points[y];
      const double angle = std::min({smallest_angle(pa, q, pc), smallest_angle(q, pb, pc), smallest_angle(pa, q, py), smallest_angle(q, pb, py)});
      if (angle > best_angle) best_angle = angle, region = k + 1;
    }
  }
  if (region >= 1 && region <= 3) {  // on edge (f[k], f[k+1]): split both facets on it
    const int k = region - 1, a = f[k], b = f[(k + 1) % 3];
    const int x = m.add(q);
    for (size_t t = 0; t < m.tris.size(); ++t) {
      if (m.gone[t]) continue;
      const auto g = m.tris[t];
      for (int j = 0; j < 3; ++j)
        if ((g[j] == a && g[(j + 1) % 3] == b) || (g[j] == b && g[(j + 1) % 3] == a)) {
          m.replace(int(t), {{g[j], x, g[(j + 2) % 3]}, {x, g[(j + 1) % 3], g[(j + 2) % 3]}});
          facets.push_back(int(m.tris.size()) - 2), facets.push_back(int(m.tris.size()) - 1);
          break;
        }
    }
    return x;
  }
  const int x = m.add(q);
  m.replace(best, {{f[0], f[1], x}, {f[1], f[2], x}, {f[2], f[0], x}});
  for (int j = 3; j >= 1; --j) facets.push_back(int(m.tris.size()) - j);
  return x;
}

// Vertices a hair off the plane, in a flat neighbourhood near the segment P -> Q: onto the plane (before
// the corner is put in, so that it lands in a facet of the final shape).
void snap_onto_plane(SplitMesh& m, const MeshTopology& mesh, const std::vector<int>& facets, const EndCut& cut, int p,
                     const Vec3& P, const Vec3& Q, double slack) {
  const Vec3 S = Q - P;
  auto along = [&](const Vec3& x) { return (x - P).dot(S) / S.squaredNorm(); };
  for (int t : facets) {
    if (m.gone[t]) continue;
    for (int v : m.tris[t]) {
      if (v >= mesh.num_vertices() || v == p) continue;
      const double d = cut.past(m.points[v]), a = along(m.points[v]);
      if (std::abs(d) <= slack || a < -0.1 || a > 1.1) continue;
      double shortest = INFINITY;
      bool flat = true;
      const Vec3 n0 = mesh.facet_normal(*mesh.facets_begin(v));
      for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g) flat &= mesh.facet_normal(*g).dot(n0) > 1 - 1e-6;
      for (int w : mesh.vertex_neighbours(v)) shortest = std::min(shortest, (mesh.point(w) - mesh.point(v)).norm());
      if (!flat || std::abs(d) > kSnapShare * shortest) continue;
      Vec3 dir = cut.normal - cut.normal.dot(n0) * n0;  // in the face, across the plane
      if (dir.norm() < 0.3) continue;
      dir.normalize();
      // Only where no facet around v turns over or gets a smaller angle than min(kSnapKeepsAngle, its own):
      // within a quarter of its shortest edge, v can still cross a neighbour's far side that runs nearly
      // across the plane (the drafted pocket's coarse mesh at r = 3: a vertex moved 0.046 mm onto a floor
      // round's end plane went 5e-4 past the side of a facet an earlier round's trim had made, and the
      // facet folded over it).
      const Vec3 to = m.points[v] - dir * (d / dir.dot(cut.normal));
      if (move_keeps_shape(m, mesh, v, to, 1.0, INFINITY)) m.points[v] = to;
    }
  }
}

// Splits the facets crossed by the segment p -> q (both vertices, on the cut's plane) along the plane.
void split_crossed(SplitMesh& m, std::vector<int>& facets, const EndCut& cut, int p, int q, double slack) {
  const Vec3 P = m.points[p], Q = m.points[q], S = Q - P;
  auto along = [&](const Vec3& x) { return (x - P).dot(S) / S.squaredNorm(); };
  const size_t count = facets.size();
  for (size_t i = 0; i < count; ++i) {
    const int t = facets[i];
    if (m.gone[t]) continue;
    const auto f = m.tris[t];
    double d[3];
    for (int k = 0; k < 3; ++k) {
      d[k] = cut.past(m.points[f[k]]);
      if (std::abs(d[k]) <= slack) d[k] = 0;
    }
    const bool pos = d[0] > 0 || d[1] > 0 || d[2] > 0, neg = d[0] < 0 || d[1] < 0 || d[2] < 0;
    if (!pos || !neg) continue;
    // Where the plane crosses each edge (or passes through a vertex), and whether that lies on p -> q.
    Vec3 cross_pts[3];
    int n_cross = 0;
    for (int k = 0; k < 3; ++k) {
      const int j = (k + 1) % 3;
      if (d[k] == 0) cross_pts[n_cross++] = m.points[f[k]];
      else if (d[j] != 0 && (d[k] > 0) != (d[j] > 0)) cross_pts[n_cross++] = m.points[f[k]] + (m.points[f[j]] - m.points[f[k]]) * (d[k] / (d[k] - d[j]));
    }
    if (n_cross != 2) continue;
    const double mid = along(0.5 * (cross_pts[0] + cross_pts[1]));
    if (mid <= 0 || mid >= 1) continue;
    // Rotate so that the lone vertex (or the one on the plane) is first.
    int k0 = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      if (d[k] == 0 || (d[a] != 0 && d[b] != 0 && (d[a] > 0) == (d[b] > 0) && (d[k] > 0) != (d[a] > 0))) k0 = k;
    }
    const int a = f[k0], b = f[(k0 + 1) % 3], c = f[(k0 + 2) % 3];
    const double da = d[k0], db = d[(k0 + 1) % 3], dc = d[(k0 + 2) % 3];
    auto on = [&](int x, int y, double dx, double dy) { return m.point_on_edge(x, y, m.points[x] + (m.points[y] - m.points[x]) * (dx / (dx - dy))); };
    if (da == 0) {  // through a: b and c on either side
      const int x = on(b, c, db, dc);
      m.replace(t, {{a, b, x}, {a, x, c}});
      facets.push_back(int(m.tris.size()) - 2), facets.push_back(int(m.tris.size()) - 1);
    } else {  // a alone on its side
      const int x = on(a, b, da, db), y = on(c, a, dc, da);
      const bool short_bd = (m.points[b] - m.points[y]).norm() < (m.points[c] - m.points[x]).norm();
      if (short_bd) m.replace(t, {{a, x, y}, {x, b, y}, {b, c, y}});
      else m.replace(t, {{a, x, y}, {x, b, c}, {x, c, y}});
      for (int j = 3; j >= 1; --j) facets.push_back(int(m.tris.size()) - j);
    }
  }
}

// The point `step` from the corner q on the segment p -> q (made of edges now), on the edge of `facets` along
// the segment that holds it; none where the segment is shorter than kCuspPointRoom steps or a vertex on it is
// within half a step of the point already. (split_edges_through_points splits the facets on that edge.)
void put_cusp_point(SplitMesh& m, const std::vector<int>& facets, const EndCut& cut, int p, int q, double step, double radius,
                    double slack) {
  const Vec3 P = m.points[p], Q = m.points[q];
  const double length = (P - Q).norm();
  if (!(step > 0) || length < kCuspPointRoom * step) return;
  const Vec3 dir = (P - Q) / length, X = Q + dir * step;
  const double cusp = cusp_angle(step, radius);  // the cap's angle at the cusp
  auto along = [&](int v) { return (m.points[v] - Q).dot(dir); };
  auto on_segment = [&](int v) { return (m.points[v] - Q - dir * along(v)).norm() <= slack; };
  for (int t : facets) {
    if (m.gone[size_t(t)]) continue;
    const auto f = m.tris[size_t(t)];
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      if (!on_segment(a) || !on_segment(b)) continue;
      const double sa = along(a), sb = along(b);
      if (std::min(sa, sb) > step || std::max(sa, sb) < step) continue;
      if (std::abs(sa - step) < 0.5 * step || std::abs(sb - step) < 0.5 * step) return;
      // Each facet on the edge past the plane (kept: the one before it is the band's), split there, keeps its
      // pieces' angles at the cusp's own (half the profile's step) or at kCuspKeepsShare of its own, whichever
      // is less (a CAD face's facet from a far corner to the segment would leave pieces thinner than itself):
      // else no point.
      for (size_t u = 0; u < m.tris.size(); ++u) {
        if (m.gone[u]) continue;
        const auto g = m.tris[u];
        const int c = g[0] + g[1] + g[2] - a - b;
        if (std::count(g.begin(), g.end(), a) != 1 || std::count(g.begin(), g.end(), b) != 1 || cut.past(m.points[c]) <= slack) continue;
        const Vec3 A = m.points[a], B = m.points[b], C = m.points[c];
        const double own = smallest_angle(A, B, C);
        if (std::min(smallest_angle(A, X, C), smallest_angle(X, B, C)) < std::min(cusp, kCuspKeepsShare * own)) return;
      }
      m.point_on_edge(a, b, X);
      return;
    }
  }
}

// The chain edge seg.edge split at seg.start on both sides (or the vertex already there); the pieces of
// the split facets join `facets`. Returns the vertex.
int split_chain_edge(SplitMesh& m, const MeshTopology& mesh, std::unordered_map<std::uint64_t, std::vector<int>>& on_chain,
                     const EndSegment& seg, double slack, std::vector<int>& facets) {
  std::vector<int>& on = on_chain[edge_key(seg.edge[0], seg.edge[1])];
  if (on.empty()) on = {seg.edge[0], seg.edge[1]};
  for (int v : on)
    if ((m.points[v] - seg.start).norm() <= slack) return v;
  // A chain vertex within kSideShare of the edge's length of the point slides along the chain onto it, where
  // its facets keep their planes (a straight chain between flat faces) and shapes: a split there would leave
  // a sliver (a box corner's sphere plane at r = 19.999 crossed a 2 mm edge 0.001 mm from its vertex).
  const double length = (m.points[seg.edge[1]] - m.points[seg.edge[0]]).norm();
  for (int v : seg.edge)
    if (v < mesh.num_vertices() && v != seg.end_vertex && (m.points[v] - seg.start).norm() <= kSideShare * length &&
        move_keeps_shape(m, mesh, v, seg.start, kSlideKeepsAngle, kSlideOffPlane * length)) {
      m.points[v] = seg.start;
      return v;
    }
  const int x = m.add(seg.start);
  auto holds = [&](int a, int b) {  // a piece of the chain edge with seg.start inside it
    if (std::find(on.begin(), on.end(), a) == on.end() || std::find(on.begin(), on.end(), b) == on.end()) return false;
    const Vec3 d = m.points[b] - m.points[a];
    const double t = (seg.start - m.points[a]).dot(d) / d.squaredNorm();
    return t > 0 && t < 1;
  };
  for (size_t t = 0, count = m.tris.size(); t < count; ++t) {
    if (m.gone[t]) continue;
    const auto g = m.tris[t];
    for (int j = 0; j < 3; ++j) {
      const int a = g[j], b = g[(j + 1) % 3];
      if (!holds(a, b)) continue;
      const bool mine = std::find(facets.begin(), facets.end(), int(t)) != facets.end();
      m.replace(int(t), {{a, x, g[(j + 2) % 3]}, {x, b, g[(j + 2) % 3]}});
      if (mine) facets.push_back(int(m.tris.size()) - 2), facets.push_back(int(m.tris.size()) - 1);
      break;
    }
  }
  on.push_back(x);
  return x;
}

// A point put on an edge splits every facet on that edge, not only the facets of the side being split:
// a neighbour whose crossing lies past the segment's end (split_crossed leaves it) would keep the edge
// whole, and the mesh would open there (a crack as thin as the point's offset from the edge's end).
void split_edges_through_points(SplitMesh& m, const MeshTopology& mesh) {
  const int n = mesh.num_vertices();
  const size_t input_facets = size_t(mesh.num_facets());
  for (const auto& [key, x] : m.edge_point) {
    const int a = int(key >> 32), b = int(key & 0xffffffffu);
    std::vector<int> on_edge;
    if (a < n && b < n) {
      int pair[2];
      const int count = mesh.edge_facet_pair(a, b, pair);
      for (int i = 0; i < std::min(count, 2); ++i) m.live(pair[i], on_edge);
    }
    for (size_t t = input_facets; t < m.tris.size(); ++t)  // the pieces made so far
      if (!m.gone[t]) on_edge.push_back(int(t));
    for (int t : on_edge) {
      if (m.gone[size_t(t)]) continue;
      const auto g = m.tris[size_t(t)];
      for (int j = 0; j < 3; ++j)
        if ((g[j] == a && g[(j + 1) % 3] == b) || (g[j] == b && g[(j + 1) % 3] == a)) {
          m.replace(t, {{g[j], x, g[(j + 2) % 3]}, {x, g[(j + 1) % 3], g[(j + 2) % 3]}});
          break;
        }
    }
  }
}

}  // namespace

std::vector<EndSegment> end_segments(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base,
                                     const std::vector<ProfileStation>& stations, const RoundingSurface& surface,
                                     const std::function<double(double)>& step) {
  std::vector<EndSegment> out;
  for (int end = 0; end < 2 && !chain.closed; ++end) {
    const ProfileStation& st = end ? stations.back() : stations.front();
    if (!st.cut.active) continue;
    const int v = end ? chain.vertices.back() : chain.vertices.front();
    for (int side = 0; side < 2; ++side) {
      const Vec3 corner = surface.value(end ? surface.u_last : surface.u_first, side);
      const double slack = on_plane_slack(st.radius, corner.cwiseAbs().maxCoeff());
      bool goes_on = false;
      for (int f : base.facets[side])
        for (int k = 0; k < 3 && !goes_on; ++k) goes_on = st.cut.past(mesh.corner(f, k)) > slack;
      if (!goes_on) continue;
      EndSegment seg{st.cut, v, mesh.point(v), {-1, -1}, corner, base.facets[side], step(end ? surface.u_last : surface.u_first), st.radius};
      if (std::abs(st.cut.past(mesh.point(v))) > slack) {  // the plane crosses the chain short of its end
        const int n = int(chain.vertices.size());
        for (int i = 0; i + 1 < n; ++i) {
          const int a = chain.vertices[end ? n - 1 - i : i], b = chain.vertices[end ? n - 2 - i : i + 1];
          const double da = st.cut.past(mesh.point(a)), db = st.cut.past(mesh.point(b));
          if (std::abs(db) <= slack) { seg.end_vertex = b, seg.start = mesh.point(b); break; }
          if ((da > 0) != (db > 0)) {
            seg.start = mesh.point(a) + (mesh.point(b) - mesh.point(a)) * (da / (da - db));
            seg.edge[0] = a, seg.edge[1] = b;
            break;
          }
        }
      }
      out.push_back(seg);
    }
  }
  return out;
}

bool split_along_end_segments(const MeshTopology& mesh, const std::vector<EndSegment>& segments, double weld, MeshDelta& delta) {
  if (segments.empty()) return false;
  SplitMesh m;
  for (int v = 0; v < mesh.num_vertices(); ++v) m.points.push_back(mesh.point(v));
  m.tris.reserve(size_t(mesh.num_facets()) + 64);
  for (int f = 0; f < mesh.num_facets(); ++f) m.tris.push_back({mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)});
  m.gone.assign(m.tris.size(), 0);
  // Chain edge -> the vertices on it (its ends, then each point put on it). One edge can be crossed by
  // both ends' planes (a chain of one long edge, as in a CAD mesh): the second splits the piece holding
  // its point.
  std::unordered_map<std::uint64_t, std::vector<int>> on_chain;
  for (const EndSegment& seg : segments) {
    const double slack = on_plane_slack((seg.corner - seg.start).norm(), seg.corner.cwiseAbs().maxCoeff());
    std::vector<int> facets;  // this side's facets, as earlier segments left them
    for (int f : seg.facets) m.live(f, facets);
    int p = seg.end_vertex;
    if (seg.edge[0] >= 0) p = split_chain_edge(m, mesh, on_chain, seg, slack, facets);
    snap_onto_plane(m, mesh, facets, seg.cut, p, m.points[p], seg.corner, slack);
    const int q = insert_corner(m, mesh, facets, seg, slack, weld);
    if (q < 0 || q == p) continue;
    split_crossed(m, facets, seg.cut, p, q, slack);
    put_cusp_point(m, facets, seg.cut, p, q, seg.cusp_step, seg.radius, slack);
  }
  split_edges_through_points(m, mesh);
  const int n = mesh.num_vertices(), facets = mesh.num_facets();
  bool changed = m.points.size() > size_t(n) || std::any_of(m.gone.begin(), m.gone.end(), [](char g) { return g != 0; });
  for (int v = 0; v < n && !changed; ++v) changed = m.points[size_t(v)] != mesh.point(v);  // a vertex moved onto the corner
  if (!changed) return false;
  std::vector<int> removed;
  std::vector<std::array<int, 3>> added;
  for (size_t t = 0; t < m.tris.size(); ++t) {
    if (int(t) < facets && m.gone[t]) removed.push_back(int(t));
    if (int(t) >= facets && !m.gone[t]) added.push_back(m.tris[t]);
  }
  std::vector<std::pair<int, Vec3>> moved;
  for (int v = 0; v < n; ++v)
    if (m.points[size_t(v)] != mesh.point(v)) moved.push_back({v, m.points[size_t(v)]});
  delta = make_delta(mesh, std::move(removed), moved, std::vector<Vec3>(m.points.begin() + n, m.points.end()), added);
  return true;
}

// Whether the end face's facets at the chain's end vertex all lie in the cut's plane (kOnCapPlaneShare * r):
// end_face_cut takes facets within kCoplanarDeg for one plane, but the cap's corner is removed only from
// facets in it, and the gap is filled in the plane. Two long facets 0.8 deg apart (a perturbed prism's end,
// 40 mm across) stayed while the cap was filled over them, facing the other way (found by fuzzing:
// tests/fuzz/regressions/round/fixed/unsound_fold-6f6c662). Such an end is left square.
namespace {
bool end_face_in_plane(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base, bool at_start, const EndCut& cut, double r) {
  const int v = at_start ? chain.vertices.front() : chain.vertices.back();
  for (const int* f = mesh.facets_begin(v); f != mesh.facets_end(v); ++f) {
    if (base.side_of.count(*f)) continue;
    for (int k = 0; k < 3; ++k)
      if (std::abs(cut.past(mesh.corner(*f, k))) > kOnCapPlaneShare * r) return false;
  }
  return true;
}
}  // namespace

EndPlan plan_ends(const SpineContext& ctx, const RadiusLaw& law, const NetworkPart& net, double tolerance) {
  const SharpChain& chain = ctx.chain;
  const double L = chain.length;
  EndPlan plan;
  EndCut* cut = plan.cut;
  double* setback = plan.setback;
  bool at_sphere = false;
  for (int end = 0; end < 2 && !chain.closed; ++end) {
    const bool open = (end ? chain.end_end : chain.start_end) == ChainEnd::Boundary;
    cut[end] = open ? open_end_cut(ctx.mesh, chain, end == 0) : end_face_cut(ctx.mesh, chain, ctx.base, end == 0);
    if (!open && cut[end].active && !end_face_in_plane(ctx.mesh, chain, ctx.base, end == 0, cut[end], law.at(end ? L : 0.0)))
      cut[end] = EndCut{};
    const CornerEnd* corner = corner_at(net, end ? chain.points.back() : chain.points.front());
    if (corner) {
      const Vec3 out = end ? chain.tangent_at(L) : Vec3(-chain.tangent_at(0));
      cut[end] = EndCut{true, corner->plane_point, out.dot(corner->normal) > 0 ? corner->normal : Vec3(-corner->normal), out};
    }
    if (!cut[end].active) continue;
    // Measured on a ball clear of the end face (the one at the end may already lean on it); at a sphere
    // corner, on the ball at its plane or before it (one past it would stand on the other rounds' faces).
    double to_end = std::min(2 * law.max_radius(), 0.25 * L);
    if (corner && corner->sphere)
      to_end = std::min(L, std::max(to_end, cut[end].past(end ? chain.points.back() : chain.points.front()) + kSphereMeasureInset * law.max_radius()));
    at_sphere |= corner && corner->sphere;
    // A radius over a quarter of the chain can put that ball where the balls of the other end stop short
    // of a mitre, on the other round's side (refused there as too large). Then balls elsewhere on the
    // chain are measured (on a chain of one section the setback is the same from any of them): further
    // along, as far as a setback may reach, then nearer this end. None clear: the first one's refusal.
    std::vector<double> tries{to_end};
    if (!(corner && corner->sphere))
      for (double share : {0.5, 0.75, kMaxSetbackShare, 0.1, 0.05})
        if (std::abs(share * L - to_end) > 1e-9 * L) tries.push_back(share * L);
    std::exception_ptr first_refusal;
    for (size_t k = 0; k < tries.size(); ++k) {
      try {
        const ProfileStation inside = solve_station(ctx, law, end ? L - tries[k] : tries[k]);
        // (an open end's edge is checked once a ball fits there: one that does not is radius_too_large)
        if (open) check_open_end(ctx.mesh, chain, law, tolerance, end == 0, cut[end]);
        setback[end] = end_cut_setback(inside, tries[k], cut[end], open);
        first_refusal = nullptr;
        break;
      } catch (const RoundingError& e) {
        if (e.code != ErrorCode::RadiusTooLarge) throw;
        if (!first_refusal) first_refusal = std::current_exception();
      }
    }
    // (at an open end, a ball that fits nowhere near it is refused with the chain's balls, where one meets the
    // mesh's edge)
    if (first_refusal && !open) std::rethrow_exception(first_refusal);
  }
  const double needed = setback[0] + setback[1];
  if (needed > (at_sphere ? kMaxSetbackShareAtSphere : kMaxSetbackShare) * L) {
    // (a setback many times the chain: an end face that runs nearly along the chain, its ball's poles far past it)
    const std::string how = needed < 10 * L ? format_number(needed) + " mm of its " + format_number(L) + " mm"
                                            : "an end face there runs nearly along it, " + format_number(L) + " mm long";
    throw RoundingError(ErrorCode::RadiusTooLarge, "the chain through " + format_point(chain.point_at(0.5 * L)) + " is too short for its round to "
                        "run on to the end faces leaning over it (" + how + "); try a smaller radius");
  }
  return plan;
}

}  // namespace meshround
