// The yardstick's (reference.py) two slow measures, in C++ on OCCT:
// - Triangles: exact distances from points to a set of triangles (reference.py TriangleSet): OCCT's BVH over
//   the triangles' boxes, searched branch and bound, and an exact point-triangle distance -- the plane's where
//   the point projects inside the triangle, else the nearest of its three sides (also for zero-area triangles);
// - surface_points, in_domain: a CAD face's points at (u, v), and which (u, v) lie in its trimmed domain
//   (reference.py face_samples), for a whole grid at once.
// Test code only, and none of the engine's own: the yardstick stays independent of what it measures.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BVH_BoxSet.hxx>
#include <BVH_Distance.hxx>
#include <BVH_Tools.hxx>
#include <Precision.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;

namespace {

using Vec = BVH_Vec3d;
using Boxes = BVH_BoxSet<double, 3, int>;  // each element: a triangle's index

double segment_d2(const Vec& p, const Vec& a, const Vec& b) {
  const Vec ab = b - a;
  const double t = std::clamp((p - a).Dot(ab) / std::max(ab.Dot(ab), 1e-300), 0.0, 1.0);
  const Vec d = p - a - ab * t;
  return d.Dot(d);
}

// The squared distance from p to the triangle abc.
double triangle_d2(const Vec& p, const Vec& a, const Vec& b, const Vec& c) {
  const Vec n = Vec::Cross(b - a, c - a);
  const double nn = n.Dot(n), ab2 = std::max((b - a).Dot(b - a), 1e-300);
  bool inside = nn > 1e-30 * ab2 * ab2;
  for (const auto& [x, y] : {std::pair{&a, &b}, std::pair{&b, &c}, std::pair{&c, &a}})
    inside = inside && Vec::Cross(*y - *x, p - *x).Dot(n) >= 0;  // p projects to the inner side of every edge
  if (inside) {
    const double h = (p - a).Dot(n);
    return h * h / nn;
  }
  return std::min({segment_d2(p, a, b), segment_d2(p, b, c), segment_d2(p, c, a)});
}

class Triangles {
 public:
  Triangles(py::array_t<double, py::array::c_style | py::array::forcecast> V,
            py::array_t<long long, py::array::c_style | py::array::forcecast> F) {
    if (V.ndim() != 2 || V.shape(1) != 3 || F.ndim() != 2 || F.shape(1) != 3) throw std::invalid_argument("V (n, 3), F (m, 3)");
    const auto v = V.unchecked<2>();
    const auto f = F.unchecked<2>();
    for (py::ssize_t i = 0; i < f.shape(0); ++i) {
      BVH_Box<double, 3> box;
      for (int k = 0; k < 3; ++k) {
        const long long id = f(i, k);
        if (id < 0 || id >= v.shape(0)) throw std::out_of_range("a facet's vertex index is out of range");
        corners_.push_back(Vec(v(id, 0), v(id, 1), v(id, 2)));
        box.Add(corners_.back());
      }
      set_.Add(int(i), box);
    }
    set_.Build();
  }

  // The distance from each point to the nearest triangle (inf for an empty set).
  py::array_t<double> distance(py::array_t<double, py::array::c_style | py::array::forcecast> P) const {
    if (P.ndim() != 2 || P.shape(1) != 3) throw std::invalid_argument("P (k, 3)");
    const auto p = P.unchecked<2>();
    py::array_t<double> out(p.shape(0));
    auto o = out.mutable_unchecked<1>();
    Nearest search(corners_);
    search.SetBVHSet(const_cast<Boxes*>(&set_));
    for (py::ssize_t i = 0; i < p.shape(0); ++i) {
      search.Start(Vec(p(i, 0), p(i, 1), p(i, 2)));
      o(i) = set_.Size() ? std::sqrt(search.ComputeDistance()) : std::numeric_limits<double>::infinity();
    }
    return out;
  }

 private:
  // Branch and bound: a box no nearer than the best triangle so far is skipped.
  class Nearest : public BVH_Distance<double, 3, Vec, Boxes> {
   public:
    explicit Nearest(const std::vector<Vec>& corners) : corners_(corners) {}
    void Start(const Vec& p) { SetObject(p), myDistance = std::numeric_limits<double>::max(); }
    Standard_Boolean RejectNode(const Vec& lo, const Vec& hi, double& metric) const override {
      metric = BVH_Tools<double, 3>::PointBoxSquareDistance(myObject, lo, hi);
      return RejectMetric(metric);
    }
    Standard_Boolean Accept(const Standard_Integer index, const double&) override {
      const size_t t = 3 * size_t(myBVHSet->Element(index));
      const double d2 = triangle_d2(myObject, corners_[t], corners_[t + 1], corners_[t + 2]);
      if (d2 >= myDistance) return false;
      myDistance = d2;
      return true;
    }
   private:
    const std::vector<Vec>& corners_;
  };
  std::vector<Vec> corners_;  // triangle i: corners_[3 i .. 3 i + 2]
  Boxes set_;
};

TopoDS_Face read_face(const std::string& brep) {
  TopoDS_Shape shape;
  std::istringstream in(brep);
  BRep_Builder builder;
  BRepTools::Read(shape, in, builder);
  if (shape.IsNull() || shape.ShapeType() != TopAbs_FACE) throw std::invalid_argument("not a face's BRep");
  return TopoDS::Face(shape);
}

using UVArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The points of a face's surface at (u, v) (as Part.Face.valueAt: the face's surface adaptor, its placement
// included).
py::array_t<double> surface_points(const std::string& brep, UVArray UV) {
  if (UV.ndim() != 2 || UV.shape(1) != 2) throw std::invalid_argument("UV (k, 2)");
  const BRepAdaptor_Surface surface(read_face(brep));
  const auto uv = UV.unchecked<2>();
  py::array_t<double> out({uv.shape(0), py::ssize_t(3)});
  auto o = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < uv.shape(0); ++i) {
    const gp_Pnt p = surface.Value(uv(i, 0), uv(i, 1));
    o(i, 0) = p.X(), o(i, 1) = p.Y(), o(i, 2) = p.Z();
  }
  return out;
}

// Which (u, v) points lie in a face's trimmed domain: OCCT's 2D classifier of the face's wires, made once for
// all the points (Part.Face.isPartOfDomain makes the same classifier, with the same tolerance, for each point).
py::array_t<bool> in_domain(const std::string& brep, UVArray UV) {
  if (UV.ndim() != 2 || UV.shape(1) != 2) throw std::invalid_argument("UV (k, 2)");
  const BRepTopAdaptor_FClass2d classifier(read_face(brep), Precision::Confusion());
  const auto uv = UV.unchecked<2>();
  py::array_t<bool> out(uv.shape(0));
  auto o = out.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < uv.shape(0); ++i) {
    const TopAbs_State state = classifier.Perform(gp_Pnt2d(uv(i, 0), uv(i, 1)));
    o(i) = state == TopAbs_IN || state == TopAbs_ON;
  }
  return out;
}

}  // namespace

PYBIND11_MODULE(_yardstick, m) {
  m.doc() = "The tests' yardstick's exact measures on OCCT: point to triangle set distances, face domains.";
  py::class_<Triangles>(m, "Triangles")
      .def(py::init<py::array_t<double, py::array::c_style | py::array::forcecast>,
                    py::array_t<long long, py::array::c_style | py::array::forcecast>>(),
           py::arg("V"), py::arg("F"))
      .def("distance", &Triangles::distance, py::arg("P"));
  m.def("surface_points", &surface_points, py::arg("brep"), py::arg("UV"),
        "The points (k, 3) at the rows (u, v) of UV of the face given as a BRep string (as face.valueAt).");
  m.def("in_domain", &in_domain, py::arg("brep"), py::arg("UV"),
        "Which rows (u, v) of UV lie in the trimmed domain of the face given as a BRep string (face.exportBrepToString()).");
}
