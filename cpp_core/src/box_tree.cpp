#include "box_tree.h"

#include <algorithm>
#include <numeric>

namespace meshround {

// Primitives per leaf: a few exact distances are cheaper than another level of boxes.
constexpr int kLeafSize = 4;

namespace {

// Median split on the longest axis of the boxes' centres: O(n log n), a few milliseconds for the 100k
// facets of a fine base mesh (OCCT's binned SAH builder took ten times that; nearest() answers the same
// whatever the tree: ties go to the smallest id).
struct Builder {
  const std::vector<Vec3>& corners;
  std::vector<Vec3> centre;
  std::vector<int>& order;
  std::vector<BoxTree::Node>& nodes;

  int build(int first, int last) {  // primitives order[first, last)
    const int id = int(nodes.size());
    nodes.push_back({});
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    Vec3 clo = lo, chi = hi;
    for (int k = first; k < last; ++k) {
      const int i = order[size_t(k)];
      lo = lo.cwiseMin(corners[2 * size_t(i)]), hi = hi.cwiseMax(corners[2 * size_t(i) + 1]);
      clo = clo.cwiseMin(centre[size_t(i)]), chi = chi.cwiseMax(centre[size_t(i)]);
    }
    if (last - first <= kLeafSize) {
      nodes[size_t(id)] = {lo, hi, first, last - 1, true};
      return id;
    }
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    const int mid = first + (last - first) / 2;
    std::nth_element(order.begin() + first, order.begin() + mid, order.begin() + last, [&](int a, int b) {
      const double ca = centre[size_t(a)][axis], cb = centre[size_t(b)][axis];
      return ca < cb || (ca == cb && a < b);
    });
    const int left = build(first, mid);
    const int right = build(mid, last);
    nodes[size_t(id)] = {lo, hi, left, right, false};
    return id;
  }
};

}  // namespace

BoxTree::BoxTree(const std::vector<Vec3>& corners) : num_primitives_(int(corners.size() / 2)) {
  if (num_primitives_ == 0) return;
  order_.resize(size_t(num_primitives_));
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.reserve(size_t(2 * num_primitives_ / kLeafSize + 2));
  Builder b{corners, {}, order_, nodes_};
  b.centre.reserve(size_t(num_primitives_));
  for (int i = 0; i < num_primitives_; ++i) b.centre.push_back(0.5 * (corners[2 * size_t(i)] + corners[2 * size_t(i) + 1]));
  b.build(0, num_primitives_);
}

}  // namespace meshround
