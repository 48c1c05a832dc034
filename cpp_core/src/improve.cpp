#include "meshround/improve.h"
#include "meshround/cancel.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <unordered_map>

namespace meshround {

namespace {

using Tri = std::array<int, 3>;

// Vertices are only taken out where a facet around them is worse than this (the shape target the trim
// and the end caps refine to): well-shaped grading stays as it is.
constexpr double kWellShaped = 20.0 * M_PI / 180.0;
// Where a vertex on a crease may slide to: this many equal steps between its crease neighbours.
constexpr int kSlideStops = 20;
constexpr int kRounds = 3;

// The new facets with their edges and, for new vertices, the facets around them; dead facets stay in
// place (marked) until the pass ends.
struct Patch {
  MeshEdit& edit;
  const std::unordered_set<int>& keep;
  const std::function<bool(const Vec3&)>& admit;
  std::vector<Tri>& tris;
  std::vector<bool> alive;
  std::unordered_map<std::uint64_t, std::vector<int>> edge_tris;
  std::unordered_map<int, std::vector<int>> vertex_tris;  // new vertices only

  Patch(MeshEdit& e, const std::unordered_set<int>& k, const std::function<bool(const Vec3&)>& a)
      : edit(e), keep(k), admit(a), tris(e.added), alive(e.added.size(), true) {
    for (int t = 0; t < int(tris.size()); ++t) link(t);
  }

  bool is_new(int v) const { return v >= edit.input.num_vertices(); }
  Vec3 p(int v) const { return edit.point(v); }

  void link(int t) {
    for (int k = 0; k < 3; ++k) {
      edge_tris[edge_key(tris[t][k], tris[t][(k + 1) % 3])].push_back(t);
      if (is_new(tris[t][k])) vertex_tris[tris[t][k]].push_back(t);
    }
  }
  void unlink(int t) {
    auto drop = [t](std::vector<int>& list) { list.erase(std::remove(list.begin(), list.end(), t), list.end()); };
    for (int k = 0; k < 3; ++k) {
      drop(edge_tris[edge_key(tris[t][k], tris[t][(k + 1) % 3])]);
      if (is_new(tris[t][k])) drop(vertex_tris[tris[t][k]]);
    }
    alive[t] = false;
  }
  int add(const Tri& t) {
    tris.push_back(t);
    alive.push_back(true);
    link(int(tris.size()) - 1);
    return int(tris.size()) - 1;
  }

  // An edge already in the mesh: among the new facets, or a kept input facet's.
  bool edge_exists(int a, int b) const {
    auto it = edge_tris.find(edge_key(a, b));
    if (it != edge_tris.end() && !it->second.empty()) return true;
    if (is_new(a) || is_new(b)) return false;
    for (int f : edit.input.edge_facets(a, b))
      if (!edit.removed.count(f)) return true;
    return false;
  }

  double angle(const Tri& t) const { return smallest_angle(p(t[0]), p(t[1]), p(t[2])); }
  Vec3 normal(const Tri& t) const { return (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0])); }
  bool admitted(const Tri& t) const { return admit(p(t[0])) || admit(p(t[1])) || admit(p(t[2])); }
};

// Flips the edge a-b of the coplanar facets t and u when the other diagonal is better; true if flipped.
bool try_flip(Patch& m, int t, int u, int a, int b, std::vector<int>& touched) {
  if (m.keep.count(a) && m.keep.count(b)) return false;  // the round's own edges, and its trim lines
  auto third = [&](int s) { for (int v : m.tris[s]) if (v != a && v != b) return v; return -1; };
  // Orient: t runs a -> b.
  const Tri& T = m.tris[t];
  const int k = int(std::find(T.begin(), T.end(), a) - T.begin());
  if (T[(k + 1) % 3] != b) std::swap(t, u);
  const int c = third(t), d = third(u);  // t = (a, b, c), u = (b, a, d)
  if (c < 0 || d < 0 || c == d || m.edge_exists(c, d)) return false;
  const Vec3 n = m.normal(m.tris[t]);
  if (n.norm() == 0 || n.dot(m.normal(m.tris[u])) <= 0) return false;
  const Vec3 unit = n.normalized();
  if (!on_plane(m.p(d), m.p(a), unit)) return false;
  const Tri t2{c, a, d}, u2{d, b, c};
  if (m.normal(t2).dot(unit) <= 0 || m.normal(u2).dot(unit) <= 0) return false;  // the quad is not convex
  if (std::min(m.angle(t2), m.angle(u2)) <= std::min(m.angle(m.tris[t]), m.angle(m.tris[u])) + 1e-9) return false;
  if (!m.admitted(t2) || !m.admitted(u2)) return false;
  m.unlink(t), m.unlink(u);
  touched.push_back(m.add(t2)), touched.push_back(m.add(u2));
  return true;
}

// Lawson flips over the edges of the facets in `seeds` (all facets when empty), until none improves.
int flip_all(Patch& m, std::vector<int> seeds) {
  std::deque<std::uint64_t> queue;
  std::unordered_map<std::uint64_t, std::pair<int, int>> ends;
  auto push = [&](int t) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.tris[t][k], b = m.tris[t][(k + 1) % 3];
      queue.push_back(edge_key(a, b));
      ends[edge_key(a, b)] = {a, b};
    }
  };
  if (seeds.empty())
    for (int t = 0; t < int(m.tris.size()); ++t) seeds.push_back(t);
  for (int t : seeds)
    if (m.alive[t]) push(t);
  int flips = 0;
  CancelPoll poll(64);
  while (!queue.empty()) {
    poll.tick();
    const std::uint64_t key = queue.front();
    queue.pop_front();
    const auto& pair = m.edge_tris[key];
    if (pair.size() != 2) continue;
    std::vector<int> touched;
    if (try_flip(m, pair[0], pair[1], ends[key].first, ends[key].second, touched)) {
      ++flips;
      for (int t : touched) push(t);
    }
  }
  return flips;
}

// The flat sides of new vertex v: the facets around it in one flat patch, or in two flat patches that
// meet on a straight crease through v (then v lies between the crease's two ring neighbours), each side
// as its outline without v. Empty when v is neither (on the round, at a corner, on the border of the new
// facets).
struct FlatSides {
  std::vector<int> star;                                  // the facets around v
  std::vector<std::pair<std::vector<int>, Vec3>> holes;   // each side's outline without v, its normal
};
FlatSides flat_sides(const Patch& m, int v) {
  auto found = m.vertex_tris.find(v);
  if (found == m.vertex_tris.end() || found->second.size() < 3) return {};
  const std::vector<int>& star = found->second;
  // The ring around v, in the facets' own turning order: facet (v, a, b) gives a -> b.
  std::unordered_map<int, std::pair<int, int>> next;  // a -> (b, facet)
  for (int t : star) {
    const Tri& T = m.tris[t];
    const int k = int(std::find(T.begin(), T.end(), v) - T.begin());
    if (!next.emplace(T[(k + 1) % 3], std::make_pair(T[(k + 2) % 3], t)).second) return {};
  }
  std::vector<int> ring, ring_tris;  // ring_tris[i] = (v, ring[i], ring[i + 1])
  int at = next.begin()->first;
  for (size_t i = 0; i < star.size(); ++i) {
    auto it = next.find(at);
    if (it == next.end()) return {};  // v is on the border of the new facets
    ring.push_back(at), ring_tris.push_back(it->second.second);
    at = it->second.first;
  }
  if (at != ring[0]) return {};
  const size_t n = ring.size();
  const Vec3 pv = m.p(v);
  std::vector<size_t> creases;  // ring vertices where the facets before and after are not coplanar
  for (size_t i = 0; i < n; ++i) {
    const Vec3 nb = m.normal(m.tris[ring_tris[(i + n - 1) % n]]), na = m.normal(m.tris[ring_tris[i]]);
    if (nb.norm() == 0 || na.norm() == 0) return {};
    const Vec3 far = m.p(ring[(i + 1) % n]);
    if (nb.dot(na) <= 0 || !on_plane(far, pv, nb.normalized())) creases.push_back(i);
  }
  FlatSides out{star, {}};
  if (creases.empty()) {
    Vec3 normal = Vec3::Zero();
    for (int t : ring_tris) normal += m.normal(m.tris[t]);
    for (int w : ring)  // flat as a whole, not just facet to facet
      if (!on_plane(m.p(w), pv, normal.normalized())) return {};
    out.holes.push_back({ring, normal});
    return out;
  }
  if (creases.size() != 2) return {};
  const Vec3 a = m.p(ring[creases[0]]), b = m.p(ring[creases[1]]);
  double s;
  const double slack = on_plane_slack((a - b).norm(), std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff()));
  if ((closest_point_on_segment(pv, a, b, &s) - pv).norm() > slack || s <= 0 || s >= 1) return {};
  for (int h = 0; h < 2; ++h) {
    std::vector<int> outline;
    Vec3 normal = Vec3::Zero();
    for (size_t i = creases[h];; i = (i + 1) % n) {
      outline.push_back(ring[i]);
      if (i == creases[1 - h]) break;
      normal += m.normal(m.tris[ring_tris[i]]);
    }
    const Vec3 unit = normal.normalized();  // flat as a whole, not just facet to facet
    for (int w : outline)
      if (!on_plane(m.p(w), pv, unit)) return {};
    out.holes.push_back({outline, normal});
  }
  return out;
}

// Removes new vertex v (inside a flat patch, or on a straight crease between two) when triangulating
// the hole again, each side on its own, gives a larger smallest angle around it.
bool try_remove(Patch& m, const FlatSides& sides, std::vector<int>& made) {
  double before = INFINITY;
  for (int t : sides.star) before = std::min(before, m.angle(m.tris[t]));
  std::vector<Tri> fill;
  size_t expected = 0;
  for (const auto& [outline, normal] : sides.holes) {
    triangulate_polygon(m.edit, outline, normal, fill);
    expected += outline.size() - 2;
  }
  if (fill.size() != expected) return false;
  // The outlines' edges are there already; every other edge the fill makes must be new (a crease's
  // outlines close with one: the edge that replaces v's two).
  std::unordered_set<std::uint64_t> known;
  for (const auto& hole : sides.holes) {
    const std::vector<int>& o = hole.first;
    for (size_t i = 0; i + 1 < o.size(); ++i) known.insert(edge_key(o[i], o[i + 1]));
    if (sides.holes.size() == 1) known.insert(edge_key(o.back(), o.front()));
  }
  double after = INFINITY;
  for (const Tri& t : fill) after = std::min(after, m.angle(t));
  if (after <= before + 1e-9) return false;
  for (const Tri& t : fill) {
    if (m.normal(t).norm() == 0 || !m.admitted(t)) return false;
    for (int k = 0; k < 3; ++k)
      if (known.insert(edge_key(t[k], t[(k + 1) % 3])).second && m.edge_exists(t[k], t[(k + 1) % 3])) return false;
  }
  for (int t : sides.star) m.unlink(t);
  for (const Tri& t : fill) made.push_back(m.add(t));
  return true;
}

// Slides new vertex v along the straight crease it sits on (between its two crease neighbours) to where
// the smallest angle around it is largest, when that beats where it is. Its facets keep their turn, and
// each a corner within the reach.
bool try_slide(Patch& m, int v, const FlatSides& sides) {
  if (sides.holes.size() != 2) return false;
  const std::vector<int>& outline = sides.holes[0].first;
  const Vec3 p = m.p(outline.front()), q = m.p(outline.back()), home = m.p(v);
  Vec3& at = m.edit.new_points[v - m.edit.input.num_vertices()];
  std::vector<Vec3> normals;
  for (int t : sides.star) normals.push_back(m.normal(m.tris[t]));
  auto quality = [&]() {
    double worst = INFINITY;
    for (size_t i = 0; i < sides.star.size(); ++i) {
      const Tri& t = m.tris[sides.star[i]];
      if (m.normal(t).dot(normals[i]) <= 0) return -1.0;  // a facet turned over
      worst = std::min(worst, m.angle(t));
    }
    return worst;
  };
  double best = quality();
  Vec3 best_at = home;
  for (int k = 1; k < kSlideStops; ++k) {
    at = p + (q - p) * (double(k) / kSlideStops);
    const double here = quality();
    if (here > best + 1e-9 && std::all_of(sides.star.begin(), sides.star.end(), [&](int t) { return m.admitted(m.tris[t]); }))
      best = here, best_at = at;
  }
  at = best_at;
  return best_at != home;
}

}  // namespace

ImproveStats improve_new_facets(MeshEdit& edit, const std::unordered_set<int>& keep,
                                const std::function<bool(const Vec3&)>& admit) {
  ImproveStats stats;
  Patch m(edit, keep, admit);
  stats.flips += flip_all(m, {});
  // Removals (or slides), worst surroundings first, each followed by flips around what changed; a few
  // rounds, as each change can make a neighbour's worth trying again.
  for (int round = 0; round < kRounds; ++round) {
    std::vector<std::pair<double, int>> candidates;
    for (const auto& [v, around] : m.vertex_tris) {
      if (keep.count(v) || around.empty()) continue;
      double q = INFINITY;
      for (int t : around) q = std::min(q, m.angle(m.tris[t]));
      if (q < kWellShaped) candidates.push_back({q, v});
    }
    std::sort(candidates.begin(), candidates.end());
    bool changed = false;
    for (const auto& [q, v] : candidates) {
      poll_cancel();
      const FlatSides sides = flat_sides(m, v);
      if (sides.holes.empty()) continue;
      std::vector<int> made;
      if (try_remove(m, sides, made)) {
        ++stats.vertices_removed, stats.flips += flip_all(m, made), changed = true;
      } else if (try_slide(m, v, sides)) {
        ++stats.vertices_slid, stats.flips += flip_all(m, m.vertex_tris[v]), changed = true;
      }
    }
    if (!changed) break;
  }
  std::vector<Tri> kept;
  for (size_t t = 0; t < m.tris.size(); ++t)
    if (m.alive[t]) kept.push_back(m.tris[t]);
  edit.added = std::move(kept);
  return stats;
}

}  // namespace meshround
