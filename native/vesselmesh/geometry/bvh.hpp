#pragma once
// A bounding-volume hierarchy over axis-aligned boxes: nodes in one flat array (depth-first order, the
// first child right after its parent), split at the median of the boxes' centres along their longest
// spread. Used for overlapping triangle pairs and for nearest and containing centerline pieces.

#include <array>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "vesselmesh/centerline.hpp"
#include "vesselmesh/parallel.hpp"

namespace vesselmesh {

struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());

  void extend(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void extend(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  /// Closed boxes: touching counts as overlapping.
  bool overlaps(const Box& b) const {
    return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all();
  }
  /// Distance from `p` outside the box; minus the distance to the nearest face inside it. A lower
  /// bound of the signed distance to any solid inside the box.
  double signed_distance(const Vec3& p) const;
};

class Bvh {
 public:
  explicit Bvh(const std::vector<Box>& boxes);

  /// Calls f(i, j) once for every unordered pair of distinct items whose boxes overlap. With `parallel`,
  /// the pairs are shared out over the machine's cores, and f is called from several threads at once.
  template <class F>
  void for_each_overlapping_pair(F&& f, bool parallel = false) const;

  /// Depth-first walk that enters the nodes and visits the items whose box has bound(box) <= limit,
  /// the child with the smaller bound first. `limit` is read again at every step, so that `visit` may
  /// lower it (a nearest search).
  template <class Bound, class Visit>
  void search(Bound&& bound, const double& limit, Visit&& visit) const;

 private:
  struct Node {
    Box box;
    int32_t begin = 0, end = 0;  ///< its items: items_[begin, end)
    int32_t second = -1;         ///< the second child; -1 for a leaf (the first child is the next node)
  };
  struct BuildInput {
    const std::vector<Box>& boxes;
    const std::vector<Vec3>& centres;
    const std::unordered_map<int32_t, int32_t>& counts;  ///< node_count of every subtree size
  };
  /// Nodes in a subtree of n items (median splits down to leaves of at most kLeafSize), memoised in `counts`.
  static int32_t node_count(int32_t n, std::unordered_map<int32_t, int32_t>& counts);
  /// Builds the subtree of items_[begin, end) into nodes_[index...]; its top `split_depth` levels build their
  /// two halves on two threads.
  void build(const BuildInput& in, int32_t begin, int32_t end, int32_t index, int split_depth);
  /// One step of the walk over the pairs of items under nodes a and b (a == b: the pairs within a): calls f
  /// on the overlapping pairs of two leaves, or hands `split` the node pairs to go on with.
  template <class F, class Split>
  void step(int32_t a, int32_t b, F& f, Split&& split) const;
  bool leaf(const Node& n) const { return n.second < 0; }

  std::vector<int32_t> items_;  ///< item ids in leaf order
  std::vector<Box> boxes_;      ///< boxes_[k] is the box of items_[k]
  std::vector<Node> nodes_;
};

template <class F, class Split>
void Bvh::step(int32_t a, int32_t b, F& f, Split&& split) const {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  auto leaf_pairs = [&]() {
    for (int32_t i = na.begin; i < na.end; ++i)
      for (int32_t j = (a == b ? i + 1 : nb.begin); j < nb.end; ++j)
        if (boxes_[i].overlaps(boxes_[j])) f(items_[i], items_[j]);
  };
  if (a == b) {
    if (leaf(na)) {
      leaf_pairs();
    } else {
      split(a + 1, a + 1);
      split(na.second, na.second);
      split(a + 1, na.second);
    }
  } else if (na.box.overlaps(nb.box)) {
    if (leaf(na) && leaf(nb)) {
      leaf_pairs();
    } else if (leaf(nb) || (!leaf(na) && na.end - na.begin >= nb.end - nb.begin)) {
      split(a + 1, b);
      split(na.second, b);
    } else {
      split(a, b + 1);
      split(a, nb.second);
    }
  }
}

template <class F>
void Bvh::for_each_overlapping_pair(F&& f, bool parallel) const {
  if (nodes_.empty()) return;
  using Pair = std::pair<int32_t, int32_t>;
  auto walk = [&](std::vector<Pair> stack) {
    while (!stack.empty()) {
      const auto [a, b] = stack.back();
      stack.pop_back();
      step(a, b, f, [&](int32_t c, int32_t d) { stack.push_back({c, d}); });
    }
  };
  if (!parallel) {
    walk({{0, 0}});
    return;
  }
  // Breadth first down to a few hundred node pairs (on one thread), then each one's walk is a task.
  std::vector<Pair> frontier = {{0, 0}};
  for (int round = 0; round < 16 && !frontier.empty() && frontier.size() < 256; ++round) {
    std::vector<Pair> next;
    for (const auto& [a, b] : frontier) step(a, b, f, [&](int32_t c, int32_t d) { next.push_back({c, d}); });
    frontier = std::move(next);
  }
  parallel_for(
      frontier.size(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) walk({frontier[k]});
      },
      1);
}

template <class Bound, class Visit>
void Bvh::search(Bound&& bound, const double& limit, Visit&& visit) const {
  if (nodes_.empty()) return;
  // Median splits keep the depth within log2 of the item count, so the stack never holds more than
  // one entry per level plus one.
  std::array<std::pair<int32_t, double>, 64> stack;
  int top = 0;
  stack[top++] = {0, bound(nodes_[0].box)};
  while (top > 0) {
    const auto [index, node_bound] = stack[--top];
    if (node_bound > limit) continue;
    const Node& n = nodes_[index];
    if (leaf(n)) {
      for (int32_t k = n.begin; k < n.end; ++k)
        if (bound(boxes_[k]) <= limit) visit(items_[k]);
      continue;
    }
    std::pair<int32_t, double> near{index + 1, bound(nodes_[index + 1].box)};
    std::pair<int32_t, double> far{n.second, bound(nodes_[n.second].box)};
    if (far.second < near.second) std::swap(near, far);
    if (far.second <= limit) stack[top++] = far;
    if (near.second <= limit) stack[top++] = near;
  }
}

}  // namespace vesselmesh
