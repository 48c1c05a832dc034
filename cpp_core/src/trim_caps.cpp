#include "trim_caps.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace meshround {

// x the radius: how far "above" a face a vertex on its trace may measure in the cap's corner region, the
// ball's contact directions leaning off the face's normal (up to 0.8 deg over the region's 1.4 r).
constexpr double kTraceLeanShare = 0.02;

// Facets of the end faces that the round cuts into at a capped chain end (a convex end), or that have a
// vertex on the faces' traces within the band (a concave end: the round adds to the end face, and such a
// vertex would sit right next to the arc).
void remove_cap_corner(const MeshTopology& mesh, const BaseMeshes& base, int corner, const ProfileStation& st,
                       MeshEdit& edit, int* removed) {
  // eps: "on" the traces and the arc, generous enough for float32 input coordinates (STL, Mesh.Mesh).
  const double r = st.radius, eps = 1e-4 * r;
  const Vec3 a = (st.contact[0] - st.centre).normalized(), b = (st.contact[1] - st.centre).normalized();
  Eigen::Matrix<double, 3, 2> basis;
  basis << a, b;
  const Eigen::Matrix2d gram_inv = (basis.transpose() * basis).inverse();
  const Vec3 plane_normal = a.cross(b).normalized();
  // R: the corner of the end face between the two faces' traces and the arc. `closed` admits its
  // boundary too (but not the contacts themselves, which the round keeps), and a rim a tenth of r
  // inside the arc: a vertex that near the arc would only leave slivers between itself and the arc.
  // At an end cut by its end face (st.cut) the region lies in the face's plane: a point there is taken
  // back along the chain onto the ball's section, where the region is the circle's.
  // A vertex of a base facet lies on a face's trace: the region's boundary there, though the ball's contact
  // directions may lean off the face's normal by up to kTraceLeanShare (a sharpened box's top corner made
  // again at 5 mm: 0.075 deg, which put a trace vertex 2.5 mm from the contact 0.0033 mm "above" the face,
  // and the cap kept the facet across the contact, then filled over it).
  auto in_corner_region = [&](const Vec3& q, bool closed, bool on_trace = false) {
    if (st.cut.active && std::abs(st.cut.past(q)) > kOnCapPlaneShare * r) return false;
    const Vec3 p = st.cut.active ? Vec3(q - st.cut.along * (q - st.centre).dot(st.cut.along)) : q;
    const Vec3 d = p - st.centre;
    if (std::abs(d.dot(plane_normal)) > kOnCapPlaneShare * r) return false;
    const Eigen::Vector2d ab = gram_inv * (basis.transpose() * d);
    const double e = closed ? -eps : eps;
    if (closed && ((p - st.contact[0]).norm() < 1e-6 * r || (p - st.contact[1]).norm() < 1e-6 * r)) return false;
    const double rim = closed ? 0.1 * r : -eps;
    const double lean = on_trace ? kTraceLeanShare * r : 0.0;
    return ab.x() > e && ab.y() > e && d.norm() > r - rim && d.dot(a) < r - e + lean && d.dot(b) < r - e + lean;
  };
  auto strictly_inside = [&](const Vec3& p) { return in_corner_region(p, false); };
  auto on_a_trace = [&](int v) {
    return std::any_of(mesh.facets_begin(v), mesh.facets_end(v), [&](int g) { return base.side_of.count(g) > 0; });
  };
  std::vector<int> todo(mesh.facets_begin(corner), mesh.facets_end(corner));
  std::unordered_set<int> seen(todo.begin(), todo.end());
  while (!todo.empty()) {
    const int f = todo.back();
    todo.pop_back();
    if (base.side_of.count(f)) continue;
    const Vec3 p0 = mesh.corner(f, 0), p1 = mesh.corner(f, 1), p2 = mesh.corner(f, 2), g = (p0 + p1 + p2) / 3;
    std::vector<Vec3> samples{g, (p0 + p1) / 2, (p1 + p2) / 2, (p2 + p0) / 2};
    for (int k = 0; k < 3; ++k)
      if (mesh.F(f, k) == corner) samples.push_back(mesh.point(corner) + 0.02 * (g - mesh.point(corner)));
    // (At an end cut by a plane, only the end face's facets in that plane: not a face that merely meets it.)
    const double on = kOnCapPlaneShare * r;
    if (st.cut.active && !(std::abs(st.cut.past(p0)) <= on && std::abs(st.cut.past(p1)) <= on && std::abs(st.cut.past(p2)) <= on))
      continue;
    bool vertex_in = false;
    for (int k = 0; k < 3; ++k) vertex_in |= in_corner_region(mesh.corner(f, k), true, on_a_trace(mesh.F(f, k)));
    if (!vertex_in && std::none_of(samples.begin(), samples.end(), strictly_inside)) continue;
    if (edit.removed.insert(f).second) ++*removed;
    for (int k = 0; k < 3; ++k)
      for (const int* h = mesh.facets_begin(mesh.F(f, k)); h != mesh.facets_end(mesh.F(f, k)); ++h)
        if (seen.insert(*h).second) todo.push_back(*h);
  }
}

}  // namespace meshround
