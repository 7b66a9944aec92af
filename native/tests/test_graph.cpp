// Normalisation and topology of the centerline graph, on small graphs drawn in comments.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "fixtures.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"

using namespace vesselmesh;

namespace {

CenterlineData polyline(std::vector<Vec3> points, double r = 1.0) {
  CenterlineData d;
  d.points = std::move(points);
  d.radius.assign(d.points.size(), r);
  for (int32_t i = 0; i + 1 < static_cast<int32_t>(d.points.size()); ++i) d.edges.push_back({i, i + 1});
  return d;
}

//        3
//        |
//  0 --- 1 --- 2          a Y: one joint (1), three terminals, three branches
CenterlineData y_shape() {
  CenterlineData d;
  d.points = {{0, 0, 0}, {10, 0, 0}, {20, 0, 0}, {10, 10, 0}};
  d.radius = {1, 1, 1, 0.5};
  d.edges = {{0, 1}, {1, 2}, {1, 3}};
  return d;
}

}  // namespace

TEST(Graph, YShapeHasOneJointThreeTerminalsThreeBranches) {
  const CenterlineGraph g = build_graph(y_shape());
  EXPECT_EQ(g.points.size(), 4u);
  EXPECT_EQ(g.components, 1);
  EXPECT_EQ(g.joints(), 1);
  EXPECT_EQ(g.terminals(), 3);
  EXPECT_EQ(g.branches.size(), 3u);
  EXPECT_EQ(g.max_degree(), 3);
  EXPECT_EQ(g.loops, 0);
  for (const Branch& b : g.branches) EXPECT_EQ(b.points.size(), b.edges.size() + 1);
}

TEST(Graph, ChainOfDegreeTwoPointsIsOneBranch) {
  const CenterlineGraph g = build_graph(polyline({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}}));
  ASSERT_EQ(g.branches.size(), 1u);
  EXPECT_EQ(g.branches[0].points.size(), 5u);
  EXPECT_EQ(g.terminals(), 2);
  EXPECT_EQ(g.joints(), 0);
}

//  0 --- 1
//  |     |      a ring of degree-2 points: one branch that closes on itself, one loop
//  3 --- 2
TEST(Graph, RingIsOneClosedBranchAndOneLoop) {
  CenterlineData d = polyline({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  d.edges.push_back({3, 0});
  const CenterlineGraph g = build_graph(d);
  ASSERT_EQ(g.branches.size(), 1u);
  EXPECT_EQ(g.branches[0].points.front(), g.branches[0].points.back());
  EXPECT_EQ(g.branches[0].edges.size(), 4u);
  EXPECT_EQ(g.loops, 1);
  EXPECT_EQ(g.terminals(), 0);
}

TEST(Graph, LoopsAreTheCycleRankOverComponents) {
  // Two components: a square with a diagonal (2 loops) and a separate segment (0 loops).
  CenterlineData d;
  d.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {5, 5, 5}, {6, 5, 5}};
  d.radius.assign(6, 0.1);
  d.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}, {4, 5}};
  const CenterlineGraph g = build_graph(d);
  EXPECT_EQ(g.components, 2);
  EXPECT_EQ(g.loops, 2);
  EXPECT_EQ(g.roots.size(), 2u);
}

TEST(Graph, CoincidentPointsMergeAndTheSharedTrunkEdgesCollapse) {
  // Two overlapping polylines as VMTK writes them: both repeat the trunk 0-1-2, then diverge.
  CenterlineData d;
  d.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 1, 0},     // first line
              {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, -1, 0}};   // second line, same trunk
  d.radius.assign(8, 0.2);
  d.edges = {{0, 1}, {1, 2}, {2, 3}, {4, 5}, {5, 6}, {6, 7}};
  const CenterlineGraph g = build_graph(d);
  EXPECT_EQ(g.report.merged_points, 3);
  EXPECT_EQ(g.report.duplicate_edges, 2);
  EXPECT_EQ(g.points.size(), 5u);
  EXPECT_EQ(g.edges.size(), 4u);
  EXPECT_EQ(g.joints(), 1);
  EXPECT_EQ(g.branches.size(), 3u);
  EXPECT_EQ(g.loops, 0);
}

TEST(Graph, ZeroLengthEdgeIsDroppedAndReported) {
  CenterlineData d = polyline({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}});
  const CenterlineGraph g = build_graph(d);
  EXPECT_EQ(g.report.zero_length_edges, 1);
  EXPECT_EQ(g.edges.size(), 2u);
  EXPECT_EQ(g.branches.size(), 1u);
}

TEST(Graph, MergeToleranceIsRelativeToTheRadius) {
  // The same geometry at micrometre and at metre scale: points 1e-7 r apart merge, 1e-4 r apart do not.
  for (double scale : {1e-6, 1.0, 1e6}) {
    CenterlineData d = polyline({{0, 0, 0}, {1e-7 * scale, 0, 0}, {1 * scale, 0, 0}, {(1 + 1e-4) * scale, 0, 0}},
                                scale);
    const CenterlineGraph g = build_graph(d);
    EXPECT_EQ(g.report.merged_points, 1) << "scale " << scale;
    EXPECT_EQ(g.points.size(), 3u) << "scale " << scale;
  }
}

TEST(Graph, DuplicatedVesselsMergeKeepingTheLargerRadiusAtEachEnd) {
  // A vessel traced twice from one joint (0) to coincident end points (2, 3), the second trace wider at
  // the end and drawn the other way, per point and per edge: one edge, as wide as the wider trace.
  //   1 --- 0 --- 2 == 3
  CenterlineData d;
  d.points = {{0, 0, 0}, {-10, 0, 0}, {10, 0, 0}, {10, 0, 0}};
  d.radius = {1.0, 1.0, 0.5, 0.8};
  d.edges = {{1, 0}, {0, 2}, {3, 0}};
  const CenterlineGraph g = build_graph(d);
  EXPECT_EQ(g.report.merged_points, 1);
  EXPECT_EQ(g.report.duplicate_edges, 1);
  ASSERT_EQ(g.edges.size(), 2u);
  const std::array<double, 2> kept = g.end_radius[1];  // the edge 0-2, its ends in that order
  EXPECT_EQ(g.points[g.edges[1][1]], Vec3(10, 0, 0));
  EXPECT_DOUBLE_EQ(kept[0], 1.0);
  EXPECT_DOUBLE_EQ(kept[1], 0.8);
  EXPECT_DOUBLE_EQ(g.radius[g.edges[1][1]], 0.8);

  d.radius.clear();
  d.edge_radius = {1.0, 0.5, 0.8};
  const CenterlineGraph e = build_graph(d);
  EXPECT_EQ(e.report.duplicate_edges, 1);
  EXPECT_DOUBLE_EQ(e.end_radius[1][0], 0.8);
  EXPECT_DOUBLE_EQ(e.end_radius[1][1], 0.8);
}

TEST(Graph, CoordinatesWithinAMillionthOfTheRadiusOfZeroAreZero) {
  // At any scale: 1e-7 r and a denormal are zero, 1e-5 r is kept.
  for (double scale : {1e-6, 1.0, 1e6}) {
    CenterlineData d = polyline({{1e-7 * scale, 4.9e-324, 0}, {scale, 1e-5 * scale, 0}}, scale);
    const CenterlineGraph g = build_graph(d);
    EXPECT_EQ(g.report.snapped_coordinates, 2) << "scale " << scale;
    EXPECT_EQ(g.points[0], Vec3(0, 0, 0)) << "scale " << scale;
    EXPECT_EQ(g.points[1], Vec3(scale, 1e-5 * scale, 0)) << "scale " << scale;
  }
}

TEST(Graph, AHugeRadiusDoesNotMoveItsPointsCoordinatesToZero) {
  // A millionth of a 4e9 radius is 4000: the point (0.001, 4, 3.9) stays where it is (a fuzz finding: set
  // to zero after the merging, it fell onto the other end of its edge, which became zero long).
  CenterlineData d = polyline({{0, 0, 0}, {0.001, 4, 3.9375}});
  d.radius = {1, 4e9};
  const CenterlineGraph g = build_graph(d);
  EXPECT_EQ(g.report.snapped_coordinates, 0);
  EXPECT_EQ(g.points[1], Vec3(0.001, 4, 3.9375));
}

TEST(Graph, PointsSetToZeroMergeWhereTheyMeet) {
  // Two points a little over the merge tolerance apart, both within it of zero in the coordinate they differ
  // in: set to zero, they coincide, and merge rather than leaving an edge of no length.
  CenterlineData d = polyline({{0.9e-6, 5, 5}, {-0.9e-6, 5, 5}, {0, 5, 6}});
  const CenterlineGraph g = build_graph(d);
  EXPECT_EQ(g.report.snapped_coordinates, 2);
  EXPECT_EQ(g.report.merged_points, 1);
  ASSERT_EQ(g.edges.size(), 1u);
  EXPECT_GT((g.points[g.edges[0][1]] - g.points[g.edges[0][0]]).norm(), 0.5);
}

TEST(Graph, IsolatedPointsAreDroppedAndReported) {
  CenterlineData d = polyline({{0, 0, 0}, {1, 0, 0}});
  d.points.push_back({7, 7, 7});
  d.radius.push_back(1.0);
  const CenterlineGraph g = build_graph(d);
  EXPECT_EQ(g.report.isolated_points, 1);
  EXPECT_EQ(g.points.size(), 2u);
}

TEST(Graph, PerEdgeRadiusGivesEachEdgeItsOwnEndsAndJointsTheWidest) {
  CenterlineData d = y_shape();
  d.radius.clear();
  d.edge_radius = {2.0, 1.5, 0.5};
  const CenterlineGraph g = build_graph(d);
  EXPECT_TRUE(g.radius_per_edge);
  const int32_t joint = static_cast<int32_t>(std::find_if(g.points.begin(), g.points.end(), [](const Vec3& p) {
                                               return p == Vec3(10, 0, 0);
                                             }) - g.points.begin());
  EXPECT_DOUBLE_EQ(g.radius[joint], 2.0);
  for (std::size_t e = 0; e < g.edges.size(); ++e) EXPECT_EQ(g.end_radius[e][0], g.end_radius[e][1]);
}

TEST(Graph, RootIsTheFileRootElseTheWidestTerminal) {
  CenterlineData d = y_shape();
  d.radius = {1, 1, 2, 0.5};  // terminal 2 is the widest
  EXPECT_EQ(build_graph(d).points[build_graph(d).roots[0]], Vec3(20, 0, 0));
  d.roots = {3};
  const CenterlineGraph g = build_graph(d);
  EXPECT_EQ(g.points[g.roots[0]], Vec3(10, 10, 0));
}

TEST(Graph, SixWayJointIsOnePointOfDegreeSix) {
  CenterlineData d;
  d.points = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  d.radius.assign(7, 0.1);
  for (int32_t i = 1; i <= 6; ++i) d.edges.push_back({0, i});
  const CenterlineGraph g = build_graph(d);
  EXPECT_EQ(g.max_degree(), 6);
  EXPECT_EQ(g.branches.size(), 6u);
  EXPECT_EQ(g.terminals(), 6);
}

TEST(Graph, PointsThatMergeInAChainLeavingNoEdgeAreRefusedNamingTheSource) {
  // Each point within a millionth of a radius of the next, the first and last twice as far apart: every
  // edge joins two points that merge, though no single edge is that short end to end. Away from the
  // origin, where coordinates that small would be set to zero first.
  CenterlineData d;
  d.points = {Vec3(5, 0, 0), Vec3(5 + 0.6e-6, 0, 0), Vec3(5 + 1.2e-6, 0, 0)};
  d.radius = {1, 1, 1};
  d.edges = {{0, 1}, {1, 2}, {0, 2}};
  try {
    build_graph(d, "chain.swc");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("chain.swc: every edge joins points that merge"), std::string::npos)
        << e.what();
  }
}

// Written out (as `mesh --centerline-out` does) and read back, a graph is the same graph: the same edges
// between the same places with the same radii at their ends, where a branch starts thinner from a
// duplicated joint point (a copy per radius), and where the radius is per edge.
TEST(Graph, CenterlineDataGivesTheSameGraphBack) {
  CenterlineData duplicated = y_shape();
  duplicated.points.push_back({10, 0, 0});  // the thin branch starts from its own copy of the joint
  duplicated.radius.push_back(0.5);
  duplicated.edges[2] = {4, 3};
  CenterlineData per_edge = y_shape();
  per_edge.radius.clear();
  per_edge.edge_radius = {2.0, 1.5, 0.5};
  for (const CenterlineData& d : {duplicated, per_edge}) {
    const CenterlineGraph g = build_graph(d);
    const CenterlineGraph back = build_graph(centerline_data(g));
    EXPECT_EQ(back.radius_per_edge, g.radius_per_edge);
    ASSERT_EQ(back.edges.size(), g.edges.size());
    // Edge by edge, as (end, radius) pairs in order of position.
    auto ends = [](const CenterlineGraph& h) {
      std::vector<std::array<double, 8>> out;
      for (std::size_t e = 0; e < h.edges.size(); ++e) {
        std::array<std::pair<Vec3, double>, 2> end = {std::pair{h.points[h.edges[e][0]], h.end_radius[e][0]},
                                                     std::pair{h.points[h.edges[e][1]], h.end_radius[e][1]}};
        auto less = [](const auto& a, const auto& b) {
          return std::lexicographical_compare(a.first.data(), a.first.data() + 3, b.first.data(), b.first.data() + 3);
        };
        if (less(end[1], end[0])) std::swap(end[0], end[1]);
        out.push_back({end[0].first.x(), end[0].first.y(), end[0].first.z(), end[0].second, end[1].first.x(),
                       end[1].first.y(), end[1].first.z(), end[1].second});
      }
      std::sort(out.begin(), out.end());
      return out;
    };
    EXPECT_EQ(ends(back), ends(g));
    EXPECT_EQ(back.radius, g.radius);
    EXPECT_EQ(back.joints(), 1);
  }
}

namespace {

/// The branch of `g` that ends at the point nearest `p`, and the arcs of its points: the polyline's own
/// and vessel_arc's.
std::array<std::vector<double>, 2> arcs_of_branch_ending_near(const CenterlineGraph& g, const Vec3& p) {
  const Branch* nearest = nullptr;
  double distance = 0;
  for (const Branch& b : g.branches)
    for (int32_t end : {b.points.front(), b.points.back()})
      if (const double d = (g.points[end] - p).norm(); !nearest || d < distance) nearest = &b, distance = d;
  std::vector<double> own(nearest->points.size(), 0.0);
  for (std::size_t i = 1; i < own.size(); ++i)
    own[i] = own[i - 1] + (g.points[nearest->points[i]] - g.points[nearest->points[i - 1]]).norm();
  return {own, vessel_arc(g, *nearest)};
}

}  // namespace

TEST(Graph, VesselArcIsThePolylinesWherePointsLieARadiusApartAndTheVesselsLengthUnderDenseJitter) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    // Points four radii apart, turning by 60° at each: the polyline's own arc.
    const CenterlineGraph zigzag = build_graph(fixtures::zigzag(60, 4, scale));
    const auto [own, arc] = arcs_of_branch_ending_near(zigzag, Vec3::Zero());
    for (std::size_t i = 0; i < own.size(); ++i) EXPECT_NEAR(arc[i], own[i], 1e-12 * own.back()) << scale;
    // A trunk 10 radii long traced every twentieth of a radius, jittered by up to a quarter radius: the
    // polyline is several times as long, the vessel's arc within a tenth of its length, and never falls.
    const CenterlineGraph jittered = build_graph(fixtures::jittered_dense_fork(0.25, scale));
    const auto [jittered_own, jittered_arc] = arcs_of_branch_ending_near(jittered, Vec3(0, 0, -10 * scale));
    EXPECT_GT(jittered_own.back(), 40 * scale);
    EXPECT_NEAR(jittered_arc.back(), 10 * scale, 1 * scale);
    EXPECT_TRUE(std::is_sorted(jittered_arc.begin(), jittered_arc.end()));
  }
}
