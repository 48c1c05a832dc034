// split_for_refinement(): the parts of a flat polygon that refinement cannot shape, split off first.
//
// Refinement adds points inside a polygon only where the caller admits them (within the reach) and
// never splits its sides (shared with facets that stay). Two kinds of part are then out of its reach:
//  - a side whose every well-shaped apex lies outside the polygon or where no point may go (a long side
//    beyond the reach): it gets the polygon vertex that makes its triangle best;
//  - a corner where no point may go: it is cut off by a fan to points on rays splitting its angle, as far
//    out as the polygon allows and the ears left beside the fan stay well shaped.
// Left to refinement, both are fanned to far points in slivers, and flips undo a good apex found later.
#pragma once
#include <array>
#include <functional>
#include <vector>

#include "meshround/mesh_edit.h"

namespace meshround {

using ToSpace = std::function<Vec3(const Eigen::Vector2d&)>;  // a point of the polygon's plane in 3-D

// P / Q: the polygon's points in 3-D and in its plane, the ring Q[0, boundary) counter-clockwise; points
// made for fans are appended to both. `fixed` gets the triangles split off (ids into P, counter-
// clockwise); the rings left for refinement are returned.
std::vector<std::vector<int>> split_for_refinement(std::vector<Vec3>& P, std::vector<Eigen::Vector2d>& Q, size_t boundary,
                                                   const Refinement& refine, const ToSpace& to_3d,
                                                   std::vector<std::array<int, 3>>& fixed);

}  // namespace meshround
