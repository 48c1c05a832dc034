#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <queue>
#include <set>
#include <string>
#include <unordered_map>

#include "meshround/cancel.h"
#include "meshround/mesh_edit.h"
#include "planar.h"
#include "ring_index.h"
#include "split_polygon.h"

namespace meshround {
namespace {

using namespace planar;

// The point in space at plane coordinates x: P[0] sits at Q[0], and e1, e2 span the polygon's plane.
Vec3 in_space(const std::vector<Vec3>& P, const std::vector<Eigen::Vector2d>& Q, const Vec3& e1, const Vec3& e2,
              const Eigen::Vector2d& x) {
  return P[0] + (x.x() - Q[0].x()) * e1 + (x.y() - Q[0].y()) * e2;
}

// Edge -> its one or two triangles (a polygon side has one), kept up to date through flips and insertions;
// with a log, each change can be taken back (a refinement point that made things worse).
class EdgeSides {
 public:
  static std::uint64_t key(int a, int b) { return std::uint64_t(std::min(a, b)) << 32 | std::uint32_t(std::max(a, b)); }

  // Every edge of `tris`; the inner ones (two triangles) into `inner`, if given.
  explicit EdgeSides(const std::vector<std::array<int, 3>>& tris, std::vector<std::uint64_t>* inner = nullptr) {
    map_.reserve(3 * tris.size());
    for (int t = 0; t < int(tris.size()); ++t)
      for (int k = 0; k < 3; ++k) {
        auto [it, fresh] = map_.try_emplace(key(tris[t][k], tris[t][(k + 1) % 3]), std::array<int, 2>{t, -1});
        if (!fresh) {
          it->second[1] = t;
          if (inner) inner->push_back(it->first);
        }
      }
  }
  const std::array<int, 2>* find(std::uint64_t e) const {
    const auto it = map_.find(e);
    return it == map_.end() ? nullptr : &it->second;
  }
  void set(std::uint64_t e, std::array<int, 2> sides) { remember(e), map_[e] = sides; }
  void erase(std::uint64_t e) { remember(e), map_.erase(e); }
  // Edge (a, b) now borders `to` where it bordered `from`.
  void replace(int a, int b, int from, int to) {
    std::array<int, 2> pair = map_.at(key(a, b));
    (pair[0] == from ? pair[0] : pair[1]) = to;
    set(key(a, b), pair);
  }
  void start_log() { log_.clear(), logging_ = true; }
  void stop_log() { logging_ = false; }
  void undo() {  // every change since start_log, newest first
    for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
      if (it->had) map_[it->edge] = it->sides;
      else map_.erase(it->edge);
    }
    log_.clear();
  }

 private:
  struct Change {
    std::uint64_t edge;
    bool had;
    std::array<int, 2> sides;
  };
  void remember(std::uint64_t e) {
    if (!logging_) return;
    const auto it = map_.find(e);
    log_.push_back({e, it != map_.end(), it != map_.end() ? it->second : std::array<int, 2>{-1, -1}});
  }
  std::unordered_map<std::uint64_t, std::array<int, 2>> map_;
  std::vector<Change> log_;
  bool logging_ = false;
};

// Lawson flips inside the polygon: an inner diagonal of `todo` is flipped when the other diagonal of its
// (convex) quadrilateral gives a larger smallest angle; the four edges around a flipped one are checked
// again. Boundary edges never move. The triangles flipped are added to `changed`, and their corners before
// each flip to `was`, if given.
void flip_edges(const std::vector<Vec3>& P, const std::vector<Eigen::Vector2d>& Q, std::vector<std::array<int, 3>>& tris,
                EdgeSides& sides, std::vector<std::uint64_t> todo, std::vector<int>* changed,
                std::vector<std::pair<int, std::array<int, 3>>>* was = nullptr) {
  auto key = EdgeSides::key;
  CancelPoll poll(64);
  for (size_t flips = 0; !todo.empty() && flips < 10 * tris.size() + 100;) {
    poll.tick();
    const std::uint64_t e = todo.back();
    todo.pop_back();
    const std::array<int, 2>* pair = sides.find(e);
    if (!pair || (*pair)[1] < 0) continue;
    const int t = (*pair)[0], u = (*pair)[1];
    int k = 0;  // the edge runs a -> b in t
    while (key(tris[t][k], tris[t][(k + 1) % 3]) != e) ++k;
    const int a = tris[t][k], b = tris[t][(k + 1) % 3], c = tris[t][(k + 2) % 3];
    int d = -1;
    for (int m = 0; m < 3; ++m)
      if (tris[u][m] != a && tris[u][m] != b) d = tris[u][m];
    // Both new triangles must keep a positive area, or the flip would leave the polygon.
    if (cross2(Q[c], Q[a], Q[d]) <= 0 || cross2(Q[d], Q[b], Q[c]) <= 0) continue;
    const double now = std::min(smallest_angle(P[a], P[b], P[c]), smallest_angle(P[b], P[a], P[d]));
    const double then = std::min(smallest_angle(P[c], P[a], P[d]), smallest_angle(P[d], P[b], P[c]));
    if (then <= now + 1e-9) continue;
    if (was) was->push_back({t, tris[t]}), was->push_back({u, tris[u]});
    tris[t] = {c, a, d}, tris[u] = {d, b, c};
    sides.erase(e);
    sides.set(key(c, d), {t, u});
    sides.replace(a, d, u, t), sides.replace(b, c, t, u);
    for (std::uint64_t f : {key(a, c), key(a, d), key(b, c), key(b, d)}) todo.push_back(f);
    if (changed) changed->push_back(t), changed->push_back(u);
    ++flips;
  }
}

// Flips over the whole triangulation until no flip gains (flip_edges); with `changed` (triangles just made
// in a flip-stable triangulation), starting at their edges only, the triangles flipped added to it.
void improve_by_flips(const std::vector<Vec3>& P, const std::vector<Eigen::Vector2d>& Q, std::vector<std::array<int, 3>>& tris,
                      std::vector<int>* changed = nullptr) {
  std::vector<std::uint64_t> inner;
  EdgeSides sides(tris, changed ? nullptr : &inner);
  if (changed)
    for (int t : *changed)
      for (int k = 0; k < 3; ++k) inner.push_back(EdgeSides::key(tris[t][k], tris[t][(k + 1) % 3]));
  flip_edges(P, Q, tris, sides, std::move(inner), changed);
}

// Where a point meant to mend triangle `w` may go, best first, each with the spacing it should keep from
// the polygon's sides and vertices: the circumcentre, then apexes on each side of the triangle (longest
// first) of isosceles triangles with base angles from 60 down to 12 degrees. The second kind mends thin
// triangles along a long side of the polygon, whose circumcentres lie outside it.
std::vector<std::pair<Eigen::Vector2d, double>> mending_points(const std::vector<Eigen::Vector2d>& Q,
                                                               const std::array<int, 3>& w) {
  std::vector<std::pair<Eigen::Vector2d, double>> out;
  const Eigen::Vector2d a = Q[w[0]], ba = Q[w[1]] - a, ca = Q[w[2]] - a;
  const double d = 2 * (ba.x() * ca.y() - ba.y() * ca.x());
  if (d > 0) {
    const Eigen::Vector2d centre = a + Eigen::Vector2d(ca.y() * ba.squaredNorm() - ba.y() * ca.squaredNorm(),
                                                       ba.x() * ca.squaredNorm() - ca.x() * ba.squaredNorm()) / d;
    out.emplace_back(centre, (centre - a).norm());
  }
  std::array<int, 3> sides{0, 1, 2};
  auto length = [&](int k) { return (Q[w[(k + 1) % 3]] - Q[w[k]]).norm(); };
  std::sort(sides.begin(), sides.end(), [&](int i, int j) { return length(i) > length(j); });
  for (auto [height, base_angle] : kApexHeights)
    for (int k : sides) {
      const Eigen::Vector2d s0 = Q[w[k]], s1 = Q[w[(k + 1) % 3]];
      // The triangle is counter-clockwise: its inside is left of each side.
      out.emplace_back(0.5 * (s0 + s1) + height * Eigen::Vector2d(-(s1 - s0).y(), (s1 - s0).x()),
                       height * (s1 - s0).norm());
    }
  return out;
}

// The triangle holding x, the first by index (as a scan would find it): found by walking from `start`
// across the sides x lies beyond; a scan when the walk leaves the polygon or x lies on a side. -1: none.
int locate(const std::vector<Eigen::Vector2d>& Q, const std::vector<std::array<int, 3>>& tris, const EdgeSides& sides,
           const Eigen::Vector2d& x, int start) {
  int t = start;
  for (size_t step = 0; step < tris.size() + 8; ++step) {
    int beyond = -1;
    bool on_side = false;
    for (int k = 0; k < 3 && beyond < 0; ++k) {
      const double c = cross2(Q[tris[t][k]], Q[tris[t][(k + 1) % 3]], x);
      if (c < 0) beyond = k;
      on_side |= c == 0;
    }
    if (beyond < 0 && !on_side) return t;
    if (beyond < 0) break;
    const std::array<int, 2>* pair = sides.find(EdgeSides::key(tris[t][beyond], tris[t][(beyond + 1) % 3]));
    if (!pair || (*pair)[1] < 0) break;
    t = (*pair)[0] == t ? (*pair)[1] : (*pair)[0];
  }
  for (int u = 0; u < int(tris.size()); ++u) {
    const auto &p = Q[tris[u][0]], &q = Q[tris[u][1]], &r = Q[tris[u][2]];
    if (cross2(p, q, x) >= 0 && cross2(q, r, x) >= 0 && cross2(r, p, x) >= 0) return u;
  }
  return -1;
}

// Delaunay refinement that never splits the polygon's sides (they are shared with neighbours): for the
// worst triangle, the first of its mending points that lies inside, clear of the sides and vertices,
// where the caller admits points, and after which (with flips) no triangle made is worse than the one
// mended, goes in. A point too near a side is first pushed straight away from it.
// New points follow the polygon's own in P / Q. Each point costs its own neighbourhood, not a pass over
// the polygon: the sides and points are looked up in a RingIndex, the host triangle is found by a walk from
// the triangle mended, the worst triangle is kept in a queue, and a point taken back undoes only its changes.
void add_inner_points(std::vector<Vec3>& P, std::vector<Eigen::Vector2d>& Q, std::vector<std::array<int, 3>>& tris,
                      size_t boundary, const Refinement& refine, const Vec3& e1, const Vec3& e2) {
  const double quality = refine.quality_deg * M_PI / 180;
  auto to_3d = [&](const Eigen::Vector2d& x) { return in_space(P, Q, e1, e2, x); };
  improve_by_flips(P, Q, tris);  // flip-stable from here: each point's flips start at the triangles it makes
  EdgeSides sides(tris);          // kept up to date: a point costs its own flips, not a pass over all
  RingIndex index(Q, boundary);
  std::vector<int> near_sides;
  auto host_of = [&](Eigen::Vector2d& x, double spacing, int start) {  // -1: not a good place
    if (!index.inside(x)) return -1;
    for (int round = 0;; ++round) {  // a few times over, for a corner
      bool pushed = false;
      index.sides_near(x, 0.5 * spacing, near_sides);
      for (size_t n = 0; n < near_sides.size(); ++n) {
        const size_t i = size_t(near_sides[n]);
        const Eigen::Vector2d &p = Q[i], &q = Q[(i + 1) % boundary];
        const double t = std::clamp((x - p).dot(q - p) / std::max((q - p).squaredNorm(), 1e-300), 0.0, 1.0);
        if (t <= 0 || t >= 1 || (x - (p + t * (q - p))).norm() > 0.5 * spacing) continue;  // ends: see below
        if (round == 4) return -1;
        x = p + t * (q - p) + 0.5001 * spacing * Eigen::Vector2d(-(q - p).y(), (q - p).x()).normalized();
        pushed = true;
        index.sides_near(x, 0.5 * spacing, near_sides);  // x moved: the sides after this one, near it now
        near_sides.erase(near_sides.begin(), std::upper_bound(near_sides.begin(), near_sides.end(), int(i)));
        n = size_t(-1);
      }
      if (!pushed) break;
      if (!index.inside(x)) return -1;
    }
    if (index.point_within(x, 0.25 * spacing)) return -1;
    if (refine.admit && !refine.admit(to_3d(x))) return -1;
    return locate(Q, tris, sides, x, start);
  };
  std::vector<char> hopeless(tris.size(), 0);
  // Each triangle's smallest angle, kept up to date (only the triangles a point makes or flips change).
  auto angle_of = [&](int t) { return smallest_angle(P[tris[t][0]], P[tris[t][1]], P[tris[t][2]]); };
  auto size_of = [&](int t) {
    const auto &a = Q[tris[t][0]], &b = Q[tris[t][1]], &c = Q[tris[t][2]];
    return std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  };
  std::vector<double> angle(tris.size());
  for (int t = 0; t < int(tris.size()); ++t) angle[t] = angle_of(t);
  // The bad triangles, largest first (ties: the lowest index); an entry whose triangle has changed since is
  // dropped when it comes up (the change queued the triangle again).
  std::priority_queue<std::pair<double, int>> bad;
  auto queue = [&](int t) {
    if (!hopeless[t] && angle[t] < quality) bad.push({size_of(t), -t});
  };
  for (int t = 0; t < int(tris.size()); ++t) queue(t);
  std::vector<std::pair<int, std::array<int, 3>>> was;
  std::vector<std::pair<int, double>> angle_was;
  for (size_t added = 0; added < 4 * boundary + 16;) {
    poll_cancel();
    // The largest bad triangle first: its mending point lands deep inside and later ones grade towards
    // the short sides (the worst first would pile points up at the trim line).
    int worst = -1;
    while (!bad.empty() && worst < 0) {
      const auto [size, minus_t] = bad.top();
      bad.pop();
      const int t = -minus_t;
      if (!hopeless[t] && angle[t] < quality && size_of(t) == size) worst = t;
    }
    if (worst < 0) return;
    const double worst_q = angle[worst];
    bool mended = false;
    std::vector<int> made;
    for (auto [x, spacing] : mending_points(Q, tris[worst])) {
      const int host = host_of(x, spacing, worst);
      if (host < 0) continue;
      const int k = int(P.size());
      const size_t count = tris.size();
      Q.push_back(x), P.push_back(to_3d(x));
      index.add_point(k);
      const auto h = tris[host];
      const int t1 = int(tris.size()), t2 = t1 + 1;
      was.assign(1, {host, h});
      tris[host] = {h[0], h[1], k};
      tris.push_back({h[1], h[2], k});
      tris.push_back({h[2], h[0], k});
      made = {host, t1, t2};
      sides.start_log();
      sides.replace(h[1], h[2], host, t1), sides.replace(h[2], h[0], host, t2);
      sides.set(EdgeSides::key(h[0], k), {host, t2}), sides.set(EdgeSides::key(h[1], k), {host, t1});
      sides.set(EdgeSides::key(h[2], k), {t1, t2});
      std::vector<std::uint64_t> todo;
      for (int t : made)
        for (int j = 0; j < 3; ++j) todo.push_back(EdgeSides::key(tris[t][j], tris[t][(j + 1) % 3]));
      flip_edges(P, Q, tris, sides, std::move(todo), &made, &was);
      sides.stop_log();
      angle.resize(tris.size());
      angle_was.clear();
      double made_q = INFINITY;
      for (int t : made) {
        if (size_t(t) < count) angle_was.push_back({t, angle[t]});
        made_q = std::min(made_q, angle[t] = angle_of(t));
      }
      if (made_q > worst_q + 1e-9) {
        mended = true;
        break;
      }
      // It made a triangle as bad: take it back.
      for (auto it = was.rbegin(); it != was.rend(); ++it) tris[it->first] = it->second;
      for (auto it = angle_was.rbegin(); it != angle_was.rend(); ++it) angle[it->first] = it->second;
      tris.resize(count), angle.resize(count);
      index.remove_point(k);
      P.pop_back(), Q.pop_back();
      sides.undo();
    }
    if (!mended) {
      hopeless[worst] = 1;
      continue;
    }
    hopeless.resize(tris.size(), 0);  // the triangles made may be mended again, the others not
    for (int t : made) hopeless[t] = 0, queue(t);
    queue(worst);  // (when the point went into another triangle, the one mended may still be bad)
    ++added;
  }
}

// Inner points (never the polygon's own) move where the smallest angle around them is largest: towards
// the centre of their neighbours, or a step in one of eight directions, where the caller admits points;
// a few sweeps over, each followed by flips.
void smooth_inner_points(std::vector<Vec3>& P, std::vector<Eigen::Vector2d>& Q, std::vector<std::array<int, 3>>& tris,
                         size_t boundary, const Refinement& refine, const Vec3& e1, const Vec3& e2) {
  auto to_3d = [&](const Eigen::Vector2d& x) { return in_space(P, Q, e1, e2, x); };
  improve_by_flips(P, Q, tris);  // flip-stable from here: each sweep's flips start around the points moved
  // A point is tried again only when its star changed since it last stayed put (a point or a flip in it):
  // the same star gives the same tries and the same answer.
  std::vector<char> stale(Q.size(), 1);
  const double gain = refine.smoothing_gain_deg * M_PI / 180;
  for (int sweep = 0; sweep < 16; ++sweep) {
    bool moved = false;
    std::vector<std::vector<int>> stars(Q.size());  // the triangles around each point; no flips within a sweep
    for (int t = 0; t < int(tris.size()); ++t)
      for (int c = 0; c < 3; ++c) stars[tris[t][c]].push_back(t);
    std::vector<int> touched;  // the triangles around the points moved, then those flipped
    for (size_t k = boundary; k < Q.size(); ++k) {
      if (!stale[k]) continue;
      stale[k] = 0;
      poll_cancel();
      const std::vector<int>& star = stars[k];
      Eigen::Vector2d centre = Eigen::Vector2d::Zero();
      for (int t : star)
        for (int c = 0; c < 3; ++c)
          if (tris[t][c] == int(k)) centre += Q[tris[t][(c + 1) % 3]] + Q[tris[t][(c + 2) % 3]];
      if (star.empty()) continue;
      centre /= 2.0 * star.size();  // each neighbour is counted twice around an inner point
      auto star_quality = [&]() {
        double q = INFINITY;
        for (int t : star) {
          const auto& w = tris[t];
          if (cross2(Q[w[0]], Q[w[1]], Q[w[2]]) <= 0) return -1.0;
          q = std::min(q, smallest_angle(P[w[0]], P[w[1]], P[w[2]]));
        }
        return q;
      };
      double best = star_quality();
      const Eigen::Vector2d start = Q[k];
      Eigen::Vector2d best_q = start;
      std::vector<Eigen::Vector2d> tries;
      for (double step : {1.0, 0.5, 0.25}) tries.push_back(Q[k] + step * (centre - Q[k]));
      double reach = INFINITY;  // then a compass search, in steps of the star's size
      for (int t : star)
        for (int c = 0; c < 3; ++c)
          if (tris[t][c] != int(k)) reach = std::min(reach, (Q[tris[t][c]] - Q[k]).norm());
      for (double step : {0.2 * reach, 0.05 * reach})
        for (int d = 0; d < 8; ++d) tries.push_back(Q[k] + step * Eigen::Vector2d(std::cos(d * M_PI / 4), std::sin(d * M_PI / 4)));
      for (const Eigen::Vector2d& x : tries) {
        if (refine.admit && !refine.admit(to_3d(x))) continue;
        Q[k] = x, P[k] = to_3d(x);
        const double q = star_quality();
        if (q > best + gain) best = q, best_q = x, moved = true;
      }
      if (best_q != start) {
        touched.insert(touched.end(), star.begin(), star.end());
        for (int t : star)
          for (int v : tris[t]) stale[v] = 1;
      }
      Q[k] = best_q, P[k] = to_3d(best_q);
    }
    if (!moved) return;
    improve_by_flips(P, Q, tris, &touched);
    for (int t : touched)
      for (int v : tris[t]) stale[v] = 1;
  }
}

// Ear clipping that always cuts the best-shaped ear, then flips: the polygon P / Q[0, boundary),
// counter-clockwise.
std::vector<std::array<int, 3>> clip_ears(const std::vector<Vec3>& P, const std::vector<Eigen::Vector2d>& Q, size_t boundary) {
  std::vector<int> idx(boundary);
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = int(i);
  // Each corner's state, kept between cuts: cutting corner b changes only its two neighbours' ears and
  // those ears b itself blocked (a blocker stays a blocker while it is on the ring).
  enum : int { kUnknown = -2, kNoEar = -1 };
  std::vector<int> blocker(boundary, kUnknown);  // kNoEar (reflex or flat), a blocking point, or boundary (an ear)
  std::vector<double> quality(boundary, -1);
  auto judge = [&](int i) {
    const int m = int(idx.size());
    const int a = idx[(i + m - 1) % m], b = idx[i], c = idx[(i + 1) % m];
    const auto &qa = Q[a], &qb = Q[b], &qc = Q[c];
    if (cross2(qa, qb, qc) <= 1e-9 * (qb - qa).norm() * (qc - qb).norm()) return void(blocker[b] = kNoEar);
    for (int w : idx)
      if (w != a && w != b && w != c && blocks_ear(Q[w], qa, qb, qc)) return void(blocker[b] = w);
    blocker[b] = int(boundary), quality[b] = smallest_angle(P[a], P[b], P[c]);
  };
  std::vector<std::array<int, 3>> tris;
  while (idx.size() > 3) {
    poll_cancel();
    int best = -1;
    double best_q = -1;
    const int m = int(idx.size());
    for (int i = 0; i < m; ++i) {
      if (blocker[idx[i]] == kUnknown) judge(i);
      if (blocker[idx[i]] == int(boundary) && quality[idx[i]] > best_q) best_q = quality[idx[i]], best = i;
    }
    if (best < 0) {
      // Numerically degenerate polygon: cut the flattest corner so the loop still closes.
      if (getenv("MESHROUND_DEBUG")) {
        fprintf(stderr, "ear clipping stuck on %d points:\n", m);
        for (int j = 0; j < m; ++j) fprintf(stderr, "  (%g %g %g)\n", P[idx[j]].x(), P[idx[j]].y(), P[idx[j]].z());
      }
      best = 0;
    }
    const int cut = idx[best];
    tris.push_back({idx[(best + m - 1) % m], cut, idx[(best + 1) % m]});
    idx.erase(idx.begin() + best);
    blocker[idx[(best + m - 2) % (m - 1)]] = blocker[idx[best % (m - 1)]] = kUnknown;
    for (int w : idx)
      if (blocker[w] == cut) blocker[w] = kUnknown;
  }
  tris.push_back({idx[0], idx[1], idx[2]});
  improve_by_flips(P, Q, tris);
  return tris;
}

// True if the diagonal i-j of the counter-clockwise ring Q[0, n) runs inside it: within the corner at
// both ends, and clear of every other side and vertex (a vertex within a hair of it blocks it).
bool diagonal_inside(const std::vector<Eigen::Vector2d>& Q, int n, int i, int j) {
  auto in_corner = [&](int a, int b) {
    const auto &prev = Q[(a + n - 1) % n], &next = Q[(a + 1) % n];
    if (cross2(Q[a], next, prev) >= 0) return cross2(Q[a], Q[b], prev) > 0 && cross2(Q[b], Q[a], next) > 0;
    return !(cross2(Q[a], Q[b], next) >= 0 && cross2(Q[b], Q[a], prev) >= 0);
  };
  if (!in_corner(i, j) || !in_corner(j, i)) return false;
  const double length = (Q[j] - Q[i]).norm(), hair = 1e-7 * length;
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1) % n;
    if (k != i && k != j) {
      const double t = (Q[k] - Q[i]).dot(Q[j] - Q[i]) / (length * length);
      if (t > 0 && t < 1 && std::abs(cross2(Q[i], Q[j], Q[k])) <= hair * length) return false;
    }
    if (k == i || k == j || k1 == i || k1 == j) continue;
    if (segments_cross(Q[i], Q[j], Q[k], Q[k1])) return false;
  }
  return true;
}

// The triangulation of the counter-clockwise ring P / Q[0, boundary) with the largest smallest angle,
// without inner points: dynamic programming over its diagonals (O(n^3)), then flips for the rest. Empty
// when the ring is larger than kMaxExactRing or numerically degenerate (the caller then clips ears).
constexpr size_t kMaxExactRing = 150;
std::vector<std::array<int, 3>> best_triangulation(const std::vector<Vec3>& P, const std::vector<Eigen::Vector2d>& Q, size_t boundary) {
  const int n = int(boundary);
  if (boundary > kMaxExactRing || n < 3) return {};
  std::vector<char> usable(n * n, 0);  // a side or an inner diagonal
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      usable[i * n + j] = (j == i + 1 || (i == 0 && j == n - 1)) ? 1 : diagonal_inside(Q, n, i, j);
  std::vector<double> best(n * n, -1);  // best[i * n + j]: the sub-ring i .. j closed by i-j; -1: none
  std::vector<int> apex(n * n, -1);
  for (int i = 0; i + 1 < n; ++i) best[i * n + i + 1] = INFINITY;
  for (int span = 2; span < n; ++span)
    for (int i = 0; i + span < n; ++i) {
      poll_cancel();
      const int j = i + span;
      if (!usable[i * n + j]) continue;
      for (int k = i + 1; k < j; ++k) {
        if (best[i * n + k] < 0 || best[k * n + j] < 0) continue;
        if (cross2(Q[i], Q[k], Q[j]) <= 1e-9 * (Q[k] - Q[i]).norm() * (Q[j] - Q[k]).norm()) continue;
        const double q = std::min({best[i * n + k], best[k * n + j], smallest_angle(P[i], P[k], P[j])});
        if (q > best[i * n + j]) best[i * n + j] = q, apex[i * n + j] = k;
      }
    }
  if (apex[n - 1] < 0) return {};
  std::vector<std::array<int, 3>> tris;
  std::vector<std::pair<int, int>> todo{{0, n - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j - i < 2) continue;
    const int k = apex[i * n + j];
    tris.push_back({i, k, j});
    todo.push_back({i, k}), todo.push_back({k, j});
  }
  improve_by_flips(P, Q, tris);
  return tris;
}

// Triangulates and refines the counter-clockwise ring P / Q[0, boundary); inner points are appended.
std::vector<std::array<int, 3>> mesh_ring(std::vector<Vec3>& P, std::vector<Eigen::Vector2d>& Q, size_t boundary,
                                          const Refinement& refine, bool flat, const Vec3& e1, const Vec3& e2) {
  std::vector<std::array<int, 3>> tris = best_triangulation(P, Q, boundary);
  if (tris.empty()) tris = clip_ears(P, Q, boundary);
  if (refine.quality_deg > 0 && flat) {  // inner points go in the polygon's plane
    add_inner_points(P, Q, tris, boundary, refine, e1, e2);
    smooth_inner_points(P, Q, tris, boundary, refine, e1, e2);
  }
  return tris;
}

// Meshes each ring left after split_for_refinement on its own, after the triangles split off (`tris`).
std::vector<std::array<int, 3>> mesh_ring_in_pieces(std::vector<Vec3>& P, std::vector<Eigen::Vector2d>& Q,
                                                    const std::vector<std::vector<int>>& pieces,
                                                    std::vector<std::array<int, 3>> tris, const Refinement& refine,
                                                    const Vec3& e1, const Vec3& e2) {
  for (const auto& piece : pieces) {
    std::vector<Vec3> piece_p;
    std::vector<Eigen::Vector2d> piece_q;
    for (int v : piece) piece_p.push_back(P[v]), piece_q.push_back(Q[v]);
    std::vector<int> index = piece;  // piece's ids -> P's
    for (const auto& t : mesh_ring(piece_p, piece_q, piece.size(), refine, true, e1, e2)) {
      for (size_t k = index.size(); k < piece_p.size(); ++k) index.push_back(int(P.size())), P.push_back(piece_p[k]), Q.push_back(piece_q[k]);
      tris.push_back({index[t[0]], index[t[1]], index[t[2]]});
    }
  }
  return tris;
}

double smallest_angle_of(const std::vector<Vec3>& P, const std::vector<std::array<int, 3>>& tris) {
  double q = INFINITY;
  for (const auto& t : tris) q = std::min(q, smallest_angle(P[t[0]], P[t[1]], P[t[2]]));
  return q;
}

}  // namespace

void triangulate_polygon(MeshEdit& edit, const std::vector<int>& polygon, const Vec3& normal,
                         std::vector<std::array<int, 3>>& out, const Refinement& refine) {
  std::vector<int> ring = polygon;
  // Drop repeated consecutive ids (a trim point that coincides with a corner).
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) return;
  const Vec3 n = normal.normalized();
  const Vec3 e1 = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized(), e2 = n.cross(e1);
  std::vector<Vec3> P;
  std::vector<Eigen::Vector2d> Q;
  for (int v : ring) {
    P.push_back(edit.point(v));
    Q.emplace_back(P.back().dot(e1), P.back().dot(e2));
  }
  // Work counter-clockwise in the plane; remember to flip back.
  double area = 0;
  for (size_t i = 0; i < Q.size(); ++i) {
    const auto &a = Q[i], &b = Q[(i + 1) % Q.size()];
    area += a.x() * b.y() - a.y() * b.x();
  }
  const bool flipped = area < 0;
  if (flipped) {
    std::reverse(ring.begin(), ring.end()), std::reverse(P.begin(), P.end()), std::reverse(Q.begin(), Q.end());
  }
  const size_t boundary = ring.size();
  // Flat: on a plane up to what float32 input coordinates can hold, wherever the part sits; inner points
  // go in the polygon's plane.
  double size = 0, off = 0, magnitude = 0;
  for (size_t i = 0; i < boundary; ++i) size = std::max(size, (P[i] - P[0]).norm());
  for (size_t i = 0; i < boundary; ++i) off = std::max(off, std::abs((P[i] - P[0]).dot(n)));
  for (size_t i = 0; i < boundary; ++i) magnitude = std::max(magnitude, P[i].cwiseAbs().maxCoeff());
  const bool flat = off <= std::max(on_plane_slack(size, magnitude), refine.flat_tolerance);
  // Two tries: the polygon whole, and with the parts refinement cannot shape split off first
  // (split_polygon.h); the one whose smallest angle is larger is kept. Triangles index P / Q. (The second
  // is quadratic in the ring's sides: a ring longer than refine.max_split_ring gets the first only.)
  std::vector<Vec3> P_whole = P;
  std::vector<Eigen::Vector2d> Q_whole = Q;
  std::vector<std::array<int, 3>> tris = mesh_ring(P_whole, Q_whole, boundary, refine, flat, e1, e2);
  if (refine.quality_deg > 0 && flat && boundary <= refine.max_split_ring) {
    auto to_3d = [&](const Eigen::Vector2d& x) { return in_space(P, Q, e1, e2, x); };
    std::vector<std::array<int, 3>> split;  // the parts split off, then the rest
    const auto rest = split_for_refinement(P, Q, boundary, refine, to_3d, split);
    if (!split.empty()) {
      split = mesh_ring_in_pieces(P, Q, rest, std::move(split), refine, e1, e2);
      if (smallest_angle_of(P, split) > smallest_angle_of(P_whole, tris) + 1e-9) tris = std::move(split), P_whole = P, Q_whole = Q;
    }
  }
  P = std::move(P_whole), Q = std::move(Q_whole);
  ring.resize(P.size(), -1);
  for (const auto& t : tris)  // inner points still in use become mesh vertices
    for (int k : t)
      if (ring[k] < 0) ring[k] = edit.add_point(P[k]);
  for (const auto& t : tris) {
    if (flipped) out.push_back({ring[t[2]], ring[t[1]], ring[t[0]]});
    else out.push_back({ring[t[0]], ring[t[1]], ring[t[2]]});
  }
}

void check_work_budget(double facets, long budget, const char* pass) {
  if (facets > double(budget))
    throw RoundingError(ErrorCode::WorkLimit, "the rounding would make more than " + std::to_string(budget) + " new facets (" + pass +
                        ": about " + format_number(facets) + "), the work budget max_new_facets; "
                        "use a larger radius or tolerance, or raise max_new_facets");
}

}  // namespace meshround
