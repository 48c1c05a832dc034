// A strip of rounds mitred into each other (strip_facets.h recognise_mitred): a pocket's rim whose wall
// corners stayed sharp, a box's two top edges meeting at a corner whose vertical edge stayed sharp. OCCT's
// fillet runs each round on to the plane bisecting the two walls there, where the two meet in one curve
// (a crease). The strip's sides are one plane A (the top face) and one plane B per round (its wall); each
// vertex belongs to the round whose wall is nearest (the bisecting planes are where two are equally near)
// and takes that round's frame; a vertex on a crease is folded in its round's section and then slid along
// the corner line onto the bisecting plane, where the two rebuilt sharp edges meet.
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_set>

#include "strip_facets.h"
#include "strip_line.h"

namespace meshround::strip_detail {
namespace {

// A plane of the flat facets beside the flood, and how much of the flood's border runs along it.
struct SidePlane {
  Vec3 normal = Vec3::Zero();
  double offset = 0;
  std::vector<int> facets;
  double border = 0;  // length of the flood's edges shared with its facets
  double side = 0;    // which side of it the round lies on (the sign: the flood's corners beside it)
};

// The distinct planes of `beside`: facets whose normals agree within 2 flat_deg and whose corners lie on
// one plane (within `slack`) are one; false when some facet fits none of the planes it turns like (a
// side curved along the round: the curved strip's case).
bool cluster_planes(const MeshTopology& mesh, Facets& fx, const std::vector<int>& beside, double flat_deg, double slack,
                    std::vector<SidePlane>& planes) {
  for (int f : beside) {
    SidePlane* home = nullptr;
    for (SidePlane& p : planes)
      if (angle_deg(fx.normal(f), p.normal.normalized()) < 2 * flat_deg) {
        const Vec3 n = p.normal.normalized();
        bool on = true;
        for (int k = 0; k < 3; ++k) on &= std::abs(n.dot(mesh.corner(f, k)) - p.offset) <= slack;
        if (on) home = &p;
        else if (!home) continue;
        break;
      }
    if (!home) planes.push_back({}), home = &planes.back(), home->offset = fx.normal(f).dot(fx.centroid(f));
    home->normal += fx.area(f) * fx.normal(f), home->facets.push_back(f);
  }
  for (SidePlane& p : planes) {
    p.normal.normalize();
    double sum = 0;
    for (int f : p.facets) sum += p.normal.dot(fx.centroid(f));
    p.offset = sum / double(p.facets.size());
    for (int f : p.facets)
      for (int k = 0; k < 3; ++k)
        if (std::abs(p.normal.dot(mesh.corner(f, k)) - p.offset) > slack) return false;
  }
  return true;
}

// The plane through its facets' corners, least squares (the rebuilt edges meet the walls' own facets: a
// normal from one row of facets beside the strip tilts by 1e-6 rad from float32 corners, 5e-5 mm over a
// 40 mm wall, and two rounds mitred on the rebuilt edges then no longer share their end profile).
void fit_plane(const MeshTopology& mesh, SidePlane& p) {
  std::unordered_set<int> corners;
  for (int f : p.facets)
    for (int k = 0; k < 3; ++k) corners.insert(mesh.F(f, k));
  Vec3 mean = Vec3::Zero();
  for (int v : corners) mean += mesh.point(v);
  mean /= double(corners.size());
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (int v : corners) spread += (mesh.point(v) - mean) * (mesh.point(v) - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(spread);
  Vec3 n = eig.eigenvectors().col(0).normalized();
  if (n.dot(p.normal) < 0) n = -n;
  if (angle_deg(n, p.normal) < 1) p.normal = n, p.offset = n.dot(mean);  // (a row of facets too thin to fit: as it was)
}

// A vertex is on a crease when its distances to two walls agree within kCreaseSlack of them plus kCreaseEdges
// of the strip's median edge. (OCCT's crease is an approximated intersection curve: near the walls, where
// the two rounds meet nearly tangent, its vertices lie 0.003 mm off both rounds on a 0.8 mm mesh of a 2 mm
// rim; a vertex off the crease lies a good share of an edge from it.)
constexpr double kCreaseSlack = 1e-3;
constexpr double kCreaseEdges = 0.02;
// Two walls whose rounds are mitred meet at an edge turning by this much at least (a pocket's wall corner:
// 90 degrees; a CAD mesh's columns of a wall curved in plan turn by its angular deflection, about 11).
constexpr double kMitreWallDeg = 30;
// The share of a strip's area whose facets may tilt off their round's section planes (strip.cpp's kTiltedShare).
constexpr double kTiltedArea = 0.02;

// A piece: one round of the strip, between plane A and its own plane B.
struct Piece {
  int plane = -1;  // index into the planes
  StripFrame frame;
  int next = -1, prev = -1;  // the pieces it is mitred to at its high / low end (along frame.axis)
  Vec3 start = Vec3::Zero(), end = Vec3::Zero();  // its corner line's ends (a mitre's corner or an end's foot)
  double s0 = 0;  // arc length along the strip at `start`
};

StripFrame piece_frame(const SidePlane& a, const SidePlane& b, double side_a, double side_b, const Vec3& where) {
  StripFrame f;
  f.normal[0] = a.normal, f.normal[1] = b.normal;
  f.offset[0] = a.offset, f.offset[1] = b.offset;
  f.side[0] = side_a, f.side[1] = side_b;
  f.axis = a.normal.cross(b.normal).normalized();
  f.corner = frame_solve(f.normal[0], f.normal[1], f.axis, Vec3(f.offset[0], f.offset[1], f.axis.dot(where)));
  f.centre_dir = frame_solve(f.normal[0], f.normal[1], f.axis, Vec3(f.side[0], f.side[1], 0));
  return f;
}

// The recognition's passes over one flood, in order (each false: not mitred rounds); `a` is plane A's index
// in `planes`, the others are the rounds' walls; a round is keyed by its wall's index.
struct MitrePass {
  struct Near { int piece = -1, other = -1; };  // a vertex's round (a crease's: the two rounds it joins)

  const MeshTopology& mesh;
  Facets& fx;
  const SharpenOptions& o;
  double slack = 0;                        // a vertex this near a plane lies on it (float32 coordinates)
  std::vector<SidePlane> planes;
  size_t a = 0;
  std::vector<int> flood;                  // the strip's facets
  std::unordered_set<int> in_strip;
  std::unordered_map<int, int> plane_of;   // a side's facet -> its plane
  std::unordered_map<int, int> piece_of;   // a strip facet -> its round
  std::unordered_map<int, Near> near;      // a strip vertex -> its round(s)
  std::map<int, std::vector<int>> members; // a round -> its vertices
  std::map<int, Piece> pieces;
  std::vector<int> order;                  // the rounds along the strip
  bool closed = false;

  MitrePass(const MeshTopology& m, Facets& f, const SharpenOptions& opt) : mesh(m), fx(f), o(opt) {}

  // A facet with a corner whose facets all lie in its plane or across a sharp edge from it touches the
  // round with one edge at most: a side's. (Facets::flat tells the sides on fine meshes, but a CAD mesh's
  // round has rows of facets lying flat, and a side may be one or two facets, each bordering the round.)
  bool off_the_round(int f) {
    for (int k = 0; k < 3; ++k) {
      bool flat = true;
      for (const int* h = mesh.facets_begin(mesh.F(f, k)); flat && h != mesh.facets_end(mesh.F(f, k)); ++h) {
        const double turn = angle_deg(fx.normal(f), fx.normal(*h));
        flat = turn < o.flat_deg || turn >= o.strip_turn_deg;
      }
      if (flat) return true;
    }
    return false;
  }
  // The sides' planes from the facets beside the flood that are off the round, or where they make fewer than
  // three (a CAD mesh's face of two facets, both bordering the round, was flooded), from those in the flood
  // too; `rest`: the other facets (the strip's, but for those lying on a side's plane, below).
  bool side_planes(const std::vector<int>& flood_in, const std::vector<int>& beside, std::vector<int>& rest) {
    std::vector<int> sides;
    for (int f : beside) (off_the_round(f) ? sides : rest).push_back(f);
    if (cluster_planes(mesh, fx, sides, o.flat_deg, slack, planes) && planes.size() >= 3) {
      rest.insert(rest.end(), flood_in.begin(), flood_in.end());
      return true;
    }
    planes.clear(), rest.clear();
    for (const std::vector<int>* part : {&beside, &flood_in})
      for (int f : *part) (off_the_round(f) ? sides : rest).push_back(f);
    return cluster_planes(mesh, fx, sides, o.flat_deg, slack, planes) && planes.size() >= 3;
  }

  // The planes beside the flood and the strip's facets; plane A and the side of each plane the rounds lie on.
  bool find_planes(int f0, const std::vector<int>& flood_in, const std::vector<int>& beside) {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (int f : flood_in)
      for (int k = 0; k < 3; ++k) lo = lo.cwiseMin(mesh.corner(f, k)), hi = hi.cwiseMax(mesh.corner(f, k));
    slack = 2 * on_plane_slack((hi - lo).norm(), std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()));
    std::vector<int> rest;
    if (!side_planes(flood_in, beside, rest)) return false;

    // The flood's first row on each side lies on the side's plane (a facet there is curved by Facets::flat,
    // its neighbour on the round turning from it): the side's, not the strip's.
    for (int f : rest) {
      bool on_side = false;
      for (SidePlane& p : planes) {
        if (angle_deg(fx.normal(f), p.normal) >= 2 * o.flat_deg) continue;
        bool on = true;
        for (int k = 0; k < 3; ++k) on &= std::abs(p.normal.dot(mesh.corner(f, k)) - p.offset) <= slack;
        if (on) p.facets.push_back(f), on_side = true;
        if (on) break;
      }
      if (!on_side) flood.push_back(f);
    }
    if (flood.empty() || std::find(flood.begin(), flood.end(), f0) == flood.end()) return false;
    // A mesher's sliver in a crease whose normal turns from all its neighbours' by strip_turn_deg or more was
    // not flooded: a facet across the strip's edge whose corners are all the strip's is the strip's (but for a
    // side's: a CAD mesh's facet across a mitre's corner on plane A has its corners on two rounds' borders).
    {
      std::unordered_set<int> vertices, have(flood_in.begin(), flood_in.end());
      for (const SidePlane& p : planes) have.insert(p.facets.begin(), p.facets.end());
      for (int f : flood)
        for (int k = 0; k < 3; ++k) vertices.insert(mesh.F(f, k));
      for (size_t i = 0, n = flood.size(); i < n; ++i)
        for (int k = 0; k < 3; ++k) {
          const int g = fx.across(flood[i], k);
          if (g < 0 || have.count(g)) continue;
          bool inside = true;
          for (int j = 0; j < 3; ++j) inside &= vertices.count(mesh.F(g, j)) > 0;
          for (int j = 0; j < 3 && inside; ++j) {  // (not a face's facet beside the strip: a CAD mesh's end face
            const int h = fx.across(g, j);          // fans from the arc's end to the arc's vertices)
            inside = h < 0 || have.count(h) || angle_deg(fx.normal(g), fx.normal(h)) >= o.flat_deg;
          }
          if (inside) flood.push_back(g), have.insert(g);
        }
    }
    for (SidePlane& p : planes) fit_plane(mesh, p);

    // Plane A: the one the flood's border runs along longest (the top face borders every round), not
    // parallel to any other; the rest are the rounds' planes B.
    in_strip.insert(flood.begin(), flood.end());
    for (size_t i = 0; i < planes.size(); ++i)
      for (int f : planes[i].facets) plane_of[f] = int(i);
    for (int f : flood)
      for (int k = 0; k < 3; ++k) {
        const int g = fx.across(f, k);
        auto it = g >= 0 ? plane_of.find(g) : plane_of.end();
        if (it == plane_of.end()) continue;
        SidePlane& p = planes[size_t(it->second)];
        p.border += (mesh.corner(f, k) - mesh.corner(f, (k + 1) % 3)).norm();
        p.side += p.normal.dot(mesh.corner(f, (k + 2) % 3)) - p.offset;  // (f's corner off the shared edge)
      }
    a = 0;
    for (size_t i = 1; i < planes.size(); ++i)
      if (planes[i].border > planes[a].border) a = i;
    for (size_t i = 0; i < planes.size(); ++i)
      if (i != a && std::abs(planes[i].normal.dot(planes[a].normal)) > std::cos(20 * kDeg)) return false;

    for (SidePlane& p : planes) p.side = p.side > 0 ? 1.0 : -1.0;
    return true;
  }

  // The rounds: the strip's facets split at the creases, each part a round on the wall it borders most.
  bool split_rounds() {
    // The creases: edges whose two ends are each as far from two walls (on the rounds' side of both). The
    // facets flooded from each other across every other edge are one round each; its wall is the plane B its
    // facets border most.
    const double edge = [&] {
      std::vector<double> lengths;
      for (int f : flood)
        for (int k = 0; k < 3; ++k) lengths.push_back((mesh.corner(f, k) - mesh.corner(f, (k + 1) % 3)).norm());
      std::nth_element(lengths.begin(), lengths.begin() + long(lengths.size() / 2), lengths.end());
      return lengths[lengths.size() / 2];
    }();
    auto crease_pair = [&](int v) {  // the two walls v is equally far from, or (-1, -1)
      std::vector<std::pair<double, int>> d;
      for (size_t i = 0; i < planes.size(); ++i) {
        const double x = planes[i].side * (planes[i].normal.dot(mesh.point(v)) - planes[i].offset);
        if (i != a && x >= -slack) d.push_back({x, int(i)});
      }
      for (size_t i = 0; i < d.size(); ++i)
        for (size_t j = i + 1; j < d.size(); ++j)
          if (std::abs(d[i].first - d[j].first) <= kCreaseSlack * std::max(d[i].first, d[j].first) + kCreaseEdges * edge) return std::pair<int, int>(std::min(d[i].second, d[j].second), std::max(d[i].second, d[j].second));
      return std::pair<int, int>(-1, -1);
    };
    std::unordered_map<int, std::pair<int, int>> crease;  // vertex -> its walls
    for (int f : flood)
      for (int k = 0; k < 3; ++k)
        if (!crease.count(mesh.F(f, k))) crease[mesh.F(f, k)] = crease_pair(mesh.F(f, k));
    for (int seed_facet : flood) {
      if (piece_of.count(seed_facet)) continue;
      std::vector<int> component{seed_facet};
      piece_of[seed_facet] = -1;
      for (size_t i = 0; i < component.size(); ++i) {
        const int f = component[i];
        for (int k = 0; k < 3; ++k) {
          const int g = fx.across(f, k), u = mesh.F(f, k), w = mesh.F(f, (k + 1) % 3);
          if (g < 0 || !in_strip.count(g) || piece_of.count(g)) continue;
          if (crease.at(u).first >= 0 && crease.at(u) == crease.at(w)) continue;  // a crease edge
          piece_of[g] = -1, component.push_back(g);
        }
      }
      std::map<int, double> along;  // plane B -> border length
      for (int f : component)
        for (int k = 0; k < 3; ++k) {
          const int g = fx.across(f, k);
          auto it = g >= 0 ? plane_of.find(g) : plane_of.end();
          if (it != plane_of.end() && size_t(it->second) != a) along[it->second] += (mesh.corner(f, k) - mesh.corner(f, (k + 1) % 3)).norm();
        }
      if (along.empty()) continue;  // a sliver lying in a crease (all its corners on it): its neighbour's, below
      const int wall = std::max_element(along.begin(), along.end(), [](auto x, auto y) { return x.second < y.second; })->first;
      for (int f : component) piece_of[f] = wall;
    }
    for (bool changed = true; changed;) {
      changed = false;
      for (int f : flood)
        for (int k = 0; k < 3 && piece_of.at(f) < 0; ++k) {
          const int g = fx.across(f, k);
          if (g >= 0 && in_strip.count(g) && piece_of.at(g) >= 0) piece_of[f] = piece_of.at(g), changed = true;
        }
    }
    for (int f : flood)
      if (piece_of.at(f) < 0) return false;
    // Each vertex's round (a crease vertex: the two rounds it joins).
    for (int f : flood)
      for (int k = 0; k < 3; ++k) {
        Near& n = near[mesh.F(f, k)];
        const int p = piece_of.at(f);
        if (n.piece < 0) n.piece = p, members[p].push_back(mesh.F(f, k));
        else if (n.piece != p && n.other < 0) n.other = p;
        else if (n.piece != p && n.other != p) return false;  // three rounds at one vertex: a corner blend
      }
    for (const auto& [p, vs] : members) {
      Piece& piece = pieces[p];
      piece.plane = p;
      piece.frame = piece_frame(planes[a], planes[size_t(p)], planes[a].side, planes[size_t(p)].side, mesh.point(vs.front()));
    }
    if (pieces.size() < 2) return false;
    // Every facet turns about its round's corner line (but for the mesher's slivers: kTiltedArea of the area,
    // as turning_axis allows), else the strip is a corner blend or a free-form region, not mitred rounds.
    const double facet_tilt = std::sin(o.facet_tilt_deg * kDeg);
    double tilted = 0, total = 0;
    for (int f : flood) {
      const auto piece = pieces.find(piece_of.at(f));
      if (piece == pieces.end()) return false;  // a round whose vertices are all others' (a crease's): not mitred rounds
      total += fx.area(f);
      if (std::abs(fx.normal(f).dot(piece->second.frame.axis)) > facet_tilt) tilted += fx.area(f);
    }
    return tilted <= kTiltedArea * total;
  }

  // The rounds in order along the strip, joined at the mitres' corners, their axes turned to run one way.
  bool order_rounds(int f0) {
    // The pieces in order: each crease joins two; the corner of a mitre is where plane A meets both planes B.
    std::map<std::pair<int, int>, Vec3> corners;
    for (const auto& [v, n] : near)
      if (n.other >= 0) {
        const std::pair<int, int> key(std::min(n.piece, n.other), std::max(n.piece, n.other));
        if (corners.count(key)) continue;
        const SidePlane &pa = planes[a], &p1 = planes[size_t(key.first)], &p2 = planes[size_t(key.second)];
        Eigen::Matrix3d M;
        M.row(0) = pa.normal.transpose(), M.row(1) = p1.normal.transpose(), M.row(2) = p2.normal.transpose();
        const Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
        if (std::abs(lu.determinant()) < 1e-6) return false;  // parallel walls: no corner
        corners[key] = lu.solve(Eigen::Vector3d(pa.offset, p1.offset, p2.offset));
      }
    // The middle of each round along its axis: of its vertices' extent, creases' included (their mean leans
    // to where the vertices crowd: on a CAD mesh of a drafted rim, along the creases past a corner).
    std::map<int, double> middle;
    {
      std::map<int, std::pair<double, double>> extent;
      for (const auto& [v, n] : near)
        for (int p : {n.piece, n.other}) {
          if (p < 0) continue;
          const double s = pieces.at(p).frame.axis.dot(mesh.point(v));
          auto it = extent.emplace(p, std::make_pair(s, s)).first;
          it->second.first = std::min(it->second.first, s), it->second.second = std::max(it->second.second, s);
        }
      for (const auto& [p, e] : extent) middle[p] = 0.5 * (e.first + e.second);
    }
    for (const auto& [key, c] : corners)
      for (int side = 0; side < 2; ++side) {
        Piece& piece = pieces.at(side ? key.second : key.first);
        const int other = side ? key.first : key.second;
        // Its axis points away from a corner at its low end (prev), toward the one at its high end (next).
        const bool high = piece.frame.axis.dot(c) > middle.at(piece.plane);
        int& slot = high ? piece.next : piece.prev;
        if (slot >= 0 && slot != other) return false;  // two corners at one end
        slot = other;
        (high ? piece.end : piece.start) = c;
      }
    // Walls that meet at a sharp edge: a tessellated wall curved in plan (its columns a few degrees apart) is
    // the curved strip's case.
    for (const auto& [key, c] : corners)
      if (angle_deg(planes[size_t(key.first)].normal, planes[size_t(key.second)].normal) < kMitreWallDeg) return false;
    // Every piece joined consistently (a's next is b, so b's prev is a: axes turned to run one way).
    const int first_key = near.at(mesh.F(f0, 0)).piece;
    order = {first_key};
    for (int guard = 0; guard < int(pieces.size()); ++guard) {  // walk back to the first piece of an open strip
      const Piece& p = pieces.at(order.front());
      if (p.prev < 0 || p.prev == first_key) break;
      order.insert(order.begin(), p.prev);
    }
    while (order.size() < pieces.size()) {
      const Piece& p = pieces.at(order.back());
      if (p.next < 0) break;
      Piece& q = pieces.at(p.next);
      if (q.prev != order.back()) {  // q runs the other way: turn its frame round
        std::swap(q.prev, q.next), std::swap(q.start, q.end);
        q.frame.axis = -q.frame.axis;
        if (q.prev != order.back()) return false;
      }
      if (p.next == order.front()) break;
      order.push_back(p.next);
    }
    if (order.size() != pieces.size()) return false;
    closed = pieces.at(order.back()).next == order.front();
    // An open strip's ends: its first and last pieces' vertices' extent along their own axes.
    for (int end = 0; end < 2; ++end) {
      if (closed) break;
      Piece& p = pieces.at(end ? order.back() : order.front());
      double s = end ? -INFINITY : INFINITY;
      for (int v : members.at(p.plane)) s = end ? std::max(s, p.frame.s_of(mesh.point(v))) : std::min(s, p.frame.s_of(mesh.point(v)));
      (end ? p.end : p.start) = p.frame.corner + s * p.frame.axis;
    }
    return true;
  }

  // The plane where walls i and j are equally far (on the rounds' side): their mitre's.
  StripEnd bisector(int i, int j) const {
    const SidePlane &b1 = planes[size_t(i)], &b2 = planes[size_t(j)];
    StripEnd plane;
    plane.normal = b1.side * b1.normal - b2.side * b2.normal;
    plane.offset = b1.side * b1.offset - b2.side * b2.offset;
    const double len = plane.normal.norm();
    plane.normal /= len, plane.offset /= len;
    return plane;
  }

  // The strip: every facet, each vertex in its round's frame, the corner line through the mitres' corners.
  void make_strip(int f0, RoundStrip& strip, std::vector<std::pair<int, int>>& end_edges) {
    strip.curved = true, strip.closed = closed;
    strip.mitred = true;
    double s = 0;
    for (int key : order) {
      Piece& p = pieces.at(key);
      p.s0 = s;
      p.frame.corner = p.start;  // s_of measured from the piece's start
      p.frame.piece = int(strip.pieces.size());
      strip.line.push_back(p.start), strip.line_s.push_back(s), strip.stations.push_back(p.frame);
      strip.pieces.push_back({p.frame, s, (p.end - p.start).norm(), {}});
      for (int other : {p.prev, p.next})
        if (other >= 0) strip.pieces.back().mitres.push_back(bisector(key, other));
      if (p.prev >= 0) strip.pieces.back().lo = 0;
      if (p.next >= 0) strip.pieces.back().hi = strip.pieces.back().length;
      s += (p.end - p.start).norm();
    }
    if (!closed) {
      const Piece& last = pieces.at(order.back());
      strip.line.push_back(last.end), strip.line_s.push_back(s), strip.stations.push_back(last.frame);
    }
    strip.loop_length = s;
    static_cast<StripFrame&>(strip) = pieces.at(near.at(mesh.F(f0, 0)).piece).frame;
    strip.normal[0] = planes[a].normal, strip.normal[1] = planes[size_t(near.at(mesh.F(f0, 0)).piece)].normal;
    strip.end_frame[0] = pieces.at(order.front()).frame, strip.end_frame[1] = pieces.at(order.back()).frame;
    strip.facets = flood;
    strip.facet_set.insert(flood.begin(), flood.end());
    for (const auto& [v, n] : near) {
      const Piece& p = pieces.at(n.piece);
      strip.frames[v] = p.frame;
      const Vec3 x = mesh.point(v);
      StripRole role = StripRole::Inner;
      if (std::abs(planes[a].normal.dot(x) - planes[a].offset) <= slack) role = StripRole::BorderA;
      else if (std::abs(planes[size_t(p.plane)].normal.dot(x) - planes[size_t(p.plane)].offset) <= slack) role = StripRole::BorderB;
      strip.role[v] = role;
      if (n.other >= 0 && role == StripRole::Inner)  // on a crease
        strip.mitre_of[v] = {bisector(n.piece, n.other), {std::min(pieces.at(n.piece).frame.piece, pieces.at(n.other).frame.piece),
                                                          std::max(pieces.at(n.piece).frame.piece, pieces.at(n.other).frame.piece)}};
    }
    strip.border_count[0] = strip.border_count[1] = 0;
    for (const auto& [v, role] : strip.role)
      if (role == StripRole::BorderA || role == StripRole::BorderB) ++strip.border_count[role == StripRole::BorderB];
    // The flood's edges to anything but its sides' facets: its ends (end faces, or the mesh boundary).
    for (int f : flood)
      for (int k = 0; k < 3; ++k) {
        const int g = fx.across(f, k);
        if (g < 0 || !(in_strip.count(g) || plane_of.count(g))) end_edges.push_back({f, k});
      }
    strip.s_lo = closed ? 0.0 : INFINITY, strip.s_hi = closed ? s : -INFINITY;
    if (!closed)
      for (const auto& [v, n] : near) strip.s_lo = std::min(strip.s_lo, strip.param(mesh.point(v))), strip.s_hi = std::max(strip.s_hi, strip.param(mesh.point(v)));
  }
};

}  // namespace

bool recognise_mitred(const MeshTopology& mesh, Facets& fx, int f0, const std::vector<int>& flood, const std::vector<int>& beside,
                      const SharpenOptions& o, const Vec3& where, RoundStrip& strip, std::vector<std::pair<int, int>>& end_edges) {
  (void)where;  // (a strip that is not mitred goes on to the curved strip's recognition, which names the place)
  MitrePass pass(mesh, fx, o);
  if (!pass.find_planes(f0, flood, beside) || !pass.split_rounds() || !pass.order_rounds(f0)) return false;
  pass.make_strip(f0, strip, end_edges);
  return true;
}

}  // namespace meshround::strip_detail
