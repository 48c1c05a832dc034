#include "stages.h"

#include <algorithm>
#include <cmath>

#include "corner_report.h"
#include "delta.h"
#include "facet_quality.h"
#include "meshround/improve.h"

namespace meshround {
namespace {

// The report of both stages as one (their corners' chain numbers into `offset` + the second's); facet
// counts from the edit of the input, thin facets counted again over the result.
RoundReport merge_reports(const RoundReport& a, const RoundReport& b, int offset) {
  RoundReport m = a;
  m.max_deviation = std::max(a.max_deviation, b.max_deviation);
  m.min_input_angle_deg = std::min(a.min_input_angle_deg, b.min_input_angle_deg);
  m.thin_facets_short_of_room = a.thin_facets_short_of_room + b.thin_facets_short_of_room;
  m.cusp_facets = a.cusp_facets + b.cusp_facets;
  m.cusp_angle_deg = a.cusp_facets && b.cusp_facets ? std::min(a.cusp_angle_deg, b.cusp_angle_deg) : a.cusp_angle_deg + b.cusp_angle_deg;
  m.reach_for_room = std::max(a.reach_for_room, b.reach_for_room);
  for (CornerReport c : b.corners) {
    for (int& k : c.chains) k += offset;
    m.corners.push_back(c);
  }
  for (const auto& [pass, t] : b.seconds) m.seconds[pass] += t;
  return m;
}

// The round of `rounds` (from `first` on) whose sharp edge passes nearest to p.
int nearest_round(const std::vector<RoundedChain>& rounds, size_t first, const Vec3& p) {
  int best = -1;
  double best_d = INFINITY;
  for (size_t k = first; k < rounds.size(); ++k)
    for (const Vec3& q : rounds[k].chain)
      if ((q - p).norm() < best_d) best_d = (q - p).norm(), best = int(k);
  return best;
}

// At a rolled corner whose pair have different radii (network.h RolledCorner::pair_radius), the second stage's
// law goes from one radius to the other round the odd round's end, as OCCT's fillet lets its corner ball's
// radius evolve there (an S law: zero slope at both ends): each pair chain's radius held up to the odd
// round's contact line on its side (the end of that contact line, `odd` made in the first stage), the
// cubic between them over the turn. The pair's control points within the turn give way to these two.
void evolve_round_the_end(const RolledCorner& c, const RoundedChain& odd, const std::vector<SharpChain>& chains,
                          std::vector<RadiusControl>& law) {
  Vec3 turn[2];
  for (int i : {0, 1}) {
    const std::vector<Vec3>& line = odd.contacts[i];
    turn[i] = (line.front() - c.vertex).norm() < (line.back() - c.vertex).norm() ? line.front() : line.back();
  }
  const double within = std::max((turn[0] - c.vertex).norm(), (turn[1] - c.vertex).norm());
  law.erase(std::remove_if(law.begin(), law.end(), [&](const RadiusControl& p) { return (p.point - c.vertex).norm() < within; }), law.end());
  for (const Vec3& t : turn) {
    double d[2];
    chains[c.pair[0]].project(t, &d[0]), chains[c.pair[1]].project(t, &d[1]);
    law.push_back({t, c.pair_radius[d[0] <= d[1] ? 0 : 1]});
  }
}

}  // namespace

RoundResult round_in_stages(const Points& V, const Triangles& F, const std::vector<SharpChain>& chains, const std::vector<Vec3>& seeds,
                            const std::vector<int>& stage, const std::vector<RolledCorner>& rolled, const RoundOptions& opt) {
  std::vector<Vec3> picks[2];
  std::vector<int> index_in_first(chains.size(), -1);
  for (size_t k = 0; k < chains.size(); ++k) {
    if (stage[k] == 0) index_in_first[k] = int(picks[0].size());
    picks[stage[k]].push_back(seeds[k]);
  }
  // Each stage takes its own chains' radius control points (a chain of the second stage is traced anew,
  // and takes the points of the input chains it runs along); one tolerance for both.
  const std::vector<RoundOptions> own = options_per_chain(opt, chains, seeds);
  RoundOptions stage_opt[2] = {opt, opt};
  for (int s : {0, 1}) {
    stage_opt[s].write_arrays = true;  // the second stage starts from the first's mesh
    if (opt.radius_law.empty()) continue;
    stage_opt[s].radius_law.clear();
    stage_opt[s].tolerance = opt.effective_tolerance();
    for (size_t k = 0; k < chains.size(); ++k)
      if (stage[k] == s) stage_opt[s].radius_law.insert(stage_opt[s].radius_law.end(), own[k].radius_law.begin(), own[k].radius_law.end());
  }
  const RoundResult a = round_edges(V, F, picks[0], stage_opt[0]);
  for (const RolledCorner& c : rolled)
    if (c.pair_radius[0] > 0) evolve_round_the_end(c, a.chains[size_t(index_in_first[c.odd])], chains, stage_opt[1].radius_law);
  // The first stage's rounds, exact, for the second to roll on (a chain made first at a rolled corner has one
  // radius: plan_stages).
  std::vector<ExactRound> earlier;
  for (size_t k = 0; k < chains.size(); ++k)
    if (index_in_first[k] >= 0 && constant_radius(own[k])) {
      const RoundedChain& made = a.chains[size_t(index_in_first[k])];
      earlier.push_back({made.spine, one_radius(own[k]), {made.contacts[0], made.contacts[1]}});
    }
  RoundResult b;
  try {
    std::vector<Vec3> tight_rings;
    for (const RolledCorner& c : rolled)
      if (c.tight) tight_rings.push_back(c.vertex);
    b = round_edges_after(a.vertices, a.triangles, picks[1], stage_opt[1], earlier, tight_rings);
  } catch (const RoundingError& e) {
    rethrow_on_own_mesh(e, MeshTopology(V, F), picks[1].front(), opt);
  }

  RoundResult out;
  Points V1;
  Triangles F1;
  StepOrigin origin;
  apply_delta(V, F, a.delta, V1, F1, &origin);
  out.delta = delta_through(V, F, V1, F1, origin, b.delta);
  remesh_flat_patches(MeshTopology(V, F), out.delta, within_reach_of(chains, own));  // the second stage cut the first's facets
  apply_delta(V, F, out.delta, out.vertices, out.triangles);
  out.chains = a.chains;
  out.chains.insert(out.chains.end(), b.chains.begin(), b.chains.end());
  const int offset = int(a.chains.size());
  out.report = merge_reports(a.report, b.report, offset);
  out.report.facets_removed = int(out.delta.removed.size());
  out.report.facets_added = int(out.delta.added.size());
  // Thin facets among the made ones, over both stages (the second replaces facets the first made).
  recount_new_facets(V, F, out.delta, &out.report.thin_facets, &out.report.min_new_angle_deg);
  out.report.cusp_facets = std::min(out.report.cusp_facets, out.report.thin_facets);
  for (const RolledCorner& c : rolled) {
    const int odd = index_in_first[c.odd], round = nearest_round(out.chains, size_t(offset), c.vertex);
    if (odd >= 0 && round >= 0)
      out.report.corners.push_back(report_rolled_corner(out.vertices, out.triangles, c, out.chains[size_t(odd)], out.chains[size_t(round)],
                                                        one_radius(own[c.odd]), odd, round));
  }
  if (!opt.write_arrays) out.vertices.resize(0, 3), out.triangles.resize(0, 3);
  return out;
}

}  // namespace meshround
