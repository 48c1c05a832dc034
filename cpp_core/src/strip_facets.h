// Private to the strip recognition (strip.cpp, strip_curved.cpp, strip_line.cpp): the facets' normals and
// neighbours, the flood of a strip's facets, and the refusal they share.
#pragma once
#include <algorithm>
#include <cmath>
#include <deque>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "meshround/mesh_edit.h"
#include "strip.h"

namespace meshround::strip_detail {

constexpr double kDeg = M_PI / 180.0;

[[noreturn]] inline void not_a_round(const std::string& why, const Vec3& where) {
  throw RoundingError(ErrorCode::NotARound, "the strip picked at " + format_point(where) + " is not a round between two flat sides: " + why);
}

inline double angle_deg(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(a.dot(b), -1.0, 1.0)) / kDeg; }

// The facets' normals and smooth neighbours, looked up once per facet.
class Facets {
 public:
  Facets(const MeshTopology& mesh, const SharpenOptions& o) : mesh_(mesh), o_(o) {}
  const Vec3& normal(int f) {
    auto it = normal_.find(f);
    if (it == normal_.end()) it = normal_.emplace(f, mesh_.facet_normal(f)).first;
    return it->second;
  }
  // The neighbour across edge k of f (-1: boundary), refusing a non-manifold or flipped neighbour.
  int across(int f, int k) {
    const int a = mesh_.F(f, k), b = mesh_.F(f, (k + 1) % 3);
    int pair[2];
    const int count = mesh_.edge_facet_pair(a, b, pair);
    if (count == 1) return -1;
    const Vec3 mid = 0.5 * (mesh_.point(a) + mesh_.point(b));
    if (count > 2) throw RoundingError(ErrorCode::NonManifoldInput, "the edge at " + format_point(mid) + " on the strip is non-manifold");
    const int g = pair[0] == f ? pair[1] : pair[0];
    if (mesh_.edge_direction(f, a, b) == mesh_.edge_direction(g, a, b))
      throw RoundingError(ErrorCode::NonManifoldInput, "the facets at " + format_point(mid) + " are oriented against each other (a flipped facet)");
    return g;
  }
  bool smooth(int f, int g) { return angle_deg(normal(f), normal(g)) < o_.strip_turn_deg; }
  // Flat: every smooth neighbour coplanar with it.
  bool flat(int f) {
    for (int k = 0; k < 3; ++k) {
      const int g = across(f, k);
      if (g >= 0 && smooth(f, g) && angle_deg(normal(f), normal(g)) >= o_.flat_deg) return false;
    }
    return true;
  }
  Vec3 centroid(int f) const { return (mesh_.corner(f, 0) + mesh_.corner(f, 1) + mesh_.corner(f, 2)) / 3; }
  // A cap: a facet with an angle of kCapDeg or more, its three corners nearly on one line (a mesher's facet
  // across the seam of two faces): its normal says little of the surface there.
  static constexpr double kCapDeg = 150;
  bool cap(int f) {
    auto it = cap_.find(f);
    if (it != cap_.end()) return it->second;
    bool is = false;
    for (int k = 0; k < 3 && !is; ++k) {
      const Vec3 u = mesh_.corner(f, (k + 1) % 3) - mesh_.corner(f, k), w = mesh_.corner(f, (k + 2) % 3) - mesh_.corner(f, k);
      is = std::atan2(u.cross(w).norm(), u.dot(w)) >= kCapDeg * M_PI / 180;
    }
    return cap_.emplace(f, is).first->second;
  }
  double area(int f) const { return 0.5 * (mesh_.corner(f, 1) - mesh_.corner(f, 0)).cross(mesh_.corner(f, 2) - mesh_.corner(f, 0)).norm(); }

 private:
  const MeshTopology& mesh_;
  const SharpenOptions& o_;
  std::unordered_map<int, Vec3> normal_;
  std::unordered_map<int, bool> cap_;
};

// The breadth-first flood of a strip's facets from f0 (each one's vertices Inner until told otherwise):
// visit(f, k, g) decides for edge k of strip facet f, whose neighbour g (-1: the mesh boundary) is not in
// the strip yet, whether g joins it (true), else records what the edge is (an end edge into `end_edges`).
// An end edge to a cap (whose normal says nothing) that joined later, from another of its edges, is
// dropped: the order of the flood must not make an end (a mesher's folded cap inside the S plate's round,
// where its cylinder meets its torus, turns by 78 deg from one neighbour and 81 deg from the other: taken
// for an end face mid-strip when met first from the second). (An end face's facet that joined through a
// sliver of the round stays an end's too.)
template <class Visit>
void flood_from(const MeshTopology& mesh, Facets& fx, int f0, const SharpenOptions& o, RoundStrip& strip,
                std::vector<std::pair<int, int>>& end_edges, Visit visit) {
  strip.facet_set.insert(f0);
  std::deque<int> queue{f0};
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop_front();
    strip.facets.push_back(f);
    if (long(strip.facets.size()) > o.max_new_facets) check_work_budget(double(strip.facets.size()), o.max_new_facets, "strip recognition");
    for (int k = 0; k < 3; ++k) {
      for (int v : {mesh.F(f, k), mesh.F(f, (k + 1) % 3)}) strip.role.emplace(v, StripRole::Inner);
      const int g = fx.across(f, k);
      if (g >= 0 && strip.facet_set.count(g)) continue;
      if (visit(f, k, g)) strip.facet_set.insert(g), queue.push_back(g);
    }
  }
  end_edges.erase(std::remove_if(end_edges.begin(), end_edges.end(),
                                 [&](const std::pair<int, int>& e) {
                                   const int g = fx.across(e.first, e.second);
                                   return g >= 0 && fx.cap(g) && strip.facet_set.count(g);
                                 }),
                  end_edges.end());
}

// A strip whose side B curves along the round (strip_curved.cpp).
void recognise_curved(const MeshTopology& mesh, Facets& fx, int f0, const std::vector<int>& flood, const std::vector<int>& beside,
                      const SharpenOptions& o, const Vec3& where, RoundStrip& strip, std::vector<std::pair<int, int>>& end_edges);

// A strip of straight rounds mitred into each other where their walls meet at sharp edges (a pocket's rim
// whose wall corners stayed sharp; strip_mitre.cpp): true and `strip` made (curved, its stations the
// mitres' corners) when the flat facets beside the flood are one plane A along all of it and one plane B
// per round, every facet turns about its round's corner line and the rounds join end to end; false (strip
// untouched) otherwise.
bool recognise_mitred(const MeshTopology& mesh, Facets& fx, int f0, const std::vector<int>& flood, const std::vector<int>& beside,
                      const SharpenOptions& o, const Vec3& where, RoundStrip& strip, std::vector<std::pair<int, int>>& end_edges);

}  // namespace meshround::strip_detail
