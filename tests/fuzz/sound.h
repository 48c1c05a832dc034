// An independent check that a rounding result is a sound mesh, for the fuzz harness and its regression
// tests. It shares no code with the engine: exact orientation predicates (floating-point expansions,
// Shewchuk's two-sum / two-product), its own adjacency, its own triangle-triangle test.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "meshround/types.h"

namespace meshround::fuzz {

// ---------------------------------------------------------------- exact predicates
namespace exact {
// Non-overlapping components, increasing magnitude, no zeros; on the stack (orient3d's largest
// expansion has 192 components): the harness runs under ASan, where a heap allocation per product
// made the check slower than the rounding it checks.
class Expansion {
 public:
  Expansion() = default;
  Expansion(const Expansion& o) : n_(o.n_) { std::copy(o.v_, o.v_ + o.n_, v_); }
  Expansion& operator=(const Expansion& o) {
    n_ = o.n_;
    std::copy(o.v_, o.v_ + o.n_, v_);
    return *this;
  }
  void push_back(double x) {
    if (n_ == kCapacity) std::abort();  // cannot happen for the predicates below
    v_[n_++] = x;
  }
  void reserve(int) {}
  bool empty() const { return n_ == 0; }
  int size() const { return n_; }
  double* begin() { return v_; }
  double* end() { return v_ + n_; }
  const double* begin() const { return v_; }
  const double* end() const { return v_ + n_; }
  double operator[](int i) const { return v_[i]; }

 private:
  static constexpr int kCapacity = 256;
  double v_[kCapacity];
  int n_ = 0;
};

inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a, av = x - bv;
  y = (a - av) + (b - bv);
}
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);
}
inline Expansion grow(const Expansion& e, double b) {
  Expansion h;
  h.reserve(e.size() + 1);
  double q = b;
  for (double ei : e) {
    double s, t;
    two_sum(q, ei, s, t);
    if (t != 0) h.push_back(t);
    q = s;
  }
  if (q != 0 || h.empty()) h.push_back(q);
  return h;
}
inline Expansion add(Expansion e, const Expansion& f) {
  for (double x : f) e = grow(e, x);
  return e;
}
inline Expansion scale(const Expansion& e, double b) {
  Expansion h;
  for (double ei : e) {
    double p, pe;
    two_product(ei, b, p, pe);
    h = grow(grow(h, pe), p);
  }
  return h;
}
inline Expansion mul(const Expansion& e, const Expansion& f) {
  Expansion h;
  for (double x : f) h = add(h, scale(e, x));
  return h;
}
inline Expansion diff(double a, double b) {
  double x, y;
  two_sum(a, -b, x, y);
  Expansion e;
  if (y != 0) e.push_back(y);
  e.push_back(x);
  return e;
}
inline Expansion neg(Expansion e) {
  for (double& x : e) x = -x;
  return e;
}
inline int sign(const Expansion& e) {
  for (int i = e.size() - 1; i >= 0; --i)
    if (e[i] != 0) return e[i] > 0 ? 1 : -1;
  return 0;
}

// Sign of det[a-d; b-d; c-d]: > 0 when d lies below the plane of (a, b, c) seen counter-clockwise.
inline int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 A = a - d, B = b - d, C = c - d;
  const double det = A.x() * (B.y() * C.z() - B.z() * C.y()) - A.y() * (B.x() * C.z() - B.z() * C.x()) +
                     A.z() * (B.x() * C.y() - B.y() * C.x());
  const double perm = std::abs(A.x()) * (std::abs(B.y() * C.z()) + std::abs(B.z() * C.y())) +
                      std::abs(A.y()) * (std::abs(B.x() * C.z()) + std::abs(B.z() * C.x())) +
                      std::abs(A.z()) * (std::abs(B.x() * C.y()) + std::abs(B.y() * C.x()));
  if (std::isfinite(det) && std::abs(det) > 1e-14 * perm) return det > 0 ? 1 : -1;
  Expansion ax = diff(a.x(), d.x()), ay = diff(a.y(), d.y()), az = diff(a.z(), d.z());
  Expansion bx = diff(b.x(), d.x()), by = diff(b.y(), d.y()), bz = diff(b.z(), d.z());
  Expansion cx = diff(c.x(), d.x()), cy = diff(c.y(), d.y()), cz = diff(c.z(), d.z());
  Expansion m1 = add(mul(by, cz), neg(mul(bz, cy)));
  Expansion m2 = add(mul(bx, cz), neg(mul(bz, cx)));
  Expansion m3 = add(mul(bx, cy), neg(mul(by, cx)));
  return sign(add(add(mul(ax, m1), neg(mul(ay, m2))), mul(az, m3)));
}
// 2D orientation of the points' coordinates (i, j).
inline int orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int i, int j) {
  const double det = (a[i] - c[i]) * (b[j] - c[j]) - (a[j] - c[j]) * (b[i] - c[i]);
  const double perm = std::abs((a[i] - c[i]) * (b[j] - c[j])) + std::abs((a[j] - c[j]) * (b[i] - c[i]));
  if (std::isfinite(det) && std::abs(det) > 1e-15 * perm) return det > 0 ? 1 : -1;
  return sign(add(mul(diff(a[i], c[i]), diff(b[j], c[j])), neg(mul(diff(a[j], c[j]), diff(b[i], c[i])))));
}
}  // namespace exact

// ---------------------------------------------------------------- triangle-triangle
// Closed segment pq against closed triangle abc in 3D, the two not coplanar.
inline bool segment_hits_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const int sp = exact::orient3d(a, b, c, p), sq = exact::orient3d(a, b, c, q);
  if (sp * sq > 0 || (sp == 0 && sq == 0)) return false;
  const int s1 = exact::orient3d(p, q, a, b), s2 = exact::orient3d(p, q, b, c), s3 = exact::orient3d(p, q, c, a);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}
// 2D closed segments.
inline bool segments_2d(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, int i, int j) {
  const int o1 = exact::orient2d(p, q, a, i, j), o2 = exact::orient2d(p, q, b, i, j);
  const int o3 = exact::orient2d(a, b, p, i, j), o4 = exact::orient2d(a, b, q, i, j);
  if (o1 * o2 > 0 || o3 * o4 > 0) return false;
  if (o1 == 0 && o2 == 0) {  // collinear: overlap of the projections on both axes
    for (int k : {i, j})
      if (std::max(p[k], q[k]) < std::min(a[k], b[k]) || std::max(a[k], b[k]) < std::min(p[k], q[k])) return false;
  }
  return true;
}
inline bool point_in_triangle_2d(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, int i, int j, bool strict) {
  const int s1 = exact::orient2d(a, b, p, i, j), s2 = exact::orient2d(b, c, p, i, j), s3 = exact::orient2d(c, a, p, i, j);
  if (strict) return (s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// Do triangles t = (V[t0], V[t1], V[t2]) and u intersect anywhere but in the vertices / edge they share?
inline bool triangles_intersect(const Points& V, const std::array<int, 3>& t, const std::array<int, 3>& u) {
  auto P = [&](int v) -> Vec3 { return V.row(v).transpose(); };
  int shared = 0, ts[3] = {-1, -1, -1}, us[3] = {-1, -1, -1};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (t[i] == u[j]) ts[i] = j, us[j] = i, ++shared;
  if (shared == 3) return true;  // the same facet twice
  const Vec3 a = P(t[0]), b = P(t[1]), c = P(t[2]);
  const int o[3] = {exact::orient3d(a, b, c, P(u[0])), exact::orient3d(a, b, c, P(u[1])), exact::orient3d(a, b, c, P(u[2]))};
  const bool coplanar = o[0] == 0 && o[1] == 0 && o[2] == 0;
  // Projection plane for coplanar tests: drop the normal's largest axis.
  int pi = 0, pj = 1;
  if (coplanar) {
    const Vec3 n = (b - a).cross(c - a);
    const int drop = (std::abs(n.x()) >= std::abs(n.y()) && std::abs(n.x()) >= std::abs(n.z())) ? 0 : (std::abs(n.y()) >= std::abs(n.z()) ? 1 : 2);
    pi = drop == 0 ? 1 : 0, pj = drop == 2 ? 1 : 2;
  }
  if (shared == 2) {
    if (!coplanar) return false;
    int ot = 0, ou = 0;  // the vertices off the shared edge
    for (int i = 0; i < 3; ++i) if (ts[i] < 0) ot = t[i];
    for (int j = 0; j < 3; ++j) if (us[j] < 0) ou = u[j];
    int e0 = -1, e1 = -1;
    for (int i = 0; i < 3; ++i) if (ts[i] >= 0) (e0 < 0 ? e0 : e1) = t[i];
    return exact::orient2d(P(e0), P(e1), P(ot), pi, pj) * exact::orient2d(P(e0), P(e1), P(ou), pi, pj) > 0;  // folded onto each other
  }
  if (shared == 1) {  // only the edges opposite the shared vertex can meet the other triangle
    int ta = -1, tb = -1, ua = -1, ub = -1;
    for (int i = 0; i < 3; ++i) if (ts[i] < 0) (ta < 0 ? ta : tb) = t[i];
    for (int j = 0; j < 3; ++j) if (us[j] < 0) (ua < 0 ? ua : ub) = u[j];
    if (!coplanar) return segment_hits_triangle(P(ta), P(tb), P(u[0]), P(u[1]), P(u[2])) || segment_hits_triangle(P(ua), P(ub), a, b, c);
    const Vec3 U0 = P(u[0]), U1 = P(u[1]), U2 = P(u[2]);
    for (int i = 0; i < 3; ++i)
      if (segments_2d(P(ta), P(tb), P(u[i]), P(u[(i + 1) % 3]), pi, pj) && !(us[i] >= 0 && us[(i + 1) % 3] >= 0)) return true;
    return point_in_triangle_2d(P(ta), U0, U1, U2, pi, pj, false) || point_in_triangle_2d(P(ua), a, b, c, pi, pj, false);
  }
  if (!coplanar) {
    if ((o[0] > 0 && o[1] > 0 && o[2] > 0) || (o[0] < 0 && o[1] < 0 && o[2] < 0)) return false;
    const Vec3 U[3] = {P(u[0]), P(u[1]), P(u[2])}, T[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
      if (segment_hits_triangle(U[i], U[(i + 1) % 3], a, b, c)) return true;
      if (segment_hits_triangle(T[i], T[(i + 1) % 3], U[0], U[1], U[2])) return true;
    }
    return false;
  }
  const Vec3 U[3] = {P(u[0]), P(u[1]), P(u[2])}, T[3] = {a, b, c};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_2d(T[i], T[(i + 1) % 3], U[j], U[(j + 1) % 3], pi, pj)) return true;
  return point_in_triangle_2d(U[0], a, b, c, pi, pj, false) || point_in_triangle_2d(a, U[0], U[1], U[2], pi, pj, false);
}

// ---------------------------------------------------------------- the soundness check
struct SoundnessInput {
  const Points& V_in;
  const Triangles& F_in;
  const Points& V_out;
  const Triangles& F_out;
  std::vector<Vec3> chain_ends;  // where a rounding may leave a new boundary (its end profile)
  double end_allowance = 0;      // how far from a chain end
};

inline std::uint64_t ekey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

struct PointKey {
  std::size_t operator()(const std::array<std::uint64_t, 3>& k) const { return k[0] * 0x9E3779B97F4A7C15ull ^ (k[1] + 0x632BE5AB) * 31 ^ k[2]; }
};
inline std::array<std::uint64_t, 3> point_key(const Points& V, int v) {
  std::array<std::uint64_t, 3> k;
  for (int i = 0; i < 3; ++i) {
    double x = V(v, i);
    if (x == 0) x = 0;  // -0 == 0
    std::memcpy(&k[i], &x, 8);
  }
  return k;
}

struct EdgeUse {
  int count = 0, forward = 0;  // facets on it; those running low -> high index
  int f0 = -1, f1 = -1;
};
inline std::unordered_map<std::uint64_t, EdgeUse> edge_uses(const Triangles& F) {
  std::unordered_map<std::uint64_t, EdgeUse> e;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      EdgeUse& u = e[ekey(a, b)];
      (u.count == 0 ? u.f0 : u.f1) = f;
      ++u.count;
      u.forward += a < b;
    }
  return e;
}

// The boundary loops of F; with `kept`, only those with a vertex for which kept(v) holds.
inline int boundary_loops(const Triangles& F, const std::unordered_map<std::uint64_t, EdgeUse>& uses,
                          const std::function<bool(int)>& kept = nullptr) {
  std::unordered_map<int, int> parent;
  std::function<int(int)> find = [&](int x) { int& p = parent.emplace(x, x).first->second; return p == x ? x : (p = find(p)); };
  for (auto& [k, u] : uses)
    if (u.count == 1) {
      const int a = int(k >> 32), b = int(k & 0xffffffff);
      const int ra = find(a), rb = find(b);
      if (ra != rb) parent[ra] = rb;
    }
  std::unordered_set<int> roots;
  for (auto& [v, p] : parent)
    if (!kept || kept(v)) roots.insert(find(v));
  return int(roots.size());
}

// Two facets that cross by more than a touch at the coordinates' precision. The result is kept as float32
// by FreeCAD (a relative 6e-8), so facets whose edges pass within that of each other only touch; each is
// shrunk towards its middle by `shrink` (1e-6 of the coordinates' magnitude: the engine's on-plane slack,
// on_plane_slack in mesh.h) and the exact test is made again.
inline bool cross_beyond_precision(const Points& V, const std::array<int, 3>& t, const std::array<int, 3>& u, double shrink) {
  if (!triangles_intersect(V, t, u)) return false;
  auto P = [&](int v) -> Vec3 { return V.row(v).transpose(); };
  Points W(6, 3);
  const std::array<int, 3>* tri[2] = {&t, &u};
  for (int i = 0; i < 2; ++i) {
    const Vec3 mid = (P((*tri[i])[0]) + P((*tri[i])[1]) + P((*tri[i])[2])) / 3;
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = P((*tri[i])[k]);
      const double d = (mid - p).norm();
      W.row(3 * i + k) = (d > shrink ? Vec3(p + shrink / d * (mid - p)) : mid).transpose();
    }
  }
  return triangles_intersect(W, {0, 1, 2}, {3, 4, 5});
}

// "" when the result is sound, else what is wrong (the first defect found).
inline std::string check_sound(const SoundnessInput& s) {
  const Points& Vi = s.V_in;
  const Triangles& Fi = s.F_in;
  const Points& Vo = s.V_out;
  const Triangles& Fo = s.F_out;
  if (Fo.rows() == 0 || Vo.rows() == 0) return "empty result";
  if (!Vo.allFinite()) return "a NaN or infinite output coordinate";
  for (int f = 0; f < Fo.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (Fo(f, k) < 0 || Fo(f, k) >= Vo.rows()) return "facet " + std::to_string(f) + " has an index out of range";
  // Output vertex -> input vertex at the same exact position (-1: new).
  std::unordered_map<std::array<std::uint64_t, 3>, int, PointKey> in_at;
  for (int v = 0; v < Vi.rows(); ++v) in_at.emplace(point_key(Vi, v), v);
  std::vector<int> to_in(Vo.rows(), -1);
  for (int v = 0; v < Vo.rows(); ++v) {
    auto it = in_at.find(point_key(Vo, v));
    if (it != in_at.end()) to_in[v] = it->second;
  }
  // A facet is known by its corners' positions (an input with coincident vertices keeps its facets
  // however the result numbers them).
  using TriKey = std::array<std::array<std::uint64_t, 3>, 3>;
  auto tri_key = [](const Points& V, int a, int b, int c) {
    TriKey t{point_key(V, a), point_key(V, b), point_key(V, c)};
    std::sort(t.begin(), t.end());
    return t;
  };
  std::map<TriKey, int> in_facets;
  for (int f = 0; f < Fi.rows(); ++f) in_facets.emplace(tri_key(Vi, Fi(f, 0), Fi(f, 1), Fi(f, 2)), f);
  const auto uses_in = edge_uses(Fi), uses_out = edge_uses(Fo);
  // Input facets beside a misoriented input edge: the result may keep their orientation.
  std::unordered_set<int> in_misoriented;
  for (auto& [k, u] : uses_in)
    if (u.count == 2 && u.forward != 1) in_misoriented.insert(u.f0), in_misoriented.insert(u.f1);
  std::vector<int> kept(Fo.rows(), -1);  // output facet -> the input facet it is (by positions)
  std::vector<int> fresh;
  for (int f = 0; f < Fo.rows(); ++f) {
    if (to_in[Fo(f, 0)] >= 0 && to_in[Fo(f, 1)] >= 0 && to_in[Fo(f, 2)] >= 0) {
      auto it = in_facets.find(tri_key(Vo, Fo(f, 0), Fo(f, 1), Fo(f, 2)));
      if (it != in_facets.end()) { kept[f] = it->second; continue; }
    }
    fresh.push_back(f);
  }
  auto P = [&](const Points& V, int v) -> Vec3 { return V.row(v).transpose(); };
  auto where = [&](int a, int b) { return format_point(0.5 * (P(Vo, a) + P(Vo, b))); };
  // Degenerate new facets.
  for (int f : fresh) {
    const int a = Fo(f, 0), b = Fo(f, 1), c = Fo(f, 2);
    if (a == b || b == c || c == a) return "new facet " + std::to_string(f) + " repeats a vertex";
    const Vec3 A = P(Vo, a), B = P(Vo, b), C = P(Vo, c);
    if ((B - A).cross(C - A).norm() <= 1e-12 * (B - A).norm() * (C - A).norm()) return "new facet " + std::to_string(f) + " has no area, at " + format_point(A);
  }
  // Edges: non-manifold, misoriented, boundary.
  for (auto& [k, u] : uses_out) {
    const int a = int(k >> 32), b = int(k & 0xffffffff);
    const int ia = to_in[a], ib = to_in[b];
    const EdgeUse* before = nullptr;
    if (ia >= 0 && ib >= 0) {
      auto it = uses_in.find(ekey(ia, ib));
      if (it != uses_in.end()) before = &it->second;
    }
    if (u.count > 2 && !(before && before->count > 2)) return "new non-manifold edge (" + std::to_string(u.count) + " facets) at " + where(a, b);
    if (u.count == 2 && u.forward != 1) {
      const bool inherited = (kept[u.f0] >= 0 && in_misoriented.count(kept[u.f0])) || (kept[u.f1] >= 0 && in_misoriented.count(kept[u.f1]));
      if (!inherited) return "misoriented edge (its two facets run the same way) at " + where(a, b);
    }
    if (u.count == 1 && !(before && before->count == 1)) {
      // A new boundary edge must lie on an input boundary edge, or at the end profile of a round.
      const Vec3 pa = P(Vo, a), pb = P(Vo, b), mid = 0.5 * (pa + pb);
      bool ok = false;
      for (const Vec3& e : s.chain_ends) ok = ok || (mid - e).norm() <= s.end_allowance;
      const double span = (Vi.colwise().maxCoeff() - Vi.colwise().minCoeff()).norm() + Vi.cwiseAbs().maxCoeff();
      for (auto it = uses_in.begin(); !ok && it != uses_in.end(); ++it) {
        if (it->second.count != 1) continue;
        const Vec3 qa = P(Vi, int(it->first >> 32)), qb = P(Vi, int(it->first & 0xffffffff));
        auto on = [&](const Vec3& p) {
          const Vec3 d = qb - qa;
          const double t = std::clamp((p - qa).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
          return (qa + t * d - p).norm() <= 1e-7 * span;
        };
        ok = on(pa) && on(pb);
      }
      if (!ok) return "new boundary edge (a hole or crack) at " + where(a, b);
    }
  }
  // A hole whose whole rim the edit replaced was rounded over (the band's new surface covers it): not a loop
  // the result must keep.
  std::unordered_set<int> surviving;
  for (int f = 0; f < Fo.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (to_in[Fo(f, k)] >= 0) surviving.insert(to_in[Fo(f, k)]);
  const int loops_in = boundary_loops(Fi, uses_in, [&](int v) { return surviving.count(v) > 0; });
  const int loops_out = boundary_loops(Fo, uses_out);
  if (loops_in != loops_out) return "boundary loops " + std::to_string(loops_in) + " -> " + std::to_string(loops_out);
  // Self-intersection: every new facet against the facets near it (a hash grid of boxes).
  if (fresh.empty()) return "";
  double cell = 0;
  for (int f : fresh) cell += (P(Vo, Fo(f, 0)) - P(Vo, Fo(f, 1))).norm();
  cell = std::max(cell / fresh.size(), 1e-300);
  auto box = [&](int f, Vec3& lo, Vec3& hi) {
    lo = hi = P(Vo, Fo(f, 0));
    for (int k = 1; k < 3; ++k) lo = lo.cwiseMin(P(Vo, Fo(f, k))), hi = hi.cwiseMax(P(Vo, Fo(f, k)));
  };
  Vec3 flo, fhi;
  box(fresh[0], flo, fhi);
  for (int f : fresh) {
    Vec3 lo, hi;
    box(f, lo, hi);
    flo = flo.cwiseMin(lo), fhi = fhi.cwiseMax(hi);
  }
  std::unordered_map<std::uint64_t, std::vector<int>> grid;
  std::vector<int> big;
  auto cells = [&](const Vec3& lo, const Vec3& hi, auto&& fn) {
    long l[3], h[3];
    for (int i = 0; i < 3; ++i) l[i] = long(std::floor(lo[i] / cell)), h[i] = long(std::floor(hi[i] / cell));
    if ((h[0] - l[0] + 1) * (h[1] - l[1] + 1) * (h[2] - l[2] + 1) > 64) return false;
    for (long x = l[0]; x <= h[0]; ++x)
      for (long y = l[1]; y <= h[1]; ++y)
        for (long z = l[2]; z <= h[2]; ++z) fn((std::uint64_t(x & 0x1fffff) << 42) | (std::uint64_t(y & 0x1fffff) << 21) | std::uint64_t(z & 0x1fffff));
    return true;
  };
  const double shrink = 1e-6 * Vo.cwiseAbs().maxCoeff();
  std::vector<char> is_fresh(Fo.rows(), 0);
  for (int f : fresh) is_fresh[f] = 1;
  for (int f = 0; f < Fo.rows(); ++f) {
    Vec3 lo, hi;
    box(f, lo, hi);
    if ((lo.array() > fhi.array()).any() || (hi.array() < flo.array()).any()) continue;
    if (!cells(lo, hi, [&](std::uint64_t k) { grid[k].push_back(f); })) big.push_back(f);
  }
  // Boxes once; the facets over many cells (`big`) are box-tested apart, not copied into every candidate list.
  std::vector<std::pair<Vec3, Vec3>> boxes(size_t(Fo.rows()));
  for (int g = 0; g < Fo.rows(); ++g) box(g, boxes[size_t(g)].first, boxes[size_t(g)].second);
  std::vector<int> cand;
  for (int f : fresh) {
    const Vec3 lo = boxes[size_t(f)].first, hi = boxes[size_t(f)].second;
    cand.clear();
    if (!cells(lo, hi, [&](std::uint64_t k) { auto it = grid.find(k); if (it != grid.end()) cand.insert(cand.end(), it->second.begin(), it->second.end()); }))
      for (int g = 0; g < Fo.rows(); ++g) cand.push_back(g);
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
    const std::array<int, 3> t{Fo(f, 0), Fo(f, 1), Fo(f, 2)};
    auto crosses = [&](int g) {
      if (g == f || (is_fresh[g] && g < f)) return false;
      const auto& [glo, ghi] = boxes[size_t(g)];
      if ((glo.array() > hi.array()).any() || (ghi.array() < lo.array()).any()) return false;
      if (!cross_beyond_precision(Vo, t, {Fo(g, 0), Fo(g, 1), Fo(g, 2)}, shrink)) return false;
      if (std::getenv("MESHROUND_FUZZ_VERBOSE"))
        for (int h : {f, g})
          std::fprintf(stderr, "  facet %d: (%.9g %.9g %.9g) (%.9g %.9g %.9g) (%.9g %.9g %.9g)\n", h, Vo(Fo(h, 0), 0), Vo(Fo(h, 0), 1), Vo(Fo(h, 0), 2),
                       Vo(Fo(h, 1), 0), Vo(Fo(h, 1), 1), Vo(Fo(h, 1), 2), Vo(Fo(h, 2), 0), Vo(Fo(h, 2), 1), Vo(Fo(h, 2), 2));
      return true;
    };
    for (const std::vector<int>* list : {&cand, &big})
      for (int g : *list)
        if (crosses(g))
          return "new facet " + std::to_string(f) + " intersects facet " + std::to_string(g) + " near " + format_point(P(Vo, t[0]));
  }
  return "";
}

}  // namespace meshround::fuzz
