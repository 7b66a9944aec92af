// Where the sampler puts cross-sections: sparsely where a straight piece of tube follows the input (a
// straight cone, a tracing that hardly turns), as densely as Eq. 1 on bends, so that the surface stays on
// the tubes there; the same at every scale, every tolerance being relative to the local radius.
#include <gtest/gtest.h>

#include "fixtures.hpp"
#include "vesselmesh/check/check_mesh.hpp"
#include "vesselmesh/pipeline.hpp"

using namespace vesselmesh;

namespace {

const double kScales[] = {1e-3, 1.0, 1e3};

MeshResult uniform_level_two(const CenterlineData& d, double tolerance = SamplingOptions().tolerance) {
  MeshOptions o;
  o.subdivision.method = Refinement::uniform;
  o.sampling.tolerance = tolerance;
  return mesh_centerline(build_graph(d), o);
}

/// `points` points `spacing` radii apart, each turning by `turn` degrees the same way (a tracing of a
/// circle of radius spacing / turn), radius 1.
CenterlineData gentle_tracing(int points, double spacing, double turn, double scale) {
  CenterlineData d = fixtures::start(Vec3::Zero(), scale);
  int32_t prev = 0;
  for (int i = 1; i < points; ++i) {
    const double heading = i * turn * M_PI / 180;
    prev = fixtures::run(d, prev, d.points[prev] + spacing * scale * Vec3(std::sin(heading), 0, std::cos(heading)),
                         1, scale);
  }
  return d;
}

/// The uniform level-2 surface of a tracing of `points` points 25 radii apart turning `turn` degrees each:
/// its sections, and its fidelity to the tracing's cones.
std::pair<int64_t, FidelityReport> traced_surface(int points, double turn, double scale) {
  const CenterlineData d = gentle_tracing(points, 25, turn, scale);
  const MeshResult r = uniform_level_two(d);
  return {r.sections, radius_fidelity(r.mesh, build_graph(d))};
}

}  // namespace

// Eq. 1 alone places a section every diameter on a straight cone, which the round stage makes exact
// between any two. Now the ends keep Eq. 1's step, graded away (a flat cap and a joint's squares need it),
// and the middle takes a section per 32 radii: 9 sections instead of 11 over 20 radii, 15 instead of 51
// over 100.
TEST(Sample, StraightConeTakesFewSectionsAndStaysOnItsTube) {
  for (double length : {20.0, 100.0})
    for (double scale : kScales) {
      CenterlineData d = fixtures::start(Vec3::Zero(), 1.1 * scale);
      fixtures::run(d, 0, Vec3(0, 0, length * scale), 1, 0.9 * scale);
      const MeshResult sparse = uniform_level_two(d), paper = uniform_level_two(d, 0);
      const std::string what = "length " + std::to_string(length) + " scale " + std::to_string(scale);
      EXPECT_LT(sparse.sections, paper.sections) << what;
      if (length > 50) EXPECT_LE(3 * sparse.sections, paper.sections) << what;
      const FidelityReport f = radius_fidelity(sparse.mesh, build_graph(d));
      EXPECT_LT(f.abs_relative_error.median, 0.02) << what;
      EXPECT_LT(f.centroid_error.p95, 0.03) << what;
    }
}

// Points 25 radii apart turning 0.1° each (a circle of 14,000 radii): the tube straight from point to point
// stays within 2 % of the radius of the tracing's cones (its faces' centroids; the vertices, lifted so that
// the faces straddle the tubes, within 3 %), and a tracing of 80 points takes no more sections than points
// (Eq. 1 alone: 12 a point). The graded ends cost about a dozen: 40 points take 43.
TEST(Sample, GentlyCurvingTracingWithPointsTwentyFiveRadiiApartTakesNoMoreSectionsThanPoints) {
  const int points = 80;
  for (double scale : kScales) {
    const auto [sections, f] = traced_surface(points, 0.1, scale);
    EXPECT_LE(sections, points) << "scale " << scale;
    EXPECT_LT(f.centroid_error.p95, 0.02) << "scale " << scale;
    EXPECT_LT(f.abs_relative_error.p95, 0.03) << "scale " << scale;
  }
}

// A tracing turning more (1° every 25 radii: the straight tube between its points would leave the cones by
// 5 % of the radius) takes more sections than points, and its surface stays within 3 % of the radius.
TEST(Sample, TracingTurningMoreTakesMoreSectionsAndStaysOnItsTubes) {
  const int points = 12;
  for (double scale : kScales) {
    const auto [sections, f] = traced_surface(points, 1, scale);
    EXPECT_GT(sections, points) << "scale " << scale;
    EXPECT_LT(f.abs_relative_error.p95, 0.03) << "scale " << scale;
    EXPECT_LT(f.centroid_error.p95, 0.03) << "scale " << scale;
  }
}

// A bend of 5 and of 20 radii, densely traced, with straight legs: the legs' sections spread out, the
// bend's keep Eq. 1's spacing, and the surface stays within 3 % of the radius of the true tube (its
// centroids; Eq. 1's surface measures the same).
TEST(Sample, BendKeepsSectionsDenseEnoughForItsSurfaceToStayOnTheTube) {
  for (double bend : {5.0, 20.0})
    for (double scale : kScales) {
      const CenterlineData d = fixtures::bend(bend, scale);
      const CenterlineGraph g = build_graph(d);
      const MeshResult sparse = uniform_level_two(d), paper = uniform_level_two(d, 0);
      const std::string what = "bend " + std::to_string(bend) + " scale " + std::to_string(scale);
      EXPECT_LT(sparse.sections, paper.sections) << what;
      const FidelityReport f = radius_fidelity(sparse.mesh, g), p = radius_fidelity(paper.mesh, g);
      EXPECT_LT(f.centroid_error.p95, 0.03) << what;
      EXPECT_LE(f.centroid_error.p95, p.centroid_error.p95 + 0.002) << what;
      EXPECT_LT(f.abs_relative_error.p95, 0.03) << what;
    }
}
