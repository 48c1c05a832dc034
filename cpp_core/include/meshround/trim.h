// Paper §5.1: cut the base meshes along the two contact lines and take the band between them out.
//
// Each base-mesh vertex gets a signed distance from its contact line, measured in the base surface
// (negative inside the band). Edges whose ends differ in sign are cut where that distance is zero,
// facets across the line keep their outer part (retriangulated in their own plane, so nothing outside
// the band moves), and the contact line gets extra points inside large facets so that it follows the
// surface's edge to the tolerance. At the ends of an open chain the facets of the end faces that the
// round cuts into are taken out too; their gaps are closed by the sewing pass.
#pragma once
#include <functional>
#include <vector>

#include "meshround/chain.h"
#include "meshround/mesh_edit.h"
#include "meshround/surface.h"

namespace meshround {

struct TrimPoint {
  int vertex;  // id in the MeshEdit
  double u;    // parameter of the surface's boundary line at this point
};

// The two trim lines (side A at v = 0, side B at v = 1), each sorted by u.
struct TrimLines {
  std::vector<TrimPoint> line[2];
  int facets_cut = 0, facets_removed = 0, vertices_snapped = 0;
};

struct TrimOptions {
  double tolerance;     // chordal tolerance: how closely a trim line follows the surface's edge
  std::function<double(double u)> max_spacing;  // longest step along a trim line at u (keeps facets well shaped)
  Refinement shape;     // inner points for the kept parts of cut facets and graded edges (where they may go)
};

TrimLines trim_base_meshes(const MeshTopology& mesh, const SharpChain& chain, const BaseMeshes& base,
                           const RoundingSurface& surface, const std::vector<ProfileStation>& end_profiles,
                           const TrimOptions& options, MeshEdit& edit);

}  // namespace meshround
