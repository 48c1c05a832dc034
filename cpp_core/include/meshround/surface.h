// Paper §4.4-4.5: exact circular profiles as rational quadratic NURBS, lofted into one OCCT B-spline
// surface per chain (cubic along the spine, rational quadratic across; periodic for a closed loop).
#pragma once
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TopoDS_Face.hxx>
#include <string>
#include <vector>

#include "meshround/spine.h"

namespace meshround {

struct RoundingSurface {
  Handle(Geom_BSplineSurface) surface;
  TopoDS_Face face;
  bool closed = false;
  double u_first = 0, u_last = 0;  // u = arc length along the chain; v in [0, 1] from side A to side B
  // Where a carried end's straight piece joins the loft (loft_profiles); u_first / u_last where there is none.
  double u_straight[2] = {0, 0};

  Vec3 value(double u, double v) const;
  // Point, d/du and d/dv.
  void d1(double u, double v, Vec3& p, Vec3& du, Vec3& dv) const;
  double wrap(double u) const;  // into [u_first, u_last) for a closed surface, clamped otherwise

  // Evaluation through OCCT's adaptor, which keeps the current span's polynomial cached (the surface's
  // own D0 / D1 walk its knot list on every call: slow on a long chain's thousands of stations).
  Handle(GeomAdaptor_Surface) adaptor;
};

// Rational quadratic Bezier of the circular arc from contact A to contact B about the centre:
// poles (3) and weights (1, cos(angle/2), 1); at a capped end (st.cut) the poles moved onto the end face.
void profile_arc(const ProfileStation& st, Vec3 poles[3], double weights[3]);

// Lofts the profiles (at least 4, sorted by s; for a loop, s in [0, period) and no repeat). A carried end
// station (ProfileStation::carried) is joined to its neighbour by a straight piece, C0 in u there: each
// point of the neighbour's arc moves along the chain in proportion to u until it reaches the end face (a
// cubic through that kink would overshoot past the face where a contact barely moves).
RoundingSurface loft_profiles(const std::vector<ProfileStation>& stations, bool closed, double period);

// The patch of the ball (centre, radius) bounded by the great-circle arcs between consecutive `feet` (taken
// in their order around the ball's axis `toward_corner`, from the centre towards the corner's vertex): a
// sphere corner's face, as exact as the rounds' (sphere_corner.h). A null face when OCCT cannot make it.
TopoDS_Face sphere_patch_face(const Vec3& centre, double radius, std::vector<Vec3> feet, const Vec3& toward_corner);

// OCCT BRep text of a face (what FreeCAD's Part.Shape.importBrepFromString reads).
std::string face_to_brep(const TopoDS_Face& face);

}  // namespace meshround
