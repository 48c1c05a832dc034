// The rebuilt edge once a strip is folded (sharpen.cpp): points on it much closer than its spacing made
// one, a mitre's corner one point, and the facets a fold left without area dropped; and the old contact
// lines, where a side's sliver folds against the rebuilt side, flipped smooth.
#include "sharpen_line.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_set>
#include <vector>

#include "guard.h"

namespace meshround::sharpen_detail {
namespace {

// Points on the rebuilt edge much closer than its usual spacing (a split point a hair from the end corner
// or from a vertex snapped onto the line) make slivers and a stub of an edge that round_edges reads as a
// turn: a split point closer than kMergeShare of the median spacing to its neighbour along the edge is
// merged into it (the facets between the two go).
constexpr double kMergeShare = 0.25;

// Replaces each vertex of `into` in the new facets and in the strip's facets kept whole (with a crease's
// vertex merged into a mitre's corner); facets left with a repeated corner go.
void renumber(const MeshTopology& mesh, const RoundStrip& strip, const std::unordered_map<int, int>& into, MeshEdit& edit) {
  auto mapped = [&](std::array<int, 3> f) {
    for (int& v : f)
      if (auto it = into.find(v); it != into.end()) v = it->second;
    return f;
  };
  std::vector<std::array<int, 3>> kept;
  for (const auto& f : edit.added) kept.push_back(mapped(f));
  for (int f : strip.facets) {
    const std::array<int, 3> whole{mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    if (edit.removed.count(f) || mapped(whole) == whole) continue;
    edit.removed.insert(f);
    kept.push_back(mapped(whole));
  }
  edit.added.clear();
  for (const auto& f : kept)
    if (f[0] != f[1] && f[1] != f[2] && f[2] != f[0]) edit.added.push_back(f);
}

// A vertex of a mitre's crease that folds within this share of r of the mitre's corner goes onto it (the
// crease's vertex at mid-arc of a CAD mesh lands 0.006 mm from it on a 2 mm round, as t's snap does on a
// straight round).
constexpr double kCornerSnapShare = 0.01;
// A point on the rebuilt edge within this share of r of a mitre's corner goes onto it (a split point 0.02 mm
// from it on a 2 mm rim: the chain round_edges traces there would end in a stub).
constexpr double kCornerJoinShare = 0.05;

// A mitred strip's corners (where two rebuilt edges meet): the points there -- a crease's split, points whose
// foot the corner stopped, a crease's vertex folded a hair from it -- become one, exactly there (into `into`);
// returns them all (none is merged along the line after: that would cut the corner).
std::unordered_set<int> join_at_mitre_corners(const RoundStrip& strip, const std::vector<std::pair<double, int>>& line, int n_in, double r,
                                              MeshEdit& edit, std::unordered_map<int, int>& into) {
  std::unordered_set<int> cornered;
  for (size_t i = strip.closed ? 0 : 1; strip.mitred && i < strip.pieces.size(); ++i) {
    const Vec3 c = strip.pieces[i].frame.corner;
    std::vector<int> here;
    for (const auto& [s, q] : line)
      if ((edit.point(q) - c).norm() <= kCornerJoinShare * r) here.push_back(q);
    for (const auto& [v, crease] : strip.mitre_of)
      if ((edit.point(v) - c).norm() <= kCornerSnapShare * r) here.push_back(v);
    if (here.empty()) continue;
    const int keep = *std::min_element(here.begin(), here.end());  // an input vertex, if any is there
    if (keep < n_in) edit.moved[keep] = c;
    else edit.new_points[size_t(keep - n_in)] = c;
    for (int q : here) {
      cornered.insert(q);
      if (q != keep) into[q] = keep;
    }
  }
  return cornered;
}

}  // namespace

int merge_close_points(const MeshTopology& mesh, const RoundStrip& strip, double r, MeshEdit& edit, const Fold& fold) {
  std::vector<std::pair<double, int>> line;  // (s, vertex) of every vertex on the corner line
  for (const auto& [key, q] : fold.split) (void)key, line.push_back({strip.param(edit.point(q)), q});
  for (const auto& [v, t] : fold.t)
    if (t == 0.5) line.push_back({strip.param(edit.point(v)), v});
  if (line.size() < 3) return 0;
  std::sort(line.begin(), line.end());
  std::vector<double> gaps;
  for (size_t i = 0; i + 1 < line.size(); ++i) gaps.push_back(line[i + 1].first - line[i].first);
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double close = kMergeShare * sorted[sorted.size() / 2];
  const int n_in = mesh.num_vertices();
  std::unordered_map<int, int> into;
  const std::unordered_set<int> cornered = join_at_mitre_corners(strip, line, n_in, r, edit, into);
  for (size_t i = 0; i < gaps.size(); ++i) {
    if (gaps[i] >= close) continue;
    const int a = line[i].second, b = line[i + 1].second;
    if (into.count(a) || into.count(b) || cornered.count(a) || cornered.count(b)) continue;
    if (b >= n_in && i + 2 < line.size()) into[b] = a;       // the later one, unless it ends the edge
    else if (a >= n_in && i > 0) into[a] = b;                // the earlier one, unless it starts the edge
  }
  if (into.empty()) return 0;
  renumber(mesh, strip, into, edit);
  return int(into.size());
}

// Around a mitre's corner a fold can leave a facet of no area (an angle under the output check's
// kDegenerateDeg, guard.h), its three corners on one line: a mesher's sliver lying in the crease (its corners
// on it, or at its end on the walls' corner line, where the two rounds meet nearly tangent), or a CAD mesh's
// facet the round's length whose corners at both creases fold onto the two corners and whose third is a split
// point between them. It goes, and the facet across its longest side is split at its middle corner, which lies
// on that side now. Where two of its corners fold onto one point (a sliver of a CAD mesh's crease whose side
// is 0.002 mm long, folded onto plane A), they become one instead.
constexpr double kNeedleShare = 1e-3;  // a side this share of the longest or less: its two ends are one point
int drop_flat_facets(const MeshTopology& mesh, const RoundStrip& strip, MeshEdit& edit) {
  auto flat = [&](const std::array<int, 3>& t, int* m, int* shortest) {  // *m: the corner opposite the longest side
    const Vec3 p[3] = {edit.point(t[0]), edit.point(t[1]), edit.point(t[2])};
    double longest = 0, least = INFINITY;
    for (int k = 0; k < 3; ++k) {
      const double side = (p[(k + 1) % 3] - p[(k + 2) % 3]).norm();
      if (side > longest) longest = side, *m = k;
      if (side < least) least = side, *shortest = k;
    }
    if (least > kNeedleShare * longest) *shortest = -1;
    return smallest_angle(p[0], p[1], p[2]) * 180 / M_PI < kDegenerateDeg;
  };
  auto split_across = [&](int a, int b, int mid, const std::array<int, 3>& t) {  // t has side (a, b): its two halves
    for (int k = 0; k < 3; ++k)
      if ((t[k] == a && t[(k + 1) % 3] == b) || (t[k] == b && t[(k + 1) % 3] == a)) {
        std::array<int, 3> one = t, two = t;
        one[(k + 1) % 3] = mid, two[k] = mid;
        edit.added.push_back(one), edit.added.push_back(two);
        return;
      }
  };
  int dropped = 0;
  for (bool again = true; again && dropped < int(strip.facets.size());) {
    again = false;
    std::array<int, 3> t{};
    int m = 0, shortest = -1;
    for (size_t i = 0; i < edit.added.size() && !again; ++i)
      if (flat(edit.added[i], &m, &shortest)) t = edit.added[i], again = true;
    for (size_t i = 0; i < strip.facets.size() && !again; ++i) {
      const int f = strip.facets[i];
      const std::array<int, 3> whole{mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
      if (!edit.removed.count(f) && flat(whole, &m, &shortest)) t = whole, again = true;
    }
    if (!again) break;
    ++dropped;
    if (shortest >= 0) {  // two corners on one point: the one off a crease goes into the other
      int gone = t[(shortest + 1) % 3], keep = t[(shortest + 2) % 3];
      if (strip.mitre_of.count(gone) && !strip.mitre_of.count(keep)) std::swap(gone, keep);
      if (gone < mesh.num_vertices() && !edit.moved.count(gone)) std::swap(gone, keep);  // (a border vertex stays)
      if (gone >= mesh.num_vertices() || edit.moved.count(gone)) {
        renumber(mesh, strip, {{gone, keep}}, edit);
        continue;
      }
    }
    for (size_t i = 0; i < edit.added.size(); ++i)
      if (edit.added[i] == t) {
        edit.added.erase(edit.added.begin() + long(i));
        break;
      }
    for (int f : strip.facets)
      if (std::array<int, 3>{mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)} == t) edit.removed.insert(f);
    const int a = t[(m + 1) % 3], b = t[(m + 2) % 3], mid = t[m];
    bool done = false;
    for (size_t i = 0; i < edit.added.size() && !done; ++i) {
      const std::array<int, 3> u = edit.added[i];
      if (std::count(u.begin(), u.end(), a) && std::count(u.begin(), u.end(), b)) {
        edit.added.erase(edit.added.begin() + long(i));
        split_across(a, b, mid, u), done = true;
      }
    }
    for (int g : (a < mesh.num_vertices() && b < mesh.num_vertices()) ? mesh.edge_facets(a, b) : std::vector<int>{})
      if (!done && !edit.removed.count(g)) {
        edit.removed.insert(g);
        split_across(a, b, mid, {mesh.F(g, 0), mesh.F(g, 1), mesh.F(g, 2)}), done = true;
      }
  }
  return dropped;
}

// A kink at an old border edge smaller than this is left (the edge runs along the round: the side's facets
// above and below it share their chords of a wall curved in plan, so a larger turn there is a sliver's); the
// flip must take off a quarter of it at least.
constexpr double kKinkDeg = 5;
constexpr double kKinkKept = 0.75;

int unkink_borders(const MeshTopology& mesh, const RoundStrip& strip, MeshEdit& edit) {
  auto border_side = [&](int v) {
    const auto it = strip.role.find(v);
    return it == strip.role.end() ? -1 : it->second == StripRole::BorderA ? 0 : it->second == StripRole::BorderB ? 1 : -1;
  };
  // The live facets at the border vertices: input facets kept (whole or folded) and new ones (slot -1 - i).
  std::unordered_map<int, std::vector<int>> at;
  for (size_t i = 0; i < edit.added.size(); ++i)
    for (int v : edit.added[i])
      if (border_side(v) >= 0) at[v].push_back(-1 - int(i));
  for (const auto& [v, role] : strip.role)
    if (role == StripRole::BorderA || role == StripRole::BorderB)
      for (const int* f = mesh.facets_begin(v); f != mesh.facets_end(v); ++f)
        if (!edit.removed.count(*f)) at[v].push_back(*f);
  auto corners = [&](int slot) {
    return slot < 0 ? edit.added[size_t(-1 - slot)] : std::array<int, 3>{mesh.F(slot, 0), mesh.F(slot, 1), mesh.F(slot, 2)};
  };
  auto normal = [&](const std::array<int, 3>& t) {
    return Vec3((edit.point(t[1]) - edit.point(t[0])).cross(edit.point(t[2]) - edit.point(t[0])));
  };
  auto turn = [](const Vec3& m, const Vec3& n) { return std::atan2(m.cross(n).norm(), m.dot(n)) * 180 / M_PI; };
  auto least = [&](const std::array<int, 3>& t) { return smallest_angle(edit.point(t[0]), edit.point(t[1]), edit.point(t[2])); };
  std::unordered_set<std::uint64_t> edges;  // every live edge at the border (a flip may not make one twice)
  for (const auto& [v, slots] : at)
    for (int slot : slots) {
      const auto t = corners(slot);
      for (int k = 0; k < 3; ++k) edges.insert(edge_key(t[size_t(k)], t[size_t(k + 1) % 3]));
    }
  auto input_edge = [&](int c, int d) {  // an input facet kept on (c, d), away from the border too
    if (c >= mesh.num_vertices() || d >= mesh.num_vertices()) return false;
    const std::vector<int> on = mesh.edge_facets(c, d);
    return std::any_of(on.begin(), on.end(), [&](int g) { return !edit.removed.count(g); });
  };
  std::unordered_set<int> gone;  // slots flipped away
  int flipped = 0;
  for (const int f : strip.facets)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (border_side(a) < 0 || border_side(a) != border_side(b) || !at.count(a)) continue;
      std::vector<int> pair;  // the two live facets on (a, b)
      for (int slot : at[a]) {
        const auto t = corners(slot);
        if (!gone.count(slot) && std::count(t.begin(), t.end(), b)) pair.push_back(slot);
      }
      if (pair.size() != 2) continue;
      std::array<int, 3> one = corners(pair[0]), two = corners(pair[1]);
      // one runs a -> b: its third corner c; two runs b -> a: its third d.
      auto rotate_to = [](std::array<int, 3>& t, int first) {
        while (t[0] != first) std::rotate(t.begin(), t.begin() + 1, t.end());
      };
      rotate_to(one, a), rotate_to(two, a);
      if (one[1] != b) std::swap(one, two), std::swap(pair[0], pair[1]), rotate_to(one, a), rotate_to(two, a);
      if (one[1] != b || two[2] != b) continue;  // not one orientation
      const int c = one[2], d = two[1];
      const double before = turn(normal(one), normal(two));
      if (before < kKinkDeg || edges.count(edge_key(c, d)) || input_edge(c, d)) continue;
      const std::array<int, 3> three{a, d, c}, four{d, b, c};
      const Vec3 n3 = normal(three), n4 = normal(four), n_old = normal(one).normalized() + normal(two).normalized();
      if (!(n3.dot(n_old) > 0 && n4.dot(n_old) > 0) || turn(n3, n4) > kKinkKept * before ||
          std::min(least(three), least(four)) < std::min(least(one), least(two)))
        continue;
      for (int slot : pair) {
        gone.insert(slot);
        if (slot >= 0) edit.removed.insert(slot);
      }
      edit.added.push_back(three), edit.added.push_back(four);
      for (int v : three) at[v].push_back(-int(edit.added.size()) + 1);
      for (int v : four) at[v].push_back(-int(edit.added.size()));
      edges.erase(edge_key(a, b)), edges.insert(edge_key(c, d));
      ++flipped;
    }
  // The added facets flipped away go (their slots are indices into edit.added: erased from the back).
  std::vector<int> dead;
  for (int slot : gone)
    if (slot < 0) dead.push_back(-1 - slot);
  std::sort(dead.rbegin(), dead.rend());
  for (int i : dead) edit.added.erase(edit.added.begin() + i);
  return flipped;
}

}  // namespace meshround::sharpen_detail
