#include "guard.h"

#include "ends.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <array>
#include <iterator>
#include <string>
#include <cmath>
#include <functional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "planar.h"

namespace meshround {
namespace {

using Facet = std::array<int, 3>;

[[noreturn]] void refuse(const std::string& what, const Vec3& where) {
  throw RoundingError(ErrorCode::ResultInvalid,
                      "the rounding's result failed its check (" + what + " at " + format_point(where) +
                          "); nothing was changed. Try another radius, tolerance or reach");
}

// Edge flaws among the edges with an end in `changed`, over `facets` (ids of one MeshEdit): each kind's
// edges (keys, sorted).
struct EdgeFlaws {
  std::vector<std::uint64_t> boundary, non_manifold, misoriented;
};

EdgeFlaws edge_flaws(const std::vector<Facet>& facets, const std::unordered_set<int>& changed) {
  std::unordered_map<std::uint64_t, std::pair<int, int>> edges;  // key -> (facets, sum of directions)
  for (const Facet& f : facets)
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      if (!changed.count(a) && !changed.count(b)) continue;
      auto& e = edges[edge_key(a, b)];
      e.first += 1, e.second += a < b ? 1 : -1;
    }
  EdgeFlaws out;
  for (const auto& [key, e] : edges) {
    if (e.first == 1) out.boundary.push_back(key);
    if (e.first > 2) out.non_manifold.push_back(key);
    if (e.first == 2 && e.second != 0) out.misoriented.push_back(key);
  }
  for (auto* keys : {&out.boundary, &out.non_manifold, &out.misoriented}) std::sort(keys->begin(), keys->end());
  return out;
}

Vec3 edge_middle(const MeshEdit& edit, std::uint64_t key) {
  return 0.5 * (edit.point(int(key >> 32)) + edit.point(int(key & 0xffffffffu)));
}

// More edges of one flaw after the rounding than before refuse it: as the input's fault
// (non_manifold_input, `input_fault` + the place + `advice`) where the input has that flaw within `reach` of a new
// one -- the band ran over a hole or a flipped facet the chain's own checks did not see (beyond a
// round's end, at a corner) -- else as the result's (result_invalid, `what`).
void report_new_flaw(const MeshEdit& edit, const std::vector<std::uint64_t>& was, const Vec3& at, double reach,
                     const std::string& what, const std::string& input_fault, const std::string& advice) {
  for (std::uint64_t old : was) {
    const Vec3 p = edge_middle(edit, old);
    if ((p - at).norm() <= reach)
      throw InputFlaw(input_fault + format_point(p) + "; " + advice, p);
  }
  refuse(what, at);
}

void check_new_flaws(const MeshEdit& edit, const std::vector<std::uint64_t>& was, const std::vector<std::uint64_t>& is, double reach,
                     const std::string& what, const std::string& input_fault, const std::string& advice = "repair the mesh there first") {
  if (is.size() <= was.size()) return;
  std::vector<std::uint64_t> fresh;
  std::set_difference(is.begin(), is.end(), was.begin(), was.end(), std::back_inserter(fresh));
  report_new_flaw(edit, was, edge_middle(edit, fresh.empty() ? is.front() : fresh.front()), reach, what, input_fault, advice);
}

// The boundary edges a rounding may make: pieces of an input boundary edge (split where a trim line or a
// refinement point falls on it), and the end profile of a round the mesh boundary stops
// (ChainEnd::Boundary): there the profile, in the plane of the mesh's edge at the chain's end (ends.h
// open_end_cut), becomes the mesh's edge.
// `slack`: how far off the input edge or the end plane (beyond the tolerance) a point may lie.
class BoundaryRule {
 public:
  BoundaryRule(const MeshEdit& edit, const std::vector<std::uint64_t>& was, const SharpChain& chain, double reach,
               double tolerance, double slack)
      : edit_(edit), was_(was), reach_(reach), tolerance_(tolerance), slack_(slack) {
    for (bool at_start : {true, false}) {
      const EndCut cut = open_end_cut(edit.input, chain, at_start);
      if (cut.active) ends_.push_back({cut.point, cut.normal});
    }
  }

  bool allows(std::uint64_t key) const {
    const Vec3 a = edit_.point(int(key >> 32)), b = edit_.point(int(key & 0xffffffffu));
    if (at_open_end(a, b)) return true;
    for (std::uint64_t old : was_) {
      const Vec3 p = input_point(int(old >> 32)), q = input_point(int(old & 0xffffffffu));
      if (on_segment(a, p, q) && on_segment(b, p, q)) return true;
    }
    return false;
  }

  // A vertex of the input's boundary stays on it (a snap onto a trim line may slide it along the boundary).
  bool keeps(int v, const Vec3& moved_to) const {
    bool on_boundary = false;
    for (std::uint64_t old : was_) {
      const int a = int(old >> 32), b = int(old & 0xffffffffu);
      if (a != v && b != v) continue;
      on_boundary = true;
      if (on_segment(moved_to, input_point(a), input_point(b))) return true;
    }
    return !on_boundary;
  }

 private:
  struct End {
    Vec3 point, normal;
    bool holds(const Vec3& x, double reach, double off) const {
      return (x - point).norm() <= reach && std::abs((x - point).dot(normal)) <= off;
    }
  };
  Vec3 input_point(int v) const { return edit_.input.point(v); }
  bool at_open_end(const Vec3& a, const Vec3& b) const {
    for (const End& e : ends_)
      if (e.holds(a, reach_, tolerance_ + slack_) && e.holds(b, reach_, tolerance_ + slack_)) return true;
    return false;
  }
  bool on_segment(const Vec3& x, const Vec3& p, const Vec3& q) const {
    const Vec3 d = q - p;
    const double t = std::clamp((x - p).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
    return (p + t * d - x).norm() <= slack_;
  }

  const MeshEdit& edit_;
  const std::vector<std::uint64_t>& was_;
  double reach_, tolerance_, slack_;
  std::vector<End> ends_;
};

// New boundary edges (their middles `at`) with a hole or a flipped facet of the input within `reach` of one of
// them: the gap next to that flaw was left open (its walk stops at the missing facet, or turns at the facet
// that faces the other way), so the refusal names the input's flaw (non_manifold_input), not the result.
void blame_input_flaw(const MeshEdit& edit, const EdgeFlaws& was, const std::vector<Vec3>& at, double reach) {
  const std::pair<const std::vector<std::uint64_t>*, std::string> flaws[] = {
      {&was.boundary, "the mesh is open (a hole in it, or its edge) where the rounding goes, at %; fill the hole first"},
      {&was.misoriented, "the facets are oriented against each other (a flipped facet) where the rounding goes, at %; repair the mesh there first"}};
  for (const auto& [keys, says] : flaws)
    for (std::uint64_t old : *keys) {
      const Vec3 a = edit.input.point(int(old >> 32)), b = edit.input.point(int(old & 0xffffffffu));
      for (const Vec3& x : at) {
        double t;
        const Vec3 p = closest_point_on_segment(x, a, b, &t);  // (a large facet's side: its nearest point)
        if ((p - x).norm() <= reach) {
          const size_t at_mark = says.find('%');
          throw InputFlaw(says.substr(0, at_mark) + format_point(p) + says.substr(at_mark + 1), p);
        }
      }
    }
}

// No boundary edge but those the rule allows (above), no boundary vertex moved off the boundary: a hole or
// the mesh's edge the band ran into is the input's fault (a hole in a round whose radius is changed). A hole
// wholly inside what the round replaces goes with it, as in the CAD fillet.
void check_new_boundary(const MeshEdit& edit, const EdgeFlaws& was, const std::vector<std::uint64_t>& is, const BoundaryRule& rule,
                        double reach) {
  const std::string open = "the mesh is open (a hole in it, or its edge) where the rounding goes, at ";
  for (const auto& [v, to] : edit.moved)
    if (!rule.keeps(v, to))
      report_new_flaw(edit, was.boundary, to, reach, "a vertex of the mesh boundary moved off it", open, "fill the hole first");
  std::vector<std::uint64_t> fresh;
  std::set_difference(is.begin(), is.end(), was.boundary.begin(), was.boundary.end(), std::back_inserter(fresh));
  std::vector<Vec3> refused;
  for (std::uint64_t key : fresh)
    if (!rule.allows(key)) refused.push_back(edge_middle(edit, key));
  if (refused.empty()) return;
  blame_input_flaw(edit, was, refused, reach);
  refuse("a new boundary edge, a hole in the mesh", refused.front());
}

// A vertex of the input's boundary that the result keeps stays on its boundary: a hole whose edge the band
// takes only in part is not covered over (a hole 3 mm up a pocket's wall beside its floor loop, one corner of
// it above the contact line, came back closed). A hole the band takes whole goes with it (check_new_boundary).
void check_boundary_kept(const MeshEdit& edit, const std::vector<std::uint64_t>& was, const std::vector<std::uint64_t>& is,
                         const std::vector<Facet>& after, double reach) {
  std::unordered_set<int> on_boundary, used;
  for (std::uint64_t key : is) on_boundary.insert(int(key >> 32)), on_boundary.insert(int(key & 0xffffffffu));
  for (const Facet& f : after) used.insert(f.begin(), f.end());
  for (std::uint64_t key : was)
    for (int v : {int(key >> 32), int(key & 0xffffffffu)})
      if (used.count(v) && !on_boundary.count(v))
        report_new_flaw(edit, was, edit.point(v), reach, "a hole in the mesh covered over, part of its edge kept",
                        "the mesh is open (a hole in it, or its edge) where the rounding goes, at ", "fill the hole first");
}

// Where the mesh's edge leaves the band and comes back: each pair of unchanged vertices joined by the input's
// boundary outside the band (walked once; the same before and after the rounding). False where that
// boundary is itself pinched (not judged).
using Arc = std::pair<int, int>;
bool arcs_outside(const MeshTopology& in, const std::vector<std::uint64_t>& local, const std::unordered_set<int>& changed,
                  std::vector<Arc>& arcs) {
  std::unordered_map<int, int> degree, neighbour;  // neighbour: a piece's last vertex in the band
  for (std::uint64_t key : local) {
    const int a = int(key >> 32), b = int(key & 0xffffffffu);
    ++degree[a], ++degree[b], neighbour[a] = b, neighbour[b] = a;
  }
  std::unordered_set<int> walked;
  for (const auto& [v, d] : degree) {
    if (d != 1 || changed.count(v) || !walked.insert(v).second) continue;
    int prev = neighbour[v], cur = v;
    for (int steps = 0; steps <= in.num_vertices(); ++steps) {
      int next = -1, count = 0;
      for (int w : in.vertex_neighbours(cur))
        if (w != prev && in.edge_facets(cur, w).size() == 1) next = w, ++count;
      if (count != 1) return false;
      if (changed.count(next)) {  // back at the band: cur ends a piece
        arcs.push_back({v, cur}), walked.insert(cur);
        break;
      }
      prev = cur, cur = next;
    }
  }
  return true;
}

// The loops of the mesh's edge through the band: the boundary edges `local` (an end among the changed
// vertices) closed up by `arcs`; *pinched: a vertex with more than two boundary edges.
int boundary_loops(const std::vector<std::uint64_t>& local, const std::vector<Arc>& arcs, bool* pinched) {
  std::unordered_map<int, int> parent, degree;
  std::function<int(int)> root = [&](int v) {
    auto it = parent.find(v);
    if (it == parent.end()) return parent[v] = v;
    return it->second == v ? v : it->second = root(it->second);
  };
  auto unite = [&](int a, int b) { parent[root(a)] = root(b); };
  for (std::uint64_t key : local) {
    const int a = int(key >> 32), b = int(key & 0xffffffffu);
    unite(a, b), ++degree[a], ++degree[b];
  }
  *pinched = false;
  for (const auto& [v, d] : degree) *pinched |= d > 2;
  for (const auto& [a, b] : arcs) unite(a, b);
  std::unordered_set<int> roots;
  for (const auto& [v, d] : degree) roots.insert(root(v));
  return int(roots.size());
}

// The mesh's edge neither split nor pinched: a band along it may leave a sliver of a hole between its end
// profile and the input's edge, each of its edges allowed by the rule above (found by fuzzing: an open
// tube's ragged edge, a tolerance larger than the element).
void check_boundary_loops(const MeshEdit& edit, const std::vector<std::uint64_t>& was, const std::vector<std::uint64_t>& is,
                          const std::unordered_set<int>& changed) {
  std::vector<Arc> arcs;
  if (is.empty() || !arcs_outside(edit.input, was, changed, arcs)) return;
  bool pinched_before = false, pinched_after = false;
  const int before = boundary_loops(was, arcs, &pinched_before), after = boundary_loops(is, arcs, &pinched_after);
  std::vector<std::uint64_t> fresh;  // (named at a boundary edge the rounding made, if any)
  std::set_difference(is.begin(), is.end(), was.begin(), was.end(), std::back_inserter(fresh));
  const Vec3 at = edge_middle(edit, fresh.empty() ? is.front() : fresh.front());
  if (after > before) refuse("the mesh's edge split into more loops (" + std::to_string(before) + " -> " + std::to_string(after) + "): a new hole", at);
  if (pinched_after && !pinched_before) refuse("the mesh's edge pinched at a vertex", at);
}

// ---------------------------------------------------------------------------------- facet crossings
struct Triangle {
  Vec3 p[3];
  Vec3 normal;  // not normalised: twice the area
};

// Segment p-q passes through the inside of t (not merely touching it), t and the segment not coplanar.
bool segment_pierces(const Vec3& p, const Vec3& q, const Triangle& t, double slack) {
  const double scale = t.normal.norm();
  const double dp = t.normal.dot(p - t.p[0]) / scale, dq = t.normal.dot(q - t.p[0]) / scale;
  if (!((dp > slack && dq < -slack) || (dp < -slack && dq > slack))) return false;
  const Vec3 x = p + dp / (dp - dq) * (q - p);
  for (int k = 0; k < 3; ++k) {
    const Vec3& a = t.p[k];
    const Vec3& b = t.p[(k + 1) % 3];
    if ((b - a).cross(x - a).dot(t.normal) / scale <= slack * (b - a).norm()) return false;
  }
  return true;
}

// Two coplanar triangles overlapping in more than a shared boundary.
bool coplanar_overlap(const Triangle& s, const Triangle& t) {
  int drop = 0;
  t.normal.cwiseAbs().maxCoeff(&drop);
  auto flat = [&](const Vec3& v) { return Eigen::Vector2d(v[(drop + 1) % 3], v[(drop + 2) % 3]); };
  Eigen::Vector2d S[3], T[3];
  for (int k = 0; k < 3; ++k) S[k] = flat(s.p[k]), T[k] = flat(t.p[k]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (planar::segments_cross(S[i], S[(i + 1) % 3], T[j], T[(j + 1) % 3])) return true;
  auto strictly_inside = [](const Eigen::Vector2d& x, const Eigen::Vector2d* P) {
    const double a = planar::cross2(P[0], P[1], x), b = planar::cross2(P[1], P[2], x), c = planar::cross2(P[2], P[0], x);
    return (a > 0 && b > 0 && c > 0) || (a < 0 && b < 0 && c < 0);
  };
  const Eigen::Vector2d sc = (S[0] + S[1] + S[2]) / 3, tc = (T[0] + T[1] + T[2]) / 3;
  return strictly_inside(sc, T) || strictly_inside(tc, S);
}

// Facets sharing a vertex or an edge are tested too: an edge through a shared vertex lies on the other
// facet's plane there, so it cannot pierce; what crosses is an opposite edge, or a coplanar fold-over.
// Two facets with a vertex in common that lie within a thousandth of the smaller one's size of one plane are
// tested as coplanar: a facet folded back onto its neighbour by a hair (normals opposite, 0.005 mm apart over
// 25 mm) crosses it at too shallow an angle for the piercing test's slack to see. (Of the smaller one: a
// facet a thousandth of its neighbour's size lies within a thousandth of that of any plane through their
// common vertex.)
constexpr double kFoldShare = 1e-3;
constexpr double kFoldDeg = 30;  // and their normals within this of parallel or opposite

bool triangles_cross(const Triangle& s, const Triangle& t, double slack) {
  bool shared = false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) shared |= s.p[i] == t.p[j];
  double size[2] = {0, 0};
  for (int k = 0; k < 3; ++k)
    size[0] = std::max(size[0], (s.p[(k + 1) % 3] - s.p[k]).norm()), size[1] = std::max(size[1], (t.p[(k + 1) % 3] - t.p[k]).norm());
  const double flat = shared ? std::max(slack, kFoldShare * std::min(size[0], size[1])) : slack;
  // Either on the other's plane (a small facet folded onto a large one lies on the large one's plane, while
  // the large one's far corner may be well off the small one's), and the two facing the same or the
  // opposite way: a sliver standing on its neighbour's edge at a sharp angle lies within `flat` of any plane
  // through that edge, and is no fold.
  auto on_plane_of = [flat](const Triangle& a, const Triangle& b) {
    const double bn = b.normal.norm();
    for (const Vec3& v : a.p)
      if (std::abs(b.normal.dot(v - b.p[0])) / bn > flat) return false;
    return true;
  };
  const bool facing = std::abs(s.normal.normalized().dot(t.normal.normalized())) >= std::cos(kFoldDeg * M_PI / 180);
  if (facing && on_plane_of(s, t)) return coplanar_overlap(s, t);
  if (facing && on_plane_of(t, s)) return coplanar_overlap(t, s);
  for (int k = 0; k < 3; ++k)
    if (segment_pierces(s.p[k], s.p[(k + 1) % 3], t, slack) || segment_pierces(t.p[k], t.p[(k + 1) % 3], s, slack))
      return true;
  return false;
}

// Uniform grid over the made facets' boxes; a facet spanning many cells is kept apart, and a query box over
// many cells visits every facet instead of walking the cells.
class FacetGrid {
 public:
  FacetGrid(double cell, const std::vector<std::pair<Vec3, Vec3>>& boxes) : cell_(cell), boxes_(boxes) {
    for (size_t id = 0; id < boxes.size(); ++id) {
      const auto a = cell_of(boxes[id].first), b = cell_of(boxes[id].second);
      if (cells_in(a, b) > kMaxCells) {
        oversized_.push_back(int(id));
        continue;
      }
      for (long i = a[0]; i <= b[0]; ++i)
        for (long j = a[1]; j <= b[1]; ++j)
          for (long k = a[2]; k <= b[2]; ++k) cells_[key(i, j, k)].push_back(int(id));
    }
  }
  // Each facet whose box meets lo..hi, once or more.
  template <class Visit>
  void query(const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    auto meets = [&](int id) {
      return !(boxes_[size_t(id)].first.array() > hi.array()).any() && !(boxes_[size_t(id)].second.array() < lo.array()).any();
    };
    const auto a = cell_of(lo), b = cell_of(hi);
    if (cells_in(a, b) > kMaxCells) {
      for (size_t id = 0; id < boxes_.size(); ++id)
        if (meets(int(id))) visit(int(id));
      return;
    }
    for (long i = a[0]; i <= b[0]; ++i)
      for (long j = a[1]; j <= b[1]; ++j)
        for (long k = a[2]; k <= b[2]; ++k) {
          auto it = cells_.find(key(i, j, k));
          if (it != cells_.end())
            for (int id : it->second)
              if (meets(id)) visit(id);
        }
    for (int id : oversized_)
      if (meets(id)) visit(id);
  }

 private:
  static constexpr double kMaxCells = 512;  // a box over more cells is not walked cell by cell
  static double cells_in(const std::array<long, 3>& a, const std::array<long, 3>& b) {
    return double(b[0] - a[0] + 1) * double(b[1] - a[1] + 1) * double(b[2] - a[2] + 1);
  }
  std::array<long, 3> cell_of(const Vec3& p) const {
    const auto at = [&](double x) { return long(std::clamp(std::floor(x / cell_), -1e15, 1e15)); };
    return {at(p.x()), at(p.y()), at(p.z())};
  }
  static std::uint64_t key(long i, long j, long k) {
    return (std::uint64_t(i & 0x1fffff) << 42) | (std::uint64_t(j & 0x1fffff) << 21) | std::uint64_t(k & 0x1fffff);
  }
  double cell_;
  const std::vector<std::pair<Vec3, Vec3>>& boxes_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
  std::vector<int> oversized_;
};

Triangle triangle_of(const MeshEdit& edit, const Facet& f) {
  Triangle t;
  for (int k = 0; k < 3; ++k) t.p[k] = edit.point(f[k]);
  t.normal = (t.p[1] - t.p[0]).cross(t.p[2] - t.p[0]);
  return t;
}

std::pair<Vec3, Vec3> box_of(const Triangle& t) {
  return {t.p[0].cwiseMin(t.p[1]).cwiseMin(t.p[2]), t.p[0].cwiseMax(t.p[1]).cwiseMax(t.p[2])};
}

// A made facet crossing another made facet, or a kept one: the place of the first found. The kept facets
// tested are every input facet left in place whose box meets a made facet's (the band's neighbours, and
// any farther facet a round reaches into: a wall across a thin part, a face the band folds over).
bool find_crossing(const MeshEdit& edit, const std::unordered_set<int>& around, double slack, Vec3* where) {
  const std::vector<Facet>& made = edit.added;
  if (made.empty()) return false;
  std::vector<Triangle> tri(made.size());
  std::vector<std::pair<Vec3, Vec3>> box(made.size());
  double edge_sum = 0;
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (size_t i = 0; i < made.size(); ++i) {
    tri[i] = triangle_of(edit, made[i]);
    box[i] = box_of(tri[i]);
    box[i].first.array() -= slack, box[i].second.array() += slack;
    edge_sum += (box[i].second - box[i].first).norm();
    lo = lo.cwiseMin(box[i].first), hi = hi.cwiseMax(box[i].second);
  }
  const FacetGrid grid(std::max(2 * edge_sum / double(made.size()), 1e-9), box);
  auto found = [&](const Triangle& t, const Triangle& u, const char* kind) {
    if (t.normal.squaredNorm() == 0 || u.normal.squaredNorm() == 0 || !triangles_cross(t, u, slack))
      return false;  // (no area: counted as degenerate)
    if (std::getenv("MESHROUND_DEBUG")) {  // the two facets, for whoever traces the cause
      std::fprintf(stderr, "guard: a made facet crosses %s facet:\n", kind);
      for (const Triangle* x : {&t, &u}) std::fprintf(stderr, "  (%.6f %.6f %.6f) (%.6f %.6f %.6f) (%.6f %.6f %.6f)\n", x->p[0].x(), x->p[0].y(), x->p[0].z(), x->p[1].x(), x->p[1].y(), x->p[1].z(), x->p[2].x(), x->p[2].y(), x->p[2].z());
    }
    *where = (t.p[0] + t.p[1] + t.p[2]) / 3;
    return true;
  };
  for (size_t i = 0; i < made.size(); ++i) {
    bool hit = false;
    grid.query(box[i].first, box[i].second, [&](int j) {
      if (!hit && size_t(j) > i) hit = found(tri[i], tri[size_t(j)], "a made");
    });
    if (hit) return true;
  }
  auto crosses_kept = [&](const Triangle& t) {
    const auto [flo, fhi] = box_of(t);
    if ((flo.array() > hi.array()).any() || (fhi.array() < lo.array()).any()) return false;
    bool hit = false;
    grid.query(flo, fhi, [&](int j) {
      if (!hit) hit = found(tri[size_t(j)], t, "a kept");
    });
    return hit;
  };
  // The kept facets around the changed vertices (their moved vertices where they went), then every other
  // input facet, whose vertices are the input's.
  const MeshTopology& in = edit.input;
  for (int f : around)
    if (!edit.removed.count(f) && crosses_kept(triangle_of(edit, {in.F(f, 0), in.F(f, 1), in.F(f, 2)}))) return true;
  for (int f = 0; f < in.num_facets(); ++f) {
    Triangle t;
    for (int k = 0; k < 3; ++k) t.p[k] = in.corner(f, k);
    const auto [flo, fhi] = box_of(t);
    if ((flo.array() > hi.array()).any() || (fhi.array() < lo.array()).any() || around.count(f)) continue;
    t.normal = (t.p[1] - t.p[0]).cross(t.p[2] - t.p[0]);
    if (crosses_kept(t)) return true;
  }
  return false;
}

}  // namespace

void check_result(const MeshEdit& edit, const SharpChain& chain, double reach, double tolerance,
                  const std::vector<SharpChain>* network) {
  const MeshTopology& in = edit.input;
  const int n_in = in.num_vertices();
  // A point that is not a number passes every comparison below: refused first.
  bool finite = true;
  for (const Vec3& p : edit.new_points) finite &= p.allFinite();
  for (const auto& moved : edit.moved) finite &= moved.second.allFinite();
  if (!finite) refuse("a new vertex that is not a number", chain.point_at(0.5 * chain.length));
  // The changed vertices: those of removed, made and moved facets. Every edge with an end among them
  // has all its facets among the input facets around them (before) or those plus the made ones (after).
  std::unordered_set<int> changed;
  for (int f : edit.removed)
    for (int k = 0; k < 3; ++k) changed.insert(in.F(f, k));
  for (const Facet& f : edit.added) changed.insert(f.begin(), f.end());
  for (const auto& moved : edit.moved) changed.insert(moved.first);
  std::unordered_set<int> around;
  for (int v : changed)
    if (v < n_in)
      for (const int* f = in.facets_begin(v); f != in.facets_end(v); ++f) around.insert(*f);
  std::vector<Facet> before, kept;
  for (int f : around) {
    const Facet facet{in.F(f, 0), in.F(f, 1), in.F(f, 2)};
    before.push_back(facet);
    if (!edit.removed.count(f)) kept.push_back(facet);
  }
  std::vector<Facet> after(kept);
  after.insert(after.end(), edit.added.begin(), edit.added.end());

  // Where the rounding may place points: within the box of the facets it replaced, and within the reach.
  // (A variable round's end profile is tilted off its end face by up to the tolerance.)
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Facet& f : before)
    for (int v : f) lo = lo.cwiseMin(in.point(v)), hi = hi.cwiseMax(in.point(v));
  const double span = before.empty() ? 0.0 : (hi - lo).norm();
  const double magnitude = before.empty() ? 0.0 : std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  const double slack = on_plane_slack(span, magnitude);

  const EdgeFlaws was = edge_flaws(before, changed), is = edge_flaws(after, changed);
  check_new_boundary(edit, was, is.boundary, BoundaryRule(edit, was.boundary, chain, reach, tolerance, slack), reach);
  check_boundary_kept(edit, was.boundary, is.boundary, after, reach);
  check_boundary_loops(edit, was.boundary, is.boundary, changed);
  check_new_flaws(edit, was.non_manifold, is.non_manifold, reach, "a new non-manifold edge, shared by more than two facets",
                  "the mesh is non-manifold (an edge shared by more than two facets) where the rounding goes, at ");
  check_new_flaws(edit, was.misoriented, is.misoriented, reach, "new facets facing the other way from their neighbours",
                  "the facets are oriented against each other (a flipped facet) where the rounding goes, at ");

  const double margin = tolerance + 1e-6 * span + slack;
  auto in_box = [&](const Vec3& p) {
    return !(p.array() < lo.array() - margin).any() && !(p.array() > hi.array() + margin).any();
  };
  for (const Vec3& p : edit.new_points)
    if (!in_box(p)) refuse("a new vertex beyond the faces it rounds", p);
  for (const auto& moved : edit.moved)
    if (!in_box(moved.second)) refuse("a moved vertex beyond the faces it rounds", moved.second);
  // Every made facet reaches back into the band (as the trim's points are admitted), or into an input facet
  // the band cut: the gap such a facet leaves is filled from its corners, which lie up to its size beyond
  // the reach (a 2 mm end face facet at a 0.02 mm round's end).
  auto from_chains = [&](const Vec3& p) {
    double d, nearest;
    chain.project(p, &nearest);
    if (network)
      for (const SharpChain& other : *network) {
        other.project(p, &d);
        nearest = std::min(nearest, d);
      }
    return nearest;
  };
  std::unordered_map<int, bool> near_chain;  // per input vertex of a removed facet (each is in several)
  auto in_reach = [&](int v) {
    auto it = near_chain.find(v);
    if (it == near_chain.end()) it = near_chain.emplace(v, from_chains(in.point(v)) <= reach + margin).first;
    return it->second;
  };
  double cut_size = 0;
  for (int f : edit.removed) {
    if (!in_reach(in.F(f, 0)) && !in_reach(in.F(f, 1)) && !in_reach(in.F(f, 2))) continue;
    for (int k = 0; k < 3; ++k) cut_size = std::max(cut_size, (in.corner(f, (k + 1) % 3) - in.corner(f, k)).norm());
  }
  auto within_reach = [&](int v) { return from_chains(edit.point(v)) <= reach + cut_size + margin; };
  for (const Facet& f : edit.added)
    if (!within_reach(f[0]) && !within_reach(f[1]) && !within_reach(f[2]))
      refuse("a new facet wholly beyond the reach", (edit.point(f[0]) + edit.point(f[1]) + edit.point(f[2])) / 3);

  auto check_shape = [&](const Facet& f) {
    const Vec3 a = edit.point(f[0]), b = edit.point(f[1]), c = edit.point(f[2]);
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0] || smallest_angle(a, b, c) * 180 / M_PI < kDegenerateDeg) {
      if (std::getenv("MESHROUND_DEBUG"))  // the facet, for whoever traces the cause
        std::fprintf(stderr, "guard: a degenerate facet (%.6f %.6f %.6f) (%.6f %.6f %.6f) (%.6f %.6f %.6f)\n", a.x(), a.y(), a.z(), b.x(), b.y(), b.z(), c.x(), c.y(), c.z());
      refuse("a degenerate facet (no area)", (a + b + c) / 3);
    }
  };
  for (const Facet& f : edit.added) check_shape(f);
  for (const Facet& f : kept)
    if (edit.moved.count(f[0]) || edit.moved.count(f[1]) || edit.moved.count(f[2])) check_shape(f);

  Vec3 where;
  if (find_crossing(edit, around, slack, &where)) refuse("facets that cross each other", where);
}

bool flawed_near(const MeshTopology& mesh, const Vec3& where, double distance) {
  for (int f = 0; f < mesh.num_facets(); ++f) {
    bool near = false;
    for (int k = 0; k < 3; ++k) near |= (mesh.corner(f, k) - where).norm() <= distance;
    if (!near) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      int pair[2];
      const int count = mesh.edge_facet_pair(a, b, pair);
      if (count != 2 || mesh.edge_direction(pair[0], a, b) == mesh.edge_direction(pair[1], a, b)) return true;
    }
  }
  return false;
}

}  // namespace meshround
