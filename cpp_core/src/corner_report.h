// The report's entry per corner of a network of rounds (round.h CornerReport): after every round and
// corner patch is made, the seams are found on the finished mesh and measured against the exact rounds
// (their spines, constant radius) and, at a sphere corner, the exact ball.
#pragma once
#include <utility>
#include <vector>

#include "meshround/round.h"
#include "network.h"
#include "sphere_corner.h"

namespace meshround {

// V, F: the finished mesh. network / spheres: find_corners' output for `rounds` (in rounding order, each
// with its constant `radii[k]`).
std::vector<CornerReport> report_corners(const Points& V, const Triangles& F, const std::vector<NetworkPart>& network,
                                         const std::vector<std::pair<SphereCorner, size_t>>& spheres,
                                         const std::vector<RoundedChain>& rounds, const std::vector<double>& radii);

// A rolled corner (network.h): the seam where the rolled round leans on the odd one, within 4 r of the
// vertex (r the larger of the two rounds' radii there), measured against both rounds (the odd one made
// first, of radius `odd_radius`; `odd_index` / `rolled_index` in the call's rounds).
CornerReport report_rolled_corner(const Points& V, const Triangles& F, const RolledCorner& corner, const RoundedChain& odd,
                                  const RoundedChain& rolled, double odd_radius, int odd_index, int rolled_index);

}  // namespace meshround
