#include "support.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <map>
#include <set>

#include "meshround/mesh.h"

namespace meshround::test {

TriMesh mesh_shape(const TopoDS_Shape& shape, double max_edge) {
  BRepMesh_IncrementalMesh(shape, 0.01, false, 0.2, false);
  std::map<std::array<double, 3>, int> index;  // weld the faces' copies of shared vertices
  std::vector<Vec3> pts;
  std::vector<std::array<int, 3>> tris;
  auto vertex = [&](const gp_Pnt& p) {
    std::array<double, 3> key{std::round(p.X() * 1e6) / 1e6, std::round(p.Y() * 1e6) / 1e6, std::round(p.Z() * 1e6) / 1e6};
    auto [it, fresh] = index.emplace(key, int(pts.size()));
    if (fresh) pts.emplace_back(key[0], key[1], key[2]);
    return it->second;
  };
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face face = TopoDS::Face(ex.Current());
    TopLoc_Location loc;
    Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
    for (int i = 1; i <= tri->NbTriangles(); ++i) {
      int a, b, c;
      tri->Triangle(i).Get(a, b, c);
      if (face.Orientation() == TopAbs_REVERSED) std::swap(b, c);
      tris.push_back({vertex(tri->Node(a).Transformed(loc)), vertex(tri->Node(b).Transformed(loc)),
                      vertex(tri->Node(c).Transformed(loc))});
    }
  }
  // Uniform 1 -> 4 splits keep the mesh conforming.
  auto longest = [&]() {
    double l = 0;
    for (auto& t : tris)
      for (int k = 0; k < 3; ++k) l = std::max(l, (pts[t[k]] - pts[t[(k + 1) % 3]]).norm());
    return l;
  };
  while (max_edge > 0 && longest() > max_edge) {
    std::map<std::uint64_t, int> mid;
    auto midpoint = [&](int a, int b) {
      auto [it, fresh] = mid.emplace(edge_key(a, b), int(pts.size()));
      if (fresh) pts.push_back(0.5 * (pts[a] + pts[b]));
      return it->second;
    };
    std::vector<std::array<int, 3>> next;
    for (auto& t : tris) {
      const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca}), next.push_back({ab, t[1], bc}), next.push_back({ca, bc, t[2]}), next.push_back({ab, bc, ca});
    }
    tris.swap(next);
  }
  TriMesh m;
  m.V.resize(Eigen::Index(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) m.V.row(Eigen::Index(i)) = pts[i].transpose();
  m.F.resize(Eigen::Index(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) m.F(Eigen::Index(i), k) = tris[i][k];
  return m;
}

std::vector<TopoDS_Edge> pick_edges(const TopoDS_Shape& shape, const std::function<bool(const Vec3&, const Vec3&)>& pick) {
  std::vector<TopoDS_Edge> out;
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  for (int i = 1; i <= edges.Extent(); ++i) {
    const TopoDS_Edge e = TopoDS::Edge(edges(i));
    TopoDS_Vertex a, b;
    TopExp::Vertices(e, a, b);
    const gp_Pnt p = BRep_Tool::Pnt(a), q = BRep_Tool::Pnt(b);
    if (pick(Vec3(p.X(), p.Y(), p.Z()), Vec3(q.X(), q.Y(), q.Z()))) out.push_back(e);
  }
  return out;
}

TopoDS_Shape reference_fillet(const TopoDS_Shape& shape, const std::vector<TopoDS_Edge>& edges, double radius) {
  BRepFilletAPI_MakeFillet mk(shape);
  for (const TopoDS_Edge& e : edges) mk.Add(radius, e);
  mk.Build();
  return mk.Shape();
}

double max_distance_to_shape(const std::vector<Vec3>& points, const TopoDS_Shape& shape) {
  double worst = 0;
  for (const Vec3& p : points) {
    BRepExtrema_DistShapeShape d(BRepBuilderAPI_MakeVertex(gp_Pnt(p.x(), p.y(), p.z())).Vertex(), shape);
    worst = std::max(worst, d.Value());
  }
  return worst;
}

double max_distance_to_mesh(const std::vector<Vec3>& points, const TriMesh& m) {
  double worst = 0;
  for (const Vec3& p : points) {
    double best = INFINITY;
    for (int f = 0; f < m.F.rows(); ++f) {
      const Vec3 a = m.V.row(m.F(f, 0)).transpose(), b = m.V.row(m.F(f, 1)).transpose(), c = m.V.row(m.F(f, 2)).transpose();
      best = std::min(best, (closest_point_on_triangle(p, a, b, c, nullptr) - p).norm());
    }
    worst = std::max(worst, best);
  }
  return worst;
}

std::vector<Vec3> fillet_face_samples(const TopoDS_Shape& filleted, const TopoDS_Shape& sharp, int n) {
  std::vector<Vec3> out;
  for (TopExp_Explorer ex(filleted, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face face = TopoDS::Face(ex.Current());
    BRepAdaptor_Surface s(face);
    if (s.GetType() == GeomAbs_Plane) continue;  // the rounds of these cases are the only curved faces
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double u = s.FirstUParameter() + (s.LastUParameter() - s.FirstUParameter()) * (i + 0.5) / n;
        const double v = s.FirstVParameter() + (s.LastVParameter() - s.FirstVParameter()) * (j + 0.5) / n;
        BRepClass_FaceClassifier inside(face, gp_Pnt2d(u, v), 1e-7);
        if (inside.State() != TopAbs_IN) continue;
        const gp_Pnt p = s.Value(u, v);
        out.emplace_back(p.X(), p.Y(), p.Z());
      }
  }
  (void)sharp;
  return out;
}

std::vector<Vec3> mesh_samples(const TriMesh& m) {
  std::vector<Vec3> out;
  for (int f = 0; f < m.F.rows(); ++f) {
    const Vec3 a = m.V.row(m.F(f, 0)).transpose(), b = m.V.row(m.F(f, 1)).transpose(), c = m.V.row(m.F(f, 2)).transpose();
    out.push_back((a + b + c) / 3);
    out.push_back(0.5 * (a + b)), out.push_back(0.5 * (b + c)), out.push_back(0.5 * (c + a));
  }
  return out;
}

Topology topology(const TriMesh& m) {
  std::map<std::uint64_t, int> count;
  std::map<std::pair<int, int>, int> directed;
  Topology t;
  for (int f = 0; f < m.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.F(f, k), b = m.F(f, (k + 1) % 3);
      ++count[edge_key(a, b)];
      if (++directed[{a, b}] == 2) ++t.misoriented;
    }
    const Vec3 a = m.V.row(m.F(f, 0)).transpose(), b = m.V.row(m.F(f, 1)).transpose(), c = m.V.row(m.F(f, 2)).transpose();
    if ((b - a).cross(c - a).norm() <= 1e-12 * (b - a).norm() * (c - a).norm()) ++t.degenerate;
  }
  for (auto& [k, c] : count) t.boundary += c == 1, t.nonmanifold += c > 2;
  return t;
}

}  // namespace meshround::test
