#include "meshround/round.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <cmath>
#include <array>
#include <set>

#include "delta.h"
#include "corner_report.h"
#include "meshround/element_quality.h"
#include "call_checks.h"
#include "ends.h"
#include "facet_quality.h"
#include "guard.h"
#include "network.h"
#include "sphere_corner.h"
#include "stages.h"
#include "meshround/cancel.h"
#include "meshround/radius_law.h"
#include "meshround/improve.h"
#include "meshround/sew.h"
#include "meshround/tessellate.h"

namespace meshround {
namespace {

using Clock = std::chrono::steady_clock;

class PassTimer {
 public:
  explicit PassTimer(RoundReport& r) : report_(r), t_(Clock::now()) {}
  // Every pass's end is also a cancel poll.
  void done(const char* pass) {
    poll_cancel();
    const auto now = Clock::now();
    report_.seconds[pass] += std::chrono::duration<double>(now - t_).count();
    t_ = now;
  }

 private:
  RoundReport& report_;
  Clock::time_point t_;
};

// Largest distance between the lofted surface and the exact ball at arc length s (its profile circle).
double loft_error(const RoundingSurface& surface, const ProfileStation& exact) {
  double worst = 0;
  for (int k = 0; k <= 8; ++k) {
    const Vec3 q = surface.value(exact.s, k / 8.0);
    worst = std::max(worst, std::abs((q - exact.centre).norm() - exact.radius));
  }
  return worst;
}

// Stations closer than this share of the radius are not resolved further: where a coarse mesh's crease makes the
// contact jump, a finer spacing only makes the loft ring (r / 20 everywhere failed 8 tests) ...
constexpr double kStationStepShare = 0.25;
// ... but within kTightRingReach radii of a rolled corner with a tight ring (network.h RolledCorner::tight) they
// are, down to this share: there the balls' centres turn round a ring far smaller than the balls and their
// contacts on the odd round's end sweep at up to 16 times the centres' pace (a quarter r left 7.5 / 7.5 / 8 on a
// box corner 0.0131 r off OCCT's torus just past the ring's start; a twentieth, 0.0094 r).
constexpr double kTightRingStepShare = 0.05;
constexpr double kTightRingReach = 2.5;

// Profiles along the chain: uniform to start with, then wherever the loft strays from the exact ball.
// Each station is at least two facets of the round (a quad between it and the next): stations count
// against the work budget as two facets, checked before they are solved.
// An open chain's balls are solved on [s_lo, s_hi] (short of a capped end whose face leans over the
// round, see ends.h); a loop's on all of it. `tight_rings` (or null): NetworkPart::tight_rings.
std::vector<ProfileStation> sample_profiles(const SpineContext& ctx, const RadiusLaw& law, double tolerance, long max_new_facets,
                                            double s_lo, double s_hi, const std::vector<Vec3>* tight_rings, RoundingSurface& surface,
                                            double* loft_deviation) {
  const SharpChain& chain = ctx.chain;
  const double L = chain.length, span = s_hi - s_lo;
  const double planned = std::ceil(span / (0.5 * law.min_radius())) + 1;
  check_work_budget(2 * planned, max_new_facets, "profile stations");
  const int n0 = std::max(chain.closed ? 6 : 4, int(planned));
  std::vector<ProfileStation> st;
  for (int i = 0; i < n0; ++i) {
    const double s = chain.closed ? L * i / n0 : s_lo + span * i / (n0 - 1);
    st.push_back(solve_station(ctx, law, s));
  }
  const double min_step = std::max(1e-4 * L, kStationStepShare * law.min_radius());
  const double tight_step = std::max(1e-4 * L, kTightRingStepShare * law.min_radius());
  auto near_tight_ring = [&](const ProfileStation& mid) {
    return tight_rings && std::any_of(tight_rings->begin(), tight_rings->end(), [&](const Vec3& v) {
             return (mid.centre - v).norm() <= kTightRingReach * law.max_radius();
           });
  };
  for (int round = 0; round < 12; ++round) {
    surface = loft_profiles(st, chain.closed, L);
    std::vector<ProfileStation> extra;
    *loft_deviation = 0;
    const size_t intervals = chain.closed ? st.size() : st.size() - 1;
    for (size_t i = 0; i < intervals; ++i) {
      const double a = st[i].s, b = i + 1 < st.size() ? st[i + 1].s : L;
      if (b - a < tight_step || (b - a < min_step && !near_tight_ring(st[i]) && !near_tight_ring(st[(i + 1) % st.size()]))) continue;
      const double s = 0.5 * (a + b);
      ProfileStation mid = solve_station(ctx, law, s);
      const double e = loft_error(surface, mid);
      *loft_deviation = std::max(*loft_deviation, e);
      if (e > 0.1 * tolerance) extra.push_back(mid);
    }
    if (extra.empty()) break;
    check_work_budget(2.0 * double(st.size() + extra.size()), max_new_facets, "profile stations");
    st.insert(st.end(), extra.begin(), extra.end());
    std::sort(st.begin(), st.end(), [](const ProfileStation& x, const ProfileStation& y) { return x.s < y.s; });
  }
  return st;
}


// A round's end at a sphere corner (its station carried onto the corner's plane) is the arc of the
// corner's ball between its feet on the chain's faces, where the other rounds there end too: the carried
// contacts, each round's own ball solved on its own facets, land a few 1e-6 r beside the feet where the
// faces are flat, up to about 1e-3 r where that ball leans on an earlier round's facets. Left as carried
// (the corner then refuses) when a contact lands more than the tolerance off its foot.
void end_on_corner_ball(const CornerEnd& corner, double tolerance, ProfileStation& st) {
  const Vec3 lands[2] = {st.cut.onto(st.contact[0]), st.cut.onto(st.contact[1])};
  const bool swapped = (lands[0] - corner.feet[1]).norm() + (lands[1] - corner.feet[0]).norm() <
                       (lands[0] - corner.feet[0]).norm() + (lands[1] - corner.feet[1]).norm();
  const Vec3 foot[2] = {corner.feet[swapped ? 1 : 0], corner.feet[swapped ? 0 : 1]};
  for (int k = 0; k < 2; ++k)
    if ((lands[k] - foot[k]).norm() > tolerance) return;
  st.centre = corner.plane_point;
  st.contact[0] = foot[0], st.contact[1] = foot[1];
}

// The profiles of a chain's round, its capped ends cut by their end faces or corners (ends.h plan_ends):
// the balls stop at the ends' setbacks and the last one is carried on along the chain onto the plane.
std::vector<ProfileStation> end_cut_profiles(const SpineContext& ctx, const RadiusLaw& law, double tolerance, long max_new_facets,
                                             const NetworkPart& net, RoundingSurface& surface, double* loft_deviation) {
  const SharpChain& chain = ctx.chain;
  const double L = chain.length;
  const EndPlan ends = plan_ends(ctx, law, net, tolerance);
  const EndCut* cut = ends.cut;
  const double* setback = ends.setback;
  std::vector<ProfileStation> st =
      sample_profiles(ctx, law, tolerance, max_new_facets, setback[0], L - setback[1], net.tight_rings, surface, loft_deviation);
  if (!cut[0].active && !cut[1].active) return st;
  for (int end = 0; end < 2; ++end) {
    if (!cut[end].active) continue;
    ProfileStation last = end ? st.back() : st.front();
    const Vec3 shift = setback[end] * cut[end].along;
    last.centre += shift, last.contact[0] += shift, last.contact[1] += shift;
    last.s = end ? L : 0.0;
    last.cut = cut[end];
    last.carried = setback[end] > 0;
    const CornerEnd* corner = corner_at(net, end ? chain.points.back() : chain.points.front());
    if (corner && corner->sphere) end_on_corner_ball(*corner, tolerance, last);
    if (setback[end] == 0) (end ? st.back() : st.front()) = last;
    else if (end) st.push_back(last);
    else st.insert(st.begin(), last);
  }
  surface = loft_profiles(st, false, L);
  return st;
}

// The base meshes are rebuilt: refuse a non-manifold or flipped edge among them (call_checks.h).
// (Degenerate facets are refused while the base meshes are collected.)
void check_base_meshes(const MeshTopology& mesh, const BaseMeshes& base) {
  for (int side = 0; side < 2; ++side) check_facet_edges(mesh, base.facets[side], "the chain");
}

// The reach factors (times the one asked for) tried when a chain's new facets have an angle under
// kThinDeg (facet_quality.h) that no input facet explains: a cut CAD facet far larger than the reach
// leaves only a strip between the trim line and the reach for grading from the round's spacing to the
// facet's far corners.
constexpr double kWiderReaches[] = {1.25, 1.5, 2, 3};
// The probe is not run after a round that made more new facets than this (facets hundreds of times the
// radius, cut by it): its roundings would cost as much again each, for a hint in the report.
constexpr size_t kRoomProbeMaxFacets = 10000;

// Where a chain is picked again on the mesh its round is made on: the middle of one of its edges, and that
// edge's ends in this mesh (or -1: the mesh's facets are searched for it).
struct ChainSeed {
  Vec3 point;
  std::array<int, 2> on_edge{-1, -1};
};

// The ends of the input edge (a, b) in a mesh made from the input (its lineage; empty: the input itself).
std::array<int, 2> edge_in(const Lineage& lineage, std::array<int, 2> edge) {
  if (lineage.vertex.empty()) return edge;
  std::array<int, 2> out{-1, -1};
  for (size_t j = 0; j < lineage.vertex.size(); ++j)
    for (int k = 0; k < 2; ++k)
      if (lineage.vertex[j] == edge[k]) out[k] = int(j);
  return out;
}

RoundedChain round_one_chain(const MeshTopology& mesh, const ChainSeed& seed, const RoundOptions& opt, RoundReport& report,
                             MeshDelta* delta, const NetworkPart& net = {}, std::vector<Vec3>* round_points = nullptr,
                             bool is_probe = false, bool split = false);

// The room probe: the chain is rounded again (and thrown away) at wider reaches, narrowest first (a
// wider band costs more); the first of kWiderReaches that makes no facet under kThinDeg goes into
// rep.reach_for_room (0: none does).
void probe_reach_for_room(const MeshTopology& mesh, const ChainSeed& seed, const RoundOptions& opt, const NetworkPart& net,
                          bool split, ChainReport& rep) {
  auto gives_room = [&](double wider) {
    RoundOptions o = opt;
    o.reach = wider * opt.reach;
    RoundReport scratch;
    try {
      const RoundedChain probe = round_one_chain(mesh, seed, o, scratch, nullptr, net, nullptr, true, split);
      if (probe.report.thin_facets > 0) return false;
    } catch (const RoundingError& e) {
      if (e.code == ErrorCode::Cancelled) throw;
      return false;  // e.g. the wider reach runs into another sharp feature
    }
    rep.reach_for_room = o.reach, rep.min_angle_at_reach_for_room = scratch.min_new_angle_deg;
    return true;
  };
  for (double wider : kWiderReaches)
    if (gives_room(wider)) return;
}

// The rounds made before in this call (net.earlier_round_points): their vertices on `mesh`, which the base
// meshes stop at and a shared corner's end column takes.
void find_earlier_round_vertices(const MeshTopology& mesh, const NetworkPart& net, std::unordered_set<int>& earlier,
                                 std::vector<std::pair<Vec3, int>>& earlier_points) {
  if (net.earlier_round_points.empty()) return;
  std::set<std::array<double, 3>> wanted;
  for (const Vec3& p : net.earlier_round_points) wanted.insert({p.x(), p.y(), p.z()});
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3 p = mesh.point(v);
    if (wanted.count({p.x(), p.y(), p.z()})) earlier.insert(v), earlier_points.push_back({p, v});
  }
}

// A chain's report from its passes' figures, and its spine, contacts and chain points.
void fill_chain_report(const SharpChain& chain, const std::vector<ProfileStation>& stations, const TrimLines& trim, const MeshEdit& edit,
                       const RoundMeshStats& mesh_stats, const SewStats& sew, const ImproveStats& improved, RoundedChain& out) {
  ChainReport& rep = out.report;
  rep.closed = chain.closed;
  rep.length = chain.length;
  rep.stations = int(stations.size());
  rep.facets_removed = int(edit.removed.size());
  rep.facets_cut = trim.facets_cut;
  rep.facets_added = int(edit.added.size());
  rep.vertices_snapped = trim.vertices_snapped;
  rep.mesh_deviation = mesh_stats.max_deviation;
  rep.profile_rows = mesh_stats.rows;
  rep.gap_facets = sew.gap_facets;
  rep.open_gaps = sew.open_gaps;
  rep.edges_flipped = improved.flips;
  rep.vertices_removed = improved.vertices_removed;
  rep.vertices_slid = improved.vertices_slid;
  for (const ProfileStation& st : stations) {
    out.spine.push_back(st.centre);
    for (int k = 0; k < 2; ++k) {
      out.contacts[k].push_back(st.contact[k]);
      rep.contacts_on_edges += st.region[k] == ContactRegion::Edge;
      rep.contacts_on_vertices += st.region[k] == ContactRegion::Vertex;
    }
  }
  out.chain = chain.points;
}

// A chain's figures added to the call's report.
void add_to_call_report(const ChainReport& rep, double min_new, double min_input, RoundReport& report) {
  report.facets_removed += rep.facets_removed;
  report.facets_added += rep.facets_added;
  report.max_deviation = std::max(report.max_deviation, rep.mesh_deviation);
  report.min_new_angle_deg = std::min(report.min_new_angle_deg, min_new);
  report.min_input_angle_deg = std::min(report.min_input_angle_deg, min_input);
  report.thin_facets += rep.thin_facets;
  report.cusp_facets += rep.cusp_facets;
  if (rep.cusp_facets > 0)
    report.cusp_angle_deg = report.cusp_angle_deg > 0 ? std::min(report.cusp_angle_deg, rep.cusp_angle_deg) : rep.cusp_angle_deg;
  if (rep.reach_for_room > 0) report.thin_facets_short_of_room += rep.thin_facets;
  report.reach_for_room = std::max(report.reach_for_room, rep.reach_for_room);
}

// `split`: the mesh is the input already split along the chain's end segments (ends.h). `net`: its corners
// with other chains of the call; `round_points` (if given) gets the round's vertices. `delta`: the result,
// as an edit of `mesh` (none for a probe).
RoundedChain round_one_chain(const MeshTopology& mesh, const ChainSeed& seed, const RoundOptions& opt, RoundReport& report,
                             MeshDelta* delta, const NetworkPart& net, std::vector<Vec3>* round_points,
                             bool is_probe, bool split) {
  PassTimer timer(report);
  const double r_max = opt.max_radius();
  SharpChain chain = trace_chain(mesh, seed.point, opt.feature_angle_deg, opt.reach * r_max, seed.on_edge);
  chain.index_segments();
  const RadiusLaw law(opt, chain, opt.reach * r_max);
  const double reach = opt.reach * law.max_radius();
  std::unordered_set<int> earlier;
  std::vector<std::pair<Vec3, int>> earlier_points;
  find_earlier_round_vertices(mesh, net, earlier, earlier_points);
  const BaseMeshes base = collect_base_meshes(mesh, chain, reach, opt.feature_angle_deg, earlier.empty() ? nullptr : &earlier);
  check_base_meshes(mesh, base);
  timer.done("chain");

  const double tol = opt.tolerance > 0 ? opt.tolerance : law.max_radius() / 100.0;
  const BaseDistance dist_a(mesh, base.facets[0], net.earlier_rounds), dist_b(mesh, base.facets[1], net.earlier_rounds);
  const SpineContext ctx{mesh, chain, base, {&dist_a, &dist_b}};
  RoundingSurface surface;
  RoundedChain out;
  const std::vector<ProfileStation> stations = end_cut_profiles(ctx, law, tol, opt.max_new_facets, net, surface, &out.report.surface_deviation);
  timer.done("surface");
  const BandControls controls = BandControls::of(opt);
  const int segments = profile_segments(stations, tol, controls);
  const auto step = [&](double u) { return profile_step(surface, stations, segments, u); };  // across the profile at u
  if (!split) {  // a base mesh going on past an end face's plane: split along the band's corner, round that
    MeshDelta split_delta;
    if (split_along_end_segments(mesh, end_segments(mesh, chain, base, stations, surface, step), kCornerWeldShare * tol, split_delta)) {
      Points V_split;
      Triangles F_split;
      StepOrigin from_split;
      apply_delta(mesh.V, mesh.F, split_delta, V_split, F_split, &from_split);
      const MeshTopology split_mesh(V_split, F_split);
      timer.done("ends");
      MeshDelta on_split;
      const ChainSeed on_split_mesh{seed.point, edge_in(Lineage{from_split.vertex, from_split.facet}, seed.on_edge)};
      RoundedChain out = round_one_chain(split_mesh, on_split_mesh, opt, report, delta ? &on_split : nullptr, net, round_points, is_probe, true);
      if (delta) {  // the split and the round, checked again as the one edit of `mesh` they are
        *delta = delta_through(mesh.V, mesh.F, V_split, F_split, from_split, on_split);
        check_result(edit_of(mesh, *delta), chain, reach, tol, net.chains);
      }
      return out;
    }
  }

  MeshEdit edit(mesh);
  edit.max_new_facets = opt.max_new_facets;
  auto spacing = [&](double u) { return std::max(controls.longest_along(step(u)), 1e-6); };
  // The round's rows x columns at these steps, and a row of cut facets beside each trim line (a lower bound
  // of the facets made) against the work budget, before the trim spaces its lines at them: a tiny element
  // angle or length is refused at once.
  double columns = 0;
  for (size_t i = 1; i < stations.size(); ++i)
    columns += (stations[i].s - stations[i - 1].s) / spacing(0.5 * (stations[i].s + stations[i - 1].s));
  edit.check_budget(2.0 * (segments + 2) * columns, "the round's rows and columns at its element steps");
  // Cut facets and end caps get inner points for shape, but only within the reach: beyond it every
  // facet is the input's own, or one whose other corners reach into the band.
  auto within_reach = [&](const Vec3& p) {
    double d;
    chain.project(p, &d);
    return d <= reach;
  };
  // Gaps a quarter of the tolerance from flat (a variable round's end profile is tilted by the radius's
  // slope) are filled like flat ones.
  const Refinement shape{20.0, within_reach, 0.25 * tol};
  const TrimLines trim = trim_base_meshes(mesh, chain, base, surface, stations, {tol, spacing, shape}, edit);
  timer.done("trim");
  const size_t round_begin = edit.added.size();
  SharedEnds shared;
  for (int end = 0; end < 2 && !chain.closed; ++end) {
    const CornerEnd* c = corner_at(net, end ? chain.points.back() : chain.points.front());
    shared.no_graded_rows |= c != nullptr && !c->sphere;  // both rounds at a mitre make the same rows
    shared.exact_end[end] = c != nullptr && !c->sphere;
    shared.at[end] = c && c->other_made;
  }
  // The two rounds' end columns are the same points, each computed from its own balls: where those are
  // solved (drafted walls) they agree to about 1e-6 r, far closer than any two points of a column. Faces
  // flat only to a mesher's float precision move the balls apart more: a box's top edges sharpened from a
  // MeshPart mesh of their rounds (its contact vertices 3e-5 mm off the top face) gave columns 1e-3 of the
  // tolerance apart at r = 3, 4 and 6; made again at its own 5 mm, 0.057 of it: a ball moves by r times the
  // tilt of the facet it touches, and a sharpened face keeps the old round's vertices 0.018 mm from its
  // contact line 3e-5 mm off the face (on the old cylinder), which tilts their facets by 0.1 deg. The weld
  // (guard.h kCornerWeldShare of the tolerance) is still far below a column's spacing.
  const double weld = kCornerWeldShare * tol;
  shared.vertex_at = [&](const Vec3& p) {
    for (const auto& [q, v] : earlier_points)
      if ((q - p).norm() <= weld) return v;
    return -1;
  };
  const RoundMeshStats mesh_stats = mesh_rounding_surface(surface, stations, trim, tol, controls, edit, shared);
  timer.done("tessellate");
  const SewStats sew = sew_round(edit, round_begin, round_begin + mesh_stats.facets, shape);
  timer.done("sew");
  // The round's vertices (its trim lines included) stay; the rest of the new facets are tidied.
  std::unordered_set<int> round_vertices;
  for (size_t f = round_begin; f < round_begin + mesh_stats.facets; ++f)
    round_vertices.insert(edit.added[f].begin(), edit.added[f].end());
  const ImproveStats improved = improve_new_facets(edit, round_vertices, within_reach);
  if (round_points)
    for (int v : round_vertices) round_points->push_back(edit.point(v));
  timer.done("improve");
  check_result(edit, chain, reach, tol, net.chains);  // refuses a result worse than its input (guard.h)
  timer.done("check");
  if (delta) *delta = delta_from_edit(edit);  // a probe only counts thin facets (below)
  timer.done("write");

  ChainReport& rep = out.report;
  fill_chain_report(chain, stations, trim, edit, mesh_stats, sew, improved, out);
  if (!is_probe) out.brep = face_to_brep(surface.face);

  double min_new = 180, min_input = 180;
  rep.thin_facets = count_thin_facets(mesh, edit, &min_new, &min_input);
  if (split && rep.thin_facets > 0) {  // at an end cap's cusp (ends.h)
    double cusp = 180;
    std::vector<CuspPoint> cusps;
    for (const EndSegment& seg : end_segments(mesh, chain, base, stations, surface, step)) cusps.push_back({seg.corner, seg.cusp_step, seg.radius});
    rep.cusp_facets = count_cusp_facets(edit, cusps, &cusp);
    if (rep.cusp_facets > 0) rep.cusp_angle_deg = cusp;
  }
  // Thin facets neither the input nor a cusp explains: would a larger reach give them room?
  if (!is_probe && rep.thin_facets > rep.cusp_facets && min_input >= kThinDeg && edit.added.size() <= kRoomProbeMaxFacets) {
    probe_reach_for_room(mesh, seed, opt, net, split, rep);
    timer.done("room");
  }
  add_to_call_report(rep, min_new, min_input, report);
  return out;
}

}  // namespace

std::vector<SharpChain> find_chains(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds,
                                    double feature_angle_deg, double search_radius) {
  RoundOptions checked;
  checked.feature_angle_deg = feature_angle_deg;
  validate_options(checked);
  const MeshTopology mesh(V, F);
  return find_chains(mesh, seeds, feature_angle_deg, search_radius);
}

std::vector<SharpChain> find_chains(const MeshTopology& mesh, const std::vector<Vec3>& seeds, double feature_angle_deg,
                                    double search_radius) {
  if (!(search_radius > 0)) search_radius = 0.05 * (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  std::vector<SharpChain> chains;
  std::set<std::vector<int>> seen;
  for (const Vec3& seed : seeds) {
    if (!seed.allFinite()) throw RoundingError(ErrorCode::InvalidInput, "a seed has a NaN or infinite coordinate");
    SharpChain c = trace_chain(mesh, seed, feature_angle_deg, search_radius);
    std::vector<int> key = c.vertices;
    std::sort(key.begin(), key.end());
    if (seen.insert(key).second) chains.push_back(std::move(c));
  }
  return chains;
}

void rethrow_on_own_mesh(const RoundingError& e, const MeshTopology& input, const Vec3& picked, const RoundOptions& opt) {
  if (e.code != ErrorCode::NonManifoldInput && e.code != ErrorCode::NoSharpEdge) throw;
  // A hole or a flipped facet the band ran over, there on the input too: the input's (rethrown whole, so
  // that a caller of a caller still sees where it lies)
  if (const auto* flaw = dynamic_cast<const InputFlaw*>(&e); flaw && flawed_near(input, flaw->where, opt.max_radius())) throw;
  try {  // the same chain's base meshes on the input: a fault there is the input's, named as such
    const SharpChain chain = trace_chain(input, picked, opt.feature_angle_deg, opt.reach * opt.max_radius());
    check_base_meshes(input, collect_base_meshes(input, chain, opt.reach * opt.max_radius(), opt.feature_angle_deg));
  } catch (const RoundingError& on_input) {
    if (on_input.code == ErrorCode::NonManifoldInput || on_input.code == ErrorCode::NoSharpEdge) throw;
  }
  throw RoundingError(ErrorCode::ResultInvalid, std::string("the rounds made before the chain picked at ") + format_point(picked) +
                      " left a mesh it cannot be rounded on (" + e.what() + "); nothing was changed. Try another radius, or round it in a call of its own");
}

RoundResult round_edges(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const RoundOptions& opt) {
  return round_edges_after(V, F, seeds, opt, {});
}

NetworkPlan plan_network(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const RoundOptions& opt) {
  check_call(V, seeds, opt);
  const MeshTopology input(V, F);
  const PickedChains picks = pick_chains(input, seeds, opt);
  NetworkPlan plan;
  plan.chains = picks.chains;
  plan_corners(input, picks, opt, plan);
  return plan;
}

RoundResult round_edges_after(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const RoundOptions& opt,
                              const std::vector<ExactRound>& earlier, const std::vector<Vec3>& tight_rings) {
  const auto start = Clock::now();
  const CancelScope cancel_scope(opt.cancelled);
  poll_cancel();  // cancelled before the call: refused at once
  check_call(V, seeds, opt);
  RoundResult result;
  // One seed per distinct chain, found on the input; each chain is then rounded on the latest mesh.
  const MeshTopology input(V, F);
  PickedChains picks = pick_chains(input, seeds, opt);
  std::vector<SharpChain>& chains = picks.chains;
  const std::vector<Vec3>& picked = picks.picked;
  std::vector<ChainSeed> chain_seeds;  // the middle of an edge of each chain: it picks the same chain again, even
  for (const SharpChain& c : chains) {  // after other chains are rounded
    const size_t i = (c.points.size() - 1) / 2;
    const size_t j = (i + 1) % c.points.size();
    chain_seeds.push_back({0.5 * (c.points[i] + c.points[j]), {c.vertices[i], c.vertices[j]}});
  }
  auto finished = [&](RoundResult& result) {
    RoundReport& rep = result.report;
    rep.input_forces_small_angles = rep.min_new_angle_deg < 10 && rep.min_input_angle_deg < 10;
    rep.band = added_facets_quality(V, result.delta);
    rep.seconds_total = std::chrono::duration<double>(Clock::now() - start).count();
    return std::move(result);
  };
  // Convex and concave chains mixed at a corner: the odd ones first, the others on their result (stages.h).
  std::vector<RolledCorner> rolled;
  const std::vector<int> stage = plan_stages(input, chains, picked, opt, &rolled);
  if (!rolled.empty()) {
    std::vector<Vec3> again;
    for (const ChainSeed& s : chain_seeds) again.push_back(s.point);
    result = round_in_stages(V, F, chains, again, stage, rolled, opt);
    return finished(result);
  }
  const std::vector<RoundOptions> chain_options = options_per_chain(opt, chains, picked);
  std::vector<std::pair<SphereCorner, size_t>> spheres;  // each with a chain that ends there
  std::vector<NetworkPart> network = find_corners(input, chains, picked, opt, &spheres);
  std::vector<Vec3> made_points;  // the vertices of the rounds made so far (kept only where a corner needs them)
  // Each chain is rounded on the mesh the ones before made, its result an edit (MeshDelta) of that mesh.
  // One chain alone: its edit is the call's, made at the band's cost. Several passes: each edit is applied
  // (a whole mesh), and the call's edit is found through the last mesh's lineage.
  const size_t passes = chain_seeds.size() + spheres.size();
  MeshDelta delta;
  Points cur_V;
  Triangles cur_F;
  Lineage lineage;  // of (cur_V, cur_F)
  auto apply_step = [&](const MeshDelta& step, bool on_input) {
    Points next_V;
    Triangles next_F;
    StepOrigin origin;
    apply_delta(on_input ? V : cur_V, on_input ? F : cur_F, step, next_V, next_F, &origin);
    lineage = follow(lineage, origin);
    cur_V.swap(next_V);
    cur_F.swap(next_F);
  };
  for (size_t k = 0; k < chain_seeds.size(); ++k) {
    poll_cancel();
    NetworkPart& net = network[k];
    if (chains.size() > 1) net.chains = &chains;
    if (!earlier.empty()) net.earlier_rounds = &earlier;
    if (!tight_rings.empty()) net.tight_rings = &tight_rings;
    if (std::any_of(net.corners.begin(), net.corners.end(), [](const CornerEnd& c) { return c.other_made || c.sphere; }))
      net.earlier_round_points = made_points;
    std::vector<Vec3>* keep = network.size() > 1 && !net.corners.empty() ? &made_points : nullptr;
    MeshDelta step;
    if (k == 0) {
      result.chains.push_back(round_one_chain(input, chain_seeds[k], chain_options[k], result.report, &step, net, keep));
    } else {
      const MeshTopology mesh(cur_V, cur_F);
      const ChainSeed seed{chain_seeds[k].point, edge_in(lineage, chain_seeds[k].on_edge)};
      try {
        result.chains.push_back(round_one_chain(mesh, seed, chain_options[k], result.report, &step, net, keep));
      } catch (const RoundingError& e) {
        rethrow_on_own_mesh(e, input, picked[k], chain_options[k]);
      }
    }
    if (passes == 1) delta = std::move(step);
    else apply_step(step, k == 0);
  }
  for (const auto& [corner, k] : spheres) {  // the rounds made, the ball between their ends (sphere_corner.h)
    poll_cancel();
    const double tol = chain_options[k].tolerance > 0 ? chain_options[k].tolerance : corner.radius / 100.0;
    MeshDelta step;
    blend_sphere_corner(cur_V, cur_F, corner, tol, chains[k], chain_options[k].reach * corner.radius, step);
    apply_step(step, false);
  }
  // Flat patches of the made facets with one under 10 degrees meshed again whole (improve.h), the result then
  // checked as any (guard.h): one that fails is not taken, the rounds stay as they were made.
  double reach = 0, tol = INFINITY;  // the network's largest reach and smallest tolerance
  for (const RoundOptions& o : chain_options) reach = std::max(reach, o.reach * o.max_radius()), tol = std::min(tol, o.effective_tolerance());
  auto remesh = [&]() {
    MeshDelta made = delta;
    if (!remesh_flat_patches(input, delta, within_reach_of(chains, chain_options))) return false;
    try {
      check_result(edit_of(input, delta), chains[0], reach, tol, chains.size() > 1 ? &chains : nullptr);
      return true;
    } catch (const RoundingError& e) {
      if (e.code == ErrorCode::Cancelled) throw;
      delta = std::move(made);
      return false;
    }
  };
  bool remeshed = false;
  if (passes > 1) {
    delta = delta_from_lineage(V, F, cur_V, cur_F, lineage);
    if (remesh()) apply_delta(V, F, delta, cur_V, cur_F);
  } else if (result.report.thin_facets > 0 && remesh()) {
    // One chain's thin facets on flat ground (a CAD face's fan from its far corner to the band's corner where
    // the round ends on it): its flat patches meshed again whole, as a network's are; its figures follow.
    remeshed = true;
    ChainReport& own = result.chains[0].report;
    result.report.facets_removed = own.facets_removed = int(delta.removed.size());
    result.report.facets_added = own.facets_added = int(delta.added.size());
  }
  // Later rounds and corner patches replace facets that earlier rounds made (and counted): the new facets
  // are counted again, within the chains' reach.
  const bool corners = std::any_of(network.begin(), network.end(), [](const NetworkPart& net) { return !net.corners.empty(); });
  if (remeshed || corners) {
    recount_new_facets(V, F, delta, &result.report.thin_facets, &result.report.min_new_angle_deg);
    result.report.cusp_facets = std::min(result.report.cusp_facets, result.report.thin_facets);  // (a later round's cut)
    if (remeshed) {  // (one chain: its own figures are the call's)
      ChainReport& own = result.chains[0].report;
      own.thin_facets = result.report.thin_facets, own.cusp_facets = result.report.cusp_facets;
      result.report.thin_facets_short_of_room = own.reach_for_room > 0 ? own.thin_facets : 0;
    }
  }
  if (corners) {  // (cur_V, cur_F: the network's result, made by its passes)
    std::vector<double> radii;
    for (const RoundOptions& o : chain_options) radii.push_back(o.max_radius());
    result.report.corners = report_corners(cur_V, cur_F, network, spheres, result.chains, radii);
  }
  if (opt.write_arrays) apply_delta(V, F, delta, result.vertices, result.triangles);
  result.delta = std::move(delta);
  return finished(result);
}

}  // namespace meshround
