// Networks with rolled corners (network.h RolledCorner), made in two stages by round_edges itself: the
// odd chains (and the chains that meet them at mitres and sphere corners) in a first call, the others in
// a second call on its result, traced anew from the middles of their edges -- where they met the odd
// round's chain, their sharp edge now runs on around that round's end, so two chains of the input become
// one round there. The two calls' edits are one edit of the input, their reports one report.
#pragma once
#include <vector>

#include "meshround/round.h"
#include "network.h"

namespace meshround {

// A later pass of a network (or a second stage) works on the mesh the earlier ones made: what it finds
// wrong with that mesh (a degenerate facet, an edge no longer sharp) is this call's own fault, not the
// input's, and is thrown as result_invalid naming the chain picked at `picked` -- unless the input shows the
// fault too: a hole or flipped facet (InputFlaw) the band ran over that the input has there, or a fault of
// the same chain's base meshes on the input (a flipped facet the first pass did not reach); then that input
// error is rethrown as it is. Other errors are rethrown as they are. Called only while `e` is being handled.
[[noreturn]] void rethrow_on_own_mesh(const RoundingError& e, const MeshTopology& input, const Vec3& picked, const RoundOptions& opt);

// round_edges on a mesh whose rounds `earlier` a first stage made: base facets on them are measured on
// their exact surfaces (spine.h ExactRound), so a round rolling on around one's end is tangent to it.
// `tight_rings`: the vertices of rolled corners with a tight ring (NetworkPart::tight_rings).
RoundResult round_edges_after(const Points& V, const Triangles& F, const std::vector<Vec3>& seeds, const RoundOptions& opt,
                              const std::vector<ExactRound>& earlier, const std::vector<Vec3>& tight_rings = {});

// `seeds[k]` picks chain k again (the middle of one of its edges), `stage[k]` is plan_stages' stage.
RoundResult round_in_stages(const Points& V, const Triangles& F, const std::vector<SharpChain>& chains, const std::vector<Vec3>& seeds,
                            const std::vector<int>& stage, const std::vector<RolledCorner>& rolled, const RoundOptions& opt);

}  // namespace meshround
