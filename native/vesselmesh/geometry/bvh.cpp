#include "vesselmesh/geometry/bvh.hpp"

#include <algorithm>
#include <numeric>

namespace vesselmesh {

namespace {

constexpr int32_t kLeafSize = 4;

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
  nodes_.reserve(2 * (n / kLeafSize + 1));
  build(boxes, centres, 0, n);
  boxes_.resize(n);
  for (int32_t k = 0; k < n; ++k) boxes_[k] = boxes[items_[k]];
}

int32_t Bvh::build(const std::vector<Box>& boxes, const std::vector<Vec3>& centres, int32_t begin,
                   int32_t end) {
  const int32_t index = static_cast<int32_t>(nodes_.size());
  nodes_.emplace_back();
  if (end - begin > kLeafSize) {
    Box spread;
    for (int32_t k = begin; k < end; ++k) spread.extend(centres[items_[k]]);
    int axis;
    (spread.hi - spread.lo).maxCoeff(&axis);
    const int32_t mid = begin + (end - begin) / 2;
    std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
                     [&](int32_t i, int32_t j) { return centres[i][axis] < centres[j][axis]; });
    build(boxes, centres, begin, mid);
    const int32_t second = build(boxes, centres, mid, end);
    nodes_[index].second = second;
    nodes_[index].box = nodes_[index + 1].box;
    nodes_[index].box.extend(nodes_[second].box);
  } else {
    for (int32_t k = begin; k < end; ++k) nodes_[index].box.extend(boxes[items_[k]]);
  }
  nodes_[index].begin = begin;
  nodes_[index].end = end;
  return index;
}

}  // namespace vesselmesh
