// Test support: CAD solids meshed into (V, F), the exact OCCT fillet, and distances between them.
#pragma once
#include <TopoDS_Edge.hxx>
#include <TopoDS_Shape.hxx>
#include <functional>
#include <set>
#include <vector>

#include "meshround/types.h"

namespace meshround::test {

struct TriMesh {
  Points V;
  Triangles F;
};

// Watertight mesh of a solid: OCCT's tessellation (long CAD slivers), then split 1 -> 4 until no edge
// is longer than max_edge (<= 0: the CAD tessellation as it is).
TriMesh mesh_shape(const TopoDS_Shape& shape, double max_edge);

// Edges of `shape` for which `pick` (given both end points) is true.
std::vector<TopoDS_Edge> pick_edges(const TopoDS_Shape& shape, const std::function<bool(const Vec3&, const Vec3&)>& pick);

// OCCT's own fillet of those edges (BRepFilletAPI_MakeFillet): the reference answer.
TopoDS_Shape reference_fillet(const TopoDS_Shape& shape, const std::vector<TopoDS_Edge>& edges, double radius);

// Largest distance from the points to the shape's faces.
double max_distance_to_shape(const std::vector<Vec3>& points, const TopoDS_Shape& shape);
// Largest distance from the points to the mesh.
double max_distance_to_mesh(const std::vector<Vec3>& points, const TriMesh& mesh);
// Points on the faces of `filleted` that are not on `sharp` (the round itself).
std::vector<Vec3> fillet_face_samples(const TopoDS_Shape& filleted, const TopoDS_Shape& sharp, int per_direction);
// Mesh points worth checking: vertices, facet centroids and edge midpoints within `radius` of p_near.
std::vector<Vec3> mesh_samples(const TriMesh& mesh);

struct Topology {
  int boundary = 0, nonmanifold = 0, misoriented = 0, degenerate = 0;
};
Topology topology(const TriMesh& mesh);

}  // namespace meshround::test
