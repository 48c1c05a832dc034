#include "meshround/surface.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepGProp.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GProp_GProps.hxx>
#include <Geom_SphericalSurface.hxx>
#include <ShapeFix_Face.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax3.hxx>
#include <algorithm>
#include <BRepTools.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <cmath>
#include <sstream>

namespace meshround {
namespace {

gp_Pnt to_pnt(const Vec3& p) { return gp_Pnt(p.x(), p.y(), p.z()); }
Vec3 to_vec(const gp_XYZ& p) { return Vec3(p.X(), p.Y(), p.Z()); }

// Cubic interpolation of one sequence of points at the given parameters.
Handle(Geom_BSplineCurve) interpolate_raw(const std::vector<Vec3>& pts, const std::vector<double>& params, bool periodic) {
  // A periodic interpolation takes one parameter more than points: the junction's (params has it).
  const int n = int(pts.size());
  Handle(TColgp_HArray1OfPnt) P = new TColgp_HArray1OfPnt(1, n);
  Handle(TColStd_HArray1OfReal) U = new TColStd_HArray1OfReal(1, int(params.size()));
  for (int i = 0; i < n; ++i) P->SetValue(i + 1, to_pnt(pts[i]));
  for (int i = 0; i < int(params.size()); ++i) U->SetValue(i + 1, params[i]);
  GeomAPI_Interpolate interp(P, U, periodic, Precision::Confusion());
  interp.Perform();
  if (!interp.IsDone()) throw RoundingError(ErrorCode::SurfaceFailed, "the rounding surface could not be lofted through its profiles");
  return interp.Curve();
}

// Interpolation through points that may repeat (a contact that stays on a mesh vertex while the ball
// rolls on): OCCT refuses coincident neighbours. With the parameters given the interpolation is linear
// and works coordinate by coordinate, so each coordinate is interpolated on its own, paired with the
// parameter itself (which always moves on), and the poles are put together again.
Handle(Geom_BSplineCurve) interpolate(const std::vector<Vec3>& pts, const std::vector<double>& params, bool periodic) {
  Handle(Geom_BSplineCurve) out;
  for (int c = 0; c < 3; ++c) {
    std::vector<Vec3> lifted(pts.size());
    for (size_t i = 0; i < pts.size(); ++i) lifted[i] = Vec3(pts[i][c], params[i] - params[0], 0);
    Handle(Geom_BSplineCurve) one = interpolate_raw(lifted, params, periodic);
    if (c == 0) out = one;
    if (one->NbPoles() != out->NbPoles()) throw RoundingError(ErrorCode::SurfaceFailed, "inconsistent profile lofts");
    for (int i = 1; i <= out->NbPoles(); ++i) {
      gp_Pnt p = c == 0 ? gp_Pnt(0, 0, 0) : out->Pole(i);
      p.SetCoord(c + 1, one->Pole(i).X());
      out->SetPole(i, p);
    }
  }
  return out;
}

}  // namespace

void profile_arc(const ProfileStation& st, Vec3 poles[3], double weights[3]) {
  const Vec3 a = st.contact[0] - st.centre, b = st.contact[1] - st.centre;
  const double half = 0.5 * std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
  poles[0] = st.contact[0];
  poles[2] = st.contact[1];
  // The middle pole is where the tangents at both contacts meet.
  poles[1] = st.centre + (a + b).normalized() * (st.radius / std::cos(half));
  weights[0] = weights[2] = 1.0;
  weights[1] = std::cos(half);
  if (st.cut.active)
    for (int k = 0; k < 3; ++k) poles[k] = st.cut.onto(poles[k]);
}

namespace {

// The loft's poles along u (homogeneous: pole x weight, and the weight) and its knots, for each of the
// arc's three poles.
struct LoftRows {
  std::vector<Vec3> poles[3];
  std::vector<double> weights[3];
  std::vector<double> knots;
  std::vector<int> mults;
};

// Cubic interpolation of the stations' arcs in homogeneous space (which keeps every station's section
// an exact circle).
LoftRows interpolate_stations(const std::vector<ProfileStation>& stations, bool closed, double period) {
  const int n = int(stations.size());
  std::vector<double> params(n);
  std::vector<Vec3> rows[3], weight_rows[3];
  for (int i = 0; i < n; ++i) {
    Vec3 poles[3];
    double w[3];
    profile_arc(stations[i], poles, w);
    params[i] = stations[i].s;
    // The weight rides in x; y = s only keeps consecutive points apart, as OCCT requires.
    for (int j = 0; j < 3; ++j) rows[j].push_back(poles[j] * w[j]), weight_rows[j].push_back(Vec3(w[j], params[i], 0));
  }
  if (closed) params.push_back(params.front() + period);
  Handle(Geom_BSplineCurve) cp[3], cw[3];
  try {
    for (int j = 0; j < 3; ++j) cp[j] = interpolate(rows[j], params, closed), cw[j] = interpolate_raw(weight_rows[j], params, closed);
  } catch (const Standard_Failure& e) {
    throw RoundingError(ErrorCode::SurfaceFailed, std::string("lofting the rounding surface failed: ") + e.GetMessageString());
  }
  LoftRows out;
  const int nu = cp[0]->NbPoles();
  for (int j = 0; j < 3; ++j) {
    if (cp[j]->NbPoles() != nu || cw[j]->NbPoles() != nu) throw RoundingError(ErrorCode::SurfaceFailed, "inconsistent profile lofts");
    for (int i = 1; i <= nu; ++i) out.poles[j].push_back(to_vec(cp[j]->Pole(i).XYZ())), out.weights[j].push_back(cw[j]->Pole(i).X());
  }
  for (int i = 1; i <= cp[0]->NbKnots(); ++i) out.knots.push_back(cp[0]->Knot(i)), out.mults.push_back(cp[0]->Multiplicity(i));
  return out;
}

// Joins the carried station to the loft's first (at_start) or last end by a straight cubic piece: its
// poles a third and two thirds of the way, weights with them (homogeneous: each section point moves on a
// straight line, to the carried arc's own point -- a carried arc that is not the join's translate, as at
// a sphere corner where it is the corner ball's arc, has weights a hair different).
void add_carried_piece(LoftRows& rows, const ProfileStation& carried, bool at_start) {
  Vec3 end[3];
  double w[3];
  profile_arc(carried, end, w);
  for (int j = 0; j < 3; ++j) {
    auto& P = rows.poles[j];
    auto& W = rows.weights[j];
    const Vec3 from = at_start ? P.front() : P.back(), to = end[j] * w[j];
    const double w_from = at_start ? W.front() : W.back();
    const Vec3 piece[3] = {from + (to - from) / 3, from + 2 * (to - from) / 3, to};
    const double piece_w[3] = {w_from + (w[j] - w_from) / 3, w_from + 2 * (w[j] - w_from) / 3, w[j]};
    for (int i = 0; i < 3; ++i) {
      if (at_start) P.insert(P.begin(), piece[i]), W.insert(W.begin(), piece_w[i]);
      else P.push_back(piece[i]), W.push_back(piece_w[i]);
    }
  }
  if (at_start) {
    rows.mults.front() = 3;
    rows.knots.insert(rows.knots.begin(), carried.s), rows.mults.insert(rows.mults.begin(), 4);
  } else {
    rows.mults.back() = 3;
    rows.knots.push_back(carried.s), rows.mults.push_back(4);
  }
}

}  // namespace

RoundingSurface loft_profiles(const std::vector<ProfileStation>& stations, bool closed, double period) {
  const bool carried[2] = {!closed && stations.front().carried, !closed && stations.back().carried};
  const std::vector<ProfileStation> lofted(stations.begin() + carried[0], stations.end() - carried[1]);
  if (lofted.size() < 4) throw RoundingError(ErrorCode::SurfaceFailed, "too few profiles to loft a rounding surface");
  LoftRows rows = interpolate_stations(lofted, closed, period);
  if (carried[0]) add_carried_piece(rows, stations.front(), true);
  if (carried[1]) add_carried_piece(rows, stations.back(), false);
  const int nu = int(rows.poles[0].size());
  TColgp_Array2OfPnt poles(1, nu, 1, 3);
  TColStd_Array2OfReal weights(1, nu, 1, 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 1; i <= nu; ++i) {
      const double w = rows.weights[j][i - 1];
      if (!(w > 1e-9)) throw RoundingError(ErrorCode::SurfaceFailed, "the rounding surface has a non-positive weight: profiles change too fast");
      poles(i, j + 1) = gp_Pnt(to_pnt(rows.poles[j][i - 1] / w));
      weights(i, j + 1) = w;
    }
  const int nk = int(rows.knots.size());
  TColStd_Array1OfReal uknots(1, nk), vknots(1, 2);
  TColStd_Array1OfInteger umults(1, nk), vmults(1, 2);
  for (int i = 1; i <= nk; ++i) uknots(i) = rows.knots[i - 1], umults(i) = rows.mults[i - 1];
  vknots(1) = 0, vknots(2) = 1, vmults(1) = vmults(2) = 3;

  RoundingSurface out;
  out.closed = closed;
  out.surface = new Geom_BSplineSurface(poles, weights, uknots, vknots, umults, vmults, 3, 2, closed, false);
  out.adaptor = new GeomAdaptor_Surface(out.surface);
  out.u_first = stations.front().s;
  out.u_last = closed ? out.u_first + period : stations.back().s;
  out.u_straight[0] = carried[0] ? lofted.front().s : out.u_first;
  out.u_straight[1] = carried[1] ? lofted.back().s : out.u_last;
  BRepBuilderAPI_MakeFace mk(out.surface, out.u_first, out.u_last, 0.0, 1.0, Precision::Confusion());
  if (!mk.IsDone()) throw RoundingError(ErrorCode::SurfaceFailed, "OCCT could not make a face of the rounding surface");
  out.face = mk.Face();
  return out;
}

double RoundingSurface::wrap(double u) const {
  if (closed) {
    const double p = u_last - u_first;
    return u - std::floor((u - u_first) / p) * p;
  }
  return std::clamp(u, u_first, u_last);
}

Vec3 RoundingSurface::value(double u, double v) const {
  return to_vec(adaptor->Value(wrap(u), v).XYZ());
}

void RoundingSurface::d1(double u, double v, Vec3& p, Vec3& du, Vec3& dv) const {
  gp_Pnt P;
  gp_Vec U, V;
  adaptor->D1(wrap(u), v, P, U, V);
  p = to_vec(P.XYZ()), du = to_vec(U.XYZ()), dv = to_vec(V.XYZ());
}

namespace {

// The face of `ball` bounded by the shorter great-circle arcs between consecutive feet, in that order.
TopoDS_Face ball_face(const Handle(Geom_SphericalSurface)& ball, const Vec3& centre, double radius, const std::vector<Vec3>& feet) {
  auto pnt = [](const Vec3& p) { return gp_Pnt(p.x(), p.y(), p.z()); };
  BRepBuilderAPI_MakeWire wire;
  for (size_t k = 0; k < feet.size(); ++k) {
    const Vec3 &a = feet[k], &b = feet[(k + 1) % feet.size()];
    const Vec3 mid = centre + radius * ((a - centre) + (b - centre)).normalized();
    const GC_MakeArcOfCircle arc(pnt(a), pnt(mid), pnt(b));
    if (!arc.IsDone()) return TopoDS_Face();
    wire.Add(BRepBuilderAPI_MakeEdge(arc.Value()).Edge());
  }
  if (!wire.IsDone()) return TopoDS_Face();
  BRepBuilderAPI_MakeFace make(ball, wire.Wire(), true);
  if (!make.IsDone()) return TopoDS_Face();
  ShapeFix_Face fix(make.Face());  // (the arcs' curves on the ball)
  fix.Perform();
  return fix.Face();
}

double area(const TopoDS_Face& face) {
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props);
  return props.Mass();
}

}  // namespace

TopoDS_Face sphere_patch_face(const Vec3& centre, double radius, std::vector<Vec3> feet, const Vec3& toward_corner) {
  const Vec3 axis = toward_corner.normalized();
  const Vec3 x = (std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(axis).normalized(), y = axis.cross(x);
  auto angle = [&](const Vec3& p) { return std::atan2((p - centre).dot(y), (p - centre).dot(x)); };
  std::sort(feet.begin(), feet.end(), [&](const Vec3& a, const Vec3& b) { return angle(a) < angle(b); });
  try {
    // The ball's poles on a great circle through the patch's middle, its seam opposite the patch: the patch
    // lies in one smooth chart of the parametrisation.
    const Handle(Geom_SphericalSurface) ball = new Geom_SphericalSurface(
        gp_Ax3(gp_Pnt(centre.x(), centre.y(), centre.z()), gp_Dir(y.x(), y.y(), y.z()), gp_Dir(-axis.x(), -axis.y(), -axis.z())), radius);
    // The patch lies under a hemisphere: a face whose area is not that way round is bounded the other way.
    for (int turn = 0; turn < 2; ++turn, std::reverse(feet.begin(), feet.end())) {
      const TopoDS_Face face = ball_face(ball, centre, radius, feet);
      if (face.IsNull()) return face;
      const double a = area(face);
      if (a > 0 && a < 2 * M_PI * radius * radius) return face;
    }
  } catch (const Standard_Failure&) {
  }
  return TopoDS_Face();
}

std::string face_to_brep(const TopoDS_Face& face) {
  std::ostringstream s;
  BRepTools::Write(face, s);
  return s.str();
}

}  // namespace meshround
