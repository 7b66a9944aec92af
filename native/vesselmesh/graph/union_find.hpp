#pragma once
// Disjoint sets over 0..n-1 with path halving: merging coincident points, components, joint patches.

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace vesselmesh {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }

  int32_t find(int32_t v) {
    while (parent_[v] != v) v = parent_[v] = parent_[parent_[v]];
    return v;
  }

  /// The smaller representative wins, so results do not depend on the order of the calls. Returns whether
  /// a and b were apart.
  bool unite(int32_t a, int32_t b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<int32_t> parent_;
};

}  // namespace vesselmesh
