#include "meshround/spine.h"

#include "box_tree.h"
#include "ends.h"
#include "meshround/cancel.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace meshround {

double ProfileStation::angle() const {
  const Vec3 a = (contact[0] - centre).normalized(), b = (contact[1] - centre).normalized();
  return std::acos(std::clamp(a.dot(b), -1.0, 1.0));
}

namespace {

// How near an earlier round a base facet must be to lie on it: its corners within kOnRoundShare r of the
// round (a round's vertices lie on its lofted surface, which is within a tenth of the tolerance of the
// balls; r / 100 leaves room for a finer or coarser tolerance), its middle within kChordShare r (a chord
// of a round made to r / 100 sags r / 100 at most). A flat face's facet beside the round passes only
// where it is tangent to it, which is where the two agree.
constexpr double kOnRoundShare = 0.01, kChordShare = 0.02;
// p's foot on a round lies over a facet of it when the facet's chord is within this share of r of the foot
// (the chord's sag, kChordShare, with room for the foot's drift along the chord's curve).
constexpr double kFootOverShare = 2 * kChordShare;

// Where on a polyline p is nearest: its segment i and the share t along it (clamped to the line's ends).
std::pair<size_t, double> nearest_on_segments(const std::vector<Vec3>& line, const Vec3& p) {
  std::pair<size_t, double> best{0, 0.0};
  double best_d2 = (line.front() - p).squaredNorm();
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec3 a = line[i], d = line[i + 1] - a;
    const double t = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    if ((a + t * d - p).squaredNorm() < best_d2) best_d2 = (a + t * d - p).squaredNorm(), best = {i, t};
  }
  return best;
}

Vec3 at_segment(const std::vector<Vec3>& line, const std::pair<size_t, double>& where) {
  const auto [i, t] = where;
  return i + 1 < line.size() ? Vec3((1 - t) * line[i] + t * line[i + 1]) : line[i];
}

// The point of a polyline nearest p (clamped to its ends).
Vec3 nearest_on_polyline(const std::vector<Vec3>& line, const Vec3& p) { return at_segment(line, nearest_on_segments(line, p)); }

// p's foot on `round`: on its balls (the centre nearest p on the spine, out by the radius) where that lies
// on the round's arc between its contact lines; past a contact line, on the round's tangent plane there --
// the face the round meets tangentially, which the balls' envelope leaves by d^2 / 2r. False when p is at
// the centre.
bool round_foot(const ExactRound& round, const Vec3& p, Vec3* foot) {
  const auto where = nearest_on_segments(round.spine, p);
  const Vec3 centre = at_segment(round.spine, where), d = p - centre;
  if (d.norm() <= 1e-9 * round.radius) return false;
  *foot = centre + round.radius * d.normalized();
  if (round.contacts[0].size() != round.spine.size() || round.contacts[1].size() != round.spine.size()) return true;
  const Vec3 a = at_segment(round.contacts[0], where) - centre, b = at_segment(round.contacts[1], where) - centre;
  auto angle = [](const Vec3& x, const Vec3& y) { return std::atan2(x.cross(y).norm(), x.dot(y)); };
  const double to_a = angle(a, d), to_b = angle(d, b);
  if (to_a + to_b <= angle(a, b) + 1e-9) return true;
  const Vec3 contact = centre + (to_a < to_b ? a : b), n = (contact - centre).normalized();
  *foot = p - (p - contact).dot(n) * n;
  return true;
}

// p's distance from the surface of `round` (the balls' envelope), signed: > 0 outside the balls.
double off_round(const ExactRound& round, const Vec3& p) { return (p - nearest_on_polyline(round.spine, p)).norm() - round.radius; }

}  // namespace

BaseDistance::BaseDistance(const MeshTopology& mesh, const std::vector<int>& facets, const std::vector<ExactRound>* rounds)
    : mesh_(mesh), facets_(facets), rounds_(rounds && !rounds->empty() ? rounds : nullptr) {
  if (rounds_) {
    on_round_.assign(facets.size(), -1);
    for (size_t i = 0; i < facets.size(); ++i) {
      const Vec3 a = mesh.corner(facets[i], 0), b = mesh.corner(facets[i], 1), c = mesh.corner(facets[i], 2);
      for (size_t k = 0; k < rounds_->size() && on_round_[i] < 0; ++k) {
        const ExactRound& round = (*rounds_)[k];
        const double r = round.radius;
        if (std::abs(off_round(round, a)) <= kOnRoundShare * r && std::abs(off_round(round, b)) <= kOnRoundShare * r &&
            std::abs(off_round(round, c)) <= kOnRoundShare * r && std::abs(off_round(round, (a + b + c) / 3)) <= kChordShare * r)
          on_round_[i] = int(k);
      }
    }
  }
  std::vector<Vec3> boxes;
  boxes.reserve(2 * facets.size());
  for (size_t i = 0; i < facets.size(); ++i) {
    const int f = facets[i];
    const Vec3 a = mesh.corner(f, 0), b = mesh.corner(f, 1), c = mesh.corner(f, 2);
    // A facet on a round is measured on the exact surface over it, up to a chord's sag off its box.
    const double sag = rounds_ && on_round_[i] >= 0 ? kFootOverShare * (*rounds_)[size_t(on_round_[i])].radius : 0.0;
    boxes.push_back(a.cwiseMin(b).cwiseMin(c).array() - sag), boxes.push_back(a.cwiseMax(b).cwiseMax(c).array() + sag);
  }
  tree_ = std::make_shared<const BoxTree>(boxes);
}

bool BaseDistance::exact_foot(int i, const Vec3& p, Vec3* foot) const {
  if (!rounds_ || on_round_[size_t(i)] < 0) return false;
  const ExactRound& round = (*rounds_)[size_t(on_round_[size_t(i)])];
  if (!round_foot(round, p, foot)) return false;
  const int f = facets_[size_t(i)];
  const Vec3 on_chord = closest_point_on_triangle(*foot, mesh_.corner(f, 0), mesh_.corner(f, 1), mesh_.corner(f, 2), nullptr);
  return (on_chord - *foot).norm() <= kFootOverShare * round.radius;
}

Vec3 BaseDistance::closest(const Vec3& p, int* facet, int* region) const {
  // A facet on an earlier round competes with the distance to the round's exact surface where p's foot on
  // it lies over the facet: near the line where the round meets a flat face, the ball then touches
  // whichever of the two is nearer, tangentially, not the kink between the round's chords and the face.
  auto d2 = [&](int i) {
    Vec3 foot;
    if (exact_foot(i, p, &foot)) return (foot - p).squaredNorm();
    const int f = facets_[size_t(i)];
    return (closest_point_on_triangle(p, mesh_.corner(f, 0), mesh_.corner(f, 1), mesh_.corner(f, 2), nullptr) - p).squaredNorm();
  };
  const int i = tree_->nearest(p, d2);
  if (i < 0) throw RoundingError(ErrorCode::NonManifoldInput, "a base mesh is empty near " + format_point(p));
  const int f = facets_[i];
  if (facet) *facet = f;
  Vec3 foot;
  if (rounds_ && on_round_[size_t(i)] >= 0 && round_foot((*rounds_)[size_t(on_round_[size_t(i)])], p, &foot)) {
    if (region) *region = 0;  // on an earlier round: its exact surface (and the face beyond), smooth there
    return foot;
  }
  int reg;
  const Vec3 q = closest_point_on_triangle(p, mesh_.corner(f, 0), mesh_.corner(f, 1), mesh_.corner(f, 2), &reg);
  if (region) *region = reg;
  return q;
}

namespace {

// Unit vector in facet f, perpendicular to the edge direction e, pointing from the edge into f.
Vec3 into_facet(const MeshTopology& mesh, int f, const Vec3& on_edge, const Vec3& e) {
  Vec3 best = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    Vec3 d = mesh.corner(f, k) - on_edge;
    d -= d.dot(e) * e;
    if (d.squaredNorm() > best.squaredNorm()) best = d;
  }
  return best.normalized();
}

ContactRegion region_kind(int code) {
  return code == 0 ? ContactRegion::Facet : code <= 3 ? ContactRegion::Edge : ContactRegion::Vertex;
}

// The edge of facet f that a closest_point_on_triangle region code names (-1 for facet/vertex).
std::uint64_t region_edge(const MeshTopology& mesh, int f, int code) {
  if (code < 1 || code > 3) return ~0ull;
  return edge_key(mesh.F(f, code - 1), mesh.F(f, code % 3));
}

// A vertex contact (region code 4..6) on an end of one of `edges`: the ball touches that wall there too;
// the key of one such edge, or ~0.
std::uint64_t vertex_on(const MeshTopology& mesh, int f, int code, const std::unordered_set<std::uint64_t>& edges) {
  if (code < 4 || code > 6 || edges.empty()) return ~0ull;
  const int v = mesh.F(f, code - 4);
  for (int u : mesh.vertex_neighbours(v))
    if (edges.count(edge_key(v, u))) return edge_key(v, u);
  return ~0ull;
}

// The wall edge of `edges` a contact (facet f, region code) lies on, or ~0.
std::uint64_t wall_touched(const MeshTopology& mesh, int f, int code, const std::unordered_set<std::uint64_t>& edges) {
  const std::uint64_t on_edge = region_edge(mesh, f, code);
  if (on_edge != ~0ull && edges.count(on_edge)) return on_edge;
  return vertex_on(mesh, f, code, edges);
}

// How far a line traced along the chain may fold: a point p of the ball with curvature . (p - e) >= this
// lies at (or past) the chain's centre of curvature.
constexpr double kFoldRatio = 1.0;

// The chain's curvature for a ball of radius r is measured over +-kCurvatureSpan * r of arc length: the
// circle through the chain's points there. A ball's contact line folds where the chain turns within about
// its offset, so a polygon's turns are smoothed over that scale, not read vertex by vertex (a mesh whose
// straight chain edges are split in two would otherwise double its curvature at every turn).
constexpr double kCurvatureSpan = 0.5;
// A span shorter than this share of the chain's length is not measured (float32 jitter would read as a bend).
constexpr double kCurvatureMinStep = 1e-3;

// The chain vertex nearest arc length s (wrapped on a loop).
int vertex_near(const SharpChain& chain, double s) {
  const int n = int(chain.points.size());
  const double L = chain.length;
  if (chain.closed) s -= L * std::floor(s / L);
  int i = int(std::lower_bound(chain.arc_length.begin(), chain.arc_length.end(), s) - chain.arc_length.begin());
  if (i >= n) return chain.closed && L - s < s - chain.arc_length[n - 1] ? 0 : n - 1;
  if (i > 0 && s - chain.arc_length[i - 1] < chain.arc_length[i] - s) --i;
  return i;
}

}  // namespace

Vec3 chain_curvature(const SharpChain& chain, double s, double r) {
  const double L = chain.length;
  const double h = std::max(kCurvatureSpan * r, kCurvatureMinStep * L);
  double lo = s - h, hi = s + h;
  if (!chain.closed) lo = std::max(lo, 0.0), hi = std::min(hi, L);
  if (std::min(s - lo, hi - s) < kCurvatureMinStep * L || 2 * h >= L) return Vec3::Zero();
  // The chain's vertices there (a CAD mesh's lie on the exact curve, points between them on its chords).
  const int i0 = vertex_near(chain, lo), i1 = vertex_near(chain, s), i2 = vertex_near(chain, hi);
  if (i0 == i1 || i1 == i2 || i0 == i2) return Vec3::Zero();
  const Vec3 p = chain.points[i1], a = chain.points[i0] - p, b = chain.points[i2] - p;
  const Vec3 axb = a.cross(b);
  const double d = 2 * axb.squaredNorm();
  if (!(d > 1e-24 * a.squaredNorm() * b.squaredNorm())) return Vec3::Zero();
  // From the chain point at s to the circumcentre C: kappa . (q - e) >= 1 exactly when q lies at or past C.
  const Vec3 to_centre = p + (a.squaredNorm() * b.cross(axb) + b.squaredNorm() * axb.cross(a)) / d - chain.point_at(s);
  return to_centre / to_centre.squaredNorm();
}

ProfileStation fit_station(const SpineContext& ctx, double s, double r, StationFit* fit) {
  *fit = StationFit{};
  const SharpChain& chain = ctx.chain;
  const Vec3 e = chain.point_at(s), t = chain.tangent_at(s);
  // Local wedge of the two facets at this chain edge: the start of Newton and the side of the ball.
  int seg = 0;
  {
    const int n = int(chain.points.size());
    double best = INFINITY;
    for (int i = 0; i < chain.num_edges(); ++i) {
      double tt;
      const double d = (closest_point_on_segment(e, chain.points[i], chain.points[(i + 1) % n], &tt) - e).norm();
      if (d < best) best = d, seg = i;
    }
  }
  ProfileStation st;
  st.s = s;
  st.radius = r;
  const Vec3 dir = (chain.points[(seg + 1) % chain.points.size()] - chain.points[seg]).normalized();
  const Vec3 dA = into_facet(ctx.mesh, chain.facet_a[seg], e, dir), dB = into_facet(ctx.mesh, chain.facet_b[seg], e, dir);
  const Vec3 nA = (dB - dB.dot(dA) * dA).normalized(), nB = (dA - dA.dot(dB) * dB).normalized();
  Eigen::Matrix3d M;
  M << nA.transpose(), nB.transpose(), t.transpose();
  if (std::abs(M.determinant()) < 1e-9) {
    fit->misfit = StationMisfit::FlatEdge, fit->at = e;
    return st;
  }
  Vec3 c = e + M.inverse() * Vec3(r, r, 0);

  // Newton in the section plane on (dist_A(c) - r, dist_B(c) - r).
  const Vec3 u1 = (std::abs(t.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(t).normalized(), u2 = t.cross(u1);
  int facet[2] = {-1, -1}, code[2] = {0, 0};
  double residual = INFINITY;
  for (int iter = 0; iter < 60; ++iter) {
    Vec3 g[2];
    double F[2];
    for (int k = 0; k < 2; ++k) {
      st.contact[k] = ctx.distance[k]->closest(c, &facet[k], &code[k]);
      const double d = (c - st.contact[k]).norm();
      g[k] = (c - st.contact[k]) / std::max(d, 1e-300);
      F[k] = d - r;
    }
    residual = std::max(std::abs(F[0]), std::abs(F[1]));
    if (residual < 1e-11 * std::max(1.0, r)) break;
    Eigen::Matrix2d J;
    J << g[0].dot(u1), g[0].dot(u2), g[1].dot(u1), g[1].dot(u2);
    if (std::abs(J.determinant()) < 1e-12) break;
    Eigen::Vector2d step = -J.inverse() * Eigen::Vector2d(F[0], F[1]);
    if (step.norm() > 0.5 * r) step *= 0.5 * r / step.norm();
    c += step(0) * u1 + step(1) * u2;
  }
  st.centre = c;
  if (residual > 1e-6 * std::max(1.0, r) || (c - e).dot(nA + nB) <= 0) {
    fit->misfit = StationMisfit::NoBall, fit->at = e;
    return st;
  }
  const bool at_end = !chain.closed && (s <= 1e-9 * chain.length || s >= chain.length * (1 - 1e-9));
  for (int k = 0; k < 2; ++k) {
    st.region[k] = region_kind(code[k]);
    const std::uint64_t wall = at_end ? ~0ull : wall_touched(ctx.mesh, facet[k], code[k], ctx.base.walls[k]);
    if (wall != ~0ull) {
      *fit = StationFit{StationMisfit::Wall, k, st.contact[k], wall};
      return st;
    }
    // Beyond the reach either on the base meshes' edge there, or inside one of their facets (a coarse
    // or CAD facet runs past the reach): the band would not fit in what was collected.
    double from_chain = 0;
    ctx.chain.project(st.contact[k], &from_chain);
    if (wall_touched(ctx.mesh, facet[k], code[k], ctx.base.reach_limit[k]) != ~0ull || from_chain > ctx.base.reach_distance) {
      *fit = StationFit{StationMisfit::BeyondReach, k, st.contact[k]};
      return st;
    }
  }
  // The chain's own curvature: the contact lines and the spine are offsets of the chain; one that reaches
  // the chain's centre of curvature folds back (its trim line would cross itself).
  const Vec3 kappa = chain_curvature(chain, s, r);
  const Vec3 points[3] = {st.contact[0], st.contact[1], st.centre};
  for (int k = 0; k < 3; ++k)
    if (kappa.dot(points[k] - e) >= kFoldRatio) {
      *fit = StationFit{StationMisfit::Curvature, k < 2 ? k : 0, points[k]};
      return st;
    }
  return st;
}

ProfileStation solve_station(const SpineContext& ctx, double s, double r) {
  StationFit fit;
  ProfileStation st = fit_station(ctx, s, r, &fit);
  const Vec3 e = ctx.chain.point_at(s);
  switch (fit.misfit) {
    case StationMisfit::Fits: return st;
    case StationMisfit::FlatEdge:
      throw RoundingError(ErrorCode::RadiusTooLarge, "the edge at " + format_point(e) + " is flat or folded back: no ball fits there");
    case StationMisfit::NoBall:
      throw RoundingError(ErrorCode::RadiusTooLarge, "no ball of radius " + format_number(r) + " touches both base meshes at " + format_point(e) +
                          ": the radius is too large for the faces there");
    case StationMisfit::Wall:
      // (the wall edge touched, or for a vertex contact one at it: either end on a hole's loop)
      if (fit.wall_edge != ~0ull && (on_hole(ctx.mesh, int(fit.wall_edge >> 32), r) || on_hole(ctx.mesh, int(fit.wall_edge & 0xffffffffu), r)))
        throw RoundingError(ErrorCode::RadiusTooLarge, "radius " + format_number(r) + " is too large at " + format_point(e) +
                            ": the ball would reach the edge of a hole in the mesh at " + format_point(fit.at) +
                            " (fill the hole first if it is a flaw of the mesh, or use a smaller radius)");
      throw RoundingError(ErrorCode::RadiusTooLarge, "radius " + format_number(r) + " is too large at " + format_point(e) +
                          ": the ball would reach past the next sharp edge or the mesh boundary at " + format_point(fit.at));
    case StationMisfit::BeyondReach:
      throw RoundingError(ErrorCode::BeyondReach, "the ball at " + format_point(e) + " touches the base mesh beyond the reach; "
                          "increase the reach factor");
    case StationMisfit::Curvature:
      throw RoundingError(ErrorCode::RadiusTooLarge, "radius " + format_number(r) + " is too large at " + format_point(e) +
                          ": the chain bends tighter than the ball there (its centre of curvature is " +
                          format_number(1 / chain_curvature(ctx.chain, s, r).norm()) + " mm away), so the round's edge would fold back at " +
                          format_point(fit.at));
  }
  return st;
}

ProfileStation solve_station(const SpineContext& ctx, const RadiusLaw& law, double s) {
  poll_cancel();
  try {
    return solve_station(ctx, s, law.at(s));
  } catch (const RoundingError& e) {
    const std::string control = law.nearest_control(s);
    if (control.empty()) throw;
    throw RoundingError(e.code, std::string(e.what()) + " (radius law, nearest to " + control + ")");
  }
}

}  // namespace meshround
