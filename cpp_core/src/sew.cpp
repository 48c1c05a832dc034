#include "meshround/sew.h"

#include "delta.h"
#include "meshround/cancel.h"

#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cmath>
#include <map>

namespace meshround {
namespace {

// Facets using each undirected edge that the edit touches, counted over the whole edited mesh.
struct EdgeUse {
  int count = 0;
  int a = -1, b = -1;  // direction in one facet that uses it
};

std::unordered_map<std::uint64_t, EdgeUse> edges_near_edit(const MeshEdit& edit) {
  const MeshTopology& in = edit.input;
  std::unordered_map<std::uint64_t, EdgeUse> use;
  auto add_edges = [&](const std::array<int, 3>& f) {
    for (int k = 0; k < 3; ++k) {
      EdgeUse& e = use[edge_key(f[k], f[(k + 1) % 3])];
      ++e.count, e.a = f[k], e.b = f[(k + 1) % 3];
    }
  };
  for (const auto& f : edit.added) add_edges(f);
  // Kept input facets around removed ones: their edges may now be open.
  std::unordered_set<int> ring;
  for (int f : edit.removed)
    for (int k = 0; k < 3; ++k)
      for (const int* g = in.facets_begin(in.F(f, k)); g != in.facets_end(in.F(f, k)); ++g)
        if (!edit.removed.count(*g)) ring.insert(*g);
  for (int g : ring) add_edges({in.F(g, 0), in.F(g, 1), in.F(g, 2)});
  // Input facets outside that ring cannot share an edge with an added facet, but may share one with
  // a ring facet: count those from the input itself.
  for (auto& [key, e] : use) {
    const int a = int(key >> 32), b = int(key & 0xffffffffu);
    if (a >= in.num_vertices() || b >= in.num_vertices()) continue;
    for (int g : in.edge_facets(a, b))
      if (!edit.removed.count(g) && !ring.count(g)) ++e.count;
  }
  return use;
}

// A gap's side that is an input edge runs between two kept facets' corners and cannot be split without
// splitting the kept facet beyond it too. When it is long against the gap (an end face's edge many times
// the distance to the new points), every triangle on it is a sliver; so it gets a point where the gap's
// new points come nearest, if that point is within the reach and the facet beyond splits into two
// facets no worse than itself (or than kSplitShape). Returns the loop with the points inserted.
constexpr double kLongSide = 3.0;                      // side length against its distance to new points
constexpr double kSplitShape = 15.0 * M_PI / 180.0;    // good enough for the facet beyond, whatever it was
std::vector<int> split_long_sides(MeshEdit& edit, const std::vector<int>& loop, const Refinement& fill) {
  const MeshTopology& in = edit.input;
  const int n = int(loop.size());
  std::vector<int> out;
  for (int i = 0; i < n; ++i) {
    const int a = loop[i], b = loop[(i + 1) % n];
    out.push_back(a);
    if (a >= in.num_vertices() || b >= in.num_vertices() || !fill.admit) continue;
    const std::vector<int> pair = in.edge_facets(a, b);
    std::vector<int> kept;
    for (int g : pair)
      if (!edit.removed.count(g)) kept.push_back(g);
    if (kept.size() != 1) continue;
    const Vec3 pa = edit.point(a), pb = edit.point(b);
    // Where the gap's new points come nearest to the side.
    double nearest = INFINITY, at = -1;
    for (int w : loop) {
      if (w < in.num_vertices()) continue;
      double t;
      const double d = (closest_point_on_segment(edit.point(w), pa, pb, &t) - edit.point(w)).norm();
      if (d < nearest && t > 0.1 && t < 0.9 && fill.admit(pa + t * (pb - pa))) nearest = d, at = t;
    }
    if (at < 0 || (pb - pa).norm() < kLongSide * nearest) continue;
    const int g = kept[0];
    int k = 0;
    while (!(in.F(g, k) == a && in.F(g, (k + 1) % 3) == b) && !(in.F(g, k) == b && in.F(g, (k + 1) % 3) == a)) ++k;
    const int x = in.F(g, k), y = in.F(g, (k + 1) % 3), c = in.F(g, (k + 2) % 3);
    const Vec3 p = pa + at * (pb - pa);
    const double worst = std::min(smallest_angle(edit.point(x), p, edit.point(c)), smallest_angle(p, edit.point(y), edit.point(c)));
    if (worst < std::min(kSplitShape, smallest_angle(edit.point(x), edit.point(y), edit.point(c)))) continue;
    const int v = edit.add_point(p);
    edit.removed.insert(g);
    edit.added.push_back({x, v, c});
    edit.added.push_back({v, y, c});
    out.push_back(v);
  }
  return out;
}

// The gaps' loops from their open edges (from -> to). Where loops touch at a vertex (two end caps meeting
// at one corner of a face) the walk cuts each closed sub-loop off as it comes back to a vertex it passed.
// `open_chains`: walks that end where no open edge goes on (the gap reaches the mesh boundary).
std::vector<std::vector<int>> gap_loops(const std::vector<std::pair<int, int>>& edges, int* open_chains) {
  std::map<int, std::vector<int>> out;  // (ordered: the loops come in a fixed order)
  for (const auto& [from, to] : edges) out[from].push_back(to);
  std::vector<std::vector<int>> loops;
  *open_chains = 0;
  while (!out.empty()) {
    std::vector<int> path{out.begin()->first};
    std::map<int, size_t> at{{path[0], 0}};
    while (true) {
      const auto it = out.find(path.back());
      if (it == out.end()) {
        if (path.size() > 1) ++*open_chains;
        break;
      }
      const int w = it->second.back();
      it->second.pop_back();
      if (it->second.empty()) out.erase(it);
      const auto seen = at.find(w);
      if (seen == at.end()) {
        at[w] = path.size();
        path.push_back(w);
        continue;
      }
      loops.emplace_back(path.begin() + long(seen->second), path.end());
      for (size_t i = seen->second + 1; i < path.size(); ++i) at.erase(path[i]);
      path.resize(seen->second + 1);
    }
  }
  return loops;
}

Vec3 newell_normal(const MeshEdit& edit, const std::vector<int>& loop) {
  Vec3 normal = Vec3::Zero();
  for (size_t i = 0; i < loop.size(); ++i) normal += edit.point(loop[i]).cross(edit.point(loop[(i + 1) % loop.size()]));
  return normal;
}

// An island: kept facets that a gap goes all round, touching the gap's outer side at one vertex (an end
// face meshed with a fan of small facets from the chain's end vertex to a far corner of the face: the cap
// takes the facets on both sides of the fan and leaves the fan). gap_loops gives its rim as a loop of its
// own, running the other way round (Newell's normal opposite the outer loop's, and smaller). The island
// lies inside the patch the gap is to become, so it goes too: its facets (kept input facets and facets
// made by the trim, never the round's), flooded from the rim's edges and not across them. False, and
// nothing removed, where the flood meets the round or the input's boundary or runs past kMaxIsland facets:
// not an island.
constexpr size_t kMaxIsland = 2000;
bool remove_islands(MeshEdit& edit, const std::vector<std::vector<int>>& loops, size_t round_begin, size_t round_end) {
  const MeshTopology& in = edit.input;
  std::vector<Vec3> normal(loops.size());
  for (size_t i = 0; i < loops.size(); ++i) normal[i] = newell_normal(edit, loops[i]);
  std::unordered_set<std::uint64_t> rim;  // the islands' rims' edges
  for (size_t i = 0; i < loops.size(); ++i)
    for (size_t j = 0; j < loops.size(); ++j) {
      if (i == j || !(normal[i].norm() < normal[j].norm()) || normal[i].dot(normal[j]) > -0.9 * normal[i].norm() * normal[j].norm()) continue;
      const std::unordered_set<int> outer(loops[j].begin(), loops[j].end());
      if (std::none_of(loops[i].begin(), loops[i].end(), [&](int v) { return outer.count(v) > 0; })) continue;
      for (size_t k = 0; k < loops[i].size(); ++k) rim.insert(edge_key(loops[i][k], loops[i][(k + 1) % loops[i].size()]));
    }
  if (rim.empty()) return false;
  // The edited mesh's facets by edge, near the edit: ids >= 0 input facets, -1 - i made facet i.
  std::unordered_map<std::uint64_t, std::vector<int>> made_at;
  for (size_t i = 0; i < edit.added.size(); ++i)
    for (int k = 0; k < 3; ++k) made_at[edge_key(edit.added[i][k], edit.added[i][(k + 1) % 3])].push_back(-1 - int(i));
  auto corners = [&](int f) { return f >= 0 ? std::array<int, 3>{in.F(f, 0), in.F(f, 1), in.F(f, 2)} : edit.added[size_t(-1 - f)]; };
  auto facets_at = [&](int a, int b) {
    std::vector<int> out;
    if (a < in.num_vertices() && b < in.num_vertices())
      for (int g : in.edge_facets(a, b))
        if (!edit.removed.count(g)) out.push_back(g);
    const auto it = made_at.find(edge_key(a, b));
    if (it != made_at.end()) out.insert(out.end(), it->second.begin(), it->second.end());
    return out;
  };
  std::unordered_set<int> island;
  std::vector<int> todo;
  for (std::uint64_t key : rim)
    for (int f : facets_at(int(key >> 32), int(key & 0xffffffffu)))
      if (island.insert(f).second) todo.push_back(f);
  while (!todo.empty()) {
    const int f = todo.back();
    todo.pop_back();
    if (f < 0 && size_t(-1 - f) >= round_begin && size_t(-1 - f) < round_end) return false;  // the round
    if (island.size() > kMaxIsland) return false;
    const std::array<int, 3> c = corners(f);
    for (int k = 0; k < 3; ++k) {
      const int a = c[size_t(k)], b = c[size_t((k + 1) % 3)];
      if (rim.count(edge_key(a, b))) continue;
      const std::vector<int> next = facets_at(a, b);
      if (next.size() < 2) return false;  // the input's boundary: not enclosed
      for (int g : next)
        if (island.insert(g).second) todo.push_back(g);
    }
  }
  std::vector<std::array<int, 3>> kept;
  for (size_t i = 0; i < edit.added.size(); ++i)
    if (!island.count(-1 - int(i))) kept.push_back(edit.added[i]);
  edit.added = std::move(kept);
  for (int f : island)
    if (f >= 0) edit.removed.insert(f);
  return true;
}

// Whether the loop lies in one plane (its own, Newell's), by triangulate_polygon's rule: within `flat` or what
// float input coordinates hold (mesh.h on_plane_slack).
bool loop_is_flat(const MeshEdit& edit, const std::vector<int>& loop, double flat) {
  const Vec3 n = newell_normal(edit, loop);
  if (!(n.norm() > 0)) return false;
  const Vec3 p0 = edit.point(loop[0]);
  double size = 0, off = 0, magnitude = 0;
  for (int v : loop) {
    const Vec3 p = edit.point(v);
    size = std::max(size, (p - p0).norm()), off = std::max(off, std::abs((p - p0).dot(n.normalized())));
    magnitude = std::max(magnitude, p.cwiseAbs().maxCoeff());
  }
  return off <= std::max(on_plane_slack(size, magnitude), flat);
}

// A gap that runs over two faces of the solid -- where a CAD mesh's large facets on both sides of one of its
// sharp edges were all cut out (a chain's capped end on one face and its other end's cap, or its band, on the
// next: a box corner's rolled round from the front face round to the bottom) -- is split along the input edges
// those removed facets shared, into pieces that are each one plane; filled whole, it cut through the solid
// (facets from the bottom face to the top front edge, sound in topology, 8 mm off the box). A loop that is one
// plane, or that no such edge splits so, is left as it is. Loops of more than kMaxSplitSides sides are not split.
constexpr size_t kMaxSplitSides = 2000;
void split_at_removed_edges(const MeshEdit& edit, const std::vector<int>& loop, double flat, std::vector<std::vector<int>>& out) {
  const MeshTopology& in = edit.input;
  const size_t n = loop.size();
  if (n < 4 || n > kMaxSplitSides || loop_is_flat(edit, loop, flat)) {
    out.push_back(loop);
    return;
  }
  auto removed_edge = [&](int a, int b) {  // an input edge whose facets are all removed
    if (a >= in.num_vertices() || b >= in.num_vertices()) return false;
    const std::vector<int> sides = in.edge_facets(a, b);
    return !sides.empty() && std::all_of(sides.begin(), sides.end(), [&](int g) { return edit.removed.count(g) > 0; });
  };
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 2; j < n; ++j) {
      if ((j + 1) % n == i || !removed_edge(loop[i], loop[j])) continue;
      const std::vector<int> a(loop.begin() + long(i), loop.begin() + long(j) + 1);
      std::vector<int> b(loop.begin() + long(j), loop.end());
      b.insert(b.end(), loop.begin(), loop.begin() + long(i) + 1);
      if (!loop_is_flat(edit, a, flat) && !loop_is_flat(edit, b, flat)) continue;
      split_at_removed_edges(edit, a, flat, out);
      split_at_removed_edges(edit, b, flat, out);
      return;
    }
  out.push_back(loop);
}

}  // namespace

SewStats sew_round(MeshEdit& edit, size_t round_begin, size_t round_end, const Refinement& fill) {
  SewStats stats;
  // Orientation: the round runs each shared edge against the trimmed facet next to it.
  std::unordered_map<std::uint64_t, int> direction;  // directed edge of a non-round facet
  auto directed = [](int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); };
  for (size_t i = 0; i < edit.added.size(); ++i)
    if (i < round_begin || i >= round_end)
      for (int k = 0; k < 3; ++k) direction[directed(edit.added[i][k], edit.added[i][(k + 1) % 3])] = 1;
  int agree = 0, disagree = 0;
  for (size_t i = round_begin; i < round_end; ++i)
    for (int k = 0; k < 3; ++k) {
      const int a = edit.added[i][k], b = edit.added[i][(k + 1) % 3];
      if (direction.count(directed(a, b))) ++disagree;
      if (direction.count(directed(b, a))) ++agree;
    }
  if (disagree > agree) {
    stats.round_flipped = true;
    for (size_t i = round_begin; i < round_end; ++i) std::swap(edit.added[i][1], edit.added[i][2]);
  }

  // Gaps: loops of edges that are open now but were not open in the input.
  const MeshTopology& in = edit.input;
  int open_chains = 0;
  auto find_gaps = [&] {
    std::vector<std::pair<int, int>> open_edges;  // fill loops run against the open edges' facets: b -> a
    for (const auto& [key, e] : edges_near_edit(edit)) {
      if (e.count != 1) continue;
      const bool input_edge = e.a < in.num_vertices() && e.b < in.num_vertices();
      if (input_edge && in.edge_facets(e.a, e.b).size() == 1) continue;  // the input's own boundary
      open_edges.push_back({e.b, e.a});
    }
    open_chains = 0;
    return gap_loops(open_edges, &open_chains);
  };
  std::vector<std::vector<int>> loops = find_gaps();
  if (remove_islands(edit, loops, round_begin, round_end)) loops = find_gaps();
  {
    std::vector<std::vector<int>> pieces;
    for (const std::vector<int>& loop : loops) split_at_removed_edges(edit, loop, fill.flat_tolerance, pieces);
    loops.swap(pieces);
  }
  for (std::vector<int>& loop : loops) {
    poll_cancel();
    if (loop.size() < 3) {
      ++stats.open_gaps;
      continue;
    }
    const Vec3 normal = newell_normal(edit, loop);
    if (getenv("MESHROUND_DEBUG")) {
      fprintf(stderr, "gap loop of %zu:", loop.size());
      for (int v : loop) fprintf(stderr, " %d(%.3f %.3f %.3f)", v, edit.point(v).x(), edit.point(v).y(), edit.point(v).z());
      fprintf(stderr, "\n");
    }
    const size_t before = edit.added.size();
    loop = split_long_sides(edit, loop, fill);
    triangulate_polygon(edit, loop, normal, edit.added, fill);
    stats.gap_facets += int(edit.added.size() - before);
  }
  stats.open_gaps += open_chains;
  return stats;
}

void write_mesh(const MeshEdit& edit, Points& V, Triangles& F, StepOrigin* origin) {
  apply_delta(edit.input.V, edit.input.F, delta_from_edit(edit), V, F, origin);
}

}  // namespace meshround
