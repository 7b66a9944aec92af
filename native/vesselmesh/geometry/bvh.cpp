#include "vesselmesh/geometry/bvh.hpp"

#include <algorithm>
#include <numeric>
#include <thread>
#include <unordered_map>

namespace vesselmesh {

namespace {

constexpr int32_t kLeafSize = 4;
/// Subtrees of fewer items than this are built on one thread: starting a thread would cost more.
constexpr int32_t kParallelFrom = 1 << 14;

}  // namespace

double Box::signed_distance(const Vec3& p) const {
  const Vec3 outside = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
  if ((outside.array() > 0).any()) return outside.norm();
  return -(p - lo).cwiseMin(hi - p).minCoeff();
}

Bvh::Bvh(const std::vector<Box>& boxes) {
  const int32_t n = static_cast<int32_t>(boxes.size());
  if (n == 0) return;
  items_.resize(n);
  std::iota(items_.begin(), items_.end(), 0);
  std::vector<Vec3> centres(n);
  for (int32_t i = 0; i < n; ++i) centres[i] = 0.5 * (boxes[i].lo + boxes[i].hi);
  // Median splits fix every subtree's size, and so its node count and its place in the array, before it
  // is built: the top subtrees are built on threads of their own, into the same nodes as on one thread.
  std::unordered_map<int32_t, int32_t> counts;
  nodes_.resize(node_count(n, counts));
  const auto cores = std::max(1u, std::thread::hardware_concurrency());
  int split_depth = 0;  // the levels whose two halves are built at once: about a subtree per core
  while ((1u << split_depth) < cores && (n >> split_depth) > kParallelFrom) ++split_depth;
  build({boxes, centres, counts}, 0, n, 0, split_depth);
  boxes_.resize(n);
  for (int32_t k = 0; k < n; ++k) boxes_[k] = boxes[items_[k]];
}

int32_t Bvh::node_count(int32_t n, std::unordered_map<int32_t, int32_t>& counts) {
  if (const auto known = counts.find(n); known != counts.end()) return known->second;
  const int32_t count = n <= kLeafSize ? 1 : 1 + node_count(n / 2, counts) + node_count(n - n / 2, counts);
  return counts[n] = count;
}

void Bvh::build(const BuildInput& in, int32_t begin, int32_t end, int32_t index, int split_depth) {
  Node& node = nodes_[index];
  node.begin = begin;
  node.end = end;
  if (end - begin <= kLeafSize) {
    for (int32_t k = begin; k < end; ++k) node.box.extend(in.boxes[items_[k]]);
    return;
  }
  Box spread;
  for (int32_t k = begin; k < end; ++k) spread.extend(in.centres[items_[k]]);
  int axis;
  (spread.hi - spread.lo).maxCoeff(&axis);
  const int32_t mid = begin + (end - begin) / 2;
  std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
                   [&](int32_t i, int32_t j) { return in.centres[i][axis] < in.centres[j][axis]; });
  const int32_t first = index + 1;
  const int32_t second = first + in.counts.at(mid - begin);
  const int depth = std::max(split_depth - 1, 0);
  const auto halves = [&](std::size_t from, std::size_t to) {
    for (std::size_t half = from; half < to; ++half)
      half == 0 ? build(in, begin, mid, first, depth) : build(in, mid, end, second, depth);
  };
  // On two threads, or one when split_depth is spent; parallel_for rethrows what a half threw.
  if (split_depth > 0)
    parallel_for(2, halves, 1);
  else
    halves(0, 2);
  node.second = second;
  node.box = nodes_[first].box;
  node.box.extend(nodes_[second].box);
}

}  // namespace vesselmesh
