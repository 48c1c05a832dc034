// The checks every engine call makes before it works (private to cpp_core): the options, the precision
// the mesh's coordinates carry, and the seeds.
#pragma once
#include <vector>

#include <string>

#include "meshround/mesh.h"
#include "meshround/options.h"
#include "meshround/types.h"

namespace meshround {

// Largest |coordinate| of the finite coordinates (the mesh's own check refuses the others): the magnitude
// the mesh's float32 precision is judged by (on_plane_slack), here and in the passes.
double coordinate_magnitude(const Points& V);

// The options (validate_options), the radius and tolerance against the mesh's precision
// (radius_too_small, naming the smallest value that works), and at least one seed.
void check_call(const Points& V, const std::vector<Vec3>& seeds, const RoundOptions& opt);

// The rounding rebuilds the facets around a chain or a corner, so they must be 2-manifold and
// consistently oriented: refuses (non_manifold_input, naming the place) an edge of `facets` shared by
// more than two facets, or whose two facets run it the same way (one of them is flipped: the pieces cut
// from it would face against the round). `near` names what the place is next to ("the chain").
void check_facet_edges(const MeshTopology& mesh, const std::vector<int>& facets, const std::string& near);

}  // namespace meshround
