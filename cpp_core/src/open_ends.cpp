// Chains that run off the mesh's edge (ChainEnd::Boundary): the plane their round ends on and the check of that
// end (ends.h open_end_cut, check_open_end).
#include "ends.h"

#include <algorithm>
#include <cmath>

#include "guard.h"

namespace meshround {
namespace {

constexpr double kMinSpan = 0.17;  // sin of the angle two edges must make to span a plane (10 deg)

// The mesh boundary through vertex v, from v along its open edge (v, w0): the next vertex after (prev, cur),
// or -1 where the boundary branches or stops.
int next_on_boundary(const MeshTopology& mesh, int prev, int cur) {
  int next = -1;
  for (int x : mesh.vertex_neighbours(cur))
    if (x != prev && mesh.edge_facet_count(cur, x) == 1) {
      if (next >= 0) return -1;
      next = x;
    }
  return next;
}

// The mesh boundary followed from v along its open edge (v, w0), visit(q) at each point, out to where it leaves
// the sphere of radius `within` about v (that point on the sphere the last one), or stops.
template <class Visit>
void walk_boundary(const MeshTopology& mesh, int v, int w0, double within, Visit visit) {
  const Vec3 p = mesh.point(v);
  for (int prev = v, cur = w0, steps = 0; cur >= 0 && cur != v && steps < 100000; ++steps) {
    const Vec3 a = mesh.point(prev), b = mesh.point(cur);
    if ((b - p).norm() > within) {  // the edge's point at distance `within` from p (a inside the sphere, b outside)
      const Vec3 d = b - a, f = a - p;
      const double fd = f.dot(d), dd = d.squaredNorm();
      const double t_out = (-fd + std::sqrt(std::max(fd * fd - dd * (f.squaredNorm() - within * within), 0.0))) / dd;
      visit(Vec3(a + std::clamp(t_out, 0.0, 1.0) * d));
      return;
    }
    visit(b);
    const int next = next_on_boundary(mesh, prev, cur);
    prev = cur, cur = next;
  }
}

// How far out the end profile of a chain's end reaches across the faces: r tan(turn / 2) from the chain.
double end_profile_reach(const MeshTopology& mesh, const SharpChain& chain, const RadiusLaw& law, bool at_start) {
  const int e = at_start ? 0 : chain.num_edges() - 1;
  const double turn = std::acos(std::clamp(mesh.facet_normal(chain.facet_a[e]).dot(mesh.facet_normal(chain.facet_b[e])), -1.0, 1.0));
  return law.at(at_start ? 0.0 : chain.length) * std::tan(0.5 * turn);
}

// How far the boundary through v stands off the plane `cut` (through v), followed both ways from v out to where
// the end profile's contacts are: `reach` from the chain in the faces, so reach / sin(a) along a boundary at
// angle a to the chain. The largest distance and where, and the longest way followed.
struct OffPlane {
  double off = 0, within = 0;
  Vec3 at;
};
OffPlane boundary_off_plane(const MeshTopology& mesh, int v, const EndCut& cut, double reach) {
  const Vec3 p = mesh.point(v);
  OffPlane worst{0.0, 0.0, p};
  for (int w0 : mesh.vertex_neighbours(v)) {
    if (mesh.edge_facet_count(v, w0) != 1 || mesh.point(w0) == p) continue;
    const double sine = (mesh.point(w0) - p).normalized().cross(cut.along).norm();
    const double within = reach / std::max(sine, kMinCrossing);
    worst.within = std::max(worst.within, within);
    walk_boundary(mesh, v, w0, within, [&](const Vec3& q) {
      if (std::abs(cut.past(q)) > worst.off) worst.off = std::abs(cut.past(q)), worst.at = q;
    });
  }
  return worst;
}

// The box of the boundary loop through v if it closes within `limit` (its length), else an empty box.
Eigen::AlignedBox3d short_loop_box(const MeshTopology& mesh, int v, double limit) {
  for (int w0 : mesh.vertex_neighbours(v)) {
    if (mesh.edge_facet_count(v, w0) != 1) continue;
    double length = (mesh.point(w0) - mesh.point(v)).norm();
    Eigen::AlignedBox3d box(mesh.point(v));
    for (int prev = v, cur = w0; cur >= 0 && length <= limit;) {
      if (cur == v) return box;
      box.extend(mesh.point(cur));
      const int next = next_on_boundary(mesh, prev, cur);
      if (next >= 0) length += (mesh.point(next) - mesh.point(cur)).norm();
      prev = cur, cur = next;
    }
    return {};
  }
  return {};
}

constexpr double kHoleLoop = 8.0;   // x r: a boundary loop this short near a round may be a hole, not the mesh's edge,
constexpr double kHoleSize = 0.5;   // when it spans less than this share of the mesh's box (a sheet's edge spans it all)

}  // namespace

bool on_hole(const MeshTopology& mesh, int v, double r) {
  const Eigen::AlignedBox3d loop = short_loop_box(mesh, v, kHoleLoop * r);
  if (loop.isEmpty()) return false;
  Eigen::AlignedBox3d all;
  for (int w = 0; w < mesh.num_vertices(); ++w) all.extend(mesh.point(w));
  return loop.diagonal().norm() < kHoleSize * all.diagonal().norm();
}

// The end of a chain that runs off the mesh's edge, refused where it cannot be made (ends.h open_end_cut):
// a hole there, an edge nearly along the chain, an edge that is not one plane out to the contacts.
void check_open_end(const MeshTopology& mesh, const SharpChain& chain, const RadiusLaw& law, double tolerance, bool at_start,
                    const EndCut& cut) {
  const int v = at_start ? chain.vertices.front() : chain.vertices.back();
  const Vec3 p = mesh.point(v);
  const double r = law.at(at_start ? 0.0 : chain.length);
  const auto [off, within, at] = boundary_off_plane(mesh, v, cut, (1 + 1e-9) * end_profile_reach(mesh, chain, law, at_start));
  const bool along = std::abs(cut.along.dot(cut.normal)) < kMinCrossing;
  if (!along && off <= tolerance + on_plane_slack(within, p.cwiseAbs().maxCoeff())) return;
  if (on_hole(mesh, v, r))
    throw InputFlaw("the mesh is open (a hole in it) at the end of the chain at " + format_point(p) + "; fill the hole first", p);
  if (along)
    throw RoundingError(ErrorCode::CornerNotBlendable,
                        "the chain runs off the mesh's edge at " + format_point(p) + " along that edge, nearly: a round cannot end "
                        "there. Trim the mesh across the chain there, or round it before it is cut");
  throw RoundingError(ErrorCode::CornerNotBlendable,
                      "the chain runs off the mesh's edge at " + format_point(p) + ", but that edge is not one plane there: at " +
                          format_point(at) + " it stands " + format_number(off) + " off the plane of its edges at the chain's "
                          "end (more than the tolerance " + format_number(tolerance) + "); a round ends only on a mesh edge in one "
                          "plane. Trim the mesh straight across the chain there, or round it before it is cut");
}

EndCut open_end_cut(const MeshTopology& mesh, const SharpChain& chain, bool at_start) {
  EndCut cut;
  if (chain.closed || chain.vertices.empty() || (at_start ? chain.start_end : chain.end_end) != ChainEnd::Boundary) return cut;
  // The end vertex in `mesh` (a chain traced on another mesh, as a corner's check gets it: found by its place).
  int v = at_start ? chain.vertices.front() : chain.vertices.back();
  const Vec3 p = at_start ? chain.points.front() : chain.points.back();
  if (v < 0 || v >= mesh.num_vertices() || mesh.point(v) != p) {
    v = -1;
    for (int i = 0; i < mesh.num_vertices() && v < 0; ++i)
      if (mesh.point(i) == p) v = i;
    if (v < 0) return cut;
  }
  const Vec3 out = at_start ? Vec3(-chain.tangent_at(0)) : chain.tangent_at(chain.length);
  std::vector<Vec3> away;  // the directions of the mesh's edge from v
  for (int w : mesh.vertex_neighbours(v))
    if (mesh.edge_facet_count(v, w) == 1 && mesh.point(w) != p) away.push_back((mesh.point(w) - p).normalized());
  Vec3 n = out;  // the plane across the chain: where the edge is not two lines, or they are nearly one line
  if (away.size() == 2 && away[0].cross(away[1]).norm() > kMinSpan) n = away[0].cross(away[1]).normalized();
  else if (away.size() == 2) {  // nearly one line d: the plane through it nearest the plane across the chain
    const Vec3 d = (away[0] - away[1]).normalized();
    if ((out - d * d.dot(out)).norm() > 0) n = (out - d * d.dot(out)).normalized();
  }
  cut.active = true;
  cut.point = p;
  cut.normal = out.dot(n) >= 0 ? n : Vec3(-n);
  cut.along = out;
  return cut;
}

}  // namespace meshround
