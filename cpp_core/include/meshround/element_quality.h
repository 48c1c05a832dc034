// Element quality as CAE pre-processors check it, over shell elements of 3 or 4 nodes: the band's figures
// in the rounding report (RoundReport::band) and in a rounded deck's report (elements, quads included).
//
//   angle         each corner's angle between its two sides (degrees): the smallest and the largest
//   aspect ratio  longest side / shortest side of an element (LS-PrePost's definition)
//   warpage       quads only: the angle between the normals of the two triangles a diagonal splits the
//                 quad into, the larger over both diagonals (HyperMesh's definition); 0 for a flat quad
//   smallest side the shortest side of any element (mm): it sets an explicit solver's time step
#pragma once
#include <array>
#include <vector>

#include "meshround/mesh_delta.h"
#include "meshround/types.h"

namespace meshround {

struct ElementQuality {
  int elements = 0, quads = 0;       // elements looked at; of them, quads (the rest are triangles)
  double min_angle_deg = 0;          // over all corners (0 when there is no element)
  double max_angle_deg = 0;
  double max_aspect_ratio = 0;
  double max_warpage_deg = 0;        // quads only
  double min_side = 0;               // mm
};

// Elements as node index quadruples; a triangle has -1 as its fourth. Indices must lie in V.
ElementQuality element_quality(const Points& V, const std::vector<std::array<int, 4>>& elements);

// The quality of the facets a rounding added (delta.added), placed as apply_delta places them.
ElementQuality added_facets_quality(const Points& V, const MeshDelta& delta);

}  // namespace meshround
