#include "meshround/sharpen.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>

#include "delta.h"
#include "guard.h"
#include "sharpen_line.h"
#include "strip.h"
#include "meshround/cancel.h"
#include "meshround/mesh_edit.h"
#include "meshround/sew.h"

namespace meshround {
namespace {

using sharpen_detail::Fold;

int side_of(double t) { return t < 0.5 ? -1 : t > 0.5 ? 1 : 0; }

// The image of a vertex in its own section: the arc from contact A to contact B laid, in proportion, onto
// contact A -> corner -> contact B; an end face's vertex then slides along the corner line onto that face.
Vec3 fold_vertex(const StripFrame& strip, const Vec3& p, double r, double snap, double* t_out) {
  const Vec3 P = strip.across(p), O = r * strip.centre_dir;
  const Vec3 ta = O - strip.side[0] * r * strip.normal[0], tb = O - strip.side[1] * r * strip.normal[1];
  auto angle = [](const Vec3& u, const Vec3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); };
  const double phi = angle(ta - O, tb - O);
  double t = std::clamp(angle(P - O, ta - O) / phi, 0.0, 1.0);
  if (std::abs(t - 0.5) < snap) t = 0.5;
  *t_out = t;
  const Vec3 image = t <= 0.5 ? Vec3(ta * (1 - 2 * t)) : Vec3(tb * (2 * t - 1));
  return strip.corner + strip.axis * strip.s_of(p) + image;
}

Vec3 onto_end(const StripFrame& strip, const StripEnd& end, const Vec3& p) {
  return p + strip.axis * ((end.offset - end.normal.dot(p)) / end.normal.dot(strip.axis));
}

// Near a mitre, a round's vertices move along its corner line as its crease does at their place on the arc.
// A crease point slides along the line onto the plane bisecting the two walls (the rebuilt edges meet there:
// on plane A on its diagonal, on the walls down their corner line), by up to 0.29 r at mid-arc; a vertex
// beside it, folded at its own place along the line, would land past it (the fold keeps the place, the crease
// moves). Each vertex within kMitreBlend r of its crease (along the line) is moved by the crease's shift at
// its arc position, tapering to none at that distance: the order along the line is kept.
constexpr double kMitreBlend = 1.0;

Vec3 follow_crease(const RoundStrip& strip, const StripFrame& frame, const Vec3& p, const Vec3& image, double r) {
  if (!strip.mitred || frame.piece < 0) return image;
  const RoundStrip::Piece& piece = strip.pieces[size_t(frame.piece)];
  const Vec3 middle = frame.corner + frame.axis * (0.5 * piece.length);
  Vec3 out = image;
  for (const StripEnd& plane : piece.mitres) {
    const Vec3 crease = onto_end(frame, plane, p);             // the crease at p's place on the arc
    const double from = frame.axis.dot(p - crease);             // p's distance from it along the line
    if (std::abs(from) >= kMitreBlend * r) continue;
    const double shift = frame.axis.dot(onto_end(frame, plane, image) - image) + from;  // the crease's move along the line
    out += frame.axis * (shift * (1 - std::abs(from) / (kMitreBlend * r)));
    // (A vertex a hair past the crease -- the mesher's crease is an approximated curve -- stays on it.)
    if ((plane.normal.dot(out) - plane.offset) * (plane.normal.dot(middle) - plane.offset) < 0) out = onto_end(frame, plane, out);
  }
  return out;
}

// Moves every strip vertex (borders stay) and records its t.
void fold_vertices(const MeshTopology& mesh, const RoundStrip& strip, const SharpenOptions& o, MeshEdit& edit, Fold& fold) {
  for (const auto& [v, role] : strip.role) {
    if (role == StripRole::BorderA || role == StripRole::BorderB) {
      fold.t[v] = role == StripRole::BorderA ? 0.0 : 1.0;
      continue;
    }
    double t;
    Vec3 image = fold_vertex(strip.frame(v), mesh.point(v), strip.radius.at(v), o.snap, &t);
    if (role == StripRole::End) {
      const StripEnd& end = strip.ends[strip.end_of.at(v)];
      if (end.face) image = onto_end(strip.frame(v), end, image);
    }
    if (auto crease = strip.mitre_of.find(v); crease != strip.mitre_of.end()) image = onto_end(strip.frame(v), crease->second.plane, image);
    else image = follow_crease(strip, strip.frame(v), mesh.point(v), image, strip.radius.at(v));
    fold.t[v] = t;
    fold.setback = std::max(fold.setback, (image - mesh.point(v)).norm());
    edit.moved[v] = image;
  }
}

// The point on the corner line where the folded edge (u, v) crosses it.
int split_point(const MeshTopology& mesh, const RoundStrip& strip, MeshEdit& edit, Fold& fold, int u, int v) {
  const std::uint64_t key = edge_key(u, v);
  auto it = fold.split.find(key);
  if (it != fold.split.end()) return it->second;
  const double tu = fold.t.at(u), tv = fold.t.at(v);
  const Vec3 pu = edit.point(u), pv = edit.point(v);
  const double w = (0.5 - tu) / (tv - tu);
  Vec3 q = strip.corner + strip.axis * ((1 - w) * strip.s_of(pu) + w * strip.s_of(pv));
  if (strip.curved) {  // between the two vertices' corner points (each in its own section)
    // A vertex on a mitre's crease takes the other one's round (its point is on both); two on one crease
    // meet the corner line at the mitre's corner; two on the two creases of one round (a CAD mesh's facet
    // the round's length) take that round.
    const auto cu = strip.mitre_of.find(u), cv = strip.mitre_of.find(v);
    const bool on_u = cu != strip.mitre_of.end(), on_v = cv != strip.mitre_of.end();
    const StripFrame* fu = &strip.frame(on_u && !on_v ? v : u);
    const StripFrame* fv = &strip.frame(on_v && !on_u ? u : v);
    const bool one_crease = on_u && on_v && cu->second.pieces[0] == cv->second.pieces[0] && cu->second.pieces[1] == cv->second.pieces[1];
    if (one_crease) fv = fu;  // both feet on one round's corner line, which meets the crease's plane at the corner
    if (on_u && on_v && !one_crease)
      for (int p : cu->second.pieces)
        if (p == cv->second.pieces[0] || p == cv->second.pieces[1]) fu = fv = &strip.pieces[size_t(p)].frame;
    q = (1 - w) * strip.foot(*fu, pu) + w * strip.foot(*fv, pv);
    if (one_crease) q = onto_end(*fu, cu->second.plane, q);
  }
  auto eu = strip.end_of.find(u), ev = strip.end_of.find(v);
  if (eu != strip.end_of.end() && ev != strip.end_of.end() && eu->second == ev->second && strip.ends[eu->second].face)
    q = onto_end(strip.curved ? strip.end_frame[eu->second] : strip, strip.ends[eu->second], q);
  (void)mesh;
  return fold.split[key] = edit.add_point(q);
}

// Triangles of a convex polygon (3 or 4 corners; a quad split along its diagonal with the larger smallest angle).
void add_pieces(MeshEdit& edit, const std::vector<int>& poly) {
  if (poly.size() < 3) return;
  if (poly.size() == 3) {
    edit.added.push_back({poly[0], poly[1], poly[2]});
    return;
  }
  auto p = [&](int i) { return edit.point(poly[size_t(i % 4)]); };
  double d02 = std::min(smallest_angle(p(0), p(1), p(2)), smallest_angle(p(0), p(2), p(3)));
  double d13 = std::min(smallest_angle(p(1), p(2), p(3)), smallest_angle(p(1), p(3), p(0)));
  // A split whose halves overlap (their areas add up to more than the quad's: near a mitre's corner a corner
  // of the quad can lie on its opposite side, a crease's image on the diagonal) is not one: the other, whose
  // flat half drop_flat_facets resolves.
  auto area = [&](int a, int b, int c) { return 0.5 * (p(b) - p(a)).cross(p(c) - p(a)).norm(); };
  const double quad = 0.25 * ((p(2) - p(0)).cross(p(3) - p(1))).norm() * 2;
  if (area(0, 1, 2) + area(0, 2, 3) > quad * (1 + 1e-9) + 1e-300) d02 = -1;
  if (area(1, 2, 3) + area(1, 3, 0) > quad * (1 + 1e-9) + 1e-300) d13 = -1;
  if (d02 >= d13) edit.added.push_back({poly[0], poly[1], poly[2]}), edit.added.push_back({poly[0], poly[2], poly[3]});
  else edit.added.push_back({poly[1], poly[2], poly[3]}), edit.added.push_back({poly[1], poly[3], poly[0]});
}

// Strip facets across the corner line are split on it: the part on each side, in that side's plane.
int split_facets(const MeshTopology& mesh, const RoundStrip& strip, MeshEdit& edit, Fold& fold) {
  int count = 0;
  for (int f : strip.facets) {
    std::vector<int> poly;
    std::vector<int> side;
    bool any = false;
    for (int k = 0; k < 3; ++k) {
      const int u = mesh.F(f, k), v = mesh.F(f, (k + 1) % 3);
      poly.push_back(u), side.push_back(side_of(fold.t.at(u)));
      if (side_of(fold.t.at(u)) * side_of(fold.t.at(v)) < 0) poly.push_back(split_point(mesh, strip, edit, fold, u, v)), side.push_back(0), any = true;
    }
    if (!any) continue;
    ++count;
    edit.removed.insert(f);
    for (int want : {-1, 1}) {
      std::vector<int> piece;
      for (size_t i = 0; i < poly.size(); ++i)
        if (side[i] * want >= 0) piece.push_back(poly[i]);
      add_pieces(edit, piece);
    }
  }
  return count;
}

// Around a concave round's rebuilt corner, the end face's vertices within this share of r of the corner
// are re-meshed too; its outline is then triangulated with inner points while a triangle is under
// kEndQualityDeg (within kEndMargin + 1 radii of the corner line).
constexpr double kEndMargin = 0.25, kEndQualityDeg = 20;

// A concave round fills the corner: its end face lies on the corner's side of the arc, away from the ball's
// centre (a convex round's end face lies on the centre's side). Voted over the end facets along the arc.
bool concave_at(const MeshTopology& mesh, const RoundStrip& round, const StripEnd& end, double r) {
  int votes = 0;
  for (int g : end.facets) {
    int on[3], n_on = 0, off = -1;
    for (int k = 0; k < 3; ++k)
      if (round.role.count(mesh.F(g, k))) on[n_on++] = mesh.F(g, k);
      else off = mesh.F(g, k);
    if (n_on != 2 || off < 0) continue;
    const StripFrame& strip = round.frame(on[0]);
    const Vec3 O = r * strip.centre_dir;
    const Vec3 a = strip.across(mesh.point(on[0])), b = strip.across(mesh.point(on[1])), x = strip.across(mesh.point(off));
    const Vec3 side = (b - a).cross(strip.axis);  // the chord's normal in the section
    votes += side.dot(x - a) * side.dot(O - a) < 0 ? 1 : -1;
  }
  return votes > 0;
}

// The end face's facets re-meshed near the corner: those touching a moved vertex, and for a concave round
// those reaching into the corner the round filled (on the round's side of both planes), are replaced by a
// triangulation of their outline, whose arc now runs along the two sides to the corner.
int remesh_end(const MeshTopology& mesh, const RoundStrip& round, int e, double r, double flat_deg, MeshEdit& edit, const Fold& fold) {
  const RoundStrip& strip = round;
  const StripFrame& frame = round.curved ? round.end_frame[e] : round;  // the planes and corner line at this end
  const StripEnd& end = strip.ends[e];
  const double cos_flat = std::cos(2 * flat_deg * M_PI / 180);
  auto on_face = [&](int g) { return !strip.facet_set.count(g) && std::abs(mesh.facet_normal(g).dot(end.normal)) >= cos_flat; };
  std::unordered_set<int> patch;
  std::vector<int> queue;
  for (const auto& [v, end_v] : strip.end_of) {
    if (end_v != e || !edit.moved.count(v)) continue;
    for (const int* g = mesh.facets_begin(v); g != mesh.facets_end(v); ++g)
      if (on_face(*g) && patch.insert(*g).second) queue.push_back(*g);
  }
  if (concave_at(mesh, strip, end, r)) {
    // Vertices in the corner, or within kEndMargin * r of it (they would leave slivers along the rebuilt
    // edge's ends), go with their facets.
    const double margin = kEndMargin * r;
    auto in_corner = [&](int v) {
      const Vec3 p = mesh.point(v);
      return frame.side[0] * (frame.normal[0].dot(p) - frame.offset[0]) > -margin && frame.side[1] * (frame.normal[1].dot(p) - frame.offset[1]) > -margin &&
             frame.across(p).norm() <= (1 + kEndMargin) * r && !strip.role.count(v);
    };
    while (!queue.empty()) {
      const int f = queue.back();
      queue.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int g = mesh.neighbour(f, mesh.F(f, k), mesh.F(f, (k + 1) % 3));
        if (g < 0 || patch.count(g) || !on_face(g)) continue;
        if (in_corner(mesh.F(g, 0)) || in_corner(mesh.F(g, 1)) || in_corner(mesh.F(g, 2))) patch.insert(g), queue.push_back(g);
      }
    }
  }
  // The outline: the patch's edges whose other facet is not in it, in the patch's own direction. Where it
  // touches itself (a CAD mesh's end face of a few facets: two of them fanning from the arc meet at a far
  // corner), the face's facets around that vertex join the patch.
  std::unordered_map<int, int> next;
  while (next.empty()) {
    int pinch = -1;
    for (int f : patch)
      for (int k = 0; k < 3 && pinch < 0; ++k) {
        const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
        const int g = mesh.neighbour(f, a, b);
        if (g >= 0 && patch.count(g)) continue;
        if (!next.emplace(a, b).second) pinch = a;
      }
    if (pinch < 0) break;
    next.clear();
    const size_t before = patch.size();
    for (const int* g = mesh.facets_begin(pinch); g != mesh.facets_end(pinch); ++g)
      if (on_face(*g)) patch.insert(*g);
    if (patch.size() == before)
      throw RoundingError(ErrorCode::ResultInvalid, "the end face at " + format_point(mesh.point(pinch)) + " around the rebuilt corner is not one "
                          "patch (its outline touches itself); nothing was changed");
  }
  if (next.empty()) {  // no facet of the end face around a moved end vertex (a round one element across)
    const int g = end.facets.empty() ? -1 : end.facets[0];
    const Vec3 at = g < 0 ? frame.corner : Vec3((mesh.corner(g, 0) + mesh.corner(g, 1) + mesh.corner(g, 2)) / 3);
    throw RoundingError(ErrorCode::ResultInvalid, "the end face at " + format_point(at) + " around the rebuilt corner was not "
                        "found (no facet of it meets the round's end); nothing was changed");
  }
  std::vector<int> loop{next.begin()->first};
  while (true) {
    const int a = loop.back();
    const int b = next.at(a);
    auto q = fold.split.find(edge_key(a, b));
    if (q != fold.split.end()) loop.push_back(q->second);
    if (b == loop.front()) break;
    loop.push_back(b);
    if (loop.size() > 2 * next.size() + 2) break;
  }
  size_t own = 0;
  for (int v : loop) own += next.count(v);
  if (own != next.size())
    throw RoundingError(ErrorCode::ResultInvalid, "the end face at " + format_point(edit.point(loop.front())) +
                        " around the rebuilt corner has a hole or is not one patch; nothing was changed");
  Vec3 normal = Vec3::Zero();  // Newell's normal of the outline
  for (size_t i = 0; i < loop.size(); ++i) normal += edit.point(loop[i]).cross(edit.point(loop[(i + 1) % loop.size()]));
  for (int f : patch) edit.removed.insert(f);
  const Vec3 corner = frame.corner, axis = frame.axis;
  Refinement fill;
  fill.quality_deg = kEndQualityDeg;
  fill.admit = [corner, axis, r](const Vec3& p) { const Vec3 d = p - corner; return (d - axis * axis.dot(d)).norm() <= (1 + kEndMargin) * r; };
  triangulate_polygon(edit, loop, normal, edit.added, fill);
  return int(patch.size());
}

// The corner line as a chain, for the output check's reach (guard.h).
SharpChain corner_chain(const RoundStrip& strip) {
  SharpChain chain;
  chain.points = {strip.corner + strip.s_lo * strip.axis, strip.corner + strip.s_hi * strip.axis};
  chain.arc_length = {0.0, strip.s_hi - strip.s_lo};
  chain.length = strip.s_hi - strip.s_lo;
  if (strip.closed) {  // the stations' corner points all around
    chain.closed = true;
    chain.points = strip.line;
    chain.arc_length = strip.line_s;
    chain.length = strip.loop_length;
  } else if (strip.curved) {  // the stations' corner points between the ends
    chain.points = {strip.point_at(strip.s_lo)};
    for (size_t i = 0; i < strip.line.size(); ++i)
      if (strip.line_s[i] > strip.s_lo && strip.line_s[i] < strip.s_hi) chain.points.push_back(strip.line[i]);
    chain.points.push_back(strip.point_at(strip.s_hi));
    chain.arc_length = {0.0};
    for (size_t i = 1; i < chain.points.size(); ++i) chain.arc_length.push_back(chain.arc_length.back() + (chain.points[i] - chain.points[i - 1]).norm());
    chain.length = chain.arc_length.back();
  }
  return chain;
}

double changed_reach(const MeshEdit& edit, const SharpChain& chain) {
  double reach = 0;
  auto see = [&](int v) {
    double d;
    chain.project(edit.point(v), &d);
    reach = std::max(reach, d);
  };
  for (int f : edit.removed)
    for (int k = 0; k < 3; ++k) see(edit.input.F(f, k));
  for (const auto& f : edit.added)
    for (int v : f) see(v);
  return reach;
}

// One strip: recognised, measured, folded, its ends re-meshed, checked and written.
StripReport sharpen_one(const MeshTopology& mesh, const Vec3& seed, const SharpenOptions& o, Points& V_out, Triangles& F_out,
                        StepOrigin* origin) {
  const RoundStrip strip = recognise_strip(mesh, seed, o);
  StripReport rep;
  measure_law(mesh, strip, o, rep);
  poll_cancel();
  MeshEdit edit(mesh);
  edit.max_new_facets = o.max_new_facets;
  Fold fold;
  fold_vertices(mesh, strip, o, edit, fold);
  rep.facets_split = split_facets(mesh, strip, edit, fold);
  for (int e = 0; e < 2; ++e)
    if (strip.ends[e].face) ++rep.end_faces, rep.end_facets_remeshed += remesh_end(mesh, strip, e, rep.found_radius, o.flat_deg, edit, fold);
  rep.points_merged = sharpen_detail::merge_close_points(mesh, strip, rep.found_radius, edit, fold);
  if (strip.mitred) sharpen_detail::drop_flat_facets(mesh, strip, edit);
  rep.border_flips = sharpen_detail::unkink_borders(mesh, strip, edit);
  const SharpChain chain = corner_chain(strip);
  check_result(edit, chain, changed_reach(edit, chain) * 1.001 + 1e-9, fold.setback);
  write_mesh(edit, V_out, F_out, origin);
  rep.opening_deg = std::acos(std::clamp(strip.normal[0].dot(strip.normal[1]), -1.0, 1.0)) * 180 / M_PI;
  rep.convex = true;
  for (int e = 0; e < 2; ++e)
    if (strip.ends[e].face) rep.convex = !concave_at(mesh, strip, strip.ends[e], rep.found_radius);
  rep.corner[0] = chain.points.front(), rep.corner[1] = chain.points.back();
  rep.corner_line = chain.points;
  if (strip.mitred) rep.mitres = int(strip.pieces.size()) - (strip.closed ? 0 : 1);
  rep.strip_facets = int(strip.facets.size());
  rep.border_vertices[0] = strip.border_count[0], rep.border_vertices[1] = strip.border_count[1];
  rep.recognised = strip.recognised;
  return rep;
}

void validate(const SharpenOptions& o) {
  auto bad = [](const std::string& what) { throw RoundingError(ErrorCode::InvalidInput, what); };
  if (!(o.strip_turn_deg > 0 && o.strip_turn_deg < 180)) bad("strip_turn_deg must lie in (0, 180)");
  if (!(o.flat_deg > 0 && o.flat_deg < o.strip_turn_deg)) bad("flat_deg must lie in (0, strip_turn_deg)");
  if (!(o.axis_tilt_deg > 0 && o.axis_tilt_deg < 90)) bad("axis_tilt_deg must lie in (0, 90)");
  if (!(o.facet_tilt_deg > 0 && o.facet_tilt_deg < 90)) bad("facet_tilt_deg must lie in (0, 90)");
  if (!(o.fit_tolerance > 0 && o.fit_tolerance < 1)) bad("fit_tolerance must lie in (0, 1)");
  if (!(o.measure_clearance >= 0 && o.measure_clearance < 0.5)) bad("measure_clearance must lie in [0, 0.5)");
  if (!(o.law_step > 0) || !(o.snap >= 0 && o.snap < 0.5) || o.max_new_facets < 1) bad("law_step, snap or max_new_facets out of range");
}

// A seed on a strip sharpened before in the same call (within 2 r of its corner line, along it).
bool already_done(const std::vector<StripReport>& done, const Vec3& seed) {
  for (const StripReport& s : done) {
    if (s.corner_line.size() > 2) {  // a curved corner line: near one of its segments
      for (size_t i = 0; i + 1 < s.corner_line.size(); ++i) {
        const Vec3 a = s.corner_line[i], d = s.corner_line[i + 1] - a;
        const double w = std::clamp(d.dot(seed - a) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
        if ((a + w * d - seed).norm() <= 2 * s.found_radius) return true;
      }
      continue;
    }
    const Vec3 d = s.corner[1] - s.corner[0];
    const double L = d.norm(), along = d.dot(seed - s.corner[0]) / L;
    const double off = (seed - s.corner[0] - d * (along / L)).norm();
    if (off <= 2 * s.found_radius && along >= -s.found_radius && along <= L + s.found_radius) return true;
  }
  return false;
}

// sharpen_rounds; `lineage` (if given) follows each vertex and facet of the result back to the input.
SharpenResult sharpen_traced(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const SharpenOptions& o,
                             Lineage* lineage) {
  validate(o);
  if (seeds.empty()) throw RoundingError(ErrorCode::InvalidInput, "no seed given: pick a point on an existing round");
  SharpenResult out;
  out.vertices = V, out.triangles = F;
  for (const Vec3& seed : seeds) {
    if (!seed.allFinite()) throw RoundingError(ErrorCode::InvalidInput, "a seed has a NaN or infinite coordinate");
    if (already_done(out.strips, seed)) continue;
    const MeshTopology mesh(out.vertices, out.triangles);
    Points next_V;
    Triangles next_F;
    StepOrigin step;
    out.strips.push_back(sharpen_one(mesh, seed, o, next_V, next_F, lineage ? &step : nullptr));
    out.vertices.swap(next_V), out.triangles.swap(next_F);
    if (lineage) *lineage = follow(*lineage, step);
  }
  return out;
}

}  // namespace

SharpenResult sharpen_rounds(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const SharpenOptions& o) {
  return sharpen_traced(V, F, seeds, o, nullptr);
}

ChangeRadiusResult change_radius(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const RoundOptions& round,
                                 const SharpenOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const CancelScope cancel_scope(round.cancelled);
  poll_cancel();
  const bool sharpen_only = round.radius_law.empty() && round.radius == 0;
  if (!sharpen_only) validate_options(round);
  SharpenOptions o = options;
  o.max_new_facets = std::min(o.max_new_facets, round.max_new_facets);
  Lineage lineage;  // each vertex / facet of the sharpened mesh: the input's it is, or -1
  SharpenResult sharp = sharpen_traced(V, F, seeds, o, &lineage);
  ChangeRadiusResult out;
  out.strips = sharp.strips;
  out.seconds_sharpen = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (sharpen_only) {
    out.round.delta = delta_from_lineage(V, F, sharp.vertices, sharp.triangles, lineage);
    if (round.write_arrays) out.round.vertices.swap(sharp.vertices), out.round.triangles.swap(sharp.triangles);
    out.round.report.seconds_total = out.seconds_sharpen;
    return out;
  }
  std::vector<Vec3> corner_seeds;
  for (const StripReport& s : sharp.strips) {
    if (s.mitres > 0) {  // a seed on each round's sharp edge (round_edges mitres them again)
      const size_t n = s.corner_line.size(), segments = n - (s.mitres == int(n) ? 0 : 1);
      for (size_t i = 0; i < segments; ++i) corner_seeds.push_back(0.5 * (s.corner_line[i] + s.corner_line[(i + 1) % n]));
      continue;
    }
    corner_seeds.push_back(s.corner_line.size() > 2 ? s.corner_line[s.corner_line.size() / 2] : Vec3(0.5 * (s.corner[0] + s.corner[1])));
  }
  RoundOptions again = round;
  again.write_arrays = false;  // made below, with where each vertex and facet comes from
  out.round = round_edges(sharp.vertices, sharp.triangles, corner_seeds, again);
  // The two steps as one edit of the caller's input (a solver deck keeps what the band does not touch).
  StepOrigin step;
  apply_delta(sharp.vertices, sharp.triangles, out.round.delta, out.round.vertices, out.round.triangles, &step);
  out.round.delta = delta_from_lineage(V, F, out.round.vertices, out.round.triangles, follow(lineage, step));
  if (!round.write_arrays) out.round.vertices.resize(0, 3), out.round.triangles.resize(0, 3);
  out.round.report.seconds["sharpen"] = out.seconds_sharpen;
  out.round.report.seconds_total += out.seconds_sharpen;
  return out;
}

}  // namespace meshround
