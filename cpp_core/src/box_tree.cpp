#include "box_tree.h"

#include <BVH_BinnedBuilder.hxx>
#include <BVH_BoxSet.hxx>

namespace meshround {

// Primitives per leaf: a few exact distances are cheaper than another level of boxes.
constexpr int kLeafSize = 4;

BoxTree::BoxTree(const std::vector<Vec3>& corners) : num_primitives_(int(corners.size() / 2)) {
  if (num_primitives_ == 0) return;
  opencascade::handle<BVH_Builder<double, 3>> builder = new BVH_BinnedBuilder<double, 3, 32>(kLeafSize, BVH_Constants_MaxTreeDepth);
  BVH_BoxSet<double, 3, int> set(builder);
  set.SetSize(num_primitives_);
  for (int i = 0; i < num_primitives_; ++i) {
    const Vec3 &lo = corners[2 * i], &hi = corners[2 * i + 1];
    set.Add(i, BVH_Box<double, 3>(BVH_Vec3d(lo.x(), lo.y(), lo.z()), BVH_Vec3d(hi.x(), hi.y(), hi.z())));
  }
  set.Build();
  const opencascade::handle<BVH_Tree<double, 3>>& tree = set.BVH();
  order_.resize(num_primitives_);
  for (int i = 0; i < num_primitives_; ++i) order_[i] = set.Element(i);
  nodes_.resize(tree->Length());
  for (int k = 0; k < tree->Length(); ++k) {
    Node& n = nodes_[k];
    const BVH_Vec3d &lo = tree->MinPoint(k), &hi = tree->MaxPoint(k);
    n.lo = Vec3(lo.x(), lo.y(), lo.z()), n.hi = Vec3(hi.x(), hi.y(), hi.z());
    n.leaf = tree->IsOuter(k);
    if (n.leaf) n.first = tree->BegPrimitive(k), n.last = tree->EndPrimitive(k);
    else n.first = tree->Child<0>(k), n.last = tree->Child<1>(k);
  }
}

}  // namespace meshround
