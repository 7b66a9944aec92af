// The synthetic arterial network: determinism, size, topology, Murray's law and the geometric
// properties the meshing stages rely on (spacing, gentle bends, tubes that keep clear of each other).

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <queue>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "vesselmesh/synth/synth.hpp"

namespace vesselmesh {
namespace {

CenterlineData synth(int64_t sections, int loops = 0, uint64_t seed = 1) {
  SynthOptions options;
  options.sections = sections;
  options.loops = loops;
  options.seed = seed;
  return synthesize_network(options);
}

using Neighbours = std::vector<std::vector<int32_t>>;

Neighbours neighbours(const CenterlineData& d) {
  Neighbours n(d.points.size());
  for (const Edge& e : d.edges) {
    n[e[0]].push_back(e[1]);
    n[e[1]].push_back(e[0]);
  }
  return n;
}

/// Breadth-first parents from the root (point 0): -1 for the root, -2 for points it does not reach.
std::vector<int32_t> bfs_parents(const Neighbours& n) {
  std::vector<int32_t> parent(n.size(), -2);
  std::queue<int32_t> queue;
  parent[0] = -1;
  queue.push(0);
  while (!queue.empty()) {
    const int32_t p = queue.front();
    queue.pop();
    for (int32_t q : n[p])
      if (parent[q] == -2) {
        parent[q] = p;
        queue.push(q);
      }
  }
  return parent;
}

bool connected(const CenterlineData& d) {
  const std::vector<int32_t> parent = bfs_parents(neighbours(d));
  return std::find(parent.begin(), parent.end(), -2) == parent.end();
}

double distance(const CenterlineData& d, int32_t a, int32_t b) { return (d.points[a] - d.points[b]).norm(); }

/// Whether a graph path shorter than `limit` (sum of edge lengths) joins a and b.
bool joined_within(const CenterlineData& d, const Neighbours& n, int32_t a, int32_t b, double limit) {
  std::unordered_map<int32_t, double> best{{a, 0.0}};
  using Item = std::pair<double, int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  queue.push({0.0, a});
  while (!queue.empty()) {
    const auto [length, p] = queue.top();
    queue.pop();
    if (p == b) return true;
    if (length > best[p]) continue;
    for (int32_t q : n[p]) {
      const double next = length + distance(d, p, q);
      if (next >= limit) continue;
      const auto it = best.find(q);
      if (it != best.end() && it->second <= next) continue;
      best[q] = next;
      queue.push({next, q});
    }
  }
  return false;
}

// Tubes of a thin child start inside the thick parent, so "adjacent" cannot be a count of edges: a pair
// counts as adjacent (one junction) when a graph path shorter than 3 (r_a + r_b) joins them.
constexpr double kAdjacent = 3.0;
constexpr double kClear = 1.2;

/// Checks one pair of points: tubes closer than kClear (r_a + r_b) must be adjacent.
void expect_clear(const CenterlineData& d, const Neighbours& n, int32_t a, int32_t b, int& failures) {
  const double sum = d.radius[a] + d.radius[b];
  if (distance(d, a, b) >= kClear * sum || joined_within(d, n, a, b, kAdjacent * sum)) return;
  if (++failures <= 5)
    ADD_FAILURE() << "points " << a << " and " << b << " (radii " << d.radius[a] << ", " << d.radius[b]
                  << ") are " << distance(d, a, b) << " apart but not adjacent";
}

uint64_t fingerprint(const CenterlineData& d) {
  uint64_t h = 14695981039346656037ull;
  const auto mix = [&h](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  for (const Vec3& p : d.points) mix(p.data(), 3 * sizeof(double));
  mix(d.radius.data(), d.radius.size() * sizeof(double));
  mix(d.edges.data(), d.edges.size() * sizeof(Edge));
  return h;
}

TEST(Synth, SameSeedGivesIdenticalArrays) {
  const CenterlineData a = synth(5000, 5, 7), b = synth(5000, 5, 7);
  EXPECT_TRUE(a.points == b.points);
  EXPECT_TRUE(a.radius == b.radius);
  EXPECT_TRUE(a.edges == b.edges);
  EXPECT_TRUE(a.roots == b.roots);
}

TEST(Synth, DifferentSeedGivesDifferentNetwork) {
  const CenterlineData a = synth(5000, 5, 7), b = synth(5000, 5, 8);
  EXPECT_FALSE(a.points == b.points);
  EXPECT_FALSE(a.radius == b.radius);
}

// The same bits on every (little-endian) platform, compiler and build type: a change here means that the
// generator changed (then record the new value) or that a platform computes differently (a bug).
TEST(Synth, MatchesRecordedFingerprint) {
  EXPECT_EQ(fingerprint(synth(3000, 5, 1)), 11911783895867840302ull);
}

TEST(Synth, PassesValidateWithOneRootAtTheThickestPoint) {
  const CenterlineData d = synth(2000, 5);
  EXPECT_NO_THROW(validate(d, "synthetic"));
  ASSERT_EQ(d.roots, std::vector<int32_t>{0});
  EXPECT_EQ(d.radius[0], 1.5);
  EXPECT_EQ(*std::max_element(d.radius.begin(), d.radius.end()), 1.5);
}

TEST(Synth, SectionCountIsWithinThreePercentOfTheRequest) {
  for (int64_t sections : {50, 100, 2000, 50000}) {
    EXPECT_NEAR(static_cast<double>(synth(sections).points.size()), sections, 0.03 * sections) << sections;
    const int loops = static_cast<int>(sections / 200);
    EXPECT_NEAR(static_cast<double>(synth(sections, loops).points.size()), sections, 0.03 * sections)
        << sections << " with " << loops << " loops";
  }
}

TEST(Synth, WithoutLoopsIsATree) {
  for (uint64_t seed : {1, 2, 3}) {
    const CenterlineData d = synth(3000, 0, seed);
    EXPECT_EQ(d.edges.size() + 1, d.points.size());
    EXPECT_TRUE(connected(d));
  }
}

TEST(Synth, EachLoopAddsOneIndependentCycle) {
  for (int loops : {1, 5, 20}) {
    const CenterlineData d = synth(5000, loops);
    EXPECT_EQ(static_cast<int64_t>(d.edges.size()) - static_cast<int64_t>(d.points.size()) + 1, loops);
    EXPECT_TRUE(connected(d));
  }
}

TEST(Synth, PlacesOneLoopPer200Sections) {
  for (int64_t sections : {1000, 2000, 20000, 100000})
    for (uint64_t seed : {1, 2, 3}) EXPECT_NO_THROW(synth(sections, static_cast<int>(sections / 200), seed));
}

TEST(Synth, TooManyLoopsThrowsSayingHowManyFit) {
  try {
    synth(200, 100);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("of the 100 requested"), std::string::npos) << e.what();
  }
}

TEST(Synth, RejectsInvalidOptions) {
  EXPECT_THROW(synth(1), std::invalid_argument);
  EXPECT_THROW(synth(1000, -1), std::invalid_argument);
}

// The branch point carries the parent's end radius and the children's first points their own radii,
// so the law holds to rounding; tapering happens along branches, not across a branching.
TEST(Synth, MurraysLawHoldsAtEveryBranching) {
  const CenterlineData d = synth(20000);
  const Neighbours n = neighbours(d);
  const std::vector<int32_t> parent = bfs_parents(n);
  int branchings = 0;
  for (std::size_t p = 0; p < n.size(); ++p) {
    if (n[p].size() != 3) continue;
    ++branchings;
    double children = 0.0;
    for (int32_t q : n[p])
      if (q != parent[p]) children += std::pow(d.radius[q], 3);
    EXPECT_NEAR(children / std::pow(d.radius[p], 3), 1.0, 1e-9) << "branching at point " << p;
  }
  EXPECT_GT(branchings, 200);
}

TEST(Synth, DegreeIsAtMostThree) {
  const Neighbours n = neighbours(synth(20000, 100));
  for (std::size_t p = 0; p < n.size(); ++p) EXPECT_LE(n[p].size(), 3u) << "point " << p;
  EXPECT_EQ(n[0].size(), 1u);
}

// Spacing relative to the thinner end: a child's first edge starts at the centre of its thick parent.
TEST(Synth, ConsecutivePointsAreAboutHalfARadiusApart) {
  const CenterlineData d = synth(20000, 100);
  for (const Edge& e : d.edges) {
    const double ratio = distance(d, e[0], e[1]) / std::min(d.radius[e[0]], d.radius[e[1]]);
    EXPECT_GE(ratio, 0.3) << "edge " << e[0] << "-" << e[1];
    EXPECT_LE(ratio, 0.8) << "edge " << e[0] << "-" << e[1];
  }
}

TEST(Synth, BendRadiusIsAtLeastFiveRadii) {
  const CenterlineData d = synth(20000, 100);
  const Neighbours n = neighbours(d);
  for (std::size_t p = 0; p < n.size(); ++p) {
    if (n[p].size() != 2) continue;
    const Vec3 a = d.points[n[p][0]], b = d.points[p], c = d.points[n[p][1]];
    const double circumradius =
        (a - b).norm() * (b - c).norm() * (c - a).norm() / (2.0 * (b - a).cross(c - a).norm());
    EXPECT_GE(circumradius, 5.0 * d.radius[p]) << "point " << p;
  }
}

TEST(Synth, NonAdjacentTubesKeepClearBruteForce) {
  const CenterlineData d = synth(3000, 10);
  const Neighbours n = neighbours(d);
  int failures = 0;
  for (int32_t a = 0; a < static_cast<int32_t>(d.points.size()); ++a)
    for (int32_t b = a + 1; b < static_cast<int32_t>(d.points.size()); ++b)
      expect_clear(d, n, a, b, failures);
  EXPECT_EQ(failures, 0);
}

TEST(Synth, NonAdjacentTubesKeepClearOnGrid) {
  const CenterlineData d = synth(50000, 200);
  const Neighbours n = neighbours(d);
  // Cells as wide as the largest clearance, so every pair to check lies in neighbouring cells.
  const double cell = kClear * 2.0 * *std::max_element(d.radius.begin(), d.radius.end());
  const auto key = [cell](const Vec3& p, int di, int dj, int dk) {
    const auto c = [cell](double x, int dx) {
      return static_cast<uint64_t>(std::floor(x / cell) + dx + (1 << 20));
    };
    return (c(p.x(), di) << 42) | (c(p.y(), dj) << 21) | c(p.z(), dk);
  };
  std::unordered_map<uint64_t, std::vector<int32_t>> cells;
  for (int32_t p = 0; p < static_cast<int32_t>(d.points.size()); ++p)
    cells[key(d.points[p], 0, 0, 0)].push_back(p);
  int failures = 0;
  for (int32_t a = 0; a < static_cast<int32_t>(d.points.size()); ++a)
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj)
        for (int dk = -1; dk <= 1; ++dk) {
          const auto it = cells.find(key(d.points[a], di, dj, dk));
          if (it == cells.end()) continue;
          for (int32_t b : it->second)
            if (b > a) expect_clear(d, n, a, b, failures);
        }
  EXPECT_EQ(failures, 0);
}

TEST(Synth, MillionSectionsTiming) {
  for (int loops : {0, 5000}) {
    const auto start = std::chrono::steady_clock::now();
    const CenterlineData d = synth(1000000, loops);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("[ timing   ] 1,000,000 sections, %d loops: %zu points in %.3f s\n", loops, d.points.size(),
                seconds);
    EXPECT_NEAR(static_cast<double>(d.points.size()), 1e6, 3e4);
  }
}

}  // namespace
}  // namespace vesselmesh
