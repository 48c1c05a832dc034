// BoxTree: a bounding volume hierarchy over axis-aligned boxes (facets, chain segments), split at the
// median on the longest axis (box_tree.cpp) and kept private to the engine. Its one query, nearest(), is
// an exact branch-and-bound closest-primitive search: it visits only nodes whose box is nearer than the
// best primitive found so far, so its cost follows the primitives near the query point, never the
// empty space between them (a uniform grid walks every empty cell of the box it searches).
#pragma once
#include <cmath>
#include <vector>

#include "meshround/types.h"

namespace meshround {

class BoxTree {
 public:
  // corners[2 i], corners[2 i + 1]: the lower and upper corner of primitive i's box.
  explicit BoxTree(const std::vector<Vec3>& corners);
  int size() const { return num_primitives_; }
  int num_nodes() const { return int(nodes_.size()); }

  // The primitive nearest to p: `exact(id)` returns the squared distance from p to primitive id.
  // Returns -1 for an empty tree. Ties go to the smallest id, so the answer does not depend on how the
  // tree was built. `*best_d2` receives the squared distance; `visited` (optional) counts the
  // primitives measured (for tests and budgets).
  template <class Exact>
  int nearest(const Vec3& p, Exact&& exact, double* best_d2 = nullptr, int* visited = nullptr) const;

  struct Node {
    Vec3 lo, hi;
    int first, last;  // a leaf: primitives order_[first..last]; an inner node: its two children
    bool leaf;
  };

 private:
  static double box_d2(const Node& n, const Vec3& p) {
    const Vec3 gap = (n.lo - p).cwiseMax(p - n.hi).cwiseMax(0.0);
    return gap.squaredNorm();
  }
  std::vector<Node> nodes_;
  std::vector<int> order_;  // primitive ids in leaf order
  int num_primitives_ = 0;
};

template <class Exact>
int BoxTree::nearest(const Vec3& p, Exact&& exact, double* best_d2, int* visited) const {
  double best = INFINITY;
  int best_id = -1, count = 0;
  if (!nodes_.empty()) {
    // Depth-first, nearer child first; a node is skipped when its box is farther than the best so far
    // (not when it is as far: an equally near primitive with a smaller id may lie in it).
    struct Item { int node; double d2; };
    Item stack[2 * 64 + 2];
    int top = 0;
    stack[top++] = {0, box_d2(nodes_[0], p)};
    while (top > 0) {
      const Item it = stack[--top];
      if (it.d2 > best) continue;
      const Node& n = nodes_[it.node];
      if (n.leaf) {
        for (int k = n.first; k <= n.last; ++k) {
          const int id = order_[k];
          const double d = exact(id);
          ++count;
          if (d < best || (d == best && id < best_id)) best = d, best_id = id;
        }
        continue;
      }
      const double d0 = box_d2(nodes_[n.first], p), d1 = box_d2(nodes_[n.last], p);
      // Push the farther first so the nearer is taken next.
      if (d0 <= d1) {
        if (d1 <= best) stack[top++] = {n.last, d1};
        if (d0 <= best) stack[top++] = {n.first, d0};
      } else {
        if (d0 <= best) stack[top++] = {n.first, d0};
        if (d1 <= best) stack[top++] = {n.last, d1};
      }
    }
  }
  if (best_d2) *best_d2 = best;
  if (visited) *visited = count;
  return best_id;
}

}  // namespace meshround
