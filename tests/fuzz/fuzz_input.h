// Decodes fuzz bytes into a rounding call: a generated mesh (prisms -- boxes, wedges of any angle,
// pockets, L-channels, star profiles -- or a height-field sheet with a fold, a ridge or a pocket),
// subdivided, perturbed, with a few facets removed, flipped or doubled near the chain, moved and
// scaled; seeds on or near its sharp edges; a radius (constant, tiny, huge or a law), tolerance,
// feature angle and reach. Header-only so that the GoogleTest replay uses the very same decoder.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "meshround/options.h"
#include "meshround/types.h"

namespace meshround::fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* d, std::size_t n) : d_(d), n_(n) {}
  std::uint8_t u8() { return i_ < n_ ? d_[i_++] : 0; }
  // Every read is its own statement: the order of evaluation of operands and arguments is unspecified
  // (clang reads left to right, gcc right to left), and the decoding must not depend on the compiler.
  std::uint16_t u16() {
    const unsigned lo = u8(), hi = u8();
    return std::uint16_t(lo | (hi << 8));
  }
  std::uint32_t u32() {
    const std::uint32_t lo = u16(), hi = u16();
    return lo | (hi << 16);
  }
  double unit() { return u16() / 65535.0; }                        // [0, 1]
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  int below(int n) { return n <= 1 ? 0 : int(u8() % n); }
  int range(int lo, int hi) { return lo + below(hi - lo + 1); }
  bool chance(int in256) { return u8() < in256; }
  double raw_double() {  // any bit pattern: NaN, inf, denormals, huge
    const std::uint64_t lo = u32(), hi = u32();
    const std::uint64_t b = lo | (hi << 32);
    double x;
    std::memcpy(&x, &b, 8);
    return x;
  }
  Vec3 vec(double lo, double hi) {  // x, then y, then z
    const double x = uniform(lo, hi), y = uniform(lo, hi), z = uniform(lo, hi);
    return Vec3(x, y, z);
  }
  bool exhausted() const { return i_ >= n_; }

 private:
  const std::uint8_t* d_;
  std::size_t n_, i_ = 0;
};

struct Rng {  // per-vertex noise without spending a byte per vertex
  std::uint64_t s;
  double next() {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    return (s >> 11) * (1.0 / 9007199254740992.0);
  }
};

struct FuzzCase {
  Points V;
  Triangles F;
  std::vector<Vec3> seeds;
  RoundOptions options;
  std::vector<Vec3> features;  // points on the sharp lines the generator made (for the record)
  double element = 1;          // typical edge length
};

namespace detail {

struct Builder {
  std::vector<Vec3> P;
  std::vector<std::array<int, 3>> T;
  int add(const Vec3& p) { P.push_back(p); return int(P.size()) - 1; }
  void quad(int a, int b, int c, int d, bool diag) {  // a b c d counter-clockwise
    if (diag) T.push_back({a, b, c}), T.push_back({a, c, d});
    else T.push_back({a, b, d}), T.push_back({b, c, d});
  }
};

inline double cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Ear clipping of a simple counter-clockwise polygon (indices into pts); false when it gets stuck.
inline bool ear_clip(const std::vector<Eigen::Vector2d>& pts, std::vector<std::array<int, 3>>& out) {
  std::vector<int> idx(pts.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = int(i);
  int guard = 0;
  while (idx.size() > 3 && guard++ < 10000) {
    bool clipped = false;
    const int n = int(idx.size());
    for (int i = 0; i < n && !clipped; ++i) {
      const int a = idx[(i + n - 1) % n], b = idx[i], c = idx[(i + 1) % n];
      if (cross2(pts[a], pts[b], pts[c]) <= 1e-12 * (pts[b] - pts[a]).norm() * (pts[c] - pts[b]).norm()) continue;
      bool inside = false;
      for (int j = 0; j < n && !inside; ++j) {
        const int p = idx[j];
        if (p == a || p == b || p == c) continue;
        inside = cross2(pts[a], pts[b], pts[p]) >= 0 && cross2(pts[b], pts[c], pts[p]) >= 0 && cross2(pts[c], pts[a], pts[p]) >= 0;
      }
      if (inside) continue;
      out.push_back({a, b, c});
      idx.erase(idx.begin() + i);
      clipped = true;
    }
    if (!clipped) return false;
  }
  if (idx.size() == 3) {
    if (cross2(pts[idx[0]], pts[idx[1]], pts[idx[2]]) <= 0) return false;
    out.push_back({idx[0], idx[1], idx[2]});
  }
  return true;
}

// Prism: a counter-clockwise profile in (y, z), extruded along x.
inline void prism(ByteReader& in, Builder& b, std::vector<Vec3>& features, double& element) {
  std::vector<Eigen::Vector2d> prof;
  const int kind = in.below(5);
  const double W = in.uniform(5, 60), H = in.uniform(5, 60);
  if (kind == 0) {  // box
    prof = {{0, 0}, {W, 0}, {W, H}, {0, H}};
  } else if (kind == 1) {  // wedge: the corner at the origin has any angle
    const double theta = in.uniform(2, 178) * M_PI / 180, B = in.uniform(5, 60);
    prof = {{0, 0}, {W, 0}, {B * std::cos(theta), B * std::sin(theta)}};
  } else if (kind == 2) {  // pocket (U profile): concave edges at its floor
    const double t = W * in.uniform(0.1, 0.45), d = H * in.uniform(0.05, 0.9);
    prof = {{0, 0}, {W, 0}, {W, H}, {W - t, H}, {W - t, d}, {t, d}, {t, H}, {0, H}};
  } else if (kind == 3) {  // L channel
    const double t = std::min(W, H) * in.uniform(0.05, 0.9);
    prof = {{0, 0}, {W, 0}, {W, t}, {t, t}, {t, H}, {0, H}};
  } else {  // star: random angles and radii (convex and concave corners of any angle)
    const int n = in.range(3, 8);
    std::vector<double> ang;
    for (int i = 0; i < n; ++i) ang.push_back(in.uniform(0, 2 * M_PI));
    std::sort(ang.begin(), ang.end());
    for (int i = 0; i < n; ++i) {
      const double r = in.uniform(3, 40);
      prof.push_back({r * std::cos(ang[i]), r * std::sin(ang[i])});
    }
    double area = 0;
    for (int i = 0; i < n; ++i) area += prof[i].x() * prof[(i + 1) % n].y() - prof[(i + 1) % n].x() * prof[i].y();
    if (!(area > 1e-6)) prof = {{0, 0}, {W, 0}, {W, H}, {0, H}};
  }
  const double L = in.uniform(10, 120);
  const int seg = in.range(1, 4), nx = in.range(1, 16);
  const int caps = in.below(3);  // 0 open tube, 1 one cap, 2 both
  const int diag_mode = in.below(3);
  const std::uint32_t diag_seed = in.u8();
  // The ring: each profile edge in `seg` pieces.
  std::vector<Eigen::Vector2d> ring;
  std::vector<int> corner_at;
  for (size_t i = 0; i < prof.size(); ++i) {
    corner_at.push_back(int(ring.size()));
    for (int k = 0; k < seg; ++k) ring.push_back(prof[i] + (prof[(i + 1) % prof.size()] - prof[i]) * (double(k) / seg));
  }
  const int R = int(ring.size());
  std::vector<std::vector<int>> id(nx + 1, std::vector<int>(R));
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j < R; ++j) id[i][j] = b.add(Vec3(L * i / nx, ring[j].x(), ring[j].y()));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < R; ++j) {
      const bool diag = diag_mode == 0 ? true : diag_mode == 1 ? ((i + j) & 1) : (((i * 7919u + j * 104729u) ^ diag_seed) & 4);
      b.quad(id[i][j], id[i][(j + 1) % R], id[i + 1][(j + 1) % R], id[i + 1][j], diag);
    }
  if (caps > 0) {
    std::vector<std::array<int, 3>> tris;
    if (ear_clip(ring, tris))
      for (auto& t : tris) {
        b.T.push_back({id[nx][t[0]], id[nx][t[1]], id[nx][t[2]]});                 // +x
        if (caps == 2) b.T.push_back({id[0][t[0]], id[0][t[2]], id[0][t[1]]});     // -x
      }
  }
  for (int c : corner_at) features.push_back(Vec3(L * in.unit(), ring[c].x(), ring[c].y()));
  element = std::min(L / nx, (prof[1] - prof[0]).norm() / seg);
}

// Height-field sheet z = h(x, y) with a crease: a fold, a ridge, a step pocket, or two folds.
inline void sheet(ByteReader& in, Builder& b, std::vector<Vec3>& features, double& element) {
  const int nx = in.range(2, 24), ny = in.range(2, 24);
  const double Lx = in.uniform(10, 100), Ly = in.uniform(10, 100);
  const int kind = in.below(4);
  const double phi = in.uniform(0, M_PI), slope = std::tan(in.uniform(1, 89) * M_PI / 180);
  const Eigen::Vector2d dir(std::cos(phi), std::sin(phi));
  const double u0 = in.uniform(0.2, 0.8) * (Lx * std::abs(dir.x()) + Ly * std::abs(dir.y()));
  const double px0 = in.uniform(0.1, 0.5) * Lx, px1 = in.uniform(0.5, 0.9) * Lx, py0 = in.uniform(0.1, 0.5) * Ly,
               py1 = in.uniform(0.5, 0.9) * Ly, depth = in.uniform(-30, 30);
  const double u1 = u0 + in.uniform(1, 40);
  auto h = [&](double x, double y) {
    const double u = dir.x() * x + dir.y() * y;
    switch (kind) {
      case 0: return slope * std::max(0.0, u - u0);
      case 1: return -slope * std::abs(u - u0);
      case 2: return (x > px0 && x < px1 && y > py0 && y < py1) ? -depth : 0.0;
      default: return slope * (std::max(0.0, u - u0) - std::max(0.0, u - u1));
    }
  };
  const int diag_mode = in.below(2);
  std::vector<std::vector<int>> id(nx + 1, std::vector<int>(ny + 1));
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j) {
      const double x = Lx * i / nx, y = Ly * j / ny;
      id[i][j] = b.add(Vec3(x, y, h(x, y)));
    }
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) b.quad(id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1], diag_mode ? ((i + j) & 1) : true);
  // Points on the crease (near it for a grid that does not follow it).
  const double t = in.unit();
  if (kind == 2) {
    features.push_back(Vec3(px0 + t * (px1 - px0), py0, 0));
    features.push_back(Vec3(px0, py0 + t * (py1 - py0), 0));
  } else {
    const Eigen::Vector2d along(-dir.y(), dir.x());
    Eigen::Vector2d p = u0 * dir + (t - 0.5) * 50 * along;
    features.push_back(Vec3(std::clamp(p.x(), 0.0, Lx), std::clamp(p.y(), 0.0, Ly), 0));
    if (kind == 3) {
      p = u1 * dir + (t - 0.5) * 50 * along;
      features.push_back(Vec3(std::clamp(p.x(), 0.0, Lx), std::clamp(p.y(), 0.0, Ly), slope * (u1 - u0)));
    }
  }
  element = std::min(Lx / nx, Ly / ny);
}

}  // namespace detail

inline FuzzCase decode_case(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  FuzzCase c;
  detail::Builder b;
  if (in.below(3) < 2) detail::prism(in, b, c.features, c.element);
  else detail::sheet(in, b, c.features, c.element);
  const double h = c.element;
  // Perturbation: none, every vertex, or only vertices near a feature line.
  const int perturb = in.below(4);
  const double amp = h * (in.chance(32) ? in.uniform(0, 0.45) : in.uniform(0, 0.1));
  Rng rng{std::uint64_t(in.u32()) | 1};
  if (perturb > 0)
    for (Vec3& p : b.P) {
      if (perturb == 2) {
        double d = INFINITY;
        for (const Vec3& f : c.features) d = std::min(d, (p - f).norm());
        if (d > 10 * h) continue;
      }
      if (perturb == 3 && rng.next() < 0.7) continue;
      p += amp * Vec3(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 2;
    }
  // Damage near the first feature point: facets removed (holes), flipped, or a fin (non-manifold edge).
  std::vector<std::array<int, 3>>& T = b.T;
  auto near_facet = [&](int k) {  // the k-th nearest facet to a feature point (k < 24)
    const Vec3 f = c.features.empty() ? Vec3::Zero() : c.features[0];
    std::vector<std::pair<double, int>> d;
    for (size_t i = 0; i < T.size(); ++i) d.push_back({((b.P[T[i][0]] + b.P[T[i][1]] + b.P[T[i][2]]) / 3 - f).norm(), int(i)});
    const int n = std::min<int>(24, int(d.size()));
    std::partial_sort(d.begin(), d.begin() + n, d.end());
    return d[std::min(k, n - 1)].second;
  };
  if (!T.empty() && in.chance(40)) {
    const int holes = in.range(1, 3);
    for (int k = 0; k < holes && T.size() > 1; ++k) T.erase(T.begin() + near_facet(in.below(24)));
  }
  if (!T.empty() && in.chance(40)) {
    const int flips = in.range(1, 3);
    for (int k = 0; k < flips; ++k) {
      const int f = near_facet(in.below(24));
      std::swap(T[f][1], T[f][2]);
    }
  }
  if (!T.empty() && in.chance(16)) {
    const auto t = T[near_facet(in.below(24))];
    const Vec3 m = (b.P[t[0]] + b.P[t[1]] + b.P[t[2]]) / 3 + h * Vec3(0.3, -0.2, 0.9);
    T.push_back({t[1], t[0], b.add(m)});  // a fin on edge (t0, t1)
  }
  // Placement: rotation, scale, translation (far from the origin tests float-like magnitudes).
  const Vec3 axis = in.vec(-1, 1) + Vec3(1e-3, 0, 0);
  const double angle = in.chance(128) ? 0 : in.uniform(0, 2 * M_PI);
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  const double scale = in.chance(200) ? 1 : std::pow(10.0, in.uniform(-3, 4));
  Vec3 shift = Vec3::Zero();
  if (!in.chance(200)) {
    shift = in.vec(-1, 1);
    shift *= std::pow(10.0, in.uniform(0, 6));
  }
  auto place = [&](const Vec3& p) -> Vec3 { return scale * (rot * p) + shift; };
  c.V.resize(Eigen::Index(b.P.size()), 3);
  for (size_t i = 0; i < b.P.size(); ++i) c.V.row(Eigen::Index(i)) = place(b.P[i]).transpose();
  c.F.resize(Eigen::Index(T.size()), 3);
  for (size_t i = 0; i < T.size(); ++i)
    for (int k = 0; k < 3; ++k) c.F(Eigen::Index(i), k) = T[i][k];
  for (Vec3& f : c.features) f = place(f);
  c.element = h * scale;
  const double hs = c.element;
  // Radius: a few elements, occasionally tiny or huge; sometimes a law of control points.
  RoundOptions& o = c.options;
  const int rmode = in.below(16);
  const double r = hs * (rmode == 0 ? std::pow(10.0, in.uniform(-9, -1.5)) : rmode == 1 ? std::pow(10.0, in.uniform(1.5, 6)) : std::pow(10.0, in.uniform(-1.2, 1.2)));
  o.radius = r;
  if (in.chance(10)) o.radius = in.chance(128) ? -r : in.raw_double();
  if (in.chance(48) && !c.features.empty()) {
    const int n = in.range(1, 4);
    for (int k = 0; k < n; ++k) {
      const Vec3 on = c.features[in.below(int(c.features.size()))];
      const double dx = in.uniform(-20, 20), dy = in.uniform(-1, 1), dz = in.uniform(-1, 1);
      const Vec3 p = on + hs * Vec3(dx, dy, dz);
      o.radius_law.push_back({p, r * in.uniform(0.2, 3)});
    }
    if (in.chance(8)) o.radius_law[0].radius = in.raw_double();
  }
  // Seeds: on a feature line, near it, or anywhere in the box.
  const int nseeds = in.range(1, 3);
  const Vec3 lo = c.V.colwise().minCoeff().transpose(), hi = c.V.colwise().maxCoeff().transpose();
  for (int k = 0; k < nseeds; ++k) {
    const int mode = in.below(8);
    const Vec3 off = in.vec(-1, 1);
    if (mode < 6 && !c.features.empty()) c.seeds.push_back(c.features[in.below(int(c.features.size()))] + (mode < 4 ? 0.01 : 0.5) * std::min(hs, r) * off);
    else c.seeds.push_back(lo + (hi - lo).cwiseProduct(0.5 * (off + Vec3::Ones())));
  }
  o.tolerance = in.chance(128) ? 0 : r * std::pow(10.0, in.chance(16) ? in.uniform(-3.2, -2) : in.uniform(-2, 0.3));
  o.feature_angle_deg = in.chance(160) ? 30 : in.uniform(0.5, 179.5);
  o.reach = in.chance(160) ? 3 : (in.chance(16) ? in.uniform(0, 1000) : in.uniform(1, 12));
  // A law's points from a few multiples of r, so that chains of one radius and of 1.5 to 3 times it meet
  // at corners (mitres, sphere and rolled corners with radii of their own). Read last: inputs made before
  // it (they end earlier, and a spent input reads 0) decode as they did.
  if (!o.radius_law.empty() && in.below(4) == 1) {
    constexpr double kMultiples[4] = {1.0, 1.5, 2.0, 3.0};
    for (RadiusControl& p : o.radius_law) p.radius = r * kMultiples[in.below(4)];
  }
  return c;
}

}  // namespace meshround::fuzz
