#include "meshround/improve.h"
#include "meshround/cancel.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "delta.h"
#include "facet_quality.h"
#include "planar.h"

namespace meshround {

namespace {

using Tri = std::array<int, 3>;

// An annulus (a face around a pocket rim) is cut in two across it, from two vertices half its shorter
// loop apart; this many such pairs are tried, spread along the loop.
constexpr int kSplitsTried = 4;

// Flat pieces of the made facets: the facets, their side (area-weighted normal, not unit) and smallest angle.
struct FlatPiece {
  std::vector<int> facets;
  Vec3 normal = Vec3::Zero();
  double worst = INFINITY;  // radians
  int thin = 0;             // facets under kThinDeg
};

// The made facets connected to `seed` across edges that lie on its plane and face its way; each gets `id`
// in piece_of.
FlatPiece grow_piece(const MeshTopology& mesh, const std::vector<char>& made, int seed, std::vector<int>& piece_of, int id) {
  FlatPiece out;
  const Vec3 origin = mesh.corner(seed, 0), unit = mesh.facet_normal(seed);
  std::vector<int> todo{seed};
  piece_of[seed] = id;
  while (!todo.empty()) {
    const int f = todo.back();
    todo.pop_back();
    out.facets.push_back(f);
    out.normal += (mesh.corner(f, 1) - mesh.corner(f, 0)).cross(mesh.corner(f, 2) - mesh.corner(f, 0));
    const double angle = smallest_angle(mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2));
    out.worst = std::min(out.worst, angle);
    out.thin += angle < kThinDeg * M_PI / 180;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      const int g = mesh.neighbour(f, a, b);
      if (g < 0 || !made[g] || piece_of[g] >= 0 || mesh.facet_degenerate(g) || mesh.facet_normal(g).dot(unit) <= 0) continue;
      if (!on_plane(mesh.corner(g, 0), origin, unit) || !on_plane(mesh.corner(g, 1), origin, unit) ||
          !on_plane(mesh.corner(g, 2), origin, unit))
        continue;
      piece_of[g] = id;
      todo.push_back(g);
    }
  }
  return out;
}

// The loops of the piece's outline (its edges with no facet of the piece across), each in the facets' own
// direction; empty when the outline passes a vertex twice.
std::vector<std::vector<int>> outline_loops(const MeshTopology& mesh, const FlatPiece& piece, const std::vector<int>& piece_of,
                                            int id) {
  std::unordered_map<int, int> next;
  for (int f : piece.facets)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      const int g = mesh.neighbour(f, a, b);
      if (g >= 0 && piece_of[g] == id) continue;
      if (!next.emplace(a, b).second) return {};
    }
  std::vector<std::vector<int>> loops;
  std::unordered_set<int> seen;
  for (const auto& [start, unused] : next) {
    if (seen.count(start)) continue;
    std::vector<int> loop;
    for (int v = start; !seen.count(v); v = next.at(v)) {
      if (!next.count(v)) return {};
      seen.insert(v), loop.push_back(v);
    }
    if (loop.empty() || loop.front() != next.at(loop.back())) return {};
    loops.push_back(std::move(loop));
  }
  return loops;
}

// A disk of the piece meshed again: its outline kept, points added inside where `admit` allows.
struct DiskFill {
  std::vector<Tri> fill;
  double worst = -1;  // its smallest angle; < 0: it does not fit
  int thin = 0;       // its facets under kThinDeg
};

// The fill fits when every facet faces the piece's way and reaches into the band, and no edge it makes
// between outline vertices is in the mesh outside the piece (`piece_of` != id) or in `made_edges` (the
// other half's fill); its edges go into made_edges.
DiskFill fill_disk(MeshEdit& edit, const std::vector<int>& outline, const Vec3& normal, const std::vector<int>& piece_of, int id,
                   const std::function<bool(const Vec3&)>& admit, std::unordered_set<std::uint64_t>& made_edges) {
  const MeshTopology& mesh = edit.input;
  DiskFill out;
  triangulate_polygon(edit, outline, normal, out.fill, Refinement{20.0, admit});
  if (out.fill.size() + 2 < outline.size()) return out;
  std::unordered_set<std::uint64_t> sides;
  for (size_t i = 0; i < outline.size(); ++i) sides.insert(edge_key(outline[i], outline[(i + 1) % outline.size()]));
  double worst = INFINITY;
  for (const Tri& t : out.fill) {
    const Vec3 a = edit.point(t[0]), b = edit.point(t[1]), c = edit.point(t[2]);
    if ((b - a).cross(c - a).dot(normal) <= 0 || (!admit(a) && !admit(b) && !admit(c))) return out;
    const double angle = smallest_angle(a, b, c);
    worst = std::min(worst, angle);
    out.thin += angle < kThinDeg * M_PI / 180;
    for (int k = 0; k < 3; ++k) {
      const int p = t[k], q = t[(k + 1) % 3];
      if (p >= mesh.num_vertices() || q >= mesh.num_vertices() || sides.count(edge_key(p, q))) continue;
      for (int g : mesh.edge_facets(p, q))
        if (piece_of[g] != id) return out;
      if (made_edges.count(edge_key(p, q))) return out;
    }
  }
  for (const Tri& t : out.fill)
    for (int k = 0; k < 3; ++k) made_edges.insert(edge_key(t[k], t[(k + 1) % 3]));
  out.worst = worst;
  return out;
}

// A straight cut across an annulus from a vertex of one loop to one of the other: inside the piece (its
// middle between the loops) and crossing no side of either loop. In plane coordinates (`Q` per vertex).
bool cut_clear(const std::unordered_map<int, Eigen::Vector2d>& Q, const std::vector<std::vector<int>>& loops,
               const std::vector<std::vector<Eigen::Vector2d>>& rings, int a, int b) {
  const Eigen::Vector2d p = Q.at(a), q = Q.at(b), mid = 0.5 * (p + q);
  if (planar::inside_polygon(mid, rings[0], rings[0].size()) == planar::inside_polygon(mid, rings[1], rings[1].size())) return false;
  for (size_t l = 0; l < 2; ++l)
    for (size_t k = 0; k < loops[l].size(); ++k) {
      const int u = loops[l][k], w = loops[l][(k + 1) % loops[l].size()];
      if (u == a || u == b || w == a || w == b) continue;
      if (planar::segments_cross(p, q, Q.at(u), Q.at(w))) return false;
      // a loop vertex on the cut (or within a hair of it) blocks it too
      const Eigen::Vector2d x = Q.at(u);
      const double t = (x - p).dot(q - p) / (q - p).squaredNorm();
      if (t > 0 && t < 1 && (p + t * (q - p) - x).norm() <= 1e-9 * (q - p).norm()) return false;
    }
  return true;
}

// The ring from o1 along loop `outer` to o2, across to i2, along loop `inner` to i1 and back across: one half
// of an annulus cut at (o1, i1) and (o2, i2), the piece on its left as on the loops'.
std::vector<int> half_ring(const std::vector<int>& outer, size_t o1, size_t o2, const std::vector<int>& inner, size_t i2, size_t i1) {
  std::vector<int> ring;
  for (size_t k = o1;; k = (k + 1) % outer.size()) {
    ring.push_back(outer[k]);
    if (k == o2) break;
  }
  for (size_t k = i2;; k = (k + 1) % inner.size()) {
    ring.push_back(inner[k]);
    if (k == i1) break;
  }
  return ring;
}

// The fills that replace the piece (empty: none better than it: a larger smallest angle, and no more facets
// under kThinDeg). One loop: the piece meshed whole. Two
// (an annulus): cut in two along two straight cuts across (from vertices of the shorter loop half of it
// apart, each to the nearest vertex of the other loop it reaches clear), each half meshed on its own; the
// best of the cuts tried.
std::vector<Tri> remesh_piece(MeshEdit& edit, const std::function<bool(int)>& may_go,
                              const FlatPiece& piece, std::vector<int>& piece_of, int id,
                              const std::function<bool(const Vec3&)>& admit) {
  const MeshTopology& mesh = edit.input;
  const std::vector<std::vector<int>> loops = outline_loops(mesh, piece, piece_of, id);
  // Only made vertices inside the piece (refinement and graded points) may go: the outline stays.
  std::unordered_set<int> on_outline;
  for (const auto& loop : loops) on_outline.insert(loop.begin(), loop.end());
  for (int f : piece.facets)
    for (int k = 0; k < 3; ++k)
      if (!on_outline.count(mesh.F(f, k)) && !may_go(mesh.F(f, k))) return {};
  if (loops.size() == 1) {
    std::unordered_set<std::uint64_t> made_edges;
    DiskFill d = fill_disk(edit, loops[0], piece.normal, piece_of, id, admit, made_edges);
    return d.worst > piece.worst + 1e-9 && d.thin <= piece.thin ? d.fill : std::vector<Tri>{};
  }
  if (loops.size() != 2) return {};
  // In the piece's plane: each loop vertex's coordinates, and the loops as rings.
  const Vec3 n = piece.normal.normalized();
  const Vec3 e1 = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized(), e2 = n.cross(e1);
  std::unordered_map<int, Eigen::Vector2d> Q;
  std::vector<std::vector<Eigen::Vector2d>> rings(2);
  for (int l = 0; l < 2; ++l)
    for (int v : loops[l]) rings[l].push_back(Q[v] = Eigen::Vector2d(mesh.point(v).dot(e1), mesh.point(v).dot(e2)));
  const int outer = loops[0].size() <= loops[1].size() ? 0 : 1, inner = 1 - outer;  // cuts start on the shorter
  const std::vector<int>&O = loops[outer], &I = loops[inner];
  // The cut from outer vertex k to the nearest inner vertex it reaches clear; -1: none.
  auto cut_from = [&](size_t k) {
    std::vector<size_t> order(I.size());
    for (size_t j = 0; j < I.size(); ++j) order[j] = j;
    std::sort(order.begin(), order.end(), [&](size_t x, size_t y) { return (Q[I[x]] - Q[O[k]]).norm() < (Q[I[y]] - Q[O[k]]).norm(); });
    for (size_t j : order)
      if (cut_clear(Q, loops, rings, O[k], I[j])) return long(j);
    return -1L;
  };
  const size_t tries = std::min(O.size() / 2, size_t(kSplitsTried));
  std::vector<Tri> best;
  double best_worst = piece.worst + 1e-9;
  for (size_t t = 0; t < tries; ++t) {
    const size_t o1 = t * O.size() / (2 * tries), o2 = o1 + O.size() / 2;
    const long i1 = cut_from(o1), i2 = cut_from(o2);
    if (i1 < 0 || i2 < 0 || i1 == i2) continue;
    bool apart = true;  // a cut must not be an edge outside the piece
    for (auto [o, i] : {std::pair{o1, i1}, {o2, i2}})
      for (int g : mesh.edge_facets(O[o], I[size_t(i)])) apart &= piece_of[g] == id;
    if (!apart) continue;
    std::unordered_set<std::uint64_t> made_edges;
    const DiskFill a = fill_disk(edit, half_ring(O, o1, o2, I, size_t(i2), size_t(i1)), piece.normal, piece_of, id, admit, made_edges);
    if (a.worst <= best_worst) continue;
    const DiskFill b = fill_disk(edit, half_ring(O, o2, o1, I, size_t(i1), size_t(i2)), piece.normal, piece_of, id, admit, made_edges);
    if (std::min(a.worst, b.worst) <= best_worst || a.thin + b.thin > piece.thin) continue;
    best = a.fill;
    best.insert(best.end(), b.fill.begin(), b.fill.end());
    best_worst = std::min(a.worst, b.worst);
  }
  return best;
}

}  // namespace

ImproveStats remesh_flat_patches(MeshEdit& edit, const std::vector<char>& made, const std::function<bool(int)>& may_go,
                                 const std::function<bool(const Vec3&)>& admit) {
  ImproveStats stats;
  const MeshTopology& mesh = edit.input;
  std::vector<int> piece_of(mesh.num_facets(), -1);
  const double thin = kThinDeg * M_PI / 180;
  CancelPoll poll(16);
  for (int seed = 0; seed < mesh.num_facets(); ++seed) {
    if (!made[seed] || piece_of[seed] >= 0 || mesh.facet_degenerate(seed)) continue;
    poll.tick();
    FlatPiece piece = grow_piece(mesh, made, seed, piece_of, seed);
    if (piece.facets.size() < 2 || piece.worst >= thin) continue;
    const std::vector<Tri> fill = remesh_piece(edit, may_go, piece, piece_of, seed, admit);
    if (fill.empty()) continue;
    edit.removed.insert(piece.facets.begin(), piece.facets.end());
    edit.added.insert(edit.added.end(), fill.begin(), fill.end());
    ++stats.patches_remeshed;
  }
  return stats;
}

bool remesh_flat_patches(const MeshTopology& input, MeshDelta& delta, const std::function<bool(const Vec3&)>& admit) {
  // Most calls make no facet under kThinDeg: they pay for this look at the facets made, not for the whole mesh.
  const int n = input.num_vertices();
  std::unordered_map<int, Vec3> moved;
  for (size_t i = 0; i < delta.moved.size(); ++i) moved[delta.moved[i]] = delta.moved_to[i];
  auto point = [&](int v) -> Vec3 {
    if (v >= n) return delta.new_points[size_t(v - n)];
    auto it = moved.find(v);
    return it != moved.end() ? it->second : input.point(v);
  };
  const double thin = kThinDeg * M_PI / 180;
  if (std::none_of(delta.added.begin(), delta.added.end(), [&](const Tri& t) { return smallest_angle(point(t[0]), point(t[1]), point(t[2])) < thin; }))
    return false;
  // The band alone as a mesh: the facets made, then the kept input facets around their vertices (all the
  // facets an edge between two of those vertices can have), each vertex known by its id in the result.
  std::vector<Tri> facets(delta.added.begin(), delta.added.end());
  {
    const std::unordered_set<int> removed(delta.removed.begin(), delta.removed.end());
    std::unordered_set<int> around;
    for (const Tri& t : delta.added)
      for (int v : t)
        if (v < n)
          for (const int* f = input.facets_begin(v); f != input.facets_end(v); ++f)
            if (!removed.count(*f) && around.insert(*f).second) facets.push_back({input.F(*f, 0), input.F(*f, 1), input.F(*f, 2)});
  }
  std::unordered_map<int, int> local;
  std::vector<int> global;
  for (Tri& t : facets)
    for (int& v : t) {
      auto [it, fresh] = local.emplace(v, int(global.size()));
      if (fresh) global.push_back(v);
      v = it->second;
    }
  Points Vb(Eigen::Index(global.size()), 3);
  for (size_t k = 0; k < global.size(); ++k) Vb.row(Eigen::Index(k)) = point(global[k]).transpose();
  Triangles Fb(Eigen::Index(facets.size()), 3);
  for (size_t f = 0; f < facets.size(); ++f) Fb.row(Eigen::Index(f)) << facets[f][0], facets[f][1], facets[f][2];
  const MeshTopology band(Vb, Fb);
  std::vector<char> made(facets.size(), 0);
  std::fill(made.begin(), made.begin() + long(delta.added.size()), 1);
  MeshEdit edit(band);
  if (remesh_flat_patches(edit, made, [&](int v) { return global[size_t(v)] >= n; }, admit).patches_remeshed == 0 || !edit.moved.empty())
    return false;
  // Back to the call's ids: the made facets kept and the patches' new ones (their points after the delta's).
  std::vector<Tri> added;
  for (size_t f = 0; f < delta.added.size(); ++f)
    if (!edit.removed.count(int(f))) added.push_back(delta.added[f]);
  const int extra = n + int(delta.new_points.size());
  for (Tri t : edit.added) {
    for (int& v : t) v = v < int(global.size()) ? global[size_t(v)] : extra + (v - int(global.size()));
    added.push_back(t);
  }
  std::vector<Vec3> points = delta.new_points;
  points.insert(points.end(), edit.new_points.begin(), edit.new_points.end());
  std::vector<std::pair<int, Vec3>> moves;
  for (size_t i = 0; i < delta.moved.size(); ++i) moves.push_back({delta.moved[i], delta.moved_to[i]});
  delta = make_delta(input, delta.removed, moves, points, added);  // (points the patches dropped go)
  return true;
}

}  // namespace meshround
