// The tessellation pass (tessellate.h) and its sub-passes (tessellate_rows.h): the round's rows placed on the
// surface, zipped into facets and refined until they keep the tolerance; the band controls' rules.
#include "meshround/tessellate.h"
#include "meshround/cancel.h"
#include "tessellate_rows.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unordered_set>

#include <Eigen/Dense>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <gp_Pnt.hxx>

namespace meshround {
namespace {

// v of the point at `fraction` of the profile's angle, on the profile at u (angle measured at the centre).
double v_at_angle_fraction(const RoundingSurface& s, const ProfileStation& st, double fraction) {
  const Vec3 a = (st.contact[0] - st.centre).normalized();
  const double target = fraction * st.angle();
  double lo = 0, hi = 1;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    const Vec3 p = (s.value(st.s, mid) - st.centre).normalized();
    (std::acos(std::clamp(a.dot(p), -1.0, 1.0)) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Distance from p to the surface, by Gauss-Newton from the parameters (u, v) that p was made from: the
// surface's parametrisation need not be uniform, so S(u, v) itself may lie beside p along the surface.
// *u, *v become the foot's parameters, v held to the surface's edges.
double project_onto_surface(const RoundingSurface& s, const Vec3& p, double* foot_u, double* foot_v) {
  Vec3 q, su, sv;
  double u = *foot_u, v = *foot_v;
  double best = (s.value(u, v) - p).norm();
  for (int it = 0; it < 6 && best > 0; ++it) {
    s.d1(u, v, q, su, sv);
    Eigen::Matrix2d JtJ;
    JtJ << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
    Eigen::Vector2d step = JtJ.ldlt().solve(Eigen::Vector2d(su.dot(p - q), sv.dot(p - q)));
    if (!step.allFinite()) break;
    // Damped: a step is taken only when it brings the surface point nearer (halved until it does).
    bool improved = false;
    const double before = best;
    for (int half = 0; half < 6 && !improved; ++half, step *= 0.5) {
      const double u2 = u + step(0), v2 = std::clamp(v + step(1), 0.0, 1.0), d = (s.value(u2, v2) - p).norm();
      if (d < best) best = d, u = u2, v = v2, improved = true;
    }
    if (!improved || before - best < 1e-3 * before) break;  // converged
  }
  *foot_u = u, *foot_v = v;
  return best;
}

double distance_to_surface(const RoundingSurface& s, const Vec3& p, double u, double v) { return project_onto_surface(s, p, &u, &v); }

// Distance from p to the rounded result near the surface: to the surface, or, where p's foot lies on a
// contact line (v = 0 or 1), to the surface's tangent plane there -- the face the round meets
// tangentially. Facets between the round's last row and a chord of its trim line lie on that face beside
// the surface's edge (far from the edge where the contact line turns tightly: a rolled corner's), not off
// the result.
double distance_from(const RoundingSurface& s, const Vec3& p, double u, double v) {
  const double d = project_onto_surface(s, p, &u, &v);
  if (v > 0 && v < 1) return d;
  Vec3 q, su, sv, unused;
  s.d1(u, v, q, su, sv);
  Vec3 n = su.cross(sv);
  if (!(n.norm() > 1e-9 * sv.squaredNorm()))  // a contact line shrunk to a point: the normal from just inside
    s.d1(u, v > 0.5 ? 1 - 1e-4 : 1e-4, unused, su, sv), n = su.cross(sv);
  return n.norm() > 0 ? std::min(d, std::abs((p - q).dot(n.normalized()))) : d;
}
// (`far`: beyond it, the distance is measured again by OCCT's projection onto the whole surface, and from both
// contact lines at the same u, the least taken. Where a rolled corner's ring shrinks to nothing, the contact line
// on the face is a point over a stretch of u and the damped projection from (u, v) stalls: the report read
// 0.5-1.0 mm on 8 / 8 / 5 at a box corner, whose facets lie within 0.06 mm of the surface.)
double distance_to_result(const RoundingSurface& s, const Vec3& p, double u, double v, double far) {
  double d = distance_from(s, p, u, v);
  if (d <= far) return d;
  d = std::min({d, distance_from(s, p, u, 0.0), distance_from(s, p, u, 1.0)});
  GeomAPI_ProjectPointOnSurf whole(gp_Pnt(p.x(), p.y(), p.z()), s.surface, s.u_first, s.u_last, 0.0, 1.0);
  return whole.NbPoints() > 0 ? std::min(d, whole.LowerDistance()) : d;
}

// Linear interpolation at u over items sorted by key(item), held constant beyond the ends.
template <class Item, class Key, class Value>
auto interpolate_at(const std::vector<Item>& items, double u, Key key, Value value) {
  auto it = std::lower_bound(items.begin(), items.end(), u, [&](const Item& x, double y) { return key(x) < y; });
  if (it == items.begin()) return value(items.front());
  if (it == items.end()) return value(items.back());
  const Item &a = *(it - 1), &b = *it;
  const double t = (u - key(a)) / std::max(key(b) - key(a), 1e-300);
  return decltype(value(a))((1 - t) * value(a) + t * value(b));
}

}  // namespace

BandControls BandControls::of(const RoundOptions& o) {
  return {o.max_element_angle_deg * M_PI / 180.0, o.element_length, o.max_aspect_ratio};
}

double BandControls::longest_along(double across) const {
  const double by_shape = (max_aspect > 0 ? std::min(max_aspect, kMaxStepRatio) : kMaxStepRatio) * across;
  return element_length > 0 ? std::min(by_shape, element_length) : by_shape;
}

double BandControls::shortest_along(double across) const {
  // With an element length the inner rows keep samples about that far apart (0.7 of it: a trim line's
  // points a little closer than the length stay); else the built-in share of the step across.
  const double lo = element_length > 0 ? 0.7 * element_length : kMinStepRatio * across;
  return std::min(lo, longest_along(across));
}

int profile_segments(const std::vector<ProfileStation>& stations, double tolerance, const BandControls& controls) {
  int n = 2;
  for (const ProfileStation& st : stations) {
    const double step = 2 * std::acos(std::max(0.0, 1 - 0.5 * tolerance / st.radius));  // chord sag <= tol / 2
    n = std::max(n, int(std::ceil(st.angle() / step)));
    if (controls.max_angle > 0) n = std::max(n, int(std::ceil(st.angle() / controls.max_angle - 1e-9)));
    if (controls.max_aspect > 0 && controls.element_length > 0)  // across <= max_aspect x the length along
      n = std::max(n, int(std::ceil(st.radius * st.angle() / (controls.max_aspect * controls.element_length) - 1e-9)));
  }
  return n;
}

double profile_step(const RoundingSurface& surface, const std::vector<ProfileStation>& stations, int segments, double u) {
  return interpolate_at(stations, surface.wrap(u), [](const ProfileStation& st) { return st.s; },
                        [&](const ProfileStation& st) { return st.radius * st.angle() / segments; });
}


Vec3 EdgeOffsets::along(int side, double u) const {
  return interpolate_at(rows_[side], u, [](const auto& x) { return x.first; }, [](const auto& x) -> Vec3 { return x.second; });
}

RowTessellation::RowTessellation(const RoundingSurface& surface, const std::vector<ProfileStation>& stations, double tolerance,
                                 const BandControls& controls, MeshEdit& edit, const SharedEnds& shared)
    : surface(surface), stations(stations), tolerance(tolerance), controls(controls), edit(edit), shared(shared),
      debug(getenv("MESHROUND_DEBUG") != nullptr), period(surface.u_last - surface.u_first) {}

void RowTessellation::place_levels() {
  nv = profile_segments(stations, tolerance, controls);
  // (A capped end's profile is moved onto its end face: the surface there is not the ball's section.)
  for (const ProfileStation& st : stations)
    if (!st.cut.active && (!widest || st.angle() > widest->angle())) widest = &st;
  levels.resize(nv + 1);
  for (int j = 0; j <= nv; ++j) levels[j] = j == 0 ? 0.0 : j == nv ? 1.0 : v_at_angle_fraction(surface, *widest, double(j) / nv);
}

void RowTessellation::read_trim_lines(const TrimLines& trim) {
  // Trim rows, unwrapped and closed on themselves for a loop.
  for (int side = 0; side < 2; ++side) {
    auto& row = trim_row[side];
    for (const TrimPoint& tp : trim.line[side]) row.push_back({tp.vertex, tp.u, double(side)});
    if (row.size() < 2) throw RoundingError(ErrorCode::SurfaceFailed, "the trim line on side " + std::string(side ? "B" : "A") + " is empty");
    if (surface.closed) row.push_back({row.front().id, row.front().u + period, double(side)});
  }
  // Where the base mesh leaves the lofted edge between two profiles (a coarse mesh's creases and tilted
  // facets), the trim points lie off the surface's edge. The inner rows follow them: each is moved by the
  // trim lines' offsets from the edge, fading out towards the middle of the profile, so that rows never
  // cross near a trim line. Facets are measured against this target, the report against the surface.
  offsets = EdgeOffsets(surface, trim_row[0], trim_row[1], edit);
  if (debug)
    for (int side = 0; side < 2; ++side) {
      fprintf(stderr, "row %d:", side);
      for (const RowPoint& p : trim_row[side]) fprintf(stderr, " %d@%.4f", p.id, p.u);
      fprintf(stderr, "\n");
    }
}

// A row's samples from sorted u values: u_lo, those at least scale x h_min from the previous one (and
// from u_hi), u_hi; then gaps longer than scale x h_max split evenly.
std::vector<double> RowTessellation::row_samples(const std::vector<double>& sorted, double scale) const {
  std::vector<double> thinned{u_lo};
  for (double u : sorted)
    if (u - thinned.back() >= scale * h_min(u) && u_hi - u >= scale * h_min(u)) thinned.push_back(u);
  thinned.push_back(u_hi);
  std::vector<double> out{thinned.front()};
  for (size_t i = 1; i < thinned.size(); ++i) {
    const double a = thinned[i - 1], b = thinned[i];
    const int n = std::max(1, int(std::ceil((b - a) / (scale * std::min(h_max(a), h_max(b))))));
    for (int k = 1; k <= n; ++k) out.push_back(a + (b - a) * k / n);
  }
  return out;
}

void RowTessellation::sample_inner_rows() {
  // u samples of the inner rows: both trim lines merged, thinned, gaps filled.
  for (const auto& row : trim_row)
    for (const RowPoint& p : row) us.push_back(p.u);
  std::sort(us.begin(), us.end());
  // A loop's inner rows span exactly one period from the first sample (their last point is their first).
  u_lo = us.front(), u_hi = surface.closed ? u_lo + period : us.back();
  // With an element length the inner rows are evenly spaced at it (the trim lines' points do not set them).
  U = row_samples(controls.element_length > 0 ? std::vector<double>{} : us, 1.0);
}

// Graded rows beside a trim line whose points lie much closer together than the first inner row is far
// (a fine mesh cut by the contact line: a vertex just off the line leaves cut points a fifth of an
// element apart, and a step of that length facing a row a profile step away is a sliver). Rows at a
// half, a quarter, ... of that distance, while the line's typical step (its median) is under
// kGradedStep of the next row out; each samples the trim line's own u thinned to 0.4 of its distance.
void RowTessellation::plan_graded_rows() {
  for (int side = 0; side < 2; ++side) {
    const auto& row = trim_row[side];
    std::vector<double> line_us;
    for (const RowPoint& p : row) line_us.push_back(p.u);
    std::vector<double> steps;  // trim steps relative to the profile step there
    for (size_t i = 1; i < row.size(); ++i)
      steps.push_back((row[i].u - row[i - 1].u) / profile_step(surface, stations, nv, row[i - 1].u));
    std::sort(steps.begin(), steps.end());
    const double typical_step = steps.empty() ? INFINITY : steps[steps.size() / 2];
    for (int k = 1; k <= kGradedRows && !shared.no_graded_rows && typical_step < kGradedStep * 2.0 / (1 << k); ++k) {
      const double share = 1.0 / (1 << k);  // its distance from the line, in profile steps
      graded[side].push_back({v_at_angle_fraction(surface, *widest, side ? 1 - share / nv : share / nv), row_samples(line_us, share)});
    }
  }
  std::reverse(graded[0].begin(), graded[0].end());
}

// One end's straight piece of the row at v, from the face towards the join (which is not included); drops
// the first sample beyond from `mid` (the samples on the lofted part) when it is too near the face.
std::vector<double> RowTessellation::end_piece(int end, double v, std::vector<double>& mid) const {
  const double face_u = end ? u_hi : u_lo, join_u = surface.u_straight[end];
  std::vector<double> piece{face_u};
  if (join_u == face_u) return piece;
  const Vec3 at_face = surface.value(face_u, v);
  const double step = end ? mid.back() - mid[mid.size() - 2] : mid[1] - mid[0];
  const int n = int(std::lround((at_face - surface.value(join_u, v)).norm() / step));
  for (int k = 1; k < n; ++k) piece.push_back(face_u + (join_u - face_u) * k / n);
  const double u_near = end ? mid.back() : mid.front();
  if (n == 0 && mid.size() > 2 && (surface.value(u_near, v) - at_face).norm() < 0.5 * step) {
    if (end) mid.pop_back();
    else mid.erase(mid.begin());
  }
  return piece;
}

// A carried end's straight piece (loft_profiles) is as long on each row as that row's point moves to the
// end face: from nothing beside a contact that meets the face where the balls stop, to the setback. Each
// inner row spaces its own points there, as the step beyond; a row whose piece is shorter than half a step
// keeps only its end point on the face (the first sample beyond too near it is dropped).
std::vector<double> RowTessellation::samples_on_row(const std::vector<double>& samples, double v) const {
  if (surface.closed || (surface.u_straight[0] <= u_lo && surface.u_straight[1] >= u_hi)) return samples;
  std::vector<double> mid;  // the samples on the lofted part
  for (double u : samples)
    if (u > surface.u_straight[0] && u < surface.u_straight[1]) mid.push_back(u);
  if (mid.size() < 2) return samples;
  std::vector<double> out = end_piece(0, v, mid);
  const std::vector<double> last = end_piece(1, v, mid);
  out.insert(out.end(), mid.begin(), mid.end());
  out.insert(out.end(), last.rbegin(), last.rend());
  return out;
}

// An end column lies on its end face's plane (a capped end: the trim lines' offsets within that plane
// only) or is the exact end profile (a mitre's, shared with the other round's).
Vec3 RowTessellation::end_offset(int end, double u, double v) const {
  if (shared.exact_end[end]) return Vec3::Zero();
  const Vec3 d = offsets.at(u, v);
  const EndCut& cut = (end ? stations.back() : stations.front()).cut;
  return cut.active ? Vec3(d - cut.normal * d.dot(cut.normal)) : d;
}

void RowTessellation::add_row(const std::vector<double>& row_u, double v) {
  poll_cancel();
  const std::vector<double> samples = samples_on_row(row_u, v);
  std::vector<RowPoint> row;
  for (size_t i = 0; i < samples.size(); ++i) {
    if (surface.closed && i + 1 == samples.size()) {  // a loop's row ends where it began
      row.push_back({row.front().id, samples[i], v});
      break;
    }
    const bool end = !surface.closed && (i == 0 || i + 1 == samples.size());
    const Vec3 p = surface.value(samples[i], v) + (end ? end_offset(i == 0 ? 0 : 1, samples[i], v) : offsets.at(samples[i], v));
    if (end && shared.at[i == 0 ? 0 : 1]) {  // the other round's vertex at this corner
      const int id = shared.vertex_at(p);
      if (id < 0)
        throw RoundingError(ErrorCode::CornerNotBlendable, "the rounds meeting at " + format_point(p) +
                            " do not meet along one curve (their radii or faces differ there): that corner is not made yet");
      row.push_back({id, samples[i], v});
      continue;
    }
    inner.push_back(p);
    row.push_back({-int(inner.size()), samples[i], v});
  }
  rows.push_back(row);
}

void RowTessellation::make_rows() {
  inner.clear();
  tris.clear();
  rows = {trim_row[0]};
  // The work budget, before the rows are made: every inner row point costs about two facets.
  double planned = 0;
  for (int side = 0; side < 2; ++side)
    for (const GradedRow& g : graded[side]) planned += double(g.U.size());
  planned += double(nv - 1) * double(U.size());
  edit.check_budget(2.0 * (planned + double(edit.new_points.size())), "the round's rows");
  for (const GradedRow& g : graded[0]) add_row(g.U, g.v);
  for (int j = 1; j < nv; ++j) add_row(U, levels[j]);
  for (const GradedRow& g : graded[1]) add_row(g.U, g.v);
  rows.push_back(trim_row[1]);
}

// Zip neighbouring rows, always taking the shorter diagonal.
void RowTessellation::zip_rows() {
  for (size_t j = 0; j + 1 < rows.size(); ++j) {
    poll_cancel();
    const auto &b = rows[j], &t = rows[j + 1];
    size_t i = 0, k = 0;
    while (i + 1 < b.size() || k + 1 < t.size()) {
      bool bottom;
      if (i + 1 >= b.size()) bottom = false;
      else if (k + 1 >= t.size()) bottom = true;
      else bottom = (position(b[i + 1]) - position(t[k])).norm() < (position(b[i]) - position(t[k + 1])).norm();
      if (bottom) tris.push_back({b[i], b[i + 1], t[k]}), ++i;
      else tris.push_back({b[i], t[k + 1], t[k]}), ++k;
    }
  }
}

// The u ranges of the facets that stray from the surface (to refine); the largest distance of any facet
// from the surface itself into the stats.
std::vector<URange> RowTessellation::measure_facets(int round) {
  std::vector<URange> bad;
  stats.max_deviation = 0;
  // Facets between a trim line and its outermost graded row are a fraction of a profile step across:
  // their sag is a fraction of the regular rows', so the centroid alone is measured (the report's
  // figure), and they never call for refinement.
  const double strip_a = graded[0].empty() ? -1 : graded[0].back().v, strip_b = graded[1].empty() ? 2 : graded[1].front().v;
  for (const auto& tri : tris) {
    poll_cancel();
    const bool in_strip = std::all_of(tri.begin(), tri.end(), [&](const RowPoint& p) { return p.v <= strip_a; }) ||
                          std::all_of(tri.begin(), tri.end(), [&](const RowPoint& p) { return p.v >= strip_b; });
    double worst = 0, from_surface = 0;
    for (int e = 0; e < (in_strip ? 1 : 4); ++e) {  // centroid, then the three edge midpoints
      const RowPoint* a = &tri[e == 0 ? 0 : e - 1];
      const RowPoint* b2 = &tri[e == 0 ? 1 : e % 3];
      Vec3 p;
      double u, v;
      if (e == 0) {
        p = (position(tri[0]) + position(tri[1]) + position(tri[2])) / 3;
        u = (tri[0].u + tri[1].u + tri[2].u) / 3, v = (tri[0].v + tri[1].v + tri[2].v) / 3;
      } else {
        p = 0.5 * (position(*a) + position(*b2));
        u = 0.5 * (a->u + b2->u), v = 0.5 * (a->v + b2->v);
      }
      // (measured again only where it would raise the largest so far: see distance_to_result)
      from_surface = std::max(from_surface, distance_to_result(surface, p, u, v, std::max({0.5 * tolerance, stats.max_deviation, from_surface})));
      // A piece of the trim line stays as trimmed (its points were placed by the trim pass for the
      // tolerance): refining the rows cannot bring it nearer.
      if (e > 0 && a->id >= 0 && b2->id >= 0) continue;
      worst = std::max(worst, distance_to_surface(surface, p - offsets.at(u, v), u, v));
    }
    stats.max_deviation = std::max(stats.max_deviation, from_surface);
    if (!in_strip && worst > kRefineShare * tolerance)
      bad.push_back({std::min({tri[0].u, tri[1].u, tri[2].u}), std::max({tri[0].u, tri[1].u, tri[2].u})});
  }
  if (debug) fprintf(stderr, "refine round %d: %zu facets, %zu bad, U %zu, max dev %g\n", round, tris.size(), bad.size(), U.size(), stats.max_deviation);
  return bad;
}

// Refine u where a facet strays from the surface: the inner rows' steps that overlap a bad facet's u range
// halved. False when none is (nothing left to refine).
bool RowTessellation::refine_samples(std::vector<URange>& bad) {
  // Does a bad facet's u range overlap (a, b)? Bad ranges sorted by their start, with the running
  // largest end: one binary search per interval instead of a scan of every bad facet.
  std::sort(bad.begin(), bad.end());
  std::vector<double> reach_end(bad.size());
  for (size_t i = 0; i < bad.size(); ++i) reach_end[i] = std::max(bad[i].second, i ? reach_end[i - 1] : -INFINITY);
  auto overlaps_bad = [&](double a, double b) {
    const size_t n = size_t(std::lower_bound(bad.begin(), bad.end(), b, [](auto& r, double x) { return r.first < x; }) - bad.begin());
    return n > 0 && reach_end[n - 1] > a;
  };
  std::vector<double> refined{U.front()};
  for (size_t i = 1; i < U.size(); ++i) {
    poll_cancel();
    const double a = U[i - 1], b = U[i];
    // Never finer than the least step (a facet that still strays then sits on a trim point that
    // lies off the surface: thinner facets would not bring it nearer).
    const bool split = 0.5 * (b - a) >= h_min(a) && overlaps_bad(a, b);
    if (split) refined.push_back(0.5 * (a + b));
    refined.push_back(b);
  }
  if (refined.size() == U.size()) return false;
  U.swap(refined);
  return true;
}

// Commit: inner points become mesh vertices, facets follow in (u, v) order (counter-clockwise).
RoundMeshStats RowTessellation::commit() {
  std::vector<int> ids(inner.size());
  for (size_t i = 0; i < inner.size(); ++i) ids[i] = edit.add_point(inner[i]);
  auto id_of = [&](const RowPoint& p) { return p.id >= 0 ? p.id : ids[-1 - p.id]; };
  for (const auto& tri : tris) {
    const std::array<int, 3> f{id_of(tri[0]), id_of(tri[1]), id_of(tri[2])};
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
    edit.added.push_back(f);
    ++stats.facets;
  }
  stats.rows = nv + 1 + int(graded[0].size() + graded[1].size());
  return stats;
}

RoundMeshStats mesh_rounding_surface(const RoundingSurface& surface, const std::vector<ProfileStation>& stations,
                                     const TrimLines& trim, double tolerance, const BandControls& controls, MeshEdit& edit,
                                     const SharedEnds& shared) {
  RowTessellation t(surface, stations, tolerance, controls, edit, shared);
  t.place_levels();
  t.read_trim_lines(trim);
  t.sample_inner_rows();
  t.plan_graded_rows();
  for (int round = 0; round < kRefineRounds; ++round) {
    t.make_rows();
    t.zip_rows();
    std::vector<URange> bad = t.measure_facets(round);
    if (bad.empty() || !t.refine_samples(bad)) break;
  }
  return t.commit();
}

}  // namespace meshround
