#include "delta.h"

#include <algorithm>
#include <cstring>

#include "meshround/cancel.h"

namespace meshround {
namespace {

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), 3 * sizeof(double)) == 0; }

// Sorted union of two ascending lists.
std::vector<int> merged(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> out;
  out.reserve(a.size() + b.size());
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

// The vertices that only removed facets use (`removed` ascending): the band's inside.
std::vector<int> vertices_left_without_facets(const MeshTopology& in, const std::vector<int>& removed) {
  std::vector<int> corners;
  corners.reserve(3 * removed.size());
  for (int f : removed)
    for (int k = 0; k < 3; ++k) corners.push_back(in.F(f, k));
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  std::vector<int> out;
  for (int v : corners)
    if (std::all_of(in.facets_begin(v), in.facets_end(v), [&](int f) { return std::binary_search(removed.begin(), removed.end(), f); }))
      out.push_back(v);
  return out;
}

// New ids for the made points `added` uses (ids >= n), in the points' order: -1 for an unused one.
std::vector<int> used_point_ids(const std::vector<std::array<int, 3>>& added, int n, size_t points) {
  std::vector<int> id(points, -1);
  for (const auto& f : added)
    for (int v : f)
      if (v >= n) id[size_t(v - n)] = 0;
  int next = n;
  for (int& i : id)
    if (i == 0) i = next++;
  return id;
}

}  // namespace

MeshDelta make_delta(const MeshTopology& in, std::vector<int> removed, const std::vector<std::pair<int, Vec3>>& moved,
                     const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& added) {
  const int n = in.num_vertices();
  MeshDelta d;
  d.input_vertices = n, d.input_facets = in.num_facets();
  std::sort(removed.begin(), removed.end());
  removed.erase(std::unique(removed.begin(), removed.end()), removed.end());
  d.freed = merged(vertices_left_without_facets(in, removed), in.unused_vertices());
  d.removed = std::move(removed);
  std::vector<std::pair<int, Vec3>> sorted_moves(moved);
  std::sort(sorted_moves.begin(), sorted_moves.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [v, p] : sorted_moves) d.moved.push_back(v), d.moved_to.push_back(p);
  const std::vector<int> id = used_point_ids(added, n, points.size());
  for (size_t k = 0; k < points.size(); ++k)
    if (id[k] >= 0) d.new_points.push_back(points[k]);
  d.added = added;
  for (auto& f : d.added)
    for (int& v : f)
      if (v >= n) v = id[size_t(v - n)];
  return d;
}

MeshDelta delta_from_edit(const MeshEdit& edit) {
  std::vector<std::pair<int, Vec3>> moved(edit.moved.begin(), edit.moved.end());
  return make_delta(edit.input, std::vector<int>(edit.removed.begin(), edit.removed.end()), moved, edit.new_points, edit.added);
}

void apply_delta(const Points& V, const Triangles& F, const MeshDelta& d, Points& V_out, Triangles& F_out) {
  apply_delta(V, F, d, V_out, F_out, nullptr);
}

void apply_delta(const Points& V, const Triangles& F, const MeshDelta& d, Points& V_out, Triangles& F_out, StepOrigin* origin) {
  const int n = int(V.rows()), m = int(F.rows());
  if (d.input_vertices != n || d.input_facets != m)
    throw RoundingError(ErrorCode::ResultInvalid, "a mesh delta was applied to another mesh than its own");
  std::vector<int> index(size_t(n), -1);
  int next = 0;
  for (int v = 0, i = 0; v < n; ++v) {
    if (size_t(i) < d.freed.size() && d.freed[size_t(i)] == v) ++i;
    else index[size_t(v)] = next++;
  }
  constexpr int kReused = -2;  // a freed vertex that an added facet uses
  for (const auto& f : d.added)
    for (int v : f)
      if (v < n && index[size_t(v)] < 0) index[size_t(v)] = kReused;
  for (int v : d.freed)  // ascending
    if (index[size_t(v)] == kReused) index[size_t(v)] = next++;
  const int first_new = next;
  V_out.resize(first_new + Eigen::Index(d.new_points.size()), 3);
  for (int v = 0; v < n; ++v)
    if (index[size_t(v)] >= 0) V_out.row(index[size_t(v)]) = V.row(v);  // bit for bit
  for (size_t i = 0; i < d.moved.size(); ++i)
    if (index[size_t(d.moved[i])] >= 0) V_out.row(index[size_t(d.moved[i])]) = d.moved_to[i].transpose();
  for (size_t k = 0; k < d.new_points.size(); ++k) V_out.row(first_new + Eigen::Index(k)) = d.new_points[k].transpose();
  F_out.resize(m - Eigen::Index(d.removed.size()) + Eigen::Index(d.added.size()), 3);
  auto id = [&](int v) {
    if (v < 0 || v >= n + int(d.new_points.size())) throw RoundingError(ErrorCode::ResultInvalid, "a mesh delta's facet has no such vertex");
    const int out = v < n ? index[size_t(v)] : first_new + (v - n);
    if (out < 0) throw RoundingError(ErrorCode::ResultInvalid, "a mesh delta keeps a facet on a vertex it frees");
    return out;
  };
  Eigen::Index row = 0;
  if (origin) origin->facet.clear(), origin->facet.reserve(size_t(F_out.rows()));
  CancelPoll poll(1 << 16);
  for (int f = 0, i = 0; f < m; ++f) {
    poll.tick();
    if (size_t(i) < d.removed.size() && d.removed[size_t(i)] == f) {
      ++i;
      continue;
    }
    F_out.row(row++) << id(F(f, 0)), id(F(f, 1)), id(F(f, 2));
    if (origin) origin->facet.push_back(f);
  }
  for (const auto& f : d.added) {
    F_out.row(row++) << id(f[0]), id(f[1]), id(f[2]);
    if (origin) origin->facet.push_back(-1);
  }
  if (origin) {
    origin->vertex.assign(size_t(V_out.rows()), -1);
    for (int v = 0; v < n; ++v)
      if (index[size_t(v)] >= 0) origin->vertex[size_t(index[size_t(v)])] = v;
  }
}

Lineage follow(const Lineage& before, const StepOrigin& step) {
  if (before.vertex.empty()) return Lineage{step.vertex, step.facet};
  Lineage out;
  out.vertex.reserve(step.vertex.size()), out.facet.reserve(step.facet.size());
  for (int v : step.vertex) out.vertex.push_back(v >= 0 ? before.vertex[size_t(v)] : -1);
  for (int f : step.facet) out.facet.push_back(f >= 0 ? before.facet[size_t(f)] : -1);
  return out;
}

MeshDelta delta_from_lineage(const Points& V0, const Triangles& F0, const Points& V, const Triangles& F, const Lineage& lineage) {
  const int n0 = int(V0.rows()), m0 = int(F0.rows());
  MeshDelta d;
  d.input_vertices = n0, d.input_facets = m0;
  std::vector<char> kept(size_t(m0), 0), used(size_t(n0), 0);
  for (Eigen::Index g = 0; g < F.rows(); ++g)
    if (lineage.facet[size_t(g)] >= 0) kept[size_t(lineage.facet[size_t(g)])] = 1;
  for (int f = 0; f < m0; ++f) {
    if (!kept[size_t(f)]) d.removed.push_back(f);
    else used[size_t(F0(f, 0))] = used[size_t(F0(f, 1))] = used[size_t(F0(f, 2))] = 1;
  }
  for (int v = 0; v < n0; ++v)
    if (!used[size_t(v)]) d.freed.push_back(v);
  // Made vertices get new ids in their order in (V, F); input ones keep theirs, moved where they differ.
  std::vector<int> id(size_t(V.rows()), -1);
  for (Eigen::Index j = 0; j < V.rows(); ++j) {
    const int o = lineage.vertex[size_t(j)];
    if (o < 0) continue;
    id[size_t(j)] = o;
    const Vec3 p = V.row(j).transpose(), q = V0.row(o).transpose();
    if (!same_bits(p, q)) d.moved.push_back(o), d.moved_to.push_back(p);
  }
  std::vector<char> made_used(size_t(V.rows()), 0);
  for (Eigen::Index g = 0; g < F.rows(); ++g) {
    const int o = lineage.facet[size_t(g)];
    for (int k = 0; k < 3; ++k) {
      if (o >= 0 && lineage.vertex[size_t(F(g, k))] != F0(o, k))
        throw RoundingError(ErrorCode::ResultInvalid, "a kept facet lost its vertices through the passes");
      if (o < 0 && id[size_t(F(g, k))] < 0) made_used[size_t(F(g, k))] = 1;
    }
  }
  for (Eigen::Index j = 0; j < V.rows(); ++j)
    if (made_used[size_t(j)]) id[size_t(j)] = n0 + int(d.new_points.size()), d.new_points.push_back(V.row(j).transpose());
  std::vector<std::pair<int, size_t>> order;  // moved ascending by input id
  for (size_t i = 0; i < d.moved.size(); ++i) order.push_back({d.moved[i], i});
  std::sort(order.begin(), order.end());
  std::vector<int> moved;
  std::vector<Vec3> moved_to;
  for (const auto& [v, i] : order) moved.push_back(v), moved_to.push_back(d.moved_to[i]);
  d.moved.swap(moved), d.moved_to.swap(moved_to);
  for (Eigen::Index g = 0; g < F.rows(); ++g)
    if (lineage.facet[size_t(g)] < 0) d.added.push_back({id[size_t(F(g, 0))], id[size_t(F(g, 1))], id[size_t(F(g, 2))]});
  return d;
}

MeshEdit edit_of(const MeshTopology& in, const MeshDelta& d) {
  MeshEdit edit(in);
  edit.removed.insert(d.removed.begin(), d.removed.end());
  for (size_t i = 0; i < d.moved.size(); ++i) edit.moved.emplace(d.moved[i], d.moved_to[i]);
  edit.new_points = d.new_points;
  edit.added = d.added;
  return edit;
}

MeshDelta delta_through(const Points& V0, const Triangles& F0, const Points& V1, const Triangles& F1, const StepOrigin& first_origin,
                        const MeshDelta& then) {
  Points V2;
  Triangles F2;
  StepOrigin second_origin;
  apply_delta(V1, F1, then, V2, F2, &second_origin);
  return delta_from_lineage(V0, F0, V2, F2, follow(Lineage{first_origin.vertex, first_origin.facet}, second_origin));
}

}  // namespace meshround
