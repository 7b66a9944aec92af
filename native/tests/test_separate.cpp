// The separate stage: vessels whose tubes cross away from any joint are moved apart, and nothing else.
#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <string>

#include "fixtures.hpp"
#include "vesselmesh/check/check_mesh.hpp"
#include "vesselmesh/geometry/closest_point.hpp"
#include "vesselmesh/pipeline.hpp"
#include "vesselmesh/separate/hidden.hpp"
#include "vesselmesh/separate/separate.hpp"

using namespace vesselmesh;

namespace {

/// The smallest clearance between the tubes of two edges of different branches, away from the joints
/// (kJointReach times the radii round each), relative to the sum of their radii (negative: they overlap).
double smallest_clearance(const CenterlineGraph& g) {
  const RoundCones cones(g);
  double smallest = 1e300;
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    for (std::size_t f = e + 1; f < g.edges.size(); ++f) {
      const RoundCone& k = cones.cone(static_cast<int32_t>(e));
      const RoundCone& l = cones.cone(static_cast<int32_t>(f));
      if (k.branch == l.branch) continue;
      const auto [s, t] = closest_parameters(k.c0, k.c1, l.c0, l.c1);
      const double radii = k.radius_at(s) + l.radius_at(t);
      bool near_joint = false;
      for (std::size_t v = 0; v < g.points.size(); ++v)
        near_joint = near_joint || (g.degree(static_cast<int32_t>(v)) > 2 &&
                                    (g.points[v] - k.point_at(s)).norm() < kJointReach * radii);
      if (!near_joint) smallest = std::min(smallest, (k.point_at(s) - l.point_at(t)).norm() / radii - 1);
    }
  return smallest;
}

int64_t crossing_pairs(const CenterlineGraph& g, int levels, Crossings crossings) {
  MeshOptions o;
  o.subdivision.levels = levels;
  o.crossings = crossings;
  return find_self_intersections(mesh_centerline(g, o).mesh).pairs;
}

/// Separates the crossing vessels of `data`, which cross at `at` (the thickest radius there `radius`).
void expect_moved_apart(const CenterlineData& data, const Vec3& at, double radius, const std::string& what) {
  const CenterlineGraph g = build_graph(data);
  const Separation s = separate_crossings(g, RoundCones(g));
  EXPECT_GT(s.crossings, 0) << what;
  EXPECT_EQ(s.left, 0) << what;
  EXPECT_TRUE(crossing_edges(s.graph, RoundCones(s.graph)).empty()) << what;
  EXPECT_LT(smallest_clearance(g), 0.0) << what;
  EXPECT_GT(smallest_clearance(s.graph), 0.0) << what;
  // Only the points round the crossing move, and the graph keeps its topology and radii.
  EXPECT_GT(s.moved_points, 0) << what;
  for (std::size_t p = 0; p < g.points.size(); ++p) {
    if ((g.points[p] - at).norm() > 4 * kJointReach * radius)
      EXPECT_EQ(s.graph.points[p], g.points[p]) << what;
    EXPECT_EQ(s.graph.radius[p], g.radius[p]) << what;
  }
  EXPECT_EQ(s.graph.components, g.components) << what;
  EXPECT_EQ(s.graph.loops, g.loops) << what;
  EXPECT_EQ(s.graph.branches.size(), g.branches.size()) << what;
  EXPECT_EQ(s.graph.joints(), g.joints()) << what;
}

}  // namespace

TEST(Separate, VesselsCrossingLikeAnXEndUpApartAtEveryScale) {
  for (double apart : {0.0, 0.3})
    for (double scale : {1e-3, 1.0, 1e3})
      expect_moved_apart(fixtures::crossing(apart, scale), Vec3::Zero(), scale,
                         "apart " + std::to_string(apart) + " scale " + std::to_string(scale));
}

TEST(Separate, ABranchLoopingBackThroughItsParentIsMovedOutOfItAtEveryScale) {
  for (double scale : {1e-3, 1.0, 1e3})
    expect_moved_apart(fixtures::loop_through_parent(scale), Vec3(0, 0, 3 * scale), scale,
                       "scale " + std::to_string(scale));
}

TEST(Separate, SurfacesOfSeparatedVesselsDoNotCrossWhereKeptOnesDo) {
  for (const CenterlineData& d : {fixtures::crossing(0.3, 1.0), fixtures::loop_through_parent(1.0)}) {
    const CenterlineGraph g = build_graph(d);
    for (int levels : {0, 2}) {
      EXPECT_GT(crossing_pairs(g, levels, Crossings::keep), 0) << levels;
      EXPECT_EQ(crossing_pairs(g, levels, Crossings::separate), 0) << levels;
    }
  }
}

TEST(Separate, BranchesOverlappingWhereTheyMeetAtAJointAreNoCrossing) {
  // Branches that meet at a joint (at a small angle, curling back, from a soma's centre) overlap there
  // by design: nothing moves. Three joint kinds have crossings besides: two of ring_between_branches'
  // corner branches run side by side all their length, their tubes overlapping, the side branches of
  // soma_with_close_dendrites run through the other dendrite, and tiny_angle_5deg's children overlap all
  // their length (BranchesOverlappingFarBeyondTheirJointsReachArePartedThere).
  for (const fixtures::Named& kind : fixtures::joint_kinds()) {
    if (kind.name == "ring_between_branches" || kind.name.rfind("soma_with_", 0) == 0 ||
        kind.name == "tiny_angle_5deg")
      continue;
    for (double scale : {1e-3, 1.0, 1e3}) {
      const CenterlineGraph g = build_graph(kind.make(scale));
      const RoundCones cones(g);
      EXPECT_TRUE(crossing_edges(g, cones).empty()) << kind.name << " scale " << scale;
      const Separation s = separate_crossings(g, cones);
      EXPECT_EQ(s.moved_points, 0) << kind.name << " scale " << scale;
      EXPECT_EQ(s.graph.points, g.points) << kind.name << " scale " << scale;
    }
  }
}

TEST(Separate, BranchesOverlappingFarBeyondTheirJointsReachArePartedThere) {
  // Two children 5° apart (radius 0.7) overlap all their 10 from the joint: a fork's tubes part by
  // themselves within twice the joint's reach, these run on side by side, and are parted beyond the reach
  // like crossing vessels (a child traced back along its parent so gave the joint's patch a fin along both).
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::tiny_angle(5, scale));
    const RoundCones cones(g);
    const std::vector<std::array<int32_t, 2>> crossing = crossing_edges(g, cones);
    EXPECT_FALSE(crossing.empty()) << "scale " << scale;
    for (const auto& [e, f] : crossing) {
      const RoundCone& k = cones.cone(e);
      const RoundCone& l = cones.cone(f);
      const auto [s, t] = closest_parameters(k.c0, k.c1, l.c0, l.c1);
      // The joint is at the origin.
      EXPECT_GT(k.point_at(s).norm(), kJointReach * (k.radius_at(s) + l.radius_at(t))) << "scale " << scale;
    }
    const Separation s = separate_crossings(g, cones);
    EXPECT_GT(s.moved_points, 0) << "scale " << scale;
    EXPECT_EQ(s.left, 0) << "scale " << scale;
  }
}

TEST(Separate, AVesselPassingCloseByAJointMovesAwayAndOnePassingATubeStays) {
  // A bifurcation's joint patch bulges out of its tubes: a vessel passing a tenth of a radius from a
  // child's tube 1.5 along it (within the joint's reach) moves away; one passing as close 8 along stays.
  for (double along : {1.5, 8.0}) {
    CenterlineData d = fixtures::bifurcation(1.0);
    const Vec3 child = fixtures::dir(30), across(child.z(), 0, -child.x());
    const double child_radius = 1.0 - 0.2 * along / 10;  // the child narrows from 1 to 0.8
    const Vec3 at = along * child + (child_radius + 0.5 + 0.1) * across;
    d.points.push_back(at - Vec3(0, 5, 0));
    d.radius.push_back(0.5);
    fixtures::run(d, static_cast<int32_t>(d.points.size()) - 1, at + Vec3(0, 5, 0), 20, 0.5);
    const CenterlineGraph g = build_graph(d);
    ASSERT_EQ(g.components, 2);
    const Separation s = separate_crossings(g, RoundCones(g));
    if (along < kJointReach)
      EXPECT_GT(s.moved_points, 0);
    else
      EXPECT_EQ(s.moved_points, 0);
  }
}

TEST(Separate, IsAStageOfThePipelineThatKeepLeavesOut) {
  const CenterlineGraph g = build_graph(fixtures::crossing(0.0, 1.0));
  MeshOptions o;
  o.crossings = Crossings::keep;
  const MeshResult kept = mesh_centerline(g, o);
  EXPECT_EQ(kept.stages.front().stage, "tile");
  EXPECT_EQ(kept.separated_points, 0);
  o.crossings = Crossings::separate;
  const MeshResult separated = mesh_centerline(g, o);
  EXPECT_EQ(separated.stages.front().stage, "separate");
  EXPECT_GT(separated.crossings, 0);
  EXPECT_GT(separated.separated_points, 0);
  EXPECT_EQ(separated.crossings_left, 0);
  EXPECT_GT(separated.largest_separation, 0.0);
}

// A vessel traced back along another's very line (a tracing that doubles back): the points added along
// both where they cross must not fall on each other or on the other's points, or the graph would merge
// them into loops the vessels do not have (brava-records BH0006 gained two).
TEST(Separate, VesselsOnOneLineGetNoLoopFromThePointsAddedAlongThem) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    CenterlineData d = fixtures::start(Vec3(0, 0, -10) * scale, 1 * scale);
    const int32_t joint = fixtures::run(d, 0, Vec3::Zero(), 4, 1 * scale);
    fixtures::run(d, joint, Vec3(20, 0, 0) * scale, 4, 0.8 * scale);  // along x, points every 5
    int32_t up = fixtures::run(d, joint, Vec3(0, 0, 12) * scale, 3, 0.8 * scale);
    up = fixtures::run(d, up, Vec3(26, 0, 12) * scale, 4, 0.8 * scale);
    up = fixtures::run(d, up, Vec3(26, 0, 0) * scale, 3, 0.8 * scale);
    fixtures::run(d, up, Vec3(11, 0, 0) * scale, 3, 0.8 * scale);  // back along the first child's line
    const CenterlineGraph g = build_graph(d);
    ASSERT_EQ(g.loops, 0);
    const Separation s = separate_crossings(g, RoundCones(g));
    EXPECT_GT(s.crossings, 0) << scale;
    EXPECT_EQ(s.graph.loops, 0) << scale;
    const MeshResult r = mesh_centerline(g, MeshOptions());
    EXPECT_EQ(r.verification.topology.genus, 0) << scale;
    EXPECT_EQ(r.verification.problem(), "") << scale;
  }
}

// A trunk of radius 1 with a twig inside it, a branch to a joint inside it whose two twigs are inside it
// too (once they are dropped, the branch is a twig), and a branch that leaves it: the twigs and the branch
// to them are dropped, in two rounds, and the rest stays as it is.
TEST(Separate, TerminalBranchesHiddenInsideOtherTubesAreDroppedRoundByRound) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    CenterlineData d = fixtures::start(scale * Vec3(0, 0, -5), scale);
    int32_t below = fixtures::run(d, 0, scale * Vec3(0, 0, -2.5), 1, scale);
    const int32_t joint = fixtures::run(d, below, Vec3::Zero(), 1, scale);
    fixtures::run(d, joint, scale * Vec3(0, 0, 5), 2, scale);
    fixtures::run(d, joint, scale * Vec3(0, 0.45, 1.2), 2, 0.3 * scale);                 // a twig
    const int32_t inner = fixtures::run(d, below, scale * Vec3(0.2, 0, -2.0), 1, 0.4 * scale);
    fixtures::run(d, inner, scale * Vec3(0.3, 0.1, -1.8), 1, 0.3 * scale);                // twigs of a twig
    fixtures::run(d, inner, scale * Vec3(0.1, 0.3, -2.2), 1, 0.3 * scale);
    fixtures::run(d, joint, scale * Vec3(0, 1.8, 0.6), 2, 0.3 * scale);                  // out of the trunk
    const CenterlineGraph g = build_graph(d);
    const HiddenTerminals h = drop_hidden_terminals(g, RoundCones(g));
    EXPECT_EQ(h.dropped, 4) << scale;
    EXPECT_EQ(h.graph.edges.size(), 6u) << scale;  // the trunk's four and the branch that leaves it
    EXPECT_EQ(h.graph.components, 1) << scale;
    EXPECT_EQ(h.graph.branches.size(), 3u) << scale;
    // Nothing is hidden in the rest.
    EXPECT_EQ(drop_hidden_terminals(h.graph, RoundCones(h.graph)).dropped, 0) << scale;
    // The pipeline's form drops the same and keeps the tubes of what is left, one cone per edge.
    std::optional<RoundCones> cones;
    cones.emplace(g);
    CenterlineGraph kept;
    EXPECT_EQ(drop_hidden_terminals(g, cones, kept), 4) << scale;
    EXPECT_EQ(kept.points, h.graph.points) << scale;
    EXPECT_EQ(cones->size(), kept.edges.size()) << scale;
  }
}

// A cloud of points within one radius, read as one branch, is a tangle in the input already: left as it is
// without its crossings told apart and refined, its overlapping pairs counted only to just past a tangle's
// (32 a piece of tube). Counted in full and refined, 5,000 such points took 32 s and 20,000 223 s, their 200
// million pairs kept.
TEST(Separate, ACloudOfPointsIsATangleCountedNoFurtherThanATangle) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    CenterlineData d;
    std::mt19937 random(3);
    for (int i = 0; i < 600; ++i) {
      Vec3 p;
      for (int c = 0; c < 3; ++c) p[c] = (static_cast<double>(random()) / 4294967296.0 - 0.5) * scale;
      d.points.push_back(p);
      d.radius.push_back(scale);
      if (i > 0) d.edges.push_back({i - 1, i});
    }
    const CenterlineGraph g = build_graph(d);
    const Separation s = separate_crossings(g, RoundCones(g));
    EXPECT_TRUE(s.tangle) << scale;
    EXPECT_LE(s.crossings, static_cast<int64_t>(32 * g.edges.size() + 1)) << scale;
    EXPECT_EQ(s.graph.points.size(), g.points.size()) << scale;
  }
}
