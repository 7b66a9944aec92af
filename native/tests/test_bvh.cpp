// The bounding-volume hierarchy against brute force: the same overlapping pairs and nearest boxes, with its
// top levels built on several threads or on one.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <mutex>
#include <random>
#include <vector>

#include "vesselmesh/geometry/bvh.hpp"

using namespace vesselmesh;

namespace {

/// `n` boxes scattered in a cube of side `n`^(1/3) × 2, of sizes 0 to 3 and some of them points, a few
/// touching another exactly (touching counts as overlapping).
std::vector<Box> scattered_boxes(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> place(0, 2 * std::cbrt(n)), size(0, 3);
  std::vector<Box> boxes;
  for (int i = 0; i < n; ++i) {
    Box b;
    const Vec3 lo(place(rng), place(rng), place(rng));
    b.extend(lo);
    if (i % 7 != 0) b.extend(lo + Vec3(size(rng), size(rng), size(rng)));
    if (i % 11 == 0 && i > 0) {  // one touching the last box's corner
      b = Box();
      b.extend(boxes.back().hi);
      b.extend(boxes.back().hi + Vec3(1, 1, 1));
    }
    boxes.push_back(b);
  }
  return boxes;
}

/// The overlapping pairs (i < j) by sorting on the boxes' lower x and sweeping.
std::vector<std::array<int32_t, 2>> swept_pairs(const std::vector<Box>& boxes) {
  std::vector<int32_t> order(boxes.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int32_t>(i);
  std::sort(order.begin(), order.end(),
            [&](int32_t a, int32_t b) { return boxes[a].lo.x() < boxes[b].lo.x(); });
  std::vector<std::array<int32_t, 2>> pairs;
  for (std::size_t k = 0; k < order.size(); ++k)
    for (std::size_t l = k + 1; l < order.size() && boxes[order[l]].lo.x() <= boxes[order[k]].hi.x(); ++l)
      if (boxes[order[k]].overlaps(boxes[order[l]]))
        pairs.push_back({std::min(order[k], order[l]), std::max(order[k], order[l])});
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<std::array<int32_t, 2>> hierarchy_pairs(const Bvh& bvh, bool parallel) {
  std::vector<std::array<int32_t, 2>> pairs;
  std::mutex lock;
  bvh.for_each_overlapping_pair(
      [&](int32_t i, int32_t j) {
        const std::lock_guard<std::mutex> guard(lock);
        pairs.push_back({std::min(i, j), std::max(i, j)});
      },
      parallel);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

// 40,000 boxes: enough that the top levels are built on threads of their own where the machine has cores.
TEST(Bvh, OverlappingPairsAreExactlyThoseASweepFinds) {
  for (int n : {1, 5, 1000, 40000}) {
    const std::vector<Box> boxes = scattered_boxes(n, 7 + n);
    const Bvh bvh(boxes);
    const auto expected = swept_pairs(boxes);
    if (n == 40000) EXPECT_GT(expected.size(), 40000u);  // a test with pairs in it
    EXPECT_EQ(hierarchy_pairs(bvh, false), expected) << n << " boxes";
    EXPECT_EQ(hierarchy_pairs(bvh, true), expected) << n << " boxes";
  }
}

TEST(Bvh, NearestSearchFindsTheClosestBoxOfBruteForce) {
  const std::vector<Box> boxes = scattered_boxes(40000, 3);
  const Bvh bvh(boxes);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> place(-10, 2 * std::cbrt(40000.0) + 10);
  for (int q = 0; q < 200; ++q) {
    const Vec3 p(place(rng), place(rng), place(rng));
    double best = std::numeric_limits<double>::infinity();
    bvh.search([&](const Box& b) { return b.signed_distance(p); }, best,
               [&](int32_t i) { best = std::min(best, boxes[i].signed_distance(p)); });
    double brute = std::numeric_limits<double>::infinity();
    for (const Box& b : boxes) brute = std::min(brute, b.signed_distance(p));
    EXPECT_EQ(best, brute) << "query " << q;
  }
}
