#include "meshround/max_radius.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <unordered_set>

#include "meshround/cancel.h"
#include "meshround/options.h"
#include "meshround/round.h"
#include "meshround/spine.h"
#include "ends.h"
#include "network.h"

namespace meshround {

const char* room_limit_name(RoomLimit why) {
  switch (why) {
    case RoomLimit::None: return "none";
    case RoomLimit::FaceEnd: return "face_end";
    case RoomLimit::OppositeWall: return "opposite_wall";
    case RoomLimit::Curvature: return "curvature";
    case RoomLimit::NeighbourChain: return "neighbouring_chain";
    case RoomLimit::Boundary: return "boundary";
    case RoomLimit::Reach: return "reach";
    case RoomLimit::NoBall: return "no_ball";
    case RoomLimit::EndSetback: return "end_setback";
  }
  return "none";
}

namespace {

// The base meshes are collected for this much more than the radius bracketed (a margin for the bracket).
constexpr double kCollectMargin = 1.05;
// They are collected again while the radius found is under 1 / this of the one they were collected for.
constexpr double kCollectAgain = 1.1;
constexpr int kMaxCollections = 6;

// A chain's two base meshes collected for one reach distance, with their distance queries.
struct Collected {
  BaseMeshes base;
  std::unique_ptr<BaseDistance> distance[2];
};

std::unique_ptr<Collected> collect(const MeshTopology& mesh, const SharpChain& chain, double reach_distance, double feature_angle_deg) {
  auto c = std::make_unique<Collected>();
  c->base = collect_base_meshes(mesh, chain, reach_distance, feature_angle_deg);
  for (int k = 0; k < 2; ++k) c->distance[k] = std::make_unique<BaseDistance>(mesh, c->base.facets[k]);
  return c;
}

// Where the balls are tried: the chain's vertices, its edges' middles and `min_count` even stations (an
// open chain's two end points are not: round_edges caps its ends there), in a fixed shuffled order so
// that a chain whose room shrinks along it is not bisected at every station.
std::vector<double> station_list(const SharpChain& chain, int min_count) {
  const double L = chain.length;
  std::vector<double> s;
  const int n = int(chain.points.size());
  for (int i = 0; i < chain.num_edges(); ++i) {
    const double a = chain.arc_length[i], b = i + 1 < n ? chain.arc_length[i + 1] : L;
    s.push_back(a), s.push_back(0.5 * (a + b));
  }
  for (int i = 0; i < min_count; ++i) s.push_back(L * (i + 0.5) / min_count);
  if (!chain.closed) s.erase(std::remove_if(s.begin(), s.end(), [&](double x) { return x <= 1e-9 * L || x >= (1 - 1e-9) * L; }), s.end());
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  std::shuffle(s.begin(), s.end(), std::mt19937(16));
  return s;
}

// The smallest room over the stations: [lo, hi] brackets the largest radius fitting at all of them
// (hi = INFINITY when `cap` fits everywhere), with the refused ball at hi and its station.
struct Bracket {
  double lo = 0, hi = INFINITY, s = 0;
  StationFit fit;
  ProfileStation ball;
  bool at_end = false;  // refused by the chain's end plan (EndSetback), not by the ball at s
};

// Another picked chain that bounds one side of this chain's (no shared vertex: chains meeting at a corner
// are mitred there instead): the two rounds share that face, so this chain's contact on it must stay out
// of the other round's band -- where round_edges, rounding the chains one after the other, stops the
// later one's base mesh.
struct Neighbour {
  const SharpChain* chain = nullptr;
  int side = 0;  // this chain's side the neighbour bounds
  std::unique_ptr<Collected> collected;
  std::unique_ptr<SpineContext> ctx;
};

// How an open chain's round ends for radius r, as round_edges plans it (ends.h plan_ends): `corners` gives
// the chain's corners with the other picked chains at r. The last r's plan is kept.
struct Ends {
  std::function<NetworkPart(double)> corners;
  double r = -1;
  bool fits = true;
  EndPlan plan;
  int corner_end = -1;  // the one end at a corner with other picked chains, if only one is
  const EndPlan* at(const SpineContext& ctx, double radius) {
    if (radius != r) {
      r = radius;
      try {
        RoundOptions constant;
        constant.radius = radius;
        const NetworkPart net = corners(radius);
        const bool at[2] = {corner_at(net, ctx.chain.points.front()) != nullptr, corner_at(net, ctx.chain.points.back()) != nullptr};
        corner_end = at[0] != at[1] ? (at[0] ? 0 : 1) : -1;
        plan = plan_ends(ctx, RadiusLaw(constant, ctx.chain, 0), net, constant.effective_tolerance());
        fits = true;
      } catch (const RoundingError& e) {
        if (e.code != ErrorCode::RadiusTooLarge && e.code != ErrorCode::CornerNotBlendable && e.code != ErrorCode::BeyondReach) throw;
        fits = false;
      }
    }
    return fits ? &plan : nullptr;
  }
};

struct Scan {
  const SpineContext& ctx;
  Collected& collected;
  double reach, precision;
  std::vector<Neighbour>& neighbours;
  Ends& ends;
  int solved = 0;
  bool end_refused = false;  // the last fits() was refused by the end plan

  // The other round's band on the shared face reaches this contact: a misfit on the neighbour's edge.
  bool in_neighbour_band(const ProfileStation& ball, double r, StationFit* fit) {
    for (Neighbour& nb : neighbours) {
      const Vec3 p = ball.contact[nb.side];
      double to_other;
      const double s_other = nb.chain->project(p, &to_other);
      nb.collected->base.reach_distance = reach * r;
      StationFit other_fit;
      const ProfileStation other = fit_station(*nb.ctx, s_other, r, &other_fit);
      ++solved;
      if (other_fit.misfit != StationMisfit::Fits) continue;  // its own room is measured as its own chain's
      const Vec3 q = (other.contact[0] - p).norm() < (other.contact[1] - p).norm() ? other.contact[0] : other.contact[1];
      double band;
      nb.chain->project(q, &band);
      if (to_other >= band) continue;
      const SharpChain& c = *nb.chain;
      int i = int(std::upper_bound(c.arc_length.begin(), c.arc_length.end(), s_other) - c.arc_length.begin()) - 1;
      i = std::clamp(i, 0, c.num_edges() - 1);
      *fit = StationFit{StationMisfit::Wall, nb.side, p, edge_key(c.vertices[i], c.vertices[(i + 1) % c.vertices.size()])};
      return true;
    }
    return false;
  }

  bool fits(double s, double r, StationFit* fit, ProfileStation* ball) {
    collected.base.reach_distance = reach * r;  // what round_edges collects for r
    end_refused = false;
    const EndPlan* plan = ctx.chain.closed ? nullptr : ends.at(ctx, r);
    // Within an end's setback no ball is solved: the last one is carried on to the end's plane.
    if (plan && (s < plan->setback[0] || s > ctx.chain.length - plan->setback[1])) return true;
    ++solved;
    *ball = fit_station(ctx, s, r, fit);
    if (fit->misfit != StationMisfit::Fits || in_neighbour_band(*ball, r, fit)) return false;
    // The ball at s fits, but the ends cannot be made for r (a refusal the station's own misfit names first).
    return ctx.chain.closed || plan || !(end_refused = true);
  }

  Bracket run(const std::vector<double>& stations, double cap) {
    Bracket b;
    b.lo = cap;
    StationFit fit;
    ProfileStation ball;
    for (double s : stations) {
      poll_cancel();
      if (fits(s, b.lo, &fit, &ball)) continue;
      Bracket n{0, b.lo, s, fit, ball, end_refused};
      while (n.hi - n.lo > precision * n.hi) {
        const double mid = 0.5 * (n.lo + n.hi);
        if (fits(s, mid, &fit, &ball)) n.lo = mid;
        else n.hi = mid, n.fit = fit, n.ball = ball, n.at_end = end_refused;
      }
      b = n;
    }
    return b;
  }
};

// What a wall touched is: the mesh boundary, another picked chain, or a sharp edge where the surface
// turns towards the ball (a wall across the face) or away from it (the face's end).
RoomLimit wall_kind(const MeshTopology& mesh, const BaseMeshes& base, const StationFit& fit, const ProfileStation& ball,
                    const std::unordered_set<std::uint64_t>& other_chains) {
  const int a = int(fit.wall_edge >> 32), b = int(fit.wall_edge & 0xffffffffu);
  int pair[2];
  const int count = mesh.edge_facet_pair(a, b, pair);
  if (count < 2) return RoomLimit::Boundary;
  if (other_chains.count(fit.wall_edge)) return RoomLimit::NeighbourChain;
  if (count > 2) return RoomLimit::FaceEnd;
  const auto in = base.side_of.find(pair[0]);
  const bool first_in = in != base.side_of.end() && in->second == fit.side;
  const int f_in = first_in ? pair[0] : pair[1], f_out = first_in ? pair[1] : pair[0];
  Vec3 n = mesh.facet_normal(f_in);
  if (n.dot(ball.centre - fit.at) < 0) n = -n;
  int far = mesh.F(f_out, 0);
  for (int k = 0; k < 3; ++k)
    if (mesh.F(f_out, k) != a && mesh.F(f_out, k) != b) far = mesh.F(f_out, k);
  const Vec3 d = mesh.point(far) - mesh.point(a);
  return n.dot(d) > 1e-6 * d.norm() ? RoomLimit::OppositeWall : RoomLimit::FaceEnd;
}

RoomLimit limit_kind(const MeshTopology& mesh, const BaseMeshes& base, const Bracket& b, const std::unordered_set<std::uint64_t>& other_chains) {
  if (b.at_end) return RoomLimit::EndSetback;
  switch (b.fit.misfit) {
    case StationMisfit::Wall: return wall_kind(mesh, base, b.fit, b.ball, other_chains);
    case StationMisfit::BeyondReach: return RoomLimit::Reach;
    case StationMisfit::Curvature: return RoomLimit::Curvature;
    case StationMisfit::Fits: return RoomLimit::None;
    default: return RoomLimit::NoBall;
  }
}

// The picked chains that bound a side of `chain`'s base meshes and share no vertex with it, collected for
// the same reach distance.
std::vector<Neighbour> neighbours_of(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base,
                                     const std::vector<const SharpChain*>& others, double reach_distance, double feature_angle_deg) {
  std::vector<Neighbour> out;
  const std::unordered_set<int> own(chain.vertices.begin(), chain.vertices.end());
  for (const SharpChain* other : others) {
    if (std::any_of(other->vertices.begin(), other->vertices.end(), [&](int v) { return own.count(v) > 0; })) continue;
    for (int side = 0; side < 2; ++side) {
      bool bounds = false;
      for (int i = 0; i < other->num_edges() && !bounds; ++i)
        bounds = base.walls[side].count(edge_key(other->vertices[i], other->vertices[(i + 1) % other->vertices.size()])) > 0;
      if (!bounds) continue;
      Neighbour nb;
      nb.chain = other, nb.side = side;
      nb.collected = collect(mesh, *other, reach_distance, feature_angle_deg);
      nb.ctx = std::make_unique<SpineContext>(SpineContext{mesh, *other, nb.collected->base,
                                                           {nb.collected->distance[0].get(), nb.collected->distance[1].get()}});
      out.push_back(std::move(nb));
    }
  }
  return out;
}

ChainRoom measure_chain(const MeshTopology& mesh, const SharpChain& chain, const std::vector<const SharpChain*>& others,
                        const std::unordered_set<std::uint64_t>& other_chains, Ends& ends, const MaxRadiusOptions& o, double size) {
  ChainRoom room;
  room.chain = chain.points;
  room.closed = chain.closed;
  const std::vector<double> stations = station_list(chain, o.min_stations);
  room.stations = int(stations.size());
  double cap = size;  // no ball is larger than the mesh
  for (int round = 0; round < kMaxCollections; ++round) {
    const double reach_distance = o.reach * kCollectMargin * cap;
    std::unique_ptr<Collected> c = collect(mesh, chain, reach_distance, o.feature_angle_deg);
    const SpineContext ctx{mesh, chain, c->base, {c->distance[0].get(), c->distance[1].get()}};
    std::vector<Neighbour> neighbours = neighbours_of(mesh, chain, c->base, others, reach_distance, o.feature_angle_deg);
    Scan scan{ctx, *c, o.reach, o.precision, neighbours, ends};
    ends.r = -1;  // planned anew on these base meshes
    const Bracket b = scan.run(stations, cap);
    room.balls_solved += scan.solved;
    room.collections += 1;
    room.radius = b.lo;
    if (b.hi == INFINITY) break;  // everything up to cap fits (the first round: up to the mesh's size)
    room.radius_refused = b.hi;
    room.why = limit_kind(mesh, c->base, b, other_chains);
    // (A refused end plan names the end at the corner, or else the end nearer the station.)
    const int end = ends.corner_end >= 0 ? ends.corner_end : b.s < 0.5 * chain.length ? 0 : 1;
    room.where = b.at_end ? chain.point_at(end ? chain.length : 0) : b.fit.at;
    room.side = b.at_end ? -1 : b.fit.side;
    room.chain_point = b.at_end ? room.where : chain.point_at(b.s);
    if (room.why == RoomLimit::Curvature) room.curvature_radius = 1 / chain_curvature(chain, b.s, b.hi).norm();
    if (cap <= kCollectAgain * b.hi) break;  // collected for about this radius: what round_edges sees
    cap = kCollectMargin * b.hi;
  }
  return room;
}

}  // namespace

std::vector<ChainRoom> max_radius(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const MaxRadiusOptions& o) {
  RoundOptions checked;
  checked.feature_angle_deg = o.feature_angle_deg;
  checked.reach = o.reach;
  validate_options(checked);
  if (!(o.precision > 0 && o.precision < 0.1) || o.min_stations < 1)
    throw RoundingError(ErrorCode::InvalidInput, "max_radius: precision must be in (0, 0.1) and min_stations at least 1");
  if (seeds.empty()) throw RoundingError(ErrorCode::InvalidInput, "no seed given: pick a point on a sharp edge");
  const MeshTopology mesh(V, F);
  std::vector<SharpChain> chains = find_chains(mesh, seeds, o.feature_angle_deg, o.search_radius);
  for (SharpChain& c : chains) c.index_segments();  // project() is called for every ball's contacts
  const double size = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  std::vector<Vec3> picked;
  for (const SharpChain& c : chains) picked.push_back(c.point_at(0.5 * c.length));
  // Rolled corners (network.h) are made in two stages: round_edges finds the corners of the chains made first
  // among those alone, and traces the others anew on their result, where their ends run on around the first
  // rounds' (no corner there to plan). The stages do not depend on one radius for all.
  std::vector<int> stage(chains.size(), 0);
  std::vector<RolledCorner> rolled;
  try {
    RoundOptions any = checked;
    any.radius = 1.0;
    stage = plan_stages(mesh, chains, picked, any, &rolled);
  } catch (const RoundingError& e) {
    if (e.code != ErrorCode::CornerNotBlendable) throw;
  }
  std::vector<ChainRoom> out;
  for (size_t k = 0; k < chains.size(); ++k) {
    std::unordered_set<std::uint64_t> other_edges;
    std::vector<const SharpChain*> others;
    for (size_t j = 0; j < chains.size(); ++j) {
      if (j == k) continue;
      const SharpChain& c = chains[j];
      others.push_back(&c);
      for (int i = 0; i < c.num_edges(); ++i) other_edges.insert(edge_key(c.vertices[i], c.vertices[(i + 1) % c.vertices.size()]));
    }
    // The chain's corners with the others at radius r, as round_edges finds them (network.h); where
    // they are not made (mixed convexity, a chain ending on another's side), its ends are end faces.
    Ends ends;
    ends.corners = [&, k](double r) {
      RoundOptions at_r = checked;
      at_r.radius = r;
      if (!rolled.empty() && stage[k] != 0) return NetworkPart{};
      std::vector<SharpChain> same;  // the chains made in k's stage, k among them
      std::vector<Vec3> same_picked;
      size_t at = 0;
      for (size_t j = 0; j < chains.size(); ++j)
        if (rolled.empty() || stage[j] == 0) {
          if (j == k) at = same.size();
          same.push_back(chains[j]), same_picked.push_back(picked[j]);
        }
      std::vector<std::pair<SphereCorner, size_t>> spheres;
      try {
        return find_corners(mesh, same, same_picked, at_r, &spheres)[at];
      } catch (const RoundingError&) {
        return NetworkPart{};
      }
    };
    out.push_back(measure_chain(mesh, chains[k], others, other_edges, ends, o, size));
  }
  return out;
}

}  // namespace meshround
