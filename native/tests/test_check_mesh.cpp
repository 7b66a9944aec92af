// The mesh checker on surfaces whose answers are known analytically: topology of the Platonic solids,
// a torus and broken variants; self-intersections that cross, touch or fold; exact predicates where
// plain doubles go wrong; triangle quality; radius fidelity against straight tubes and cones. Every
// geometric case is run at the scales 1e-3, 1 and 1e3.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <nlohmann/json.hpp>
#include <random>

#include "surfaces.hpp"
#include "vesselmesh/check/check_mesh.hpp"
#include "vesselmesh/geometry/closest_point.hpp"
#include "vesselmesh/geometry/predicates.hpp"
#include "vesselmesh/geometry/round_cones.hpp"
#include "vesselmesh/geometry/self_intersections.hpp"

using namespace vesselmesh;
using surfaces::scaled;
using surfaces::torus;

namespace {

const double kScales[] = {1e-3, 1.0, 1e3};

TriMesh flipped(TriMesh mesh) {
  for (Tri& f : mesh.faces) std::swap(f[1], f[2]);
  return mesh;
}

/// Both meshes in one, the second's vertices moved by `offset`.
TriMesh merged(TriMesh a, const TriMesh& b, const Vec3& offset = Vec3::Zero()) {
  const auto n = static_cast<int32_t>(a.vertices.size());
  for (const Vec3& p : b.vertices) a.vertices.push_back(p + offset);
  for (const Tri& f : b.faces) a.faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  return a;
}

/// Appends the quad a b c d (counter-clockwise from outside) as two triangles.
void add_quad(TriMesh& m, int32_t a, int32_t b, int32_t c, int32_t d) {
  m.faces.push_back({a, b, c});
  m.faces.push_back({a, c, d});
}

TriMesh tetrahedron() {
  TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

TriMesh octahedron() {
  TriMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

/// The unit cube, vertex x + 2y + 4z at (x, y, z).
TriMesh cube() {
  TriMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  add_quad(m, 0, 2, 3, 1);  // z = 0
  add_quad(m, 4, 5, 7, 6);  // z = 1
  add_quad(m, 0, 1, 5, 4);  // y = 0
  add_quad(m, 2, 6, 7, 3);  // y = 1
  add_quad(m, 0, 4, 6, 2);  // x = 0
  add_quad(m, 1, 3, 7, 5);  // x = 1
  return m;
}

/// The unit sphere with `stacks` bands of `slices` quads between two poles (vertex 0 north, last south).
TriMesh uv_sphere(int stacks, int slices) {
  TriMesh s;
  s.vertices.push_back(Vec3(0, 0, 1));
  for (int k = 1; k < stacks; ++k)
    for (int j = 0; j < slices; ++j) {
      const double theta = M_PI * k / stacks, phi = 2 * M_PI * j / slices;
      s.vertices.push_back(
          Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  s.vertices.push_back(Vec3(0, 0, -1));
  const auto south = static_cast<int32_t>(s.vertices.size()) - 1;
  auto ring = [&](int k, int j) { return static_cast<int32_t>(1 + (k - 1) * slices + j % slices); };
  for (int j = 0; j < slices; ++j) {
    s.faces.push_back({0, ring(1, j), ring(1, j + 1)});
    for (int k = 1; k + 1 < stacks; ++k)
      add_quad(s, ring(k, j), ring(k + 1, j), ring(k + 1, j + 1), ring(k, j + 1));
    s.faces.push_back({ring(stacks - 1, j), south, ring(stacks - 1, j + 1)});
  }
  return s;
}

/// A closed tube of radius r round the segment from → to: `sections` rings of `around` vertices at
/// (k + ½)/sections along it, closed by fans to a centre vertex at each end.
TriMesh closed_tube(const Vec3& from, const Vec3& to, double r, int sections, int around) {
  const Vec3 axis = to - from;
  const Vec3 u = axis.unitOrthogonal(), v = axis.normalized().cross(u);
  TriMesh t;
  for (int k = 0; k < sections; ++k)
    for (int j = 0; j < around; ++j) {
      const double phi = 2 * M_PI * j / around;
      t.vertices.push_back(from + (k + 0.5) / sections * axis + r * (std::cos(phi) * u + std::sin(phi) * v));
    }
  t.vertices.push_back(from);
  t.vertices.push_back(to);
  const auto start = static_cast<int32_t>(t.vertices.size()) - 2, end = start + 1;
  auto at = [&](int k, int j) { return static_cast<int32_t>(k * around + j % around); };
  for (int j = 0; j < around; ++j) {
    t.faces.push_back({start, at(0, j + 1), at(0, j)});
    for (int k = 0; k + 1 < sections; ++k)
      add_quad(t, at(k, j), at(k, j + 1), at(k + 1, j + 1), at(k + 1, j));
    t.faces.push_back({end, at(sections - 1, j), at(sections - 1, j + 1)});
  }
  return t;
}

/// A centerline of straight runs, `n` edges each, all of radius r.
CenterlineGraph straight_runs(const std::vector<std::array<Vec3, 2>>& runs, double r, int n = 10) {
  CenterlineData d;
  for (const auto& [from, to] : runs) {
    for (int i = 0; i <= n; ++i) {
      d.points.push_back(from + (to - from) * i / n);
      d.radius.push_back(r);
      if (i > 0)
        d.edges.push_back(
            {static_cast<int32_t>(d.points.size()) - 2, static_cast<int32_t>(d.points.size()) - 1});
    }
  }
  return build_graph(d);
}

TriMesh triangles(const std::vector<Vec3>& vertices, const std::vector<Tri>& faces) {
  TriMesh m;
  m.vertices = vertices;
  m.faces = faces;
  return m;
}

void expect_closed_solid(const TriMesh& mesh, int64_t v, int64_t e, double volume, const std::string& what) {
  for (double s : kScales) {
    const TopologyReport t = check_topology(scaled(mesh, s));
    EXPECT_TRUE(t.closed_manifold()) << what << " at " << s;
    EXPECT_EQ(t.vertices, v) << what;
    EXPECT_EQ(t.edges, e) << what;
    EXPECT_EQ(t.faces, static_cast<int64_t>(mesh.faces.size())) << what;
    EXPECT_EQ(t.euler_characteristic, 2) << what;
    EXPECT_EQ(t.genus, 0) << what;
    EXPECT_EQ(t.components, 1) << what;
    EXPECT_NEAR(t.signed_volume, volume * s * s * s, 1e-12 * volume * s * s * s) << what << " at " << s;
  }
}

int64_t pairs(const TriMesh& mesh) { return find_self_intersections(mesh).pairs; }

}  // namespace

// --- topology ---------------------------------------------------------------------------------------

TEST(CheckTopology, PlatonicSolidsAreClosedWithEulerCharacteristicTwoAndPositiveVolume) {
  expect_closed_solid(tetrahedron(), 4, 6, 1.0 / 6.0, "tetrahedron");
  expect_closed_solid(octahedron(), 6, 12, 4.0 / 3.0, "octahedron");
  expect_closed_solid(cube(), 8, 18, 1.0, "cube");
}

TEST(CheckTopology, FlippedSurfaceHasNegativeVolume) {
  for (double s : kScales) {
    const TopologyReport t = check_topology(scaled(flipped(cube()), s));
    EXPECT_TRUE(t.closed_manifold());
    EXPECT_NEAR(t.signed_volume, -s * s * s, 1e-12 * s * s * s);
  }
}

TEST(CheckTopology, TorusHasEulerCharacteristicZeroAndGenusOne) {
  for (double s : kScales) {
    const TopologyReport t = check_topology(scaled(torus(96, 48, 2.0, 0.5), s));
    EXPECT_TRUE(t.closed_manifold());
    EXPECT_EQ(t.euler_characteristic, 0);
    EXPECT_EQ(t.genus, 1);
    const double volume = 2 * M_PI * M_PI * 2 * 0.5 * 0.5 * s * s * s;  // 2π²Rr², the grid being 0.4 % less
    EXPECT_NEAR(t.signed_volume, volume, 0.01 * volume);
  }
}

TEST(CheckTopology, TwoDisjointCubesAreTwoComponentsOfGenusZero) {
  const TopologyReport t = check_topology(merged(cube(), cube(), Vec3(3, 0, 0)));
  EXPECT_TRUE(t.closed_manifold());
  EXPECT_EQ(t.components, 2);
  EXPECT_EQ(t.euler_characteristic, 4);
  EXPECT_EQ(t.genus, 0);
  EXPECT_NEAR(t.signed_volume, 2.0, 1e-12);
}

TEST(CheckTopology, CubeWithATriangleRemovedHasThreeBoundaryEdges) {
  TriMesh m = cube();
  m.faces.pop_back();
  const TopologyReport t = check_topology(m);
  EXPECT_EQ(t.boundary_edges, 3);
  EXPECT_EQ(t.non_manifold_edges, 0);
  EXPECT_EQ(t.non_manifold_vertices, 0);
  EXPECT_EQ(t.inconsistent_edges, 0);
  EXPECT_FALSE(t.closed_manifold());
  EXPECT_EQ(t.genus, 0);
}

TEST(CheckTopology, CubeWithOneTriangleFlippedHasThreeInconsistentEdges) {
  TriMesh m = cube();
  std::swap(m.faces[5][1], m.faces[5][2]);
  const TopologyReport t = check_topology(m);
  EXPECT_EQ(t.inconsistent_edges, 3);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_FALSE(t.closed_manifold());
}

TEST(CheckTopology, TetrahedraSharingOneVertexMakeANonManifoldVertex) {
  TriMesh m = tetrahedron();
  const TriMesh other = flipped(scaled(tetrahedron(), -1.0));  // point-reflected through vertex 0, outward
  const auto n = static_cast<int32_t>(m.vertices.size());
  for (int i = 1; i < 4; ++i) m.vertices.push_back(other.vertices[i]);
  for (Tri f : other.faces) {
    for (int32_t& v : f) v = v == 0 ? 0 : v - 1 + n;
    m.faces.push_back(f);
  }
  const TopologyReport t = check_topology(m);
  EXPECT_EQ(t.non_manifold_vertices, 1);
  EXPECT_EQ(t.non_manifold_edges, 0);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.vertices, 7);
  EXPECT_FALSE(t.closed_manifold());
}

TEST(CheckTopology, ThreeTrianglesOnOneEdgeMakeANonManifoldEdge) {
  const TriMesh m =
      triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, -1}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const TopologyReport t = check_topology(m);
  EXPECT_EQ(t.non_manifold_edges, 1);
  EXPECT_EQ(t.boundary_edges, 6);
  EXPECT_EQ(t.non_manifold_vertices, 0);
  EXPECT_EQ(t.edges, 7);
}

TEST(CheckTopology, RepeatedVertexAndZeroAreaFacesAreDegenerate) {
  for (double s : kScales) {
    TriMesh m = scaled(cube(), s);
    m.vertices.push_back(s * Vec3(0.5, 0, 0));  // on the edge 0–1
    m.faces.push_back({0, 8, 1});
    m.faces.push_back({2, 2, 3});
    const TopologyReport t = check_topology(m);
    EXPECT_EQ(t.degenerate_faces, 2);
    EXPECT_FALSE(t.closed_manifold());
  }
}

TEST(CheckTopology, FaceIndexOutOfRangeIsRejected) {
  TriMesh m = tetrahedron();
  m.faces.push_back({0, 1, 4});
  EXPECT_THROW(check_topology(m), std::invalid_argument);
  EXPECT_THROW(find_self_intersections(m), std::invalid_argument);
  EXPECT_THROW(triangle_quality(m), std::invalid_argument);
}

// --- self-intersections -----------------------------------------------------------------------------

// Triangle A lies in z = 0 in every case below, so scaling keeps every contact exact.
const std::vector<Vec3> kA = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};

TriMesh with_a(const std::vector<Vec3>& b) {
  std::vector<Vec3> v = kA;
  v.insert(v.end(), b.begin(), b.end());
  return triangles(v, {{0, 1, 2}, {3, 4, 5}});
}

TEST(SelfIntersections, CrossingTrianglesAreFound) {
  for (double s : kScales) {
    EXPECT_EQ(pairs(scaled(with_a({{0.5, 0.2, -1}, {0.5, 0.2, 1}, {0.5, 1.5, 0}}), s)), 1) << s;
    // one passing through the other with a single edge
    EXPECT_EQ(pairs(scaled(with_a({{0.5, 0.5, -1}, {0.5, 0.5, 1}, {-3, -3, 0.5}}), s)), 1) << s;
  }
}

TEST(SelfIntersections, TrianglesTouchingAtAPointOrAlongAnEdgeDoNotCount) {
  for (double s : kScales) {
    EXPECT_EQ(pairs(scaled(with_a({{0.5, 0.5, 0}, {1, 0.5, 1}, {0.5, 1, 1}}), s)), 0) << "vertex on A, " << s;
    EXPECT_EQ(pairs(scaled(with_a({{0.2, 0.2, 0}, {1, 0.2, 0}, {0.5, 0.5, 1}}), s)), 0) << "edge on A, " << s;
    EXPECT_EQ(pairs(scaled(with_a({{1, -1, 0}, {1, 1, 0}, {1, 0, 1}}), s)), 0) << "edge through A, " << s;
    EXPECT_EQ(pairs(scaled(with_a({{1, 1, -1}, {1, 1, 1}, {3, 3, 0}}), s)), 0)
        << "edge across A's edge, " << s;
    EXPECT_EQ(pairs(scaled(with_a({{2, 0, 0}, {0, 2, 0}, {2, 2, 0}}), s)), 0) << "side by side, " << s;
  }
}

TEST(SelfIntersections, PairsSharingAVertexCountOnlyWhenTheyCrossElsewhere) {
  for (double s : kScales) {
    const std::vector<Vec3> v = {{0, 0, 0},    {2, 0, 0},   {0, 2, 0},     {1, 0.5, 1},
                                 {1, 0.5, -1}, {0.5, 1, 1}, {-1, -1, -0.5}};
    EXPECT_EQ(pairs(scaled(triangles(v, {{0, 1, 2}, {0, 3, 4}}), s)), 1) << "opposite edge through A, " << s;
    EXPECT_EQ(pairs(scaled(triangles(v, {{0, 1, 2}, {0, 3, 5}}), s)), 0) << "above A, " << s;
    EXPECT_EQ(pairs(scaled(triangles(v, {{0, 1, 2}, {0, 6, 3}}), s)), 0)
        << "through A's plane outside A, " << s;
    // both opposite edges end on the other triangle's boundary, yet the two overlap along a segment
    const std::vector<Vec3> w = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 1, -1}, {1, 1, 1}};
    EXPECT_EQ(pairs(scaled(triangles(w, {{0, 1, 2}, {0, 3, 4}}), s)), 1) << "crossing to A's edge, " << s;
  }
}

TEST(SelfIntersections, CoplanarTrianglesCountWhenTheyOverlap) {
  for (double s : kScales) {
    EXPECT_EQ(pairs(scaled(with_a({{0.5, 0.5, 0}, {3, 0.5, 0}, {0.5, 3, 0}}), s)), 1) << s;
    EXPECT_EQ(pairs(scaled(with_a({{0.2, 0.2, 0}, {0.8, 0.2, 0}, {0.2, 0.8, 0}}), s)), 1) << "inside, " << s;
    EXPECT_EQ(pairs(scaled(with_a(kA), s)), 1) << "duplicate, " << s;
    EXPECT_EQ(pairs(scaled(with_a({{1, 1, 0}, {3, 1, 0}, {1, 3, 0}}), s)), 0) << "corner on edge, " << s;
  }
}

TEST(SelfIntersections, NeighboursCountOnlyWhenFoldedBackOntoEachOther) {
  for (double s : kScales) {
    const std::vector<Vec3> v = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 2, 0}, {0.5, 0.5, 0}, {2, 2, 1}};
    EXPECT_EQ(pairs(scaled(triangles(v, {{0, 1, 2}, {2, 1, 3}}), s)), 0) << "flat, " << s;
    EXPECT_EQ(pairs(scaled(triangles(v, {{0, 1, 2}, {2, 1, 5}}), s)), 0) << "bent, " << s;
    EXPECT_EQ(pairs(scaled(triangles(v, {{0, 1, 2}, {2, 1, 4}}), s)), 1) << "folded, " << s;
  }
}

TEST(SelfIntersections, ClosedSurfacesWithoutSelfContactHaveNone) {
  for (double s : kScales) {
    EXPECT_EQ(pairs(scaled(tetrahedron(), s)), 0);
    EXPECT_EQ(pairs(scaled(octahedron(), s)), 0);
    EXPECT_EQ(pairs(scaled(cube(), s)), 0);
    EXPECT_EQ(pairs(scaled(torus(48, 24, 2.0, 0.5), s)), 0);
    EXPECT_EQ(pairs(scaled(uv_sphere(100, 200), s)), 0);
  }
}

TEST(SelfIntersections, VertexPushedThroughTheOppositeSideIsFound) {
  for (double s : kScales) {
    TriMesh sphere = uv_sphere(40, 80);
    sphere.vertices[0] = Vec3(0, 0, -1.5);  // the north pole, now beyond the south pole
    const IntersectionReport r = find_self_intersections(scaled(sphere, s));
    EXPECT_GT(r.pairs, 0) << s;
    ASSERT_FALSE(r.examples.empty());
    EXPECT_LE(r.examples.size(), 20u);
    EXPECT_LT(r.examples[0][0], r.examples[0][1]);
    EXPECT_EQ(r.pairs_in_overlapping_tubes, 0);
  }
}

// Two tori in one plane, their rings crossing at two places, and a face without an interior.
TEST(SelfIntersections, PairsAmongFlaggedFacesAreThePairsWithAFlaggedFaceAndNoMore) {
  TriMesh mesh = torus(48, 24, 2.0, 0.5);
  const TriMesh other = torus(40, 20, 2.0, 0.6);
  const auto n = static_cast<int32_t>(mesh.vertices.size());
  for (const Vec3& p : other.vertices) mesh.vertices.push_back(Vec3(p.x() + 1.5, p.y(), p.z()));
  for (const Tri& t : other.faces) mesh.faces.push_back({t[0] + n, t[1] + n, t[2] + n});
  mesh.faces.push_back({0, 0, 1});  // no interior, flagged or not
  for (double s : kScales) {
    const TriMesh m = scaled(mesh, s);
    const auto all = intersecting_face_pairs(m);
    ASSERT_GT(all.size(), 100u) << s;
    for (int every : {1, 3, 17}) {
      std::vector<char> among(m.faces.size());
      for (std::size_t f = 0; f < among.size(); f += every) among[f] = 1;
      std::vector<std::array<int32_t, 2>> expected;
      for (const auto& pair : all)
        if (among[pair[0]] || among[pair[1]]) expected.push_back(pair);
      EXPECT_EQ(intersecting_face_pairs(m, among), expected) << s << ", every " << every;
    }
    EXPECT_TRUE(intersecting_face_pairs(m, std::vector<char>(m.faces.size(), 0)).empty());
  }
}

// --- exactness --------------------------------------------------------------------------------------

namespace {

int sign(__int128 x) { return (x > 0) - (x < 0); }

}  // namespace

TEST(Predicates, OrientationSignsFollowTheRightHandRule) {
  EXPECT_EQ(orient2d({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(orient2d({0, 0}, {0, 1}, {1, 0}), -1);
  EXPECT_EQ(orient2d({0, 0}, {1, 1}, {3, 3}), 0);
  EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 1);
  EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}), -1);
  EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 7, 0}), 0);
}

// Points a few units in the last place from (0.5, 0.5) against the line through (12, 12) and
// (24, 24): plain doubles give signs in a scattered pattern; integer arithmetic gives the truth.
TEST(Predicates, Orient2dAgreesWithIntegerArithmeticWherePlainDoublesFail) {
  const double u = std::ldexp(1.0, -53);
  const __int128 unit = __int128{1} << 53;  // integer coordinates are multiples of u
  int naive_wrong = 0;
  for (int i = 0; i < 128; ++i)
    for (int j = 0; j < 128; ++j) {
      const Vec2 p(0.5 + i * u, 0.5 + j * u), q(12, 12), r(24, 24);
      const __int128 px = unit / 2 + i, py = unit / 2 + j, qx = 12 * unit, rx = 24 * unit;
      const int truth = sign((qx - px) * (rx - py) - (qx - py) * (rx - px));
      EXPECT_EQ(orient2d(p, q, r), truth) << i << " " << j;
      const double naive = (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
      naive_wrong += (naive > 0) - (naive < 0) != truth;
    }
  EXPECT_GT(naive_wrong, 0) << "the case should be hard for plain doubles";
}

// Random points on a grid of 2^-30, the fourth exactly on the plane of the first three or one grid step
// off it: exact integer determinants against orient3d.
TEST(Predicates, Orient3dAgreesWithIntegerArithmeticOnNearlyCoplanarPoints) {
  std::mt19937_64 rng(12345);
  std::uniform_int_distribution<int64_t> coordinate(-(int64_t{1} << 36), int64_t{1} << 36);
  std::uniform_int_distribution<int64_t> small(-2, 2), step(-1, 1);
  const double grid = std::ldexp(1.0, -30);
  using I3 = std::array<int64_t, 3>;
  auto point = [&](const I3& k) { return Vec3(k[0] * grid, k[1] * grid, k[2] * grid); };
  int naive_wrong = 0, zeros = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    I3 a, b, c, d;
    for (int i = 0; i < 3; ++i) a[i] = coordinate(rng), b[i] = coordinate(rng), c[i] = coordinate(rng);
    const int64_t m = small(rng), n = small(rng);
    for (int i = 0; i < 3; ++i)
      d[i] = a[i] + m * (b[i] - a[i]) + n * (c[i] - a[i]) + (trial % 2 ? step(rng) : 0);
    __int128 u[3], v[3], w[3];
    for (int i = 0; i < 3; ++i) u[i] = b[i] - a[i], v[i] = c[i] - a[i], w[i] = d[i] - a[i];
    const __int128 cross[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                               u[0] * v[1] - u[1] * v[0]};
    // no overflow: the cross components are under 2^75 grid units², w under 2^40 grid units
    const int truth = sign(cross[0] * w[0] + cross[1] * w[1] + cross[2] * w[2]);
    const Vec3 pa = point(a), pb = point(b), pc = point(c), pd = point(d);
    ASSERT_EQ(orient3d(pa, pb, pc, pd), truth) << trial;
    const double naive = (pb - pa).cross(pc - pa).dot(pd - pa);
    naive_wrong += (naive > 0) - (naive < 0) != truth;
    zeros += truth == 0;
  }
  EXPECT_GT(zeros, 5000);
  EXPECT_GT(naive_wrong, 0) << "the case should be hard for plain doubles";
}

// B touches A at one point that lies exactly on A's plane, where plain doubles put it off the plane
// (above or below, depending on the order of the operations) and so may see B passing through A. One
// unit in the last place further down, it does pass through.
TEST(SelfIntersections, TouchingIsToldFromCrossingExactly) {
  const Vec3 a0(41645184, 17959092, 58152684), a1(2244676, 2900524, 19617228),
      a2(24636096, 11322880, 8300084);
  const Vec3 p = a0 + (a1 - a0) / 2 + (a2 - a0) / 4;  // exact: every coordinate is a multiple of 4
  const Vec3 normal = (a1 - a0).cross(a2 - a0).normalized(), along = (a1 - a0).normalized();
  ASSERT_NE((a1 - a0).cross(a2 - a0).dot(p - a0), 0.0) << "plain doubles should get this wrong";
  ASSERT_EQ(orient3d(a0, a1, a2, p), 0);
  const std::vector<Vec3> v = {a0, a1, a2, p, p + 1000 * (normal + along), p + 1000 * (normal - along)};
  EXPECT_EQ(pairs(triangles(v, {{0, 1, 2}, {3, 4, 5}})), 0);

  TriMesh through = triangles(v, {{0, 1, 2}, {3, 4, 5}});
  int axis;
  normal.cwiseAbs().maxCoeff(&axis);
  through.vertices[3][axis] = std::nextafter(p[axis], normal[axis] > 0 ? -1e300 : 1e300);
  ASSERT_EQ(orient3d(a0, a1, a2, through.vertices[3]), -1);
  EXPECT_EQ(pairs(through), 1);
}

// --- overlapping tubes ------------------------------------------------------------------------------

TEST(SelfIntersections, CrossingInputTubesAreClassedAsOverlapping) {
  for (double s : kScales) {
    // two straight tubes of radius 1 whose axes pass 0.5 apart: the input itself overlaps
    const TriMesh mesh = merged(closed_tube(Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s, s, 40, 24),
                                closed_tube(Vec3(0, -10, 0.5) * s, Vec3(0, 10, 0.5) * s, s, 40, 24));
    const CenterlineGraph g = straight_runs(
        {{Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s}, {Vec3(0, -10, 0.5) * s, Vec3(0, 10, 0.5) * s}}, s);
    const IntersectionReport r = find_self_intersections(mesh, &g);
    EXPECT_GT(r.pairs, 0) << s;
    EXPECT_EQ(r.pairs_in_overlapping_tubes, r.pairs) << s;
    // the same surfaces against thin centerline tubes that do not overlap: nothing is excused
    const CenterlineGraph thin = straight_runs(
        {{Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s}, {Vec3(0, -10, 0.5) * s, Vec3(0, 10, 0.5) * s}}, 0.1 * s);
    EXPECT_EQ(find_self_intersections(mesh, &thin).pairs_in_overlapping_tubes, 0) << s;
  }
}

TEST(SelfIntersections, BranchesMeetingAtAJointAreNotAnOverlapOfTheInput) {
  for (double s : kScales) {
    // a T: the side tube pushed into the through tube at the joint is the mesher's fault, not the input's
    const TriMesh mesh = merged(closed_tube(Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s, s, 40, 24),
                                closed_tube(Vec3(0, 0, 0) * s, Vec3(0, 10, 0) * s, s, 20, 24));
    CenterlineData d;
    d.points = {Vec3(0, 0, 0) * s, Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s, Vec3(0, 10, 0) * s};
    d.radius = {s, s, s, s};
    d.edges = {{1, 0}, {0, 2}, {0, 3}};
    const CenterlineGraph g = build_graph(d);
    ASSERT_EQ(g.branches.size(), 3u);
    const IntersectionReport r = find_self_intersections(mesh, &g);
    EXPECT_GT(r.pairs, 0) << s;
    EXPECT_EQ(r.pairs_in_overlapping_tubes, 0) << s;
  }
}

TEST(SelfIntersections, ABranchComingBackThroughItsNeighbourNearTheirJointOverlapsTheInput) {
  for (double s : kScales) {
    // a through tube along x with a joint at the origin; the side branch leaves along y, turns, and comes
    // back down through the through tube 2 radii from the joint, inside the joint's reach
    const TriMesh mesh = merged(closed_tube(Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s, s, 40, 24),
                                closed_tube(Vec3(2, 4, 0) * s, Vec3(2, -4, 0) * s, s, 20, 24));
    CenterlineData d;
    d.points = {Vec3(0, 0, 0) * s, Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s, Vec3(0, 4, 0) * s,
                Vec3(2, 4, 0) * s, Vec3(2, -4, 0) * s};
    d.radius.assign(d.points.size(), s);
    d.edges = {{1, 0}, {0, 2}, {0, 3}, {3, 4}, {4, 5}};
    const CenterlineGraph g = build_graph(d);
    ASSERT_EQ(g.branches.size(), 3u);
    const IntersectionReport r = find_self_intersections(mesh, &g);
    EXPECT_GT(r.pairs, 0) << s;
    EXPECT_EQ(r.pairs_in_overlapping_tubes, r.pairs) << s;
  }
}

TEST(SelfIntersections, ABranchComingBackOntoItselfOverlapsTheInputButNotWhereItMerelyTurns) {
  for (double s : kScales) {
    // one branch along x, round a square 10 across, and back down along y through its own start, 0.5 off
    const TriMesh crossing = merged(closed_tube(Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s, s, 40, 24),
                                    closed_tube(Vec3(0, 10, 0.5) * s, Vec3(0, -10, 0.5) * s, s, 40, 24));
    CenterlineData d;
    d.points = {Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s, Vec3(10, 10, 0) * s, Vec3(0, 10, 0.5) * s,
                Vec3(0, -10, 0.5) * s};
    d.radius.assign(d.points.size(), s);
    d.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 4}};
    const CenterlineGraph g = build_graph(d);
    ASSERT_EQ(g.branches.size(), 1u);
    const IntersectionReport r = find_self_intersections(crossing, &g);
    EXPECT_GT(r.pairs, 0) << s;
    EXPECT_EQ(r.pairs_in_overlapping_tubes, r.pairs) << s;

    // one branch turning a right angle at the origin: its two tubes pushed into each other there are the
    // mesher's fault
    const TriMesh corner = merged(closed_tube(Vec3(-10, 0, 0) * s, Vec3(1, 0, 0) * s, s, 40, 24),
                                  closed_tube(Vec3(0, -1, 0) * s, Vec3(0, 10, 0) * s, s, 40, 24));
    CenterlineData c;
    c.points = {Vec3(-10, 0, 0) * s, Vec3(0, 0, 0) * s, Vec3(0, 10, 0) * s};
    c.radius.assign(c.points.size(), s);
    c.edges = {{0, 1}, {1, 2}};
    const CenterlineGraph h = build_graph(c);
    const IntersectionReport t = find_self_intersections(corner, &h);
    EXPECT_GT(t.pairs, 0) << s;
    EXPECT_EQ(t.pairs_in_overlapping_tubes, 0) << s;
  }
}

TEST(TubeOverlaps, AreWhereTheInputTubesOverlapAwayFromTheirJointsAtEveryScale) {
  for (double s : kScales) {
    // Two tubes of radius 1 crossing, axes 0.5 apart: one place, at the crossing.
    const std::vector<TubeOverlap> crossing = tube_overlaps(straight_runs(
        {{Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s}, {Vec3(0, -10, 0.5) * s, Vec3(0, 10, 0.5) * s}}, s));
    ASSERT_EQ(crossing.size(), 1u) << s;
    EXPECT_LT((crossing[0].at - Vec3(0, 0, 0.25) * s).norm(), 0.1 * s) << s;
    EXPECT_DOUBLE_EQ(crossing[0].radius, s);
    // The same axes with thin tubes: none.
    EXPECT_TRUE(tube_overlaps(straight_runs({{Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s},
                                             {Vec3(0, -10, 0.5) * s, Vec3(0, 10, 0.5) * s}},
                                            0.1 * s))
                    .empty())
        << s;
    // Two vessels side by side 1.2 radii apart along their whole length: one place.
    const std::vector<TubeOverlap> side = tube_overlaps(straight_runs(
        {{Vec3(0, 0, 0) * s, Vec3(20, 0, 0) * s}, {Vec3(0, 1.2, 0) * s, Vec3(20, 1.2, 0) * s}}, s));
    ASSERT_EQ(side.size(), 1u) << s;
    EXPECT_GE(side[0].edge_pairs, 10) << s;
    // A T: branches meeting at their joint are no overlap of the input.
    CenterlineData t;
    t.points = {Vec3(0, 0, 0) * s, Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s, Vec3(0, 10, 0) * s};
    t.radius.assign(t.points.size(), s);
    t.edges = {{1, 0}, {0, 2}, {0, 3}};
    EXPECT_TRUE(tube_overlaps(build_graph(t)).empty()) << s;
    // One branch along x, round a square and back down through its own start: one place; a branch that
    // merely turns a right angle: none.
    CenterlineData loop;
    loop.points = {Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s, Vec3(10, 10, 0) * s, Vec3(0, 10, 0.5) * s,
                   Vec3(0, -10, 0.5) * s};
    loop.radius.assign(loop.points.size(), s);
    loop.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 4}};
    EXPECT_EQ(tube_overlaps(build_graph(loop)).size(), 1u) << s;
    CenterlineData corner;
    corner.points = {Vec3(-10, 0, 0) * s, Vec3(0, 0, 0) * s, Vec3(0, 10, 0) * s};
    corner.radius.assign(corner.points.size(), s);
    corner.edges = {{0, 1}, {1, 2}};
    EXPECT_TRUE(tube_overlaps(build_graph(corner)).empty()) << s;
  }
}

TEST(TubeOverlaps, ABranchHookingBackThroughItsJointsTubesWithinTheJointsReachIsOne) {
  for (double s : kScales) {
    // A fat vessel along x (radius 3, its joint's reach 9) and a thin branch (radius 0.5) from its joint
    // down, across and back up through the fat tube at x = 4, every point within the reach: one place.
    CenterlineData hook;
    hook.points = {Vec3(0, 0, 0) * s,  Vec3(-10, 0, 0) * s, Vec3(10, 0, 0) * s,
                   Vec3(0, -8, 0) * s, Vec3(4, -8, 0) * s,  Vec3(4, 8, 0) * s};
    hook.edge_radius = {3 * s, 3 * s, 0.5 * s, 0.5 * s, 0.5 * s};
    hook.edges = {{1, 0}, {0, 2}, {0, 3}, {3, 4}, {4, 5}};
    EXPECT_EQ(tube_overlaps(build_graph(hook)).size(), 1u) << s;
    // The same branch turning away instead of back, within the reach: none.
    hook.points[5] = Vec3(7, -5, 0) * s;
    EXPECT_TRUE(tube_overlaps(build_graph(hook)).empty()) << s;
  }
}

TEST(TubeOverlaps, TubesTracedExactlyTouchingCountWhereverTheDataSetLies) {
  // Two vessels crossing with their axes exactly the sum of their radii apart, in decimal coordinates as
  // a file gives them: whether they touch must not depend on how the position of the data set rounds.
  for (double s : kScales)
    for (double offset : {0.0, 0.1, 1e3, 12345.678, 1e6}) {
      const Vec3 o = Vec3::Constant(offset * s);
      const std::vector<TubeOverlap> touching =
          tube_overlaps(straight_runs({{o + Vec3(-5, 0.1, 0.3) * s, o + Vec3(5, 0.1, 0.3) * s},
                                       {o + Vec3(0.2, -5, 1.0) * s, o + Vec3(0.2, 5, 1.0) * s}},
                                      0.35 * s, 1));
      EXPECT_EQ(touching.size(), 1u) << "scale " << s << ", offset " << offset;
    }
}

// --- quality ----------------------------------------------------------------------------------------

TEST(TriangleQuality, EquilateralTriangleHasRadiusRatioTwoAndAnglesOfSixtyDegrees) {
  for (double s : kScales) {
    const QualityReport q = triangle_quality(
        scaled(triangles({{0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}}, {{0, 1, 2}}), s));
    EXPECT_NEAR(q.radius_ratio.min, 2.0, 1e-12);
    EXPECT_NEAR(q.radius_ratio.max, 2.0, 1e-12);
    EXPECT_NEAR(q.min_angle.median, 60.0, 1e-9);
    EXPECT_EQ(q.radius_ratio.count, 1);
  }
}

TEST(TriangleQuality, ThreeFourFiveTriangleHasRadiusRatioTwoAndAHalf) {
  for (double s : kScales) {
    const QualityReport q =
        triangle_quality(scaled(triangles({{0, 0, 0}, {4, 0, 0}, {0, 3, 0}}, {{0, 1, 2}}), s));
    EXPECT_NEAR(q.radius_ratio.median, 2.5, 1e-12);  // R = 5/2, r = 1
    EXPECT_NEAR(q.min_angle.median, std::atan2(3.0, 4.0) * 180 / M_PI, 1e-9);
  }
}

TEST(TriangleQuality, DistributionsSummariseEveryFaceAndLeaveDegenerateOnesOut) {
  TriMesh m = cube();  // twelve right isosceles triangles: R/r = 1 + √2, smallest angle 45°
  m.vertices.push_back(Vec3(2, 0, 0));
  m.faces.push_back({0, 1, 8});  // collinear
  const QualityReport q = triangle_quality(m);
  EXPECT_EQ(q.degenerate, 1);
  EXPECT_EQ(q.radius_ratio.count, 12);
  EXPECT_EQ(q.min_angle.count, 12);
  for (double x : {q.radius_ratio.min, q.radius_ratio.median, q.radius_ratio.p95, q.radius_ratio.max,
                   q.radius_ratio.mean})
    EXPECT_NEAR(x, 1 + std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(q.min_angle.mean, 45.0, 1e-9);
}

// --- radius fidelity --------------------------------------------------------------------------------

TEST(RadiusFidelity, CylinderMatchesItsCenterlineRadiusAwayFromTheCaps) {
  for (double s : kScales) {
    // rings every half radius from 0.25 r to 9.75 r: the two at each end are within a radius of it
    const TriMesh mesh = closed_tube(Vec3::Zero(), Vec3(10 * s, 0, 0), s, 20, 32);
    const CenterlineGraph g = straight_runs({{Vec3::Zero(), Vec3(10 * s, 0, 0)}}, s, 1);
    const FidelityReport f = radius_fidelity(mesh, g);
    EXPECT_EQ(f.excluded_cap_vertices, 4 * 32 + 2) << s;
    EXPECT_EQ(f.abs_relative_error.count, 16 * 32);
    EXPECT_LT(f.abs_relative_error.max, 1e-12) << s;
  }
}

TEST(RadiusFidelity, AVesselWithNoSurfaceRoundItIsMissingAxisOfItsLength) {
  for (double s : kScales) {
    const TriMesh mesh = closed_tube(Vec3::Zero(), Vec3(10 * s, 0, 0), s, 20, 32);
    const CenterlineGraph whole = straight_runs({{Vec3::Zero(), Vec3(10 * s, 0, 0)}}, s, 10);
    EXPECT_EQ(radius_fidelity(mesh, whole).missing_axis, 0) << s;
    // A branch of the centerline the surface lost: from (5, 0, 0) out along y to (5, 12, 0), radius s. Its
    // axis lies inside the tube up to y = s, within a radius of it up to 2 s, and in its cap's reach from a
    // radius before its end: 9 radii of it have no surface round them (to the sampling's half radius).
    const CenterlineGraph branched = straight_runs(
        {{Vec3(0, 0, 0), Vec3(5 * s, 0, 0)}, {Vec3(5 * s, 0, 0), Vec3(10 * s, 0, 0)},
         {Vec3(5 * s, 0, 0), Vec3(5 * s, 12 * s, 0)}}, s, 12);
    const FidelityReport f = radius_fidelity(mesh, branched);
    EXPECT_NEAR(f.missing_axis, 9, 0.5) << s;
    EXPECT_NEAR(f.missing_axis_at.x(), 5 * s, 1e-9 * s) << s;
    EXPECT_NEAR(f.missing_axis_at.y(), 2 * s, 0.5 * s) << s;
  }
}

TEST(RadiusFidelity, CylinderAgainstATenPercentWiderCenterlineIsOneEleventhTooThin) {
  for (double s : kScales) {
    const TriMesh mesh = closed_tube(Vec3::Zero(), Vec3(10 * s, 0, 0), s, 20, 32);
    const CenterlineGraph g = straight_runs({{Vec3::Zero(), Vec3(10 * s, 0, 0)}}, 1.1 * s, 4);
    const FidelityReport f = radius_fidelity(mesh, g);
    EXPECT_NEAR(f.relative_error.min, -1.0 / 11.0, 1e-12) << s;
    EXPECT_NEAR(f.relative_error.max, -1.0 / 11.0, 1e-12) << s;
    EXPECT_NEAR(f.abs_relative_error.median, 1.0 / 11.0, 1e-12) << s;
  }
}

// Rings on the side of a round cone (r0 = 1.5, r1 = 0.5, length 10, so sinφ = 0.1), pushed out along
// its normal by 5 % of the cone's radius there: the relative error is 0.05 wherever the local radius
// is interpolated along the side correctly.
TEST(RadiusFidelity, ConeErrorIsRelativeToTheRadiusWhereTheVertexIsClosest) {
  for (double s : kScales) {
    for (double offset : {0.0, 0.05}) {
      const double r0 = 1.5, r1 = 0.5, length = 10, sin_phi = (r0 - r1) / length;
      const double cos_phi = std::sqrt(1 - sin_phi * sin_phi);
      TriMesh mesh;
      for (int k = 0; k <= 20; ++k) {
        const double lambda = k / 20.0, local = r0 + lambda * (r1 - r0);
        const double t = r0 * sin_phi + lambda * length * cos_phi * cos_phi + offset * local * sin_phi;
        const double rho = r0 * cos_phi - lambda * length * cos_phi * sin_phi + offset * local * cos_phi;
        for (int j = 0; j < 12; ++j)
          mesh.vertices.push_back(
              s * Vec3(t, rho * std::cos(2 * M_PI * j / 12), rho * std::sin(2 * M_PI * j / 12)));
      }
      CenterlineData d;
      d.points = {Vec3::Zero(), Vec3(length * s, 0, 0)};
      d.radius = {r0 * s, r1 * s};
      d.edges = {{0, 1}};
      const FidelityReport f = radius_fidelity(mesh, build_graph(d));
      EXPECT_GT(f.relative_error.count, 12 * 15);
      EXPECT_NEAR(f.relative_error.min, offset, 1e-12) << s;
      EXPECT_NEAR(f.relative_error.max, offset, 1e-12) << s;
    }
  }
}

// Two crossing tubes of radius 1 (along x, and along y through (5, 0, 0)): each vertex is measured
// against the nearer surface — the minimum over edges, not the maximum.
TEST(RadiusFidelity, UnionOfConesTakesTheSmallestSignedDistance) {
  for (double s : kScales) {
    TriMesh points;
    points.vertices = {s * Vec3(2.5, 0, 1),     // on the x tube, far from the y tube: 0
                       s * Vec3(5.5, 0, 0.9),   // 0.1 inside the x tube, 0.03 outside the y tube: −0.1
                       s * Vec3(5, 2.5, 1.1)};  // 0.1 outside the y tube, 1.7 outside the x tube: +0.1
    const CenterlineGraph g =
        straight_runs({{Vec3::Zero(), s * Vec3(10, 0, 0)}, {s * Vec3(5, -5, 0), s * Vec3(5, 5, 0)}}, s, 3);
    const FidelityReport f = radius_fidelity(points, g);
    EXPECT_EQ(f.excluded_cap_vertices, 0);
    EXPECT_NEAR(f.relative_error.min, -0.1, 1e-12) << s;
    EXPECT_NEAR(f.relative_error.median, 0.0, 1e-12) << s;
    EXPECT_NEAR(f.relative_error.max, 0.1, 1e-12) << s;
    EXPECT_NEAR(f.abs_relative_error.mean, 0.2 / 3, 1e-12) << s;
  }
}

// A ring of radius 10 with a tube of radius 1 round it, meshed two ways: as a torus; and as a band round
// the tube's outer side closed by two fans of triangles across the ring's hole, every vertex on the tube.
// The vertices cannot tell the two apart; the area off the tubes can.
TEST(RadiusFidelity, FacesSpanningAcrossTheTubesAreAreaOffThemThoughTheirCornersLieOnThem) {
  constexpr int n = 64, around = 16;
  for (double s : kScales) {
    CenterlineData d;
    auto ring = [&](double radius, double z, int i) {
      const double a = 2 * M_PI * i / n;
      return Vec3(s * radius * std::cos(a), s * radius * std::sin(a), s * z);
    };
    for (int i = 0; i < n; ++i) {
      d.points.push_back(ring(10, 0, i));
      d.radius.push_back(s);
      d.edges.push_back({i, (i + 1) % n});
    }
    const CenterlineGraph g = build_graph(d);

    TriMesh torus;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < around; ++j) {
        const double b = 2 * M_PI * j / around;
        torus.vertices.push_back(ring(10 + std::cos(b), std::sin(b), i));
        const int32_t next = ((i + 1) % n) * around;
        add_quad(torus, i * around + j, i * around + (j + 1) % around, next + (j + 1) % around, next + j);
      }
    const FidelityReport round = radius_fidelity(torus, g);
    EXPECT_LT(round.abs_relative_error.max, 0.05) << s;
    EXPECT_EQ(round.area_off_tubes, 0) << s;

    TriMesh spanning;
    for (int i = 0; i < n; ++i)
      spanning.vertices.insert(spanning.vertices.end(), {ring(10, 1, i), ring(11, 0, i), ring(10, -1, i)});
    for (int i = 0; i < n; ++i) {
      const int32_t a = 3 * i, b = 3 * ((i + 1) % n);
      add_quad(spanning, a, a + 1, b + 1, b);
      add_quad(spanning, a + 1, a + 2, b + 2, b + 1);
    }
    for (int32_t i = 1; i + 1 < n; ++i) {
      spanning.faces.push_back({0, 3 * i, 3 * (i + 1)});
      spanning.faces.push_back({2, 3 * (i + 1) + 2, 3 * i + 2});
    }
    const FidelityReport flat = radius_fidelity(spanning, g);
    EXPECT_LT(flat.abs_relative_error.max, 0.05) << s;
    EXPECT_GT(flat.area_off_tubes, 0.6) << s;
  }
}

// Two parallel tubes of radius 1, along x at y = 0 and y = 6, and a fin: one triangle from two
// neighbouring vertices on top of the first tube to one on top of the second, as a joint's hull reaching
// across to a vessel it does not belong to. Its corners lie on the tubes, and so do all the vertices; its
// centroid lies far off them, and its long edges span the gap.
TEST(RadiusFidelity, AFinFromOneTubeToAnotherShowsAsACentroidFarOffTheTubesAndALongEdgeOffThem) {
  for (double s : kScales) {
    TriMesh mesh = merged(closed_tube(Vec3::Zero(), s * Vec3(20, 0, 0), s, 40, 16),
                          closed_tube(s * Vec3(0, 6, 0), s * Vec3(20, 6, 0), s, 40, 16));
    const CenterlineGraph g =
        straight_runs({{Vec3::Zero(), s * Vec3(20, 0, 0)}, {s * Vec3(0, 6, 0), s * Vec3(20, 6, 0)}}, s);
    const FidelityReport clean = radius_fidelity(mesh, g);
    // A 16-sided ring's chords: centroids 1 − cos(π/16) inside at most, edges 0.5 along and 0.39 round.
    EXPECT_LT(clean.largest_centroid_offset, 0.02) << s;
    EXPECT_NEAR(clean.longest_edge, std::hypot(0.5, 2 * std::sin(M_PI / 16)), 1e-9) << s;
    EXPECT_EQ(clean.longest_edge_off_tubes, 0) << s;  // every edge's midpoint lies on its tube

    // The fin, from the top of ring 20 of each tube (and ring 21 of the first).
    auto top = [&](int tube, int ring) {
      int32_t best = -1;
      for (int32_t v = tube * (40 * 16 + 2) + ring * 16, j = 0; j < 16; ++j)
        if (best < 0 || mesh.vertices[v + j].z() > mesh.vertices[best].z()) best = v + j;
      return best;
    };
    const int32_t a = top(0, 20), b = top(0, 21), c = top(1, 20);
    mesh.faces.push_back({a, b, c});
    const Vec3 &pa = mesh.vertices[a], &pb = mesh.vertices[b], &pc = mesh.vertices[c];
    const Vec3 centroid = (pa + pb + pc) / 3;
    const FidelityReport fin = radius_fidelity(mesh, g);
    // The centroid lies in the plane x = const, nearest the first tube's axis (y = 2 of 6).
    EXPECT_NEAR(fin.largest_centroid_offset, Vec3(0, centroid.y(), centroid.z()).norm() / s - 1, 1e-9) << s;
    EXPECT_LT((fin.largest_centroid_offset_at - centroid).norm(), 1e-12 * s) << s;
    const bool ac = (pc - pa).norm() > (pc - pb).norm();
    const Vec3& far = ac ? pa : pb;
    EXPECT_NEAR(fin.longest_edge, (pc - far).norm() / s, 1e-9) << s;
    EXPECT_NEAR(fin.longest_edge_length, (pc - far).norm(), 1e-9 * s) << s;
    EXPECT_LT((fin.longest_edge_at - 0.5 * (pc + far)).norm(), 1e-12 * s) << s;
    EXPECT_GT(fin.longest_edge, 5.9) << s;
    EXPECT_EQ(fin.longest_edge_off_tubes, fin.longest_edge) << s;  // the fin's reaches across, off the tubes
    EXPECT_LT((fin.longest_edge_off_tubes_at - fin.longest_edge_at).norm(), 1e-12 * s) << s;
    EXPECT_GT(fin.largest_centroid_offset, 1.2) << s;
    EXPECT_EQ(fin.abs_relative_error.max, clean.abs_relative_error.max) << s;  // the vertices cannot tell
  }
}

// On a tube whose vertices all lie on its cylinder, every triangle spans one step of 2π/16 round it, and its
// centroid lies |2 + e^{iπ/8}| / 3 of the radius from the axis: that is the error between the vertices at
// every quantile, whatever the scale.
TEST(RadiusFidelity, CentroidErrorOfATubeOnItsCylinderIsItsChordsClosedForm) {
  const double expected = 1 - std::abs(2.0 + std::polar(1.0, M_PI / 8)) / 3;
  for (double s : kScales) {
    const TriMesh mesh = closed_tube(Vec3::Zero(), s * Vec3(20, 0, 0), s, 40, 16);
    const FidelityReport f = radius_fidelity(mesh, straight_runs({{Vec3::Zero(), s * Vec3(20, 0, 0)}}, s));
    EXPECT_NEAR(f.centroid_error.median, expected, 1e-9) << s;
    EXPECT_NEAR(f.centroid_error.p95, expected, 1e-9) << s;
    EXPECT_NEAR(f.centroid_error.p99, expected, 1e-9) << s;
    EXPECT_LT(f.abs_relative_error.max, 1e-9) << s;  // the vertices are exact
  }
}

// Each edge counts against the larger of the local radii at its ends: a thin vessel's edges next to a
// thick one's are not long for the thick one.
TEST(RadiusFidelity, LongestEdgeIsRelativeToTheLargerRadiusAtItsEnds) {
  for (double s : kScales) {
    // Tubes of radius 1 and 0.25 side by side, 1.5 apart, one triangle joining them: its edges 1.5 long.
    TriMesh mesh = triangles({s * Vec3(5, 0, 1), s * Vec3(5.4, 0, 1), s * Vec3(5, 1.5, 0.25)}, {{0, 1, 2}});
    CenterlineData d;
    for (double y : {0.0, 1.5})
      for (int i = 0; i <= 10; ++i) {
        d.points.push_back(s * Vec3(i, y, 0));
        d.radius.push_back(y == 0 ? s : 0.25 * s);
        if (i > 0)
          d.edges.push_back(
              {static_cast<int32_t>(d.points.size()) - 2, static_cast<int32_t>(d.points.size()) - 1});
      }
    const FidelityReport f = radius_fidelity(mesh, build_graph(d));
    const double longest = (Vec3(5.4, 0, 1) - Vec3(5, 1.5, 0.25)).norm();
    EXPECT_NEAR(f.longest_edge, longest, 1e-9) << s;  // against radius 1, not 0.25
    EXPECT_NEAR(f.longest_edge_length, longest * s, 1e-9 * s) << s;
  }
}

// --- the whole report -------------------------------------------------------------------------------

// --- distance between surfaces ----------------------------------------------------------------------

TEST(SurfaceDistance, ASurfaceIsAtDistanceZeroFromItself) {
  const TriMesh mesh = closed_tube(Vec3::Zero(), Vec3(10, 0, 0), 1, 20, 32);
  const SurfaceDistanceReport d =
      surface_distance(mesh, mesh, straight_runs({{Vec3::Zero(), Vec3(10, 0, 0)}}, 1, 1));
  EXPECT_EQ(d.vertices.max, 0);
  EXPECT_LT(d.centroids.max, 1e-12);
  EXPECT_EQ(d.centroids.count, static_cast<int64_t>(mesh.faces.size()));
}

TEST(SurfaceDistance, ATenPercentWiderTubeIsATenthOfTheRadiusAway) {
  for (double s : kScales) {
    const TriMesh narrow = closed_tube(Vec3::Zero(), Vec3(10 * s, 0, 0), s, 20, 32);
    const TriMesh wide = closed_tube(Vec3::Zero(), Vec3(10 * s, 0, 0), 1.1 * s, 20, 32);
    const SurfaceDistanceReport d =
        surface_distance(wide, narrow, straight_runs({{Vec3::Zero(), Vec3(10 * s, 0, 0)}}, s, 1));
    // Ring vertices lie straight out from the narrow tube's; the two cap centres are shared.
    EXPECT_NEAR(d.vertices.median, 0.1, 1e-9) << s;
    EXPECT_NEAR(d.vertices.max, 0.1, 1e-9) << s;
    EXPECT_EQ(d.vertices.min, 0) << s;
  }
}

TEST(ClosestPoint, EveryRegionOfATriangle) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  const std::vector<std::pair<Vec3, Vec3>> cases = {
      {{0.5, 0.5, 3}, {0.5, 0.5, 0}},  // above the face
      {{-1, -1, 1}, a},                // beyond each corner
      {{3, -1, 0}, b},
      {{-1, 3, 0}, c},
      {{1, -2, 0}, {1, 0, 0}},  // beside each edge
      {{2, 2, 0}, {1, 1, 0}},
      {{-2, 1, 5}, {0, 1, 0}}};
  for (const auto& [p, expected] : cases)
    EXPECT_LT((closest_point_on_triangle(p, a, b, c) - expected).norm(), 1e-15) << p.transpose();
  // No area: the nearest point of its edges.
  EXPECT_LT((closest_point_on_triangle(Vec3(1, 1, 0), a, b, Vec3(1, 0, 0)) - Vec3(1, 0, 0)).norm(), 1e-15);
}

TEST(CheckMesh, ReportJsonHoldsEveryPartAndFidelityOnlyWithACenterline) {
  const TriMesh mesh = closed_tube(Vec3::Zero(), Vec3(10, 0, 0), 1, 20, 16);
  const nlohmann::json plain = nlohmann::json::parse(report_json(check_mesh(mesh)));
  EXPECT_TRUE(plain.at("closed_manifold").get<bool>());
  EXPECT_EQ(plain.at("topology").at("euler_characteristic"), 2);
  EXPECT_EQ(plain.at("topology").at("genus"), 0);
  EXPECT_EQ(plain.at("intersections").at("pairs"), 0);
  EXPECT_EQ(plain.at("intersections").at("pairs_in_overlapping_tubes"), 0);
  EXPECT_EQ(plain.at("quality").at("radius_ratio").at("count"), static_cast<int64_t>(mesh.faces.size()));
  EXPECT_TRUE(plain.at("quality").at("min_angle").contains("p95"));
  EXPECT_FALSE(plain.contains("fidelity"));

  const CenterlineGraph g = straight_runs({{Vec3::Zero(), Vec3(10, 0, 0)}}, 1);
  const CheckReport report = check_mesh(mesh, &g);
  ASSERT_TRUE(report.fidelity.has_value());
  const nlohmann::json full = nlohmann::json::parse(report_json(report, -1));
  EXPECT_EQ(full.at("fidelity").at("excluded_cap_vertices"), report.fidelity->excluded_cap_vertices);
  EXPECT_LT(full.at("fidelity").at("abs_relative_error").at("max").get<double>(), 1e-12);
  EXPECT_TRUE(full.at("fidelity").at("relative_error").contains("median"));
  EXPECT_EQ(full.at("fidelity").at("largest_centroid_offset").at("relative").get<double>(),
            report.fidelity->largest_centroid_offset);
  EXPECT_EQ(full.at("fidelity").at("largest_centroid_offset").at("at").size(), 3u);
  EXPECT_EQ(full.at("fidelity").at("longest_edge").at("relative").get<double>(),
            report.fidelity->longest_edge);
  EXPECT_EQ(full.at("fidelity").at("longest_edge").at("length").get<double>(),
            report.fidelity->longest_edge_length);
  EXPECT_EQ(full.at("fidelity").at("longest_edge").at("at")[0].get<double>(),
            report.fidelity->longest_edge_at.x());
}
