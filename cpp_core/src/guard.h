// The output check (private to cpp_core): a rounding is returned only when its result is no worse than
// its input. It looks at the band alone -- the facets made, the facets removed and the facets around
// them -- so it costs what the band costs, and it is always on.
//
// Checks, each against the input's own state there (a flaw the input already had is not the result's):
// - edges: no new boundary edge but a piece of an input boundary edge or, where the mesh boundary stops the
//   chain, its end profile (which becomes the mesh's edge there), and no more loops of the mesh's edge through
//   the band than before nor a boundary vertex pinched; no new non-manifold edge, no new edge whose
//   two facets disagree in orientation (over every edge with an end on a changed facet: all other edges are
//   untouched);
// - facets: no degenerate made facet (a repeated vertex or an angle under kDegenerateDeg);
// - placement: every new or moved vertex finite and within the box of the input facets around the band (a round
//   never leaves the faces it rounds), and every made facet with a corner within `reach` of the chain (plus the size of
//   the largest input facet the band cut: its gap is filled from its corners);
// - self-intersection: no made facet crosses another made facet or a kept facet near it.
// A failure throws RoundingError(result_invalid) naming the check and the place.
#pragma once
#include <vector>

#include "meshround/chain.h"
#include "meshround/mesh_edit.h"

namespace meshround {

constexpr double kDegenerateDeg = 0.01;  // smallest angle of a sound facet (the yardstick's own)
constexpr double kWeldShare = 0.01;      // x the tolerance: two points this near are one (a snap target beside a
                                         // neighbour)
constexpr double kCornerWeldShare = 0.2; // x the tolerance: a round's end points this near are one -- two rounds'
                                         // end columns at a mitre, each from its own balls (round.cpp); the band's
                                         // corner and a vertex on its end plane (ends.cpp insert_corner)

// `reach`: the largest distance from the chain at which the rounding may place a point; `tolerance`: the
// chordal tolerance (how far the round's end profile may stand off an end face). `network`: the other
// chains rounded in the same call, if any -- a made facet may lie wholly within their reach instead (a
// large facet an earlier round cut, cut again).
void check_result(const MeshEdit& edit, const SharpChain& chain, double reach, double tolerance,
                  const std::vector<SharpChain>* network = nullptr);

// The refusal check_result gives where a new flaw lies next to the same flaw of its input (the band ran
// over a hole or a flipped facet): non_manifold_input, `where` the input flaw's place.
struct InputFlaw : RoundingError {
  InputFlaw(const std::string& what, const Vec3& at) : RoundingError(ErrorCode::NonManifoldInput, what), where(at) {}
  Vec3 where;
};

// Whether `mesh` has a boundary, non-manifold or flipped edge on a facet with a corner within `distance`
// of `where` (a scan of all facets: for error paths).
bool flawed_near(const MeshTopology& mesh, const Vec3& where, double distance);

}  // namespace meshround
