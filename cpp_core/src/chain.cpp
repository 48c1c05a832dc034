#include "meshround/chain.h"
#include "meshround/cancel.h"

#include "box_tree.h"
#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace meshround {
namespace {

bool is_sharp(const MeshTopology& mesh, int a, int b, double feature_angle_deg) {
  return mesh.edge_facet_count(a, b) == 2 && mesh.is_feature_edge(a, b, feature_angle_deg);
}

// Distance from p to facet f.
double facet_distance(const MeshTopology& mesh, int f, const Vec3& p) {
  return (closest_point_on_triangle(p, mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2), nullptr) - p).norm();
}

// The facet nearest to the seed (of equally near ones, the first), or -1: every facet is looked at, on all
// cores. With `on_edge` (a mesh edge the seed lies on) only the facets around its two ends are.
std::pair<int, double> nearest_facet(const MeshTopology& mesh, const Vec3& seed, std::array<int, 2> on_edge) {
  using Best = std::pair<double, int>;  // (distance, facet): the smaller pair is the nearer
  auto consider = [&](int f, Best& best) {
    const Vec3 a = mesh.corner(f, 0), b = mesh.corner(f, 1), c = mesh.corner(f, 2);
    const Vec3 gap = (a.cwiseMin(b).cwiseMin(c) - seed).cwiseMax(seed - a.cwiseMax(b).cwiseMax(c)).cwiseMax(0.0);
    if (gap.squaredNorm() > best.first * best.first) return;  // its bounding box is already farther
    best = std::min(best, Best{facet_distance(mesh, f, seed), f});
  };
  Best best{INFINITY, -1};
  const int n = mesh.num_vertices();
  if (on_edge[0] >= 0 && on_edge[0] < n && on_edge[1] >= 0 && on_edge[1] < n) {
    double t;
    const Vec3 on = closest_point_on_segment(seed, mesh.point(on_edge[0]), mesh.point(on_edge[1]), &t);
    const double slack = on_plane_slack((mesh.point(on_edge[1]) - mesh.point(on_edge[0])).norm(), seed.cwiseAbs().maxCoeff());
    if ((on - seed).norm() <= slack) {
      for (int v : on_edge)
        for (const int* f = mesh.facets_begin(v); f != mesh.facets_end(v); ++f) consider(*f, best);
      if (best.second >= 0 && best.first <= slack) return {best.second, best.first};  // a facet through the seed
      best = {INFINITY, -1};
    }
  }
  best = reduce_ranges(mesh.num_facets(), 1 << 15, best, [&](int begin, int end, Best& partial) {
    CancelPoll poll(1 << 14);
    for (int f = begin; f < end; ++f) {
      poll.tick();
      consider(f, partial);
    }
  }, [](Best& into, const Best& other) { into = std::min(into, other); });
  return {best.second, best.first};
}

// Best-first walk over the facets around the seed until no nearer sharp edge can exist.
std::pair<int, int> nearest_sharp_edge(const MeshTopology& mesh, const Vec3& seed, double feature_angle_deg,
                                       double search_radius, std::array<int, 2> on_edge) {
  const auto [start, dstart] = nearest_facet(mesh, seed, on_edge);
  CancelPoll poll(1 << 14);
  // No facet at a finite distance (coordinates so large that the distances overflow): nothing is near.
  if (start < 0)
    throw RoundingError(ErrorCode::NoSharpEdge, "no sharp edge within " + format_number(search_radius) + " mm of the seed " + format_point(seed));
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> todo;
  std::unordered_set<int> seen{start};
  todo.push({dstart, start});
  double best = INFINITY;
  std::pair<int, int> edge{-1, -1};
  while (!todo.empty()) {
    poll.tick();
    const auto [d, f] = todo.top();
    todo.pop();
    if (d > best || d > search_radius) break;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      double t;
      const double de = (closest_point_on_segment(seed, mesh.point(a), mesh.point(b), &t) - seed).norm();
      if (de < best && is_sharp(mesh, a, b, feature_angle_deg)) best = de, edge = {a, b};
      for (const int* g = mesh.facets_begin(a); g != mesh.facets_end(a); ++g)
        if (seen.insert(*g).second) todo.push({facet_distance(mesh, *g, seed), *g});
    }
  }
  if (edge.first < 0 || best > search_radius)
    throw RoundingError(ErrorCode::NoSharpEdge, "no sharp edge (feature angle " + format_number(feature_angle_deg) + " deg) within " +
                        format_number(search_radius) + " mm of the seed " + format_point(seed) +
                        "; for a blunter edge, lower the feature angle");
  return edge;
}

// How thin a facet along a sharp edge may be to count as part of the edge's fold: half the radius at the
// default reach factor of 3, for the distance within which the chain and its base meshes are searched.
double fold_width(double reach_distance) { return reach_distance / 6; }

// A sharp edge of a thin facet on a chain edge goes on with the chain's fold when it runs along the chain
// edge, within this angle (degrees): the surface turns about (nearly) the same line across both.
constexpr double kFoldLineDeg = 30;

// The facet with corners v, u, x, or -1.
int facet_of(const MeshTopology& mesh, int v, int u, int x) {
  for (const int* f = mesh.facets_begin(v); f != mesh.facets_end(v); ++f)
    if (mesh.facet_has_edge(*f, u, x)) return *f;
  return -1;
}

// True when a facet (v, u, x) exists and is thin: its smallest height is under a quarter of its longest
// edge and under `fold` (fold_width): a coarse mesher's triangle along a sharp edge, holding part of its
// fold.
bool thin_facet(const MeshTopology& mesh, int v, int u, int x, double fold) {
  if (facet_of(mesh, v, u, x) < 0) return false;
  const Vec3 a = mesh.point(v), b = mesh.point(u), c = mesh.point(x);
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const double height = (b - a).cross(c - a).norm() / std::max(longest, 1e-300);
  return height < 0.25 * longest && height < fold;
}

// A thin facet's sharp edge (p, q) goes on with the fold of its chain edge (along `chain_dir`) when it runs
// along it (kFoldLineDeg): the fold is spread over the facet. One that runs across (the end cap of a round
// made before, beside a sliver its trim left at a mitre) is a wall of its own.
bool along_fold(const MeshTopology& mesh, int p, int q, const Vec3& chain_dir) {
  const Vec3 d = (mesh.point(q) - mesh.point(p)).normalized();
  return std::abs(d.dot(chain_dir.normalized())) >= std::cos(kFoldLineDeg * M_PI / 180);
}

// A thin facet (v, u, x) on the chain edge (v, u) whose edge (v, x) is part of that edge's fold, not a new
// sharp edge.
bool fold_sliver(const MeshTopology& mesh, int v, int u, int x, double fold) {
  return thin_facet(mesh, v, u, x, fold) && along_fold(mesh, v, x, mesh.point(u) - mesh.point(v));
}

// How many open edges from a chain stopped by the boundary are followed to see whether the sharp edge
// resumes beyond (a hole of a few facets beside it).
constexpr int kHoleSteps = 12;

// One step along the chain from `prev` -> `v`: the next vertex, or -1 with the reason it ends.
int next_chain_vertex(const MeshTopology& mesh, int prev, int v, double feature_angle_deg, double fold,
                      ChainEnd* end) {
  std::vector<int> ahead;
  bool boundary = false;
  for (int w : mesh.vertex_neighbours(v)) {
    const int nf = mesh.edge_facet_count(v, w);
    if (nf > 2) return *end = ChainEnd::Junction, -1;
    boundary |= nf == 1;
    if (w != prev && mesh.is_feature_edge(v, w, feature_angle_deg)) ahead.push_back(w);
  }
  const Vec3 d0 = (mesh.point(v) - mesh.point(prev)).normalized();
  auto turn_deg = [&](int w) {
    return std::acos(std::clamp(d0.dot((mesh.point(w) - mesh.point(v)).normalized()), -1.0, 1.0)) * 180 / M_PI;
  };
  if (boundary) {
    // The mesh's own edge ends the chain; but where the sharp edge resumes ahead on the same open
    // boundary, a few edges along it, the boundary is a hole beside (or across) the chain, and the round
    // would stop at it half made. (A flange that ends, or a rim, has no sharp edge running on ahead.)
    const double cos_turn = std::cos(feature_angle_deg * M_PI / 180);
    std::vector<int> todo{v};
    std::unordered_map<int, int> hops{{v, 0}};
    while (!todo.empty()) {
      const int u = todo.back();
      todo.pop_back();
      for (int x : mesh.vertex_neighbours(u)) {
        const int nf = mesh.edge_facet_count(u, x);
        const Vec3 d = mesh.point(x) - mesh.point(u);
        if (nf == 2 && d0.dot(mesh.point(u) - mesh.point(v)) >= 0 && (u != v || x != prev) && d0.dot(d.normalized()) > cos_turn &&
            mesh.is_feature_edge(u, x, feature_angle_deg))
          throw RoundingError(ErrorCode::NonManifoldInput, "the mesh is open next to the chain at " + format_point(mesh.point(v)) +
                              " (a hole beside the sharp edge, which runs on past it); fill the hole first");
        if (nf == 1 && hops[u] < kHoleSteps && hops.try_emplace(x, hops[u] + 1).second) todo.push_back(x);
      }
    }
    return *end = ChainEnd::Boundary, -1;
  }
  if (ahead.empty()) return *end = ChainEnd::Fade, -1;
  // Other sharp edges make a junction, unless they only run across a thin facet on the chain (the fold
  // is spread over that facet: no new edge starts there). Of the continuations that leave no
  // such edge, the straightest.
  // Across a thin facet (v, w, x) the chain takes its long side, not the apex.
  int best = -1;
  for (int w : ahead) {
    const bool alone = std::all_of(ahead.begin(), ahead.end(), [&](int x) {
      return x == w || fold_sliver(mesh, v, prev, x, fold) || fold_sliver(mesh, v, w, x, fold);
    });
    const bool apex = std::any_of(ahead.begin(), ahead.end(), [&](int x) {
      return x != w && thin_facet(mesh, v, w, x, fold) &&
             (mesh.point(x) - mesh.point(v)).norm() > (mesh.point(w) - mesh.point(v)).norm();
    });
    if (alone && !apex && (best < 0 || turn_deg(w) < turn_deg(best))) best = w;
  }
  if (best < 0) return *end = ChainEnd::Junction, -1;
  if (turn_deg(best) > feature_angle_deg) return *end = ChainEnd::Turn, -1;
  return best;
}

// Walk the fan of v from facet f (entered across edge (v, came)) to the facet holding edge (v, target),
// never crossing a chain edge: that facet is on the same side of the chain as f.
int same_side_facet(const MeshTopology& mesh, int f, int v, int came, int target) {
  for (int guard = 0; guard < 4096; ++guard) {
    int y = -1;
    for (int k = 0; k < 3; ++k)
      if (mesh.F(f, k) != v && mesh.F(f, k) != came) y = mesh.F(f, k);
    if (y == target) return f;
    const int g = mesh.neighbour(f, v, y);
    if (g < 0)
      throw RoundingError(ErrorCode::NonManifoldInput, "the mesh is open or non-manifold at the chain vertex " + format_point(mesh.point(v)));
    came = y;
    f = g;
  }
  throw RoundingError(ErrorCode::NonManifoldInput, "cannot walk around the chain vertex " + format_point(mesh.point(v)));
}

}  // namespace

SharpChain trace_chain(const MeshTopology& mesh, const Vec3& seed, double feature_angle_deg, double search_radius,
                       std::array<int, 2> on_edge) {
  const auto [a, b] = nearest_sharp_edge(mesh, seed, feature_angle_deg, search_radius, on_edge);
  const double fold = fold_width(search_radius);
  SharpChain chain;
  std::vector<int> forward{a, b};
  ChainEnd end_fwd = ChainEnd::Fade, end_bwd = ChainEnd::Fade;
  const size_t limit = size_t(mesh.num_vertices()) + 2;
  while (forward.size() < limit) {
    poll_cancel();
    const int w = next_chain_vertex(mesh, forward[forward.size() - 2], forward.back(), feature_angle_deg, fold, &end_fwd);
    if (w < 0) break;
    if (w == forward.front()) {
      chain.closed = true;
      break;
    }
    forward.push_back(w);
  }
  std::vector<int> backward;
  if (!chain.closed) {
    int prev = b, v = a;
    while (backward.size() < limit) {
      poll_cancel();
      const int w = next_chain_vertex(mesh, prev, v, feature_angle_deg, fold, &end_bwd);
      if (w < 0) break;
      backward.push_back(w);
      prev = v, v = w;
    }
  }
  chain.vertices.assign(backward.rbegin(), backward.rend());
  chain.vertices.insert(chain.vertices.end(), forward.begin(), forward.end());
  chain.start_end = end_bwd;
  chain.end_end = end_fwd;

  // Sides: A is one facet of the first edge, then carried around each chain vertex.
  // A chain that entered the apex of a thin facet (from the seed) takes the facet's long side instead.
  for (size_t i = 1; i + 1 < chain.vertices.size() && chain.vertices.size() > 2; ++i) {
    const int v = chain.vertices[i - 1], x = chain.vertices[i], u = chain.vertices[i + 1];
    if (thin_facet(mesh, v, x, u, fold) && is_sharp(mesh, v, u, feature_angle_deg))
      chain.vertices.erase(chain.vertices.begin() + long(i--));
  }
  const int n = int(chain.vertices.size());
  const int edges = chain.closed ? n : n - 1;
  auto vtx = [&](int i) { return chain.vertices[(i + n) % n]; };
  for (int i = 0; i < edges; ++i) {
    const std::vector<int> fs = mesh.edge_facets(vtx(i), vtx(i + 1));
    if (fs.size() != 2) throw RoundingError(ErrorCode::NonManifoldInput, "the chain edge at " + format_point(mesh.point(vtx(i))) + " is not manifold");
    int fa = fs[0];
    if (i > 0) fa = same_side_facet(mesh, chain.facet_a[i - 1], vtx(i), vtx(i - 1), vtx(i + 1));
    chain.facet_a.push_back(fa);
    chain.facet_b.push_back(fa == fs[0] ? fs[1] : fs[0]);
  }
  if (chain.closed && same_side_facet(mesh, chain.facet_a.back(), vtx(0), vtx(-1), vtx(1)) != chain.facet_a[0])
    throw RoundingError(ErrorCode::NonManifoldInput, "the closed chain through " + format_point(seed) + " swaps its sides (a one-sided loop)");
  chain.finish_geometry(mesh);
  return chain;
}

void SharpChain::finish_geometry(const MeshTopology& mesh) {
  const int n = int(vertices.size());
  points.clear();
  for (int v : vertices) points.push_back(mesh.point(v));
  arc_length.assign(n, 0.0);
  for (int i = 1; i < n; ++i) arc_length[i] = arc_length[i - 1] + (points[i] - points[i - 1]).norm();
  length = arc_length.back() + (closed ? (points.front() - points.back()).norm() : 0.0);
  // Vertex tangents: mean of the two segment directions, so that section planes turn smoothly.
  const int segs = closed ? n : n - 1;
  std::vector<Vec3> dir(segs);
  for (int i = 0; i < segs; ++i) dir[i] = (points[(i + 1) % n] - points[i]).normalized();
  vertex_tangents_.resize(n);
  for (int i = 0; i < n; ++i) {
    Vec3 t;
    if (closed) t = dir[(i - 1 + segs) % segs] + dir[i];
    else t = (i == 0 ? dir[0] : i == n - 1 ? dir[segs - 1] : Vec3(dir[i - 1] + dir[i]));
    vertex_tangents_[i] = t.normalized();
  }
}

int SharpChain::segment_at(double s, double* local) const {
  const int n = int(points.size());
  if (closed) s = s - std::floor(s / length) * length;
  else s = std::clamp(s, 0.0, length);
  const int segs = closed ? n : n - 1;
  int i = int(std::upper_bound(arc_length.begin(), arc_length.end(), s) - arc_length.begin()) - 1;
  i = std::clamp(i, 0, segs - 1);
  const double l = (points[(i + 1) % n] - points[i]).norm();
  *local = l > 0 ? std::clamp((s - arc_length[i]) / l, 0.0, 1.0) : 0.0;
  return i;
}

Vec3 SharpChain::point_at(double s) const {
  double t;
  const int i = segment_at(s, &t);
  return (1 - t) * points[i] + t * points[(i + 1) % points.size()];
}

Vec3 SharpChain::tangent_at(double s) const {
  double t;
  const int i = segment_at(s, &t);
  return ((1 - t) * vertex_tangents_[i] + t * vertex_tangents_[(i + 1) % points.size()]).normalized();
}

void SharpChain::index_segments() {
  const int n = int(points.size());
  std::vector<Vec3> boxes;
  boxes.reserve(2 * num_edges());
  for (int i = 0; i < num_edges(); ++i)
    boxes.push_back(points[i].cwiseMin(points[(i + 1) % n])), boxes.push_back(points[i].cwiseMax(points[(i + 1) % n]));
  segments_ = std::make_shared<const BoxTree>(boxes);
}

double SharpChain::project(const Vec3& p, double* distance) const {
  const int n = int(points.size()), segs = closed ? n : n - 1;
  auto d2 = [&](int i) {
    double t;
    return (closest_point_on_segment(p, points[i], points[(i + 1) % n], &t) - p).squaredNorm();
  };
  double best = INFINITY;
  int i_best = -1;
  if (segments_) {
    i_best = segments_->nearest(p, d2, &best);
  } else {
    for (int i = 0; i < segs; ++i) {
      const double d = d2(i);
      if (d < best) best = d, i_best = i;
    }
  }
  double t = 0;
  if (i_best >= 0) closest_point_on_segment(p, points[i_best], points[(i_best + 1) % n], &t);
  else i_best = 0;
  if (distance) *distance = std::sqrt(best);
  return arc_length[i_best] + t * (points[(i_best + 1) % n] - points[i_best]).norm();
}

double SharpChain::project_from(const Vec3& p, double s_hint, double* distance) const {
  const int n = int(points.size()), segs = closed ? n : n - 1;
  auto dist2 = [&](int i, double* s_out) {
    double t;
    const Vec3 q = closest_point_on_segment(p, points[i], points[(i + 1) % n], &t);
    if (s_out) *s_out = arc_length[i] + t * (points[(i + 1) % n] - points[i]).norm();
    return (q - p).squaredNorm();
  };
  double local;
  int i = segment_at(s_hint, &local);
  double s_best = 0, best = dist2(i, &s_best);
  // Walk both ways while the distance falls, looking a few segments ahead past flat stretches.
  for (int dir : {-1, 1}) {
    for (int j = i, misses = 0; misses < 3;) {
      j += dir;
      if (closed) j = (j + segs) % segs;
      else if (j < 0 || j >= segs) break;
      if (j == i) break;
      double s_j;
      const double d = dist2(j, &s_j);
      if (d < best) best = d, s_best = s_j, i = j, misses = 0;
      else ++misses;
    }
  }
  if (distance) *distance = std::sqrt(best);
  return s_best;
}

BaseMeshes collect_base_meshes(const MeshTopology& mesh, const SharpChain& chain, double reach_distance,
                               double feature_angle_deg, const std::unordered_set<int>* earlier_round) {
  BaseMeshes base;
  base.reach_distance = reach_distance;
  std::unordered_set<std::uint64_t> chain_edges;
  const int n = int(chain.vertices.size());
  for (int i = 0; i < chain.num_edges(); ++i) chain_edges.insert(edge_key(chain.vertices[i], chain.vertices[(i + 1) % n]));
  // Nearness to the chain: each vertex projected from its neighbour's projection, so the flood costs
  // what the band costs; one that reads beyond the reach that way is projected onto the whole chain too
  // (the walk from a hint stops in a dip of the distance along the chain: a whole pocket's floor loop on a
  // 1.8 mm mesh read a wall vertex 5 mm from it as beyond 15, and its ball was refused beyond_reach).
  auto project = [&](int v, double s_hint) -> const ChainProjection& {
    auto [it, fresh] = base.projection.try_emplace(v);
    if (fresh) {
      it->second.s = chain.project_from(mesh.point(v), s_hint, &it->second.distance);
      double d = 0;
      if (it->second.distance > reach_distance) {
        const double s = chain.project(mesh.point(v), &d);
        if (d < it->second.distance) it->second = {s, d};
      }
    }
    return it->second;
  };
  auto within_reach = [&](int f, double s_hint) {  // projects all three corners: trimming needs them
    bool in = false;
    for (int k = 0; k < 3; ++k) in |= project(mesh.F(f, k), s_hint).distance <= reach_distance;
    return in;
  };
  for (int i = 0; i < n; ++i) project(chain.vertices[i], chain.arc_length[i]);
  for (int i = 0; i < chain.num_edges(); ++i) {
    within_reach(chain.facet_a[i], chain.arc_length[i]);
    within_reach(chain.facet_b[i], chain.arc_length[i]);
  }
  // A thin facet on a chain edge holds part of the edge's fold: its other edges are folds too, not walls,
  // where they run along the chain (along_fold).
  std::unordered_map<int, Vec3> fold_facets;  // thin facet on a chain edge -> that edge's direction
  const double fold = fold_width(reach_distance);
  for (int i = 0; i < chain.num_edges(); ++i)
    for (int f : {chain.facet_a[i], chain.facet_b[i]}) {
      const int v = chain.vertices[i], u = chain.vertices[(i + 1) % n];
      int x = mesh.F(f, 0);
      for (int k = 0; k < 3; ++k)
        if (mesh.F(f, k) != v && mesh.F(f, k) != u) x = mesh.F(f, k);
      if (thin_facet(mesh, v, u, x, fold)) fold_facets[f] = mesh.point(u) - mesh.point(v);
    }
  auto continues_fold = [&](int f, int a, int b) {
    const auto it = fold_facets.find(f);
    return it != fold_facets.end() && along_fold(mesh, a, b, it->second);
  };
  for (int side = 0; side < 2; ++side) {
    std::vector<int> todo;
    for (int f : side == 0 ? chain.facet_a : chain.facet_b) {
      auto it = base.side_of.find(f);
      if (it != base.side_of.end() && it->second != side)
        throw RoundingError(ErrorCode::NoSharpEdge, "a facet at " + format_point(mesh.corner(f, 0)) + " lies on both sides of the chain; " +
                            "where an edge turns by about the feature angle (" + format_number(feature_angle_deg) +
                            " deg) only some of its facets count as sharp: lower the feature angle");
      if (it == base.side_of.end()) base.side_of[f] = side, todo.push_back(f), base.facets[side].push_back(f);
    }
    CancelPoll poll(256);
    while (!todo.empty()) {
      poll.tick();
      const int f = todo.back();
      todo.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
        const std::uint64_t key = edge_key(a, b);
        if (chain_edges.count(key)) continue;
        const int g = mesh.neighbour(f, a, b);
        if (g >= 0 && mesh.facet_degenerate(g))
          throw RoundingError(ErrorCode::NonManifoldInput, "facet " + std::to_string(g) + " at " + format_point(mesh.corner(g, 0)) +
                              " near the chain is degenerate (no area); repair the mesh there first");
        const bool earlier = g >= 0 && earlier_round && std::all_of(&mesh.F(g, 0), &mesh.F(g, 0) + 3, [&](int x) { return earlier_round->count(x) > 0; });
        if (g < 0 || earlier || (mesh.is_feature_edge(a, b, feature_angle_deg) && !continues_fold(f, a, b))) {
          base.walls[side].insert(key);
          continue;
        }
        auto it = base.side_of.find(g);
        if (it != base.side_of.end()) {
          if (it->second != side)
            throw RoundingError(ErrorCode::NoSharpEdge, "the two sides of the chain join near " + format_point(mesh.point(a)) +
                                ": the sharp edges there do not separate two base meshes");
          continue;
        }
        if (!within_reach(g, base.projection.at(a).s)) {
          base.reach_limit[side].insert(key);
          continue;
        }
        base.side_of[g] = side;
        base.facets[side].push_back(g);
        todo.push_back(g);
      }
    }
  }
  return base;
}

}  // namespace meshround
