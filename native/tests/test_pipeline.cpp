// The surface pipeline on the project's own fixtures (one per joint kind and hard case) and on the
// shared data sets: closed, manifold, outward, one component per input component, Euler
// characteristic 2·components − 2·loops, no self-intersections, radius faithful.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <limits>

#include "fixtures.hpp"
#include "test_support.hpp"
#include "vesselmesh/check/check_mesh.hpp"
#include "vesselmesh/pipeline.hpp"
#include "vesselmesh/read/read.hpp"
#include "vesselmesh/sample/sample.hpp"
#include "vesselmesh/separate/separate.hpp"
#include "vesselmesh/synth/synth.hpp"

using namespace vesselmesh;

namespace {

MeshResult mesh_at(const CenterlineGraph& g, int levels, Caps caps = Caps::flat,
                   Refinement method = MeshOptions().subdivision.method,
                   Crossings crossings = Crossings::separate) {
  MeshOptions o;
  o.subdivision.levels = levels;
  o.subdivision.method = method;
  o.caps = caps;
  o.crossings = crossings;
  return mesh_centerline(g, o);
}

void expect_closed_surface(const TriMesh& mesh, const CenterlineGraph& g, const std::string& what) {
  const TopologyReport t = check_topology(mesh);
  EXPECT_TRUE(t.closed_manifold()) << what << ": boundary " << t.boundary_edges << ", non-manifold edges "
                                   << t.non_manifold_edges << ", vertices " << t.non_manifold_vertices
                                   << ", inconsistent " << t.inconsistent_edges << ", degenerate "
                                   << t.degenerate_faces;
  EXPECT_EQ(t.components, g.components) << what;
  EXPECT_EQ(t.euler_characteristic, 2 * g.components - 2 * g.loops) << what;
  EXPECT_GT(t.signed_volume, 0.0) << what << ": faces point inwards";
}

/// The surface of `r`, made from `g`, is closed with the graph's genus and crosses itself nowhere; returns the
/// tubes it follows, those of the centerline as the separate stage left it.
const CenterlineGraph& expect_closed_and_uncrossed(const MeshResult& r, const CenterlineGraph& g,
                                                   const std::string& what) {
  const CenterlineGraph& tubes = r.separated ? *r.separated : g;
  expect_closed_surface(r.mesh, g, what);
  EXPECT_EQ(find_self_intersections(r.mesh, &tubes).pairs, 0) << what;
  return tubes;
}

/// The surface of `r`, made from `g`, lies on its tubes (those of the centerline as the separate stage left
/// it, where it moved vessels apart): closed with the graph's genus, uncrossed, no face centroid more than
/// a local radius off the tubes, at most `area` of its area over half a radius off them, and no edge
/// reaching across off them longer than `edge` local radii (a fin or a web reaching across to a vessel it
/// does not belong to shows in these three, though every vertex may lie on a tube; an edge along a
/// straight tube, between sections many radii apart, lies on it).
void expect_on_its_tubes(const MeshResult& r, const CenterlineGraph& g, const std::string& what, double area,
                         double edge) {
  const CenterlineGraph& tubes = expect_closed_and_uncrossed(r, g, what);
  const FidelityReport f = radius_fidelity(r.mesh, tubes);
  EXPECT_LE(f.largest_centroid_offset, 1.0) << what << ", at " << f.largest_centroid_offset_at.transpose();
  EXPECT_LE(f.area_off_tubes, area) << what;
  EXPECT_LE(f.longest_edge_off_tubes, edge) << what << ", at " << f.longest_edge_off_tubes_at.transpose();
}

/// expect_on_its_tubes on the surfaces of fixture `make` at three scales, levels 0 to `top`.
/// Closed and uncrossed at levels 0 to 3 and three scales, with at most `missing` radii of its axis lying
/// outside the surface, `area` of its area over half a radius off the tubes and no face centroid over
/// `furthest` radii off them.
void expect_its_axis_covered_at_every_scale(const std::function<CenterlineData(double)>& make, double missing,
                                            double area,
                                            double furthest = std::numeric_limits<double>::infinity()) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(make(scale));
    for (int levels = 0; levels <= 3; ++levels) {
      const std::string what = "scale " + std::to_string(scale) + " level " + std::to_string(levels);
      const MeshResult r = mesh_at(g, levels);
      const FidelityReport f = radius_fidelity(r.mesh, expect_closed_and_uncrossed(r, g, what));
      EXPECT_LE(f.missing_axis, missing) << what << ", at " << f.missing_axis_at.transpose();
      EXPECT_LE(f.area_off_tubes, area) << what;
      EXPECT_LE(f.largest_centroid_offset, furthest) << what;
    }
  }
}

void expect_on_its_tubes_at_every_scale(const std::function<CenterlineData(double)>& make, int top,
                                        double area, double edge, const std::string& what = "") {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(make(scale));
    for (int levels = 0; levels <= top; ++levels)
      expect_on_its_tubes(mesh_at(g, levels), g,
                          what + "scale " + std::to_string(scale) + " level " + std::to_string(levels), area,
                          edge);
  }
}

/// Calls `expect(surface, graph, what)` on the surfaces of the test data file `name` at three scales (its
/// points and radii times 1e-3, 1 and 1e3), levels 0 to `top`.
void for_every_scale_and_level(
    const std::string& name, int top,
    const std::function<void(const MeshResult&, const CenterlineGraph&, const std::string&)>& expect) {
  const CenterlineData file = read_centerline(test::test_data(name));
  for (double scale : {1e-3, 1.0, 1e3}) {
    CenterlineData d = file;
    for (Vec3& p : d.points) p *= scale;
    for (double& r : d.radius) r *= scale;
    for (double& r : d.edge_radius) r *= scale;
    const CenterlineGraph g = build_graph(d);
    for (int levels = 0; levels <= top; ++levels)
      expect(mesh_at(g, levels), g,
             name + " scale " + std::to_string(scale) + " level " + std::to_string(levels));
  }
}

/// The surfaces of `smooth` with its points jittered by up to `jitter` of their radius (fixtures::jittered;
/// the points `fixed` stay), at levels 0 to 2, are those of its vessels: nothing moved apart, no corner
/// taken for a joint, no more than a fifth more sections than `smooth` takes, and on the tubes
/// (expect_on_its_tubes: at most 0.2 % of the area over half a radius off, no face over one radius).
void expect_jitter_meshed_as_the_vessels(const CenterlineData& smooth, double jitter,
                                         const std::vector<int32_t>& fixed, const std::string& what) {
  const MeshResult unjittered = mesh_at(build_graph(smooth), 0);
  const CenterlineGraph g = build_graph(fixtures::jittered(smooth, jitter, fixed));
  for (int levels = 0; levels <= 2; ++levels) {
    const std::string at = what + " level " + std::to_string(levels);
    const MeshResult r = mesh_at(g, levels);
    EXPECT_EQ(r.separated_points, 0) << at;
    EXPECT_EQ(r.joint_patches, unjittered.joint_patches) << at;
    EXPECT_EQ(r.absorbed_branches, 0) << at;
    EXPECT_LE(r.sections, 1.2 * static_cast<double>(unjittered.sections)) << at;
    expect_on_its_tubes(r, g, at, 0.002, 1.0);
  }
}

/// Radius fidelity of the uniform level-2 surface (the base-mesh issue's surface) of a shared set.
FidelityReport uniform_level_two_fidelity(const std::string& path) {
  const CenterlineGraph g = build_graph(read_centerline(path));
  return radius_fidelity(mesh_at(g, 2, Caps::flat, Refinement::uniform).mesh, g);
}

}  // namespace

class JointKind : public testing::TestWithParam<fixtures::Named> {};

TEST_P(JointKind, SurfaceIsClosedManifoldWithTheRightGenusAtEveryLevel) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(GetParam().make(scale));
    ASSERT_EQ(g.loops, GetParam().loops);
    for (int levels : {0, 1, 2}) {
      const std::string what =
          GetParam().name + " scale " + std::to_string(scale) + " level " + std::to_string(levels);
      expect_closed_surface(mesh_at(g, levels).mesh, g, what);
    }
  }
}

TEST_P(JointKind, SurfaceHasNoSelfIntersections) {
  const CenterlineGraph g = build_graph(GetParam().make(1.0));
  for (int levels : {0, 1, 2}) {
    const IntersectionReport r = find_self_intersections(mesh_at(g, levels).mesh, &g);
    EXPECT_EQ(r.pairs - (GetParam().tubes_cross ? r.pairs_in_overlapping_tubes : 0), 0)
        << GetParam().name << " level " << levels;
  }
}

TEST_P(JointKind, OpenCapsLeaveOneOctagonalHolePerTerminal) {
  const CenterlineGraph g = build_graph(GetParam().make(1.0));
  const MeshResult r = mesh_at(g, 0, Caps::open);
  const TopologyReport t = check_topology(r.mesh);
  EXPECT_EQ(t.non_manifold_edges, 0);
  EXPECT_EQ(t.inconsistent_edges, 0);
  // A terminal branch too short for a tube ends inside its joint's patch, and may leave no hole.
  if (r.absorbed_branches == 0)
    EXPECT_EQ(t.boundary_edges, 8 * g.terminals()) << GetParam().name;
  else
    EXPECT_TRUE(t.boundary_edges % 8 == 0 && t.boundary_edges <= 8 * g.terminals()) << GetParam().name;
}

INSTANTIATE_TEST_SUITE_P(Fixtures, JointKind, testing::ValuesIn(fixtures::joint_kinds()),
                         [](const auto& info) { return info.param.name; });

TEST(Pipeline, LoopsTooShortToPartKeepTheirHoleAsATunnel) {
  // The joints of these loops merge into one patch; the loop's genus comes from a tunnel through it.
  for (const auto& [name, make] :
       {std::pair{"lens", fixtures::lens}, std::pair{"short_loop", fixtures::short_loop}}) {
    const MeshResult r = mesh_at(build_graph(make(1.0)), 0);
    EXPECT_EQ(r.joint_patches, 1) << name;
    EXPECT_EQ(r.tunnels, 1) << name;
  }
}

TEST(Pipeline, SideBranchesTwoRadiiApartKeepAPatchEachAndTheSurfaceOnTheTubes) {
  // Each side branch leaves towards the next joint, so only a plane tilted from the trunk's tangent
  // parts two neighbouring patches; without it all six joints merged into one convex hull, 19 % of
  // whose area lay over half a radius off the tubes at level 2.
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::side_branches_in_a_row(scale));
    const MeshResult r = mesh_at(g, 2, Caps::flat, Refinement::uniform);
    EXPECT_EQ(r.joint_patches, 6) << "scale " << scale;
    EXPECT_LE(radius_fidelity(r.mesh, g).area_off_tubes, 0.01) << "scale " << scale;
  }
}

TEST(Pipeline, SomaWithDendritesFromItsCentreHasItsSphereAtEveryScale) {
  // Inside the soma's sphere every dendrite's first cone holds the surface too: it must still come out
  // onto the sphere (before, it stayed inside, the soma half as thick: the 95th percentile 28 %).
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::soma(scale));
    const FidelityReport f = radius_fidelity(mesh_at(g, 2, Caps::flat, Refinement::uniform).mesh, g);
    EXPECT_LE(f.abs_relative_error.p95, 0.031) << "scale " << scale;
    EXPECT_GE(f.relative_error.min, -0.05) << "scale " << scale;
  }
}

// A soma merged into one patch with its trunk's joints, every branch leaving the patch under half its
// width: the patch was the hull of those branches' squares, a slim blob through the soma's sphere (of the
// points at 0.9 of its radius, 21 to 24 % inside the surface at levels 0 to 2). Its sphere's own points now
// stand in the hull, and the fit brings them onto the sphere.
TEST(Pipeline, SomaMergedWithItsTrunksJointsShowsItsSphere) {
  std::vector<Vec3> sphere;  // 200 directions spread evenly (a Fibonacci sphere)
  for (int k = 0; k < 200; ++k) {
    const double z = 1 - (k + 0.5) / 100, around = k * M_PI * (3 - std::sqrt(5.0));
    sphere.push_back(
        Vec3(std::sqrt(1 - z * z) * std::cos(around), std::sqrt(1 - z * z) * std::sin(around), z));
  }
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::soma_merged_with_its_trunks_joints(scale));
    std::vector<Vec3> points;
    for (const Vec3& u : sphere) points.push_back(0.9 * 10 * scale * u);  // the soma: radius 10 at the origin
    for (int levels = 0; levels <= 2; ++levels) {
      const std::string what = "scale " + std::to_string(scale) + " level " + std::to_string(levels);
      const MeshResult r = mesh_at(g, levels);
      expect_closed_and_uncrossed(r, g, what);
      const std::vector<bool> inside = inside_surface(r.mesh, points);
      EXPECT_GE(std::count(inside.begin(), inside.end(), true), (levels == 0 ? 0.8 : 0.95) * points.size())
          << what;
    }
  }
}

// Two dendrites leaving a soma 5° apart overlap for most of their length. Before squares could tilt, their
// squares could not part, and the soma's joint merged with both their forks: one convex hull from the soma
// to the forks, 32 % of the surface's area over half a radius off the tubes at level 2 (2.6 % once squares
// tilted). The separate stage moves each fork's side branch out of the other dendrite, and parts the two
// dendrites beyond the soma's reach; the surface follows the tubes as it left them.
TEST(Pipeline, SomaWithDendritesFiveDegreesApartFollowsItsTubes) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::soma_with_close_dendrites(5, scale));
    const MeshResult r = mesh_at(g, 2, Caps::flat, Refinement::uniform);
    ASSERT_TRUE(r.separated) << "scale " << scale;
    const FidelityReport f = radius_fidelity(r.mesh, *r.separated);
    EXPECT_LE(f.area_off_tubes, 0.05) << "scale " << scale;
  }
}

// Not met before tiling kept the most sections of a tube that no two in a row cross, and made a bend too
// tight for any such sections a corner joint: sections were dropped one by one against the last kept, a
// section kept at the bottom of the U, facing down its first leg, had the whole way back up behind its
// plane, every later section was dropped, and the trunk became one straight prism from its end to the
// joint, through everything beside the U (95 crossing pairs, 30 % of the area over half a radius off the
// tubes at level 2; 22 of brava-records' 42 trees crossed themselves so). Bend radius 1.28 radii is
// tighter than the square corners reach (a corner joint), 1.5 is not (sections skip the bottom of the U).
TEST(Pipeline, UBendBeforeAJointKeepsItsTubeRoundTheBend) {
  for (double bend : {1.28, 1.5})
    expect_on_its_tubes_at_every_scale(
        [&](double scale) { return fixtures::u_bend_into_a_joint(bend, scale); }, 3, 0.04, 3.5,
        "bend " + std::to_string(bend) + " ");
}

// Not met before a sharp corner's sphere joined its patch's hull where the squares' hull misses it
// (tile/patches.cpp, uncovered_sphere_points): the corner's patch was the hull of the two legs' squares,
// pushed up the legs until they cleared each other, and the surface cut straight across above the U: 3.5 to
// 3.7 radii of its axis with no surface round it and 8 to 16 % of the area over half a radius off at levels
// 0 to 3 (now none, and 1.2 % at level 0; the thickest vessel of brava-records BH0026).
TEST(Pipeline, UBelowItsJointWithTouchingLegsKeepsItsBottom) {
  expect_its_axis_covered_at_every_scale(fixtures::u_below_its_joint_with_touching_legs, 0, 0.02, 0.75);
}

// Not met before a tube that gets round a bend only by dropping sections that stand over half a radius off
// it was cut there as a corner joint (tile/corners.cpp, kCutBend): the thin vessel's tube kept no section
// within 5.5 radii of its bend and ran straight across it, a faceted prism inside the vessels beside it
// (4.2 to 5.2 % of the area over half a radius off the tubes at levels 0 to 3, edges 2.7 to 4.9 radii; the
// prism showed in any render of brava-records BH0038). Now 0.7 to 2.2 %, edges up to 3.1 radii: what lies off
// is the corner patch's hull inside the bend of two overlapping legs, at level 0 over its coarse faces.
TEST(Pipeline, HairpinBesideTheVesselItLeavesKeepsItsTubeRoundTheBend) {
  expect_on_its_tubes_at_every_scale(fixtures::hairpin_beside_the_vessel_it_leaves, 3, 0.025, 3.2);
}

// Not met before a long terminal branch with no room for a tube after its joint's square was cut at its
// point furthest from the joint (tile/base_mesh.cpp, Tiler::curled): the whole curl was a stub, its terminal
// square a face of the joint's hull, a spike where the vessel had been: 30.5 radii of its axis with no
// surface round it and 2.3 % of the area over half a radius off the tubes at levels 0 to 3. Now none missing,
// 0.5 to 1.4 %.
TEST(Pipeline, TerminalCurlingBackToItsJointKeepsItsTube) {
  expect_its_axis_covered_at_every_scale(fixtures::terminal_curling_back_to_its_joint, 0.5, 0.015);
}

// Not met before squares pushed out of their joint's reach could tilt: each child's square had the other
// child's beside it in its plane, they pushed each other to the far ends of both, and the patch's hull
// spanned the whole pair, a flat fin between them (11 % of the area off the tubes at level 2, edges 25
// radii long; brava-records had 413 such patches).
TEST(Pipeline, SiblingsFromOnePointRunningSideBySideKeepTheirPatchAtTheJoint) {
  expect_on_its_tubes_at_every_scale(fixtures::siblings_side_by_side, 3, 0.002, 5);
}

// Not met before the separate stage parted vessels that overlap all the way back to a joint they share from
// the joint's reach on (it counted them as no crossing), and squares held back by the square beside them
// were tried on the way of each push: their squares pushed each other to the far end, and the child was
// given up into the joint's patch, whose hull spanned the whole bent pair: 11.6 to 13.4 radii off the
// tubes, 64 % of the area over half a radius off, and crossing pairs at level 0. brava-records BH0004 had
// one, 16.9 radii off. Now the two part from the joint's reach on: 0.7 radii at most, 0.6 / 0.4 / 0.2 % of
// the area over half a radius off at levels 0 / 1 / 2 (the crotch between them), edges up to 5.3 radii.
TEST(Pipeline, ChildTracedBackAlongItsParentLeavesNoFin) {
  expect_on_its_tubes_at_every_scale(fixtures::child_traced_back_along_its_parent, 2, 0.01, 6);
}

// Not met before a square could tilt once out of its own tube's reach rather than the fat vessel's (tile,
// kTiltFrom): the thin branch's square was pushed on along it, out of the fat tube, until the fat vessel's
// square stood past it, and their hull was a faceted web on the fat vessel: 1.3 to 1.5 radii off the tubes
// at levels 0 to 2, 4 to 10 % of the area over half a radius off, edges 3.3 to 4.1 radii. brava-records
// BH0002 and BH0014 had them. Now 0.6 to 0.9 radii, edges up to 2.7; 1.2 to 2.3 % of the area lies over half
// a radius off, on the flat faces between the fat vessel's narrowing and the thin branch's underside (a
// fixture this small is mostly joint: the 0.2 % is a whole tree's). Since every patch has small
// squares (tile step 7), 0.9 to 1.0 % at levels 1 and 2 (1.7 and 1.2 % before), faces up to 1.0 radii off
// (0.9 before) and edges of 3.03 radii along the same crumpled junction (2.70 before): the web's were 3.3 and
// longer, so the edge bound sits between the two.
TEST(Pipeline, ThinBranchWaveringOutOfAFatVesselLeavesNoWeb) {
  expect_on_its_tubes_at_every_scale(fixtures::thin_branch_wavering_out_of_a_fat_vessel, 2, 0.03, 3.2);
}

// A cluster of joints no square parts becomes one patch, the convex hull of all its branches' squares: on
// a bending fat trunk with a side branch at every point it spans the bend and the side branches' roots
// (neuron-hemibrain-da1's blobs). With the tubes' squares it had 60 to 68 % of the area over half a radius
// off the tubes and faces 4.7 to 5.8 radii off at levels 0 to 2; with smaller squares on a patch along a
// vessel (kSmallSquare) 8 to 17 % and 1.4 to 2.0 radii. Closed and uncrossed either way.
TEST(Pipeline, FatTrunkWithASideBranchAtEveryPointIsClosedUncrossedAndHugsTheTrunk) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::fat_trunk_with_a_side_branch_at_every_point(scale));
    for (int levels = 0; levels <= 2; ++levels) {
      const std::string what = "scale " + std::to_string(scale) + " level " + std::to_string(levels);
      const MeshResult r = mesh_at(g, levels);
      const CenterlineGraph& tubes = expect_closed_and_uncrossed(r, g, what);
      EXPECT_LE(radius_fidelity(r.mesh, tubes).largest_centroid_offset, 2.5) << what;
    }
  }
}

// Every patch has small squares where the surface is checked for crossings; where it crosses itself so, the
// patches round the crossing are built again with full squares (tile step 7 of docs/pipeline.md).
TEST(Pipeline, PatchesWhoseSmallSquaresCrossAreBuiltAgainWithFullSquares) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::crossing_with_small_squares(scale));
    for (int levels = 0; levels <= 2; ++levels) {
      const std::string what = "scale " + std::to_string(scale) + " level " + std::to_string(levels);
      const MeshResult r = mesh_at(g, levels);
      expect_closed_and_uncrossed(r, g, what);
      if (levels > 0) EXPECT_EQ(r.full_square_tries, 1) << what;
    }
  }
}

// Cut from vesselgraph-demo (91 points, one loop, radii 2 to 6 voxels, the points within 75 of one joint):
// with small squares round them, its joints merged otherwise and closed the loop inside one patch, whose
// tunnel could not open; the tile stage gave the loop up there, and the patches round that place are
// built again with full squares (tile step 7). Before, the whole surface was built again with full squares.
TEST(Pipeline, ALoopTheTileStageGaveUpWithSmallSquaresIsKeptWithFullSquaresThereOnly) {
  for_every_scale_and_level("loop_lost_with_small_squares_vertices.csv", 2,
                            [](const MeshResult& r, const CenterlineGraph& g, const std::string& what) {
                              ASSERT_EQ(g.loops, 1);
                              expect_closed_and_uncrossed(r, g, what);
                              EXPECT_TRUE(r.small_squares) << what;
                              EXPECT_EQ(r.full_square_tries, 1) << what;
                            });
}

// Not met yet: the same surface on its tubes (issue 19's target for neuron-hemibrain-da1, 1 % of the area
// over half a radius off). Deforming the hull onto the tubes does not get there, smaller squares only part
// of the way (docs/pipeline.md, decisions log): the patch must stop being one convex hull. Run with --gtest_also_run_disabled_tests.
TEST(Pipeline, DISABLED_FatTrunkWithASideBranchAtEveryPointFollowsItsTubes) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::fat_trunk_with_a_side_branch_at_every_point(scale));
    for (int levels = 0; levels <= 2; ++levels) {
      const std::string what = "scale " + std::to_string(scale) + " level " + std::to_string(levels);
      expect_on_its_tubes(mesh_at(g, levels), g, what, 0.01, 3);
    }
  }
}

// Not met yet: a branch 20 or 50 times thinner than the trunk it leaves at 45° (fixtures::perforator) has a
// flare of spiky faces at the junction, 1.3 to 4.1 of its radii off the tubes at levels 1 to 3 (0.9 at 10
// times thinner; at 90° none over 0.3): the joint's hull spans from the trunk's squares to the thin one's,
// which stands out beyond them. Run with --gtest_also_run_disabled_tests.
TEST(Pipeline, DISABLED_ThinBranchLeavingAFatTrunkFollowsItsTubes) {
  for (double step : {20.0, 50.0})
    expect_on_its_tubes_at_every_scale([&](double scale) { return fixtures::perforator(step, 45, scale); }, 3,
                                       0.002, 1.0, "step " + std::to_string(step) + " ");
}

// Not met before a short tube that no fold-free sections join to its two squares was no tube: it folded
// between two patches whose squares faced it from sides a right angle apart (9, 24, 61 and 105 crossing
// pairs at levels 0 to 3; brava-records BH0005 crossed itself so).
// Not met yet: brava-records BH0038 cut down to 9 points, a thin branch leaving a fat vessel between two of
// its joints 0.9 of its radius apart. The two joints share one patch, whose convex hull swallows the thin
// branch and reaches to its end: 7.6 to 10.9 % of the area over half a radius off the tubes, faces 0.75 to
// 1.08 radii off at levels 0 to 3, a notch at the crotch that subdivision crumples into a star of slivers
// (docs/pipeline.md, Where it stands). Run with --gtest_also_run_disabled_tests.
TEST(Pipeline, DISABLED_ThinBranchBetweenTwoCloseJointsOfAFatVesselFollowsItsTubes) {
  for_every_scale_and_level("thin_branch_between_two_close_joints.vtk", 3,
                            [](const MeshResult& r, const CenterlineGraph& g, const std::string& what) {
                              expect_on_its_tubes(r, g, what, 0.02, 3.0);
                            });
}

TEST(Pipeline, CrowdedJointsGetNoFoldedTubeBetweenThem) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::crowded_joints(scale));
    for (int levels = 0; levels <= 3; ++levels) {
      const std::string what = "scale " + std::to_string(scale) + " level " + std::to_string(levels);
      const TriMesh mesh = mesh_at(g, levels).mesh;
      expect_closed_surface(mesh, g, what);
      EXPECT_EQ(find_self_intersections(mesh, &g).pairs, 0) << what;
    }
  }
}

// Not met before terminal branches wholly inside other vessels' tubes were dropped (separate/hidden.hpp):
// 7 and 21 crossing pairs at levels 1 and 2. Their tubes add nothing to the union, which stays.
TEST(Pipeline, TwigsHiddenInsideOtherVesselsAreDroppedAndTheSurfaceIsUncrossed) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::hidden_twigs(scale));
    for (int levels = 0; levels <= 2; ++levels) {
      const std::string what = "scale " + std::to_string(scale) + " level " + std::to_string(levels);
      const MeshResult r = mesh_at(g, levels);
      EXPECT_EQ(r.hidden_terminals, 3) << what;
      ASSERT_TRUE(r.separated) << what;  // the centerline without them
      expect_closed_surface(r.mesh, g, what);
      EXPECT_EQ(find_self_intersections(r.mesh, &g).pairs, 0) << what;
      EXPECT_EQ(mesh_at(g, levels, Caps::flat, Refinement::curvature, Crossings::keep).hidden_terminals, 0) << what;
    }
  }
}

TEST(Pipeline, RadiusScaleMakesSubdividedTubesFaithful) {
  // A straight tube, away from its caps, sits at the centerline radius at every offered level: its faces
  // straddle the circle and its vertices lie within 2 % of it. At level 0 the octagons' faces lie 6.9 %
  // inside the circle through their corners: the vertices go out by as much as the fit lifts them (3 %),
  // and the faces come within 4.5 % (3.9 %).
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::straight(40, scale));
    for (int levels = 0; levels <= 4; ++levels) {
      const FidelityReport f = radius_fidelity(mesh_at(g, levels).mesh, g);
      const std::string what = "level " + std::to_string(levels) + " scale " + std::to_string(scale);
      EXPECT_LT(f.centroid_error.median, levels == 0 ? 0.045 : 0.01) << what;
      EXPECT_LT(f.abs_relative_error.median, levels == 0 ? 0.0301 : 0.02) << what;
      EXPECT_LT(std::abs(f.relative_error.mean), levels == 0 ? 0.0301 : 0.02) << what;
    }
  }
}

TEST(Pipeline, BentTubeKeepsItsRadiusRoundTheBend) {
  // Loop's limit cuts a bend like a B-spline its control polygon, and the sections, which follow the
  // smoothed tangent, lean against a coarse polyline: both are compensated (tile/tubes.cpp).
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::bend(2.0, scale));
    const FidelityReport f = radius_fidelity(mesh_at(g, 2).mesh, g);
    EXPECT_LT(f.abs_relative_error.median, 0.02) << "scale " << scale;
    EXPECT_LT(f.abs_relative_error.p95, 0.03) << "scale " << scale;  // 0.046 without the compensation
  }
}

TEST(Pipeline, CoarseZigzagKeepsItsRadius) {
  // Points four radii apart turning 30° at each, as in sparse tracings.
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::zigzag(30, 4, scale));
    const FidelityReport f = radius_fidelity(mesh_at(g, 2).mesh, g);
    EXPECT_LT(f.abs_relative_error.median, 0.025) << "scale " << scale;  // 0.039 without the compensation
    EXPECT_LT(f.abs_relative_error.p95, 0.08) << "scale " << scale;      // 0.156 without
  }
}

TEST(Pipeline, SharpCornersOfACoarseZigzagTakeASection) {
  // Turning 60° every four radii: the round cones have a whole sphere at each corner.
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::zigzag(60, 4, scale));
    const MeshResult r = mesh_at(g, 2);
    const FidelityReport f = radius_fidelity(r.mesh, g);
    EXPECT_LT(f.abs_relative_error.median, 0.04) << "scale " << scale;  // 0.050 with no section on the corners
    EXPECT_LT(f.abs_relative_error.p95, 0.15) << "scale " << scale;     // 0.218 with none
    EXPECT_EQ(find_self_intersections(r.mesh, &g).pairs, 0) << "scale " << scale;
  }
}

TEST(Pipeline, ChildrenOverlappingBeyondTheirJointsReachAreNotFittedIntoEachOther) {
  // In the crotch, a vertex just outside its sibling's tube went onto its own tube, and so into the
  // sibling's: 12 crossing pairs at levels 1 to 3 until the fit parted where such moves land.
  for (double scale : {1e-3, 1.0, 1e3})
    for (int levels : {1, 2, 3}) {
      const CenterlineGraph g = build_graph(fixtures::narrow_fork_overlapping_beyond_its_reach(scale));
      const MeshResult r = mesh_at(g, levels);
      EXPECT_TRUE(r.verification.topology.closed_manifold()) << "scale " << scale << " level " << levels;
      EXPECT_EQ(find_self_intersections(r.mesh, &g).pairs, 0) << "scale " << scale << " level " << levels;
    }
}

TEST(Pipeline, StaircaseOfAVoxelCenterlineTakesNoSectionOnItsCorners) {
  // Every point of the staircase turns by 45° or more, but stands out of the vessel's line by half a
  // voxel at most: sections snapped onto those points would zigzag.
  for (double scale : {1e-3, 1.0, 1e3}) {
    const CenterlineGraph g = build_graph(fixtures::staircase(0.5, scale));
    ASSERT_EQ(g.branches.size(), 1u);
    const BranchCurve curve = branch_curve(g, g.branches[0]);
    const std::vector<double> arcs = sample_branch(curve, 0, curve.length(), SamplingOptions{});
    int on_points = 0;
    for (std::size_t i = 1; i + 1 < arcs.size(); ++i)
      on_points += std::binary_search(curve.arc.begin(), curve.arc.end(), arcs[i]);
    EXPECT_EQ(on_points, 0) << "scale " << scale;
    EXPECT_EQ(find_self_intersections(mesh_at(g, 2).mesh, &g).pairs, 0) << "scale " << scale;
  }
}

// A fork of brava-bg0003 traced through voxels of one median radius, beside a loop: a long joint-patch
// edge's new vertex, moved onto the tubes, turned one of its triangles over, and the surface crossed itself
// at every level (3, 4 and 16 pairs at levels 0 to 2). Such a vertex stays at the edge's middle.
TEST(Pipeline, VoxelForkBesideALoopIsUncrossedWhereItsPatchEdgesAreSplit) {
  for_every_scale_and_level("voxel_loop_beside_a_fork.vtk", 3, expect_closed_and_uncrossed);
}

// A loop of five voxels of that tracing, its tubes filling its hole: its tunnel ran close under the patch's
// side, which the Loop limit folded through it at level 0 (7 pairs), with full squares too. Where the surface
// still crosses itself round a tunnel, the loop is closed, and the run names it.
TEST(Pipeline, VoxelLoopWhoseHoleCrossesItsPatchIsClosedAndNamed) {
  for_every_scale_and_level(
      "voxel_loop_of_five_voxels.vtk", 3,
      [](const MeshResult& r, const CenterlineGraph& g, const std::string& what) {
        ASSERT_EQ(g.loops, 1);
        const TopologyReport t = check_topology(r.mesh);
        EXPECT_TRUE(t.closed_manifold()) << what;
        EXPECT_EQ(find_self_intersections(r.mesh, &g).pairs, 0) << what;
        EXPECT_EQ(t.genus + static_cast<int64_t>(r.lost_loops.size()), 1) << what;
        for (const LostLoop& loop : r.lost_loops)
          EXPECT_EQ(loop.why, "the surface crossed itself round its hole through the joint patch") << what;
      });
  const CenterlineGraph g = build_graph(read_centerline(test::test_data("voxel_loop_of_five_voxels.vtk")));
  EXPECT_EQ(mesh_at(g, 0).lost_loops.size(), 1u);  // as built, at level 0
}

// secomb-rat-mesentery with its radii 1.6 times as wide (as a file giving diameters would have them), cut
// down to 7 points: a thin vessel leaves a fat joint, turns twice and comes back through the joint's fat
// tubes, all within the joint's reach. Its tubes overlap theirs there by accident of its path, not by
// design of the joint; counted as a joint's own overlap, it was not parted, and the surface crossed itself
// at 40 to 137 pairs at levels 0 to 3. Parted with the usual shares, the fat vessels, moved close to their
// joint, which stays, kinked there (4 to 5 % of the area over half a radius off); the hook moves alone.
TEST(Pipeline, ThinVesselHookingBackThroughItsFatJointIsPartedFromItAndFollowsItsTubes) {
  for_every_scale_and_level("thin_hook_through_its_fat_joint.vtk", 3,
                            [](const MeshResult& r, const CenterlineGraph& g, const std::string& what) {
                              EXPECT_GT(r.separated_points, 0) << what;
                              expect_on_its_tubes(r, g, what, 0.002, 1.0);
                            });
}

// A dense tracing jittered by a fraction of its radius (points a twentieth of a radius apart, moved by up to
// a quarter radius): its edges turn by any angle and add up to several times the vessel's length. Read
// edge by edge, its points turning by over 120° were corners (tiled as joints), the separate stage took
// the jitter for the vessel folding onto itself, and the sampler spaced sections by the jittered length:
// vmtk-aorta-centerline so jittered (docs/perturbed.py) was a convex blob, a third of its area off the tubes,
// and this fork one with 60 to 74 % of it at levels 0 to 2. (At level 3, 0.5 and 0.7 % of their area lies
// over half a radius inside the bulges of the jittered tubes: docs/pipeline.md.)
TEST(Pipeline, DenseJitteredTracingIsMeshedAsItsVesselsNotTheirJitter) {
  for (double scale : {1e-3, 1.0, 1e3})
    expect_jitter_meshed_as_the_vessels(fixtures::jittered_dense_fork(0, scale), 0.25, {200},
                                        "scale " + std::to_string(scale));
}

TEST(Pipeline, DenseJitteredRealTracingIsMeshedAsItsVesselsNotTheirJitter) {
  SHARED_DATA_OR_SKIP(path, "vmtk-aorta-centerline/aorta-centerline.vtp");
  // Jittered as read, its coincident points merged: VMTK repeats the common trunk in every cell, and
  // copies moved apart would be vessels side by side.
  expect_jitter_meshed_as_the_vessels(centerline_data(build_graph(read_centerline(path))), 0.25, {}, path);
}

TEST(Pipeline, SynthesizedNetworksOfSeveralSizesAreClosedUncrossedAndHaveTheirGenus) {
  // The generator keeps non-adjacent tubes apart, so no pair of triangles may cross, loops or not.
  for (int64_t sections : {500, 2000, 6000})
    for (int loops : {0, 2}) {
      const CenterlineGraph g = build_graph(synthesize_network({sections, loops, 7}));
      for (int levels : {0, 1, 2}) {
        const std::string what = std::to_string(sections) + " sections, " + std::to_string(loops) +
                                 " loops, level " + std::to_string(levels);
        const TriMesh mesh = mesh_at(g, levels).mesh;
        expect_closed_surface(mesh, g, what);
        EXPECT_EQ(find_self_intersections(mesh, &g).pairs, 0) << what;
      }
    }
}

TEST(Pipeline, SeveralComponentsGiveOneSurfaceEach) {
  CenterlineData d = fixtures::bifurcation(1.0);
  const CenterlineData other = fixtures::loop(1.0);
  const int32_t offset = static_cast<int32_t>(d.points.size());
  for (const Vec3& p : other.points) d.points.push_back(p + Vec3(100, 0, 0));
  d.radius.insert(d.radius.end(), other.radius.begin(), other.radius.end());
  for (const Edge& e : other.edges) d.edges.push_back({e[0] + offset, e[1] + offset});
  const CenterlineGraph g = build_graph(d);
  ASSERT_EQ(g.components, 2);
  expect_closed_surface(mesh_at(g, 1).mesh, g, "two components");
}

TEST(Pipeline, StatsCountEveryStage) {
  const CenterlineGraph g = build_graph(fixtures::bifurcation(1.0));
  MeshOptions o;
  o.subdivision.levels = 2;
  o.subdivision.method = Refinement::uniform;
  o.curvature = true;
  const MeshResult r = mesh_centerline(g, o);
  ASSERT_EQ(r.stages.size(), 8u);  // separate, tile, triangulate, subdivide, round, fit, curvature, verify
  EXPECT_EQ(r.stages[0].stage, "separate");
  EXPECT_EQ(r.stages[2].faces * 16, r.stages[3].faces);  // two uniform levels
  EXPECT_EQ(r.stages.back().faces, static_cast<int64_t>(r.mesh.faces.size()));
  EXPECT_EQ(r.tagged, std::vector<double>({1.0, 1.0}));
}

// --- shared data sets --------------------------------------------------------------------------------

const char* const kSharedCases[] = {
    "brava-bg0003/BG0003_ColorCoded.CNG.swc",
    "human-brain-arteries/arteries_smooth.vtk",
    "vmtk-aorta-centerline/aorta-centerline.vtp",
    "vascpy-mouse-vessels/penetrating_artery.vtk",
    "vascpy-mouse-vessels/test_smaller_vasculature.vtk",
    "neuron-hemibrain-da1/1734350788.swc",
    "secomb-rat-cortex-50/network.vtk",
    "secomb-rat-mesentery/network.vtk",
    "vesselgraph-demo/vertices.csv",
};

std::string case_name(const testing::TestParamInfo<const char*>& info) {
  std::string name = info.param;
  for (char& c : name)
    if (!isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class SharedSurface : public testing::TestWithParam<const char*> {};

TEST_P(SharedSurface, BaseAndSubdividedSurfacesAreClosedWithTheRightGenus) {
  SHARED_DATA_OR_SKIP(path, GetParam());
  const CenterlineGraph g = build_graph(read_centerline(path));
  for (int levels : {0, 1, 2})
    expect_closed_surface(mesh_at(g, levels).mesh, g, path + " level " + std::to_string(levels));
}

// The tubes of brava-bg0003, human-brain-arteries, neuron-hemibrain-da1, secomb-rat-mesentery and
// vesselgraph-demo overlap away from their joints (`vesselmesh info`); where they cross (vessels crossing
// in a planar network, a terminal traced back along another vessel, a branch looping back through its
// parent), the separate stage moves them apart, and elsewhere the fit presses them flat.
TEST_P(SharedSurface, LevelsZeroToTwoDoNotCrossThemselves) {
  SHARED_DATA_OR_SKIP(path, GetParam());
  const CenterlineGraph g = build_graph(read_centerline(path));
  for (int levels : {0, 1, 2})
    EXPECT_EQ(find_self_intersections(mesh_at(g, levels).mesh, &g).pairs, 0) << path << " level " << levels;
}

// Kept as the file gives them, the crossing vessels' surfaces cross there and nowhere else.
TEST_P(SharedSurface, KeptCrossingsCrossOnlyWhereTheInputTubesOverlap) {
  SHARED_DATA_OR_SKIP(path, GetParam());
  const CenterlineGraph g = build_graph(read_centerline(path));
  for (int levels : {0, 2}) {
    const IntersectionReport r = find_self_intersections(
        mesh_at(g, levels, Caps::flat, MeshOptions().subdivision.method, Crossings::keep).mesh, &g);
    EXPECT_EQ(r.pairs - r.pairs_in_overlapping_tubes, 0) << path << " level " << levels;
  }
}

INSTANTIATE_TEST_SUITE_P(Shared, SharedSurface, testing::ValuesIn(kSharedCases), case_name);

TEST(SharedFidelity, HumanBrainArteriesAtLevelTwoAreWithinTwoPercentMedianAndEightPercentP95OnTheirTubes) {
  SHARED_DATA_OR_SKIP(path, "human-brain-arteries/arteries_smooth.vtk");
  const FidelityReport f = uniform_level_two_fidelity(path);
  EXPECT_LE(f.abs_relative_error.median, 0.02);  // 0.011 measured
  EXPECT_LE(f.abs_relative_error.p95, 0.08);     // 0.028 measured (0.052 without the fit)
  EXPECT_LE(f.area_off_tubes, 0.01);             // 0.0012 measured
}

TEST(SharedFidelity, BravaAtLevelTwoIsWithinTwoPercentMedianAndEightPercentP95OnItsTubes) {
  SHARED_DATA_OR_SKIP(path, "brava-bg0003/BG0003_ColorCoded.CNG.swc");
  const FidelityReport f = uniform_level_two_fidelity(path);
  // 0.0202 and 0.030 measured; without the fit 0.020 and 0.121, too thin on the outer side of the 50° to
  // 90° corners of a tracing whose points are 4.4 radii apart. The median lies at the fit's edge: vertices
  // within 2 % of the tubes stay where Loop put them (0.0198 before every patch had small squares at this
  // level, tile step 7); the 95th percentile is what the fit holds, 3 %.
  EXPECT_LE(f.abs_relative_error.median, 0.021);
  EXPECT_LE(f.abs_relative_error.p95, 0.031);
  EXPECT_LE(f.area_off_tubes, 0.01);  // 0.0029 measured
}

// A surface too large to be checked for crossings everywhere (1.5 million triangles) is checked near its
// joints and caps, and so has small squares on every patch (tile step 7): records.swc, brava-bg0003's raw
// twin, at level 2 had a face 1.44 radii off its tubes with full squares, 0.96 with small ones.
TEST(SharedSurface, RecordsAtLevelTwoAreCheckedNearTheirJointsAndHugTheirTubes) {
  SHARED_DATA_OR_SKIP(path, "brava-bg0003/records.swc");
  const CenterlineGraph g = build_graph(read_centerline(path));
  const MeshResult r = mesh_at(g, 2);
  ASSERT_GT(r.mesh.faces.size(), static_cast<std::size_t>(kVerifyCrossingsUpTo));
  EXPECT_FALSE(r.verification.crossings_checked);
  EXPECT_TRUE(r.verification.crossings_checked_near_joints);
  EXPECT_TRUE(r.small_squares);
  expect_on_its_tubes(r, g, path, 0.002, 3.0);  // 0.13 % and edges of 2.66 radii measured
}

// Not met yet: on neuron-hemibrain-da1, 4.7 % of the surface's area lies over half a radius off the tubes
// at level 2, on the convex hulls of joints merged where no square, tilted or not, parts them (chains of
// fat branches shorter than their radius), up to 9 radii off, though every vertex lies within 3 % of the
// tubes at the 95th percentile. Run with --gtest_also_run_disabled_tests.
TEST(SharedFidelity, DISABLED_HemibrainSurfaceFollowsItsTubes) {
  SHARED_DATA_OR_SKIP(path, "neuron-hemibrain-da1/1734350788.swc");
  EXPECT_LE(uniform_level_two_fidelity(path).area_off_tubes, 0.01);
}

// --- the brava-records cohort ------------------------------------------------------------------------

/// The cohort's files (../shared/data/brava-records/*.swc), or one placeholder that skips without it.
std::vector<std::string> cohort_files() {
  std::vector<std::string> files;
  const std::string folder = test::shared_data("brava-records");
  if (!folder.empty())
    for (const auto& entry : std::filesystem::directory_iterator(folder))
      if (entry.path().extension() == ".swc") files.push_back(entry.path().filename().string());
  std::sort(files.begin(), files.end());
  if (files.empty()) files.push_back("absent.swc");
  return files;
}

class SharedCohort : public testing::TestWithParam<std::string> {};

// 42 real cerebral trees of one kind, every joint's children starting from one duplicated point, radii
// stepping by up to 4× at joints, trunks turning back in U-bends (../shared/data/brava-records/SOURCE.md).
TEST_P(SharedCohort, SurfaceIsAnUncrossedClosedManifoldWithOneComponentAndNoFin) {
  SHARED_DATA_OR_SKIP(path, "brava-records/" + GetParam());
  const CenterlineGraph g = build_graph(read_centerline(path));
  const MeshResult r = mesh_centerline(g, MeshOptions());
  const TopologyReport t = check_topology(r.mesh);
  EXPECT_TRUE(t.closed_manifold());
  EXPECT_EQ(t.components, g.components);
  // Its crossing vessels, BH0004's densest knot included, are parted rather than given up as a tangle, and
  // the surface crosses itself nowhere (the pipeline's own check; every tree is under its million triangles).
  EXPECT_FALSE(r.tangle);
  ASSERT_TRUE(r.verification.crossings_checked);
  EXPECT_EQ(r.verification.crossing_pairs, 0);
  // No fin: BH0004's child traced back along its parent made a prism 16.9 radii off the tubes, with edges
  // off them 24 radii long, before such branches were parted beyond their joint's reach; BH0014's thin
  // branch wavering out of a fat vessel a web 2.69 radii off before its square could tilt out of its own
  // reach; BH0031's hull of a thin vessel wavering into a cluster of fat joints 2.16 radii off, and BH0036's
  // edges of 5.44, before every patch had small squares (the worst tree now: 1.35 radii and edges of 5.36,
  // BH0009; the target, one radius, is DISABLED_SurfaceFollowsItsTubes… below).
  const FidelityReport f = radius_fidelity(r.mesh, r.separated ? *r.separated : g);
  EXPECT_LE(f.largest_centroid_offset, 1.5) << "at " << f.largest_centroid_offset_at.transpose();
  EXPECT_LE(f.longest_edge_off_tubes, 6.0) << "at " << f.longest_edge_off_tubes_at.transpose();
}

// Not met yet on every tree (level 2, default options; the surface measured against the centerline as the
// separate stage left it). No tree crosses itself or loses its genus any more (BH0004, BH0006 and BH0009 did
// before the separate stage's moves were smoothed and its added points kept off each other); more than
// 0.2 % of the area over half a radius off the tubes: 8 trees, up to 0.35 %; a face centroid over a local
// radius off them: 3 trees, up to 1.27 radii (BH0009), on the hulls of joints merged into one patch (11 and
// 18 trees, up to 2.29 radii, before every patch had small squares at this level, checked near its joints;
// BH0004's prism 17 radii off is gone: ChildTracedBackAlongItsParentLeavesNoFin; BH0014's web, 2.69 radii
// off at level 1, too: ThinBranchWaveringOutOfAFatVesselLeavesNoWeb). Before the tiling
// changes of this suite's commit series, 22 trees crossed themselves (21 outside overlapping tubes, up to
// 402 pairs) and 41 had more than 0.2 % off (up to 3 %). Run with --gtest_also_run_disabled_tests.
TEST_P(SharedCohort, DISABLED_SurfaceFollowsItsTubesUncrossedWithItsGenus) {
  SHARED_DATA_OR_SKIP(path, "brava-records/" + GetParam());
  const CenterlineGraph g = build_graph(read_centerline(path));
  const TriMesh mesh = mesh_at(g, 2).mesh;
  const TopologyReport t = check_topology(mesh);
  EXPECT_EQ(t.genus, g.loops);
  EXPECT_EQ(find_self_intersections(mesh, &g).pairs, 0);
  const Separation moved = separate_crossings(g, RoundCones(g));
  const FidelityReport f = radius_fidelity(mesh, moved.moved_points > 0 ? moved.graph : g);
  EXPECT_LE(f.area_off_tubes, 0.002);
  EXPECT_LE(f.largest_centroid_offset, 1.0) << "at " << f.largest_centroid_offset_at.transpose();
}

INSTANTIATE_TEST_SUITE_P(BravaRecords, SharedCohort, testing::ValuesIn(cohort_files()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });
