#include "meshround/mesh.h"
#include "meshround/cancel.h"
#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace meshround {

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::InvalidInput: return "invalid_input";
    case ErrorCode::NoSharpEdge: return "no_sharp_edge";
    case ErrorCode::NonManifoldInput: return "non_manifold_input";
    case ErrorCode::RadiusTooLarge: return "radius_too_large";
    case ErrorCode::RadiusTooSmall: return "radius_too_small";
    case ErrorCode::BeyondReach: return "beyond_reach";
    case ErrorCode::CornerNotBlendable: return "corner_not_blendable";
    case ErrorCode::SurfaceFailed: return "surface_failed";
    case ErrorCode::ResultInvalid: return "result_invalid";
    case ErrorCode::Cancelled: return "cancelled";
    case ErrorCode::WorkLimit: return "work_limit";
    case ErrorCode::NotARound: return "not_a_round";
  }
  return "invalid_input";
}

std::string format_number(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

std::string format_point(const Vec3& p) {
  return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ", " + format_number(p.z()) + ")";
}

MeshTopology::MeshTopology(const Points& V_, const Triangles& F_) : V(V_), F(F_) {
  const int n = int(V.rows()), m = int(F.rows());
  if (n == 0 || m == 0) throw RoundingError(ErrorCode::InvalidInput, "the mesh is empty");
  if (!V.allFinite()) {
    for (int i = 0; i < n; ++i)
      if (!V.row(i).allFinite())
        throw RoundingError(ErrorCode::InvalidInput, "vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
  }
  // Vertex -> facets in CSR form, built by two threads over the two halves of the facets: each counts and
  // then fills its own share of every vertex's list (the first half's facets first), so each list is in
  // facet order, as one thread makes it.
  const int half = m / 2;
  std::vector<int> count[2] = {std::vector<int>(size_t(n), 0), std::vector<int>(size_t(n), 0)};
  long bad[2] = {-1, -1};  // the first bad index entry of each half (3 f + k)
  auto count_half = [&](int part) {
    CancelPoll poll(1 << 16);
    std::vector<int>& c = count[part];
    for (int f = part ? half : 0, end = part ? m : half; f < end; ++f)
      for (int k = 0; k < 3; ++k) {
        poll.tick();
        const int v = F(f, k);
        if (v < 0 || v >= n) {
          bad[part] = 3L * f + k;
          return;
        }
        ++c[size_t(v)];
      }
  };
  in_parallel([&] { count_half(0); }, [&] { count_half(1); });
  for (long at : bad)
    if (at >= 0)
      throw RoundingError(ErrorCode::InvalidInput, "facet " + std::to_string(at / 3) + " refers to vertex " +
                          std::to_string(F(Eigen::Index(at / 3), Eigen::Index(at % 3))) + ", which does not exist");
  vf_start_.assign(size_t(n) + 1, 0);
  for (int v = 0; v < n; ++v) {
    const int here = count[0][size_t(v)] + count[1][size_t(v)];
    if (here == 0) unused_.push_back(v);
    vf_start_[size_t(v) + 1] = vf_start_[size_t(v)] + here;
    // The cursors: the first half fills from the list's start, the second after the first half's share.
    count[1][size_t(v)] = vf_start_[size_t(v)] + count[0][size_t(v)];
    count[0][size_t(v)] = vf_start_[size_t(v)];
  }
  vf_.resize(size_t(vf_start_[size_t(n)]));
  auto fill_half = [&](int part) {
    CancelPoll poll(1 << 16);
    std::vector<int>& cursor = count[part];
    for (int f = part ? half : 0, end = part ? m : half; f < end; ++f) {
      poll.tick();
      for (int k = 0; k < 3; ++k) vf_[size_t(cursor[size_t(F(f, k))]++)] = f;
    }
  };
  in_parallel([&] { fill_half(0); }, [&] { fill_half(1); });
}

bool MeshTopology::facet_has_edge(int f, int a, int b) const {
  bool ha = false, hb = false;
  for (int k = 0; k < 3; ++k) {
    ha |= F(f, k) == a;
    hb |= F(f, k) == b;
  }
  return ha && hb;
}

int MeshTopology::edge_direction(int f, int a, int b) const {
  for (int k = 0; k < 3; ++k)
    if (F(f, k) == a) return F(f, (k + 1) % 3) == b ? 1 : -1;
  return 0;
}

std::vector<int> MeshTopology::edge_facets(int a, int b) const {
  std::vector<int> out;
  for (const int* f = facets_begin(a); f != facets_end(a); ++f)
    if (facet_has_edge(*f, a, b)) out.push_back(*f);
  return out;
}

int MeshTopology::edge_facet_count(int a, int b) const {
  int pair[2];
  return edge_facet_pair(a, b, pair);
}

int MeshTopology::neighbour(int f, int a, int b) const {
  int other = -1, count = 0;
  for (const int* g = facets_begin(a); g != facets_end(a); ++g)
    if (facet_has_edge(*g, a, b)) {
      ++count;
      if (*g != f) other = *g;
    }
  return count == 2 ? other : -1;
}

std::vector<int> MeshTopology::vertex_neighbours(int v) const {
  std::vector<int> out;
  for (const int* f = facets_begin(v); f != facets_end(v); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(*f, k) != v) out.push_back(F(*f, k));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Vec3 MeshTopology::facet_normal(int f) const {
  const Vec3 n = (corner(f, 1) - corner(f, 0)).cross(corner(f, 2) - corner(f, 0));
  const double l = n.norm();
  return l > 0 ? Vec3(n / l) : Vec3::Zero();
}

bool MeshTopology::facet_degenerate(int f) const {
  const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
  if (a == b || b == c || a == c) return true;
  const Vec3 pa = point(a), pb = point(b), pc = point(c);
  const double longest = std::max({(pb - pa).norm(), (pc - pb).norm(), (pa - pc).norm()});
  return (pb - pa).cross(pc - pa).norm() <= 1e-12 * longest * longest;
}

Vec3 MeshTopology::feature_normal(int f, int a, int b, double feature_angle_deg) const {
  const Vec3 n = facet_normal(f);
  constexpr double kSliver = 10.0 * M_PI / 180.0;
  if (smallest_angle(corner(f, 0), corner(f, 1), corner(f, 2)) >= kSliver) return n;
  // A sliver's plane tilts with the smallest offset of its vertices (a chord of a curved face a hair
  // high tilts by tens of degrees): lean on its neighbours on the same face, area-weighted.
  const double cos_limit = std::cos(feature_angle_deg * M_PI / 180.0);
  Vec3 sum = (corner(f, 1) - corner(f, 0)).cross(corner(f, 2) - corner(f, 0));
  for (int k = 0; k < 3; ++k) {
    const int p = F(f, k), q = F(f, (k + 1) % 3);
    if ((p == a && q == b) || (p == b && q == a)) continue;
    const int g = neighbour(f, p, q);
    if (g < 0) continue;
    Vec3 area = (corner(g, 1) - corner(g, 0)).cross(corner(g, 2) - corner(g, 0));
    if (edge_direction(g, p, q) == edge_direction(f, p, q)) area = -area;  // align orientation
    if (area.normalized().dot(n) >= cos_limit) sum += area;
  }
  const double l = sum.norm();
  return l > 0 ? Vec3(sum / l) : n;
}

int MeshTopology::edge_facet_pair(int a, int b, int pair[2]) const {
  int n = 0;
  for (const int* f = facets_begin(a); f != facets_end(a); ++f)
    if (facet_has_edge(*f, a, b)) {
      if (n < 2) pair[n] = *f;
      ++n;
    }
  return n;
}

double MeshTopology::dihedral_deg(int f0, int f1, const Vec3& n0, Vec3 n1, int a, int b) const {
  // Consistently oriented neighbours run the shared edge in opposite directions.
  if (edge_direction(f0, a, b) == edge_direction(f1, a, b)) n1 = -n1;
  return std::acos(std::clamp(n0.dot(n1), -1.0, 1.0)) * 180.0 / M_PI;
}

double MeshTopology::dihedral_deg(int a, int b) const {
  int fs[2];
  if (edge_facet_pair(a, b, fs) != 2) return 180.0;
  return dihedral_deg(fs[0], fs[1], facet_normal(fs[0]), facet_normal(fs[1]), a, b);
}

bool MeshTopology::is_feature_edge(int a, int b, double feature_angle_deg) const {
  int fs[2];
  if (edge_facet_pair(a, b, fs) != 2) return true;
  if (dihedral_deg(fs[0], fs[1], facet_normal(fs[0]), facet_normal(fs[1]), a, b) < feature_angle_deg) return false;
  return dihedral_deg(fs[0], fs[1], feature_normal(fs[0], a, b, feature_angle_deg),
                      feature_normal(fs[1], a, b, feature_angle_deg), a, b) >= feature_angle_deg;
}

double smallest_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto ang = [](const Vec3& u, const Vec3& v) {
    const double d = u.norm() * v.norm();
    return d > 0 ? std::acos(std::clamp(u.dot(v) / d, -1.0, 1.0)) : 0.0;
  };
  // The smallest angle faces the shortest side.
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  if (bc <= ab && bc <= ca) return ang(b - a, c - a);
  if (ca <= ab) return ang(c - b, a - b);
  return ang(a - c, b - c);
}

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b, double* t) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  double s = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  if (t) *t = s;
  return a + s * ab;
}

// Ericson, Real-Time Collision Detection, 5.1.5.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, int* region) {
  int dummy;
  int& r = region ? *region : dummy;
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return r = 4, a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return r = 5, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return r = 1, a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return r = 6, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return r = 3, a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return r = 2, b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = va + vb + vc;
  if (std::abs(denom) < 1e-300) {  // degenerate triangle: nearest of its three sides
    double t;
    Vec3 best = closest_point_on_segment(p, a, b, &t);
    r = 1;
    for (auto [q0, q1, reg] : {std::tuple{b, c, 2}, std::tuple{c, a, 3}}) {
      Vec3 q = closest_point_on_segment(p, q0, q1, &t);
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q, r = reg;
    }
    return best;
  }
  r = 0;
  return a + ab * (vb / denom) + ac * (vc / denom);
}

}  // namespace meshround
