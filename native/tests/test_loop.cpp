// Uniform Loop subdivision: counts and topology, the documented numbering, agreement with OpenMesh's
// LoopT as an independent reference, boundary rules, limit positions, and the shrinkage of a square tube.
#include <gtest/gtest.h>

#include "surfaces.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <utility>

#include "vesselmesh/pipeline.hpp"
#include "vesselmesh/subdivide/loop.hpp"

using namespace vesselmesh;
using surfaces::torus;

namespace {

using EdgeKey = std::pair<int32_t, int32_t>;

EdgeKey sorted_edge(int32_t a, int32_t b) { return {std::min(a, b), std::max(a, b)}; }

/// The documented edge numbering: unique edges (lo, hi) in lexicographic order.
std::map<EdgeKey, int32_t> edge_numbering(const TriMesh& mesh) {
  std::map<EdgeKey, int32_t> numbering;
  for (const Tri& t : mesh.faces)
    for (int k = 0; k < 3; ++k) numbering.emplace(sorted_edge(t[k], t[(k + 1) % 3]), 0);
  int32_t e = 0;
  for (auto& entry : numbering) entry.second = e++;
  return numbering;
}

/// Directed edges with how often each is traversed.
std::map<EdgeKey, int> directed_edges(const TriMesh& mesh) {
  std::map<EdgeKey, int> count;
  for (const Tri& t : mesh.faces)
    for (int k = 0; k < 3; ++k) ++count[{t[k], t[(k + 1) % 3]}];
  return count;
}

double signed_volume(const TriMesh& mesh) {
  double v = 0;
  for (const Tri& t : mesh.faces)
    v += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6;
  return v;
}

/// Flips the triangles of a convex mesh that face the centroid, so that all face outwards.
void orient_outwards(TriMesh& mesh) {
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : mesh.vertices) centre += p / static_cast<double>(mesh.vertices.size());
  for (Tri& t : mesh.faces) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    if ((b - a).cross(c - a).dot(a - centre) < 0) std::swap(t[1], t[2]);
  }
}

TriMesh octahedron() {
  TriMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int32_t x : {0, 1})
    for (int32_t y : {2, 3})
      for (int32_t z : {4, 5}) m.faces.push_back({x, y, z});
  orient_outwards(m);
  return m;
}

/// A cube (vertex x + 2y + 4z, slightly jittered) whose quads are cut so that valences 3, 4, 5 and 6 occur.
TriMesh irregular_cube() {
  TriMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1) +
                         0.07 * Vec3(std::sin(i), std::cos(3 * i), std::sin(5 * i)));
  // Quads as vertex cycles; all but the last are cut along 0–2 of the cycle, the last along 1–3.
  const std::array<std::array<int32_t, 4>, 6> quads = {
      {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}}};
  for (size_t i = 0; i < quads.size(); ++i) {
    const auto& q = quads[i];
    if (i + 1 < quads.size()) {
      m.faces.push_back({q[0], q[1], q[2]});
      m.faces.push_back({q[0], q[2], q[3]});
    } else {
      m.faces.push_back({q[1], q[2], q[3]});
      m.faces.push_back({q[1], q[3], q[0]});
    }
  }
  orient_outwards(m);
  return m;
}

/// An nx × ny grid of unevenly spaced quads, cut alternately along either diagonal, lying in a tilted plane
/// through `origin` spanned by orthonormal u and v; faces counter-clockwise about u × v.
TriMesh tilted_grid(int nx, int ny, const Vec3& origin, const Vec3& u, const Vec3& v) {
  TriMesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double s = i + 0.25 * std::sin(1.7 * i + j), t = j + 0.25 * std::cos(2.3 * j + i);
      m.vertices.push_back(origin + s * u + t * v);
    }
  m.faces = surfaces::grid_faces(nx, ny);
  return m;
}

/// The single boundary loop, following the faces' orientation, from its lowest-numbered vertex.
std::vector<int32_t> boundary_loop(const TriMesh& mesh) {
  const std::map<EdgeKey, int> directed = directed_edges(mesh);
  std::map<int32_t, int32_t> next;
  for (const auto& [edge, count] : directed)
    if (!directed.count({edge.second, edge.first})) next[edge.first] = edge.second;
  std::vector<int32_t> loop = {next.begin()->first};
  while (next.at(loop.back()) != loop.front()) loop.push_back(next.at(loop.back()));
  EXPECT_EQ(loop.size(), next.size()) << "more than one boundary loop";
  return loop;
}

/// One level of cubic B-spline subdivision of a closed polygon: 1/8–3/4–1/8 at the old points, midpoints
/// between them.
std::vector<Vec3> bspline_subdivide(const std::vector<Vec3>& p) {
  const size_t n = p.size();
  std::vector<Vec3> q;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 &prev = p[(i + n - 1) % n], &next = p[(i + 1) % n];
    q.push_back(0.75 * p[i] + 0.125 * (prev + next));
    q.push_back(0.5 * (p[i] + next));
  }
  return q;
}

struct OmTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<OmTraits>;

/// Subdivides `mesh` level by level with ours and with OpenMesh's LoopT and compares the results.
///
/// Vertices are matched by numbering, not by position, so that the position check cannot match a vertex to
/// the wrong one that happens to be close: OpenMesh keeps the old vertices and appends one vertex per edge
/// in its own edge order (LoopT splits edges() in order, each split appending a vertex), so its vertex V + e
/// is the new vertex on its edge e; ours is V + (index of that edge in our numbering). Composing these per
/// level gives the correspondence at every level. Faces are compared too, as rotation-normalised triples.
void expect_matches_openmesh(const TriMesh& mesh, int levels) {
  OmMesh om;
  for (const Vec3& p : mesh.vertices) om.add_vertex(OmMesh::Point(p.x(), p.y(), p.z()));
  for (const Tri& t : mesh.faces)
    ASSERT_TRUE(
        om.add_face(OmMesh::VertexHandle(t[0]), OmMesh::VertexHandle(t[1]), OmMesh::VertexHandle(t[2]))
            .is_valid());
  OpenMesh::Subdivider::Uniform::LoopT<OmMesh> om_loop;
  om_loop.attach(om);

  TriMesh ours = mesh;
  std::vector<int32_t> ours_of_om(mesh.vertices.size());
  std::iota(ours_of_om.begin(), ours_of_om.end(), 0);
  for (int level = 1; level <= levels; ++level) {
    const std::map<EdgeKey, int32_t> numbering = edge_numbering(ours);
    const int32_t nv = static_cast<int32_t>(ours.vertices.size());
    ASSERT_EQ(om.n_edges(), numbering.size());
    ours_of_om.resize(nv + numbering.size());
    for (const auto& e : om.edges()) {
      const int32_t a = ours_of_om[e.v0().idx()], b = ours_of_om[e.v1().idx()];
      ours_of_om[nv + e.idx()] = nv + numbering.at(sorted_edge(a, b));
    }

    om_loop(1);
    ours = loop_subdivide(ours);
    ASSERT_EQ(om.n_vertices(), ours.vertices.size());
    ASSERT_EQ(om.n_faces(), ours.faces.size());

    double worst = 0;
    for (const auto& v : om.vertices()) {
      const OmMesh::Point& p = om.point(v);
      worst = std::max(worst, (Vec3(p[0], p[1], p[2]) - ours.vertices[ours_of_om[v.idx()]]).norm());
    }
    EXPECT_LT(worst, 1e-12) << "level " << level;

    const auto normalised = [](Tri t) {
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      return t;
    };
    std::set<Tri> om_faces, our_faces;
    for (const auto& f : om.faces()) {
      Tri t{};
      int k = 0;
      for (const auto& v : f.vertices()) t[k++] = ours_of_om[v.idx()];
      om_faces.insert(normalised(t));
    }
    for (const Tri& t : ours.faces) our_faces.insert(normalised(t));
    EXPECT_EQ(om_faces, our_faces) << "level " << level;
  }
  om_loop.detach();
}

}  // namespace

TEST(Loop, CountsAreVPlusEFourFTwoEPlusThreeFAndClosedEulerCharacteristicIsKept) {
  const std::vector<std::pair<const char*, TriMesh>> meshes = {
      {"octahedron", octahedron()},
      {"irregular cube", irregular_cube()},
      {"torus", torus(7, 5, 3, 1)},
      {"grid", tilted_grid(4, 3, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY())}};
  for (const auto& [name, mesh] : meshes) {
    const bool closed = std::string(name) != "grid";
    TriMesh m = mesh;
    for (int level = 1; level <= 3; ++level) {
      const int64_t v = m.vertices.size(), e = edge_numbering(m).size(), f = m.faces.size();
      m = loop_subdivide(m);
      const int64_t v1 = m.vertices.size(), e1 = edge_numbering(m).size(), f1 = m.faces.size();
      EXPECT_EQ(v1, v + e) << name << " level " << level;
      EXPECT_EQ(f1, 4 * f) << name << " level " << level;
      EXPECT_EQ(e1, 2 * e + 3 * f) << name << " level " << level;
      if (closed) EXPECT_EQ(v1 - e1 + f1, v - e + f) << name << " level " << level;
    }
  }
  EXPECT_EQ(loop_subdivide(octahedron(), 0).vertices, octahedron().vertices);
  EXPECT_THROW(loop_subdivide(octahedron(), -1), std::invalid_argument);
}

TEST(Loop, OrientationIsPreservedEveryEdgeTraversedOnceEachWay) {
  for (const TriMesh& mesh : {octahedron(), irregular_cube(), torus(6, 4, 4, 1)}) {
    ASSERT_GT(signed_volume(mesh), 0);
    const TriMesh m = loop_subdivide(mesh, 2);
    const std::map<EdgeKey, int> directed = directed_edges(m);
    for (const auto& [edge, count] : directed) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
    }
    EXPECT_GT(signed_volume(m), 0);
  }
}

TEST(Loop, NumberingKeepsOldVerticesThenEdgeVerticesInEdgeOrderAndSplitsFacesAsDocumented) {
  const TriMesh mesh = irregular_cube();
  const TriMesh m = loop_subdivide(mesh);
  const std::map<EdgeKey, int32_t> numbering = edge_numbering(mesh);
  const int32_t nv = static_cast<int32_t>(mesh.vertices.size());
  const auto mid = [&](int32_t a, int32_t b) { return nv + numbering.at(sorted_edge(a, b)); };
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto [a, b, c] = mesh.faces[f];
    EXPECT_EQ(m.faces[4 * f], (Tri{a, mid(a, b), mid(c, a)}));
    EXPECT_EQ(m.faces[4 * f + 1], (Tri{mid(a, b), b, mid(b, c)}));
    EXPECT_EQ(m.faces[4 * f + 2], (Tri{mid(c, a), mid(b, c), c}));
    EXPECT_EQ(m.faces[4 * f + 3], (Tri{mid(a, b), mid(b, c), mid(c, a)}));
  }
}

TEST(Loop, MatchesOpenMeshLoopTOnOctahedron) { expect_matches_openmesh(octahedron(), 3); }

TEST(Loop, MatchesOpenMeshLoopTOnIrregularCube) { expect_matches_openmesh(irregular_cube(), 3); }

TEST(Loop, MatchesOpenMeshLoopTOnTorusGrid) { expect_matches_openmesh(torus(9, 6, 3, 1.2), 3); }

TEST(Loop, MatchesOpenMeshLoopTOnOpenGrid) {
  expect_matches_openmesh(tilted_grid(5, 4, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()), 3);
}

TEST(Loop, PlanarGridStaysPlanarAndItsBoundaryFollowsCubicBSplineRules) {
  const Vec3 origin(0.3, -1.2, 2.0), u = Vec3(1, 2, 2).normalized(), v = Vec3(2, 1, -2).normalized();
  const Vec3 normal = u.cross(v);
  const TriMesh mesh = tilted_grid(6, 5, origin, u, v);
  std::vector<Vec3> polygon;
  for (int32_t i : boundary_loop(mesh)) polygon.push_back(mesh.vertices[i]);
  for (int level = 1; level <= 3; ++level) {
    const TriMesh m = loop_subdivide(mesh, level);
    for (const Vec3& p : m.vertices) EXPECT_NEAR(normal.dot(p - origin), 0, 1e-12);
    // Old vertices keep their indices, so both loops start at vertex 0, a grid corner.
    polygon = bspline_subdivide(polygon);
    const std::vector<int32_t> loop = boundary_loop(m);
    ASSERT_EQ(loop.size(), polygon.size());
    for (size_t i = 0; i < loop.size(); ++i)
      EXPECT_LT((m.vertices[loop[i]] - polygon[i]).norm(), 1e-12) << "level " << level << " point " << i;
  }
}

TEST(Loop, VertexWithMoreThanTwoBoundaryEdgesStaysFixed) {
  // Two triangles touching only at vertex 0 (a bow tie): vertex 0 has four boundary edges.
  TriMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  mesh.faces = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_EQ(loop_subdivide(mesh, 2).vertices[0], mesh.vertices[0]);
  EXPECT_EQ(loop_limit(mesh).vertices[0], mesh.vertices[0]);
  // Vertex 1 is an ordinary boundary vertex: 3/4 v + 1/8 (b0 + b1).
  EXPECT_LT((loop_subdivide(mesh).vertices[1] - Vec3(0.875, 0.125, 0)).norm(), 1e-15);
}

TEST(Loop, VerticesApproachTheirLimitPositionsAsLevelsIncrease) {
  // A sphere-like control mesh with valences 4 and 6.
  TriMesh sphere = loop_subdivide(octahedron(), 2);
  for (Vec3& p : sphere.vertices) p.normalize();
  const std::vector<Vec3> limit = loop_limit(sphere).vertices;
  double previous = HUGE_VAL;
  for (int level = 0; level <= 5; ++level) {
    const TriMesh m = loop_subdivide(sphere, level);
    double worst = 0;
    for (size_t i = 0; i < sphere.vertices.size(); ++i)
      worst = std::max(worst, (m.vertices[i] - limit[i]).norm());
    std::cout << "level " << level << ": largest distance to the limit " << worst << "\n";
    EXPECT_LT(worst, 0.5 * previous) << "level " << level;
    previous = worst;
    // The limit surface does not change under subdivision, nor do the limit points of old vertices.
    const std::vector<Vec3> limit_now = loop_limit(m).vertices;
    for (size_t i = 0; i < sphere.vertices.size(); ++i) EXPECT_LT((limit_now[i] - limit[i]).norm(), 1e-12);
  }
  EXPECT_LT(previous, 1e-3);
}

TEST(Loop, OnePassToTheLimitIsTheLimitOfTheNextLevel) {
  // Closed meshes with valences 3 to 6, an open grid (boundary rules), a bow tie (a fixed vertex), each with
  // a vertex property, at three scales.
  TriMesh bow_tie;
  bow_tie.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  bow_tie.faces = {{0, 1, 2}, {0, 3, 4}};
  const TriMesh grid = tilted_grid(5, 4, Vec3(0.3, -0.2, 1), Vec3(1, 0, 0), Vec3(0, 0.6, 0.8));
  for (double scale : {1e-3, 1.0, 1e3})
    for (TriMesh mesh : {octahedron(), irregular_cube(), torus(6, 4, 4, 1), grid, bow_tie}) {
      std::vector<float> height;
      for (Vec3& p : mesh.vertices) p *= scale, height.push_back(static_cast<float>(p.z() / scale));
      mesh.vertex_properties.push_back({"height", height});
      const TriMesh expected = loop_limit(loop_subdivide(mesh));
      const TriMesh one_pass = loop_subdivide_to_limit(mesh);
      EXPECT_EQ(one_pass.faces, expected.faces);
      ASSERT_EQ(one_pass.vertices.size(), expected.vertices.size());
      for (std::size_t v = 0; v < expected.vertices.size(); ++v) {
        EXPECT_LT((one_pass.vertices[v] - expected.vertices[v]).norm(), 1e-14 * scale) << "vertex " << v;
        EXPECT_NEAR(one_pass.vertex_properties[0].values[v], expected.vertex_properties[0].values[v], 1e-6);
      }
    }
}

TEST(Loop, TubesShrinkToTheKnownMeanRadius) {
  // A closed ring of square or octagonal sections (circumradius 1, sections 1.5 apart, every quad cut along
  // the same diagonal as the pipeline does) with so large a major radius that its curvature is negligible: a
  // long tube without ends. With 1000 sections instead of 240 the means change by less than 3e-5.
  const int sections = 240;
  const double major = 0.75 / std::sin(M_PI / sections);
  const auto mean_distance_from_axis = [&](const std::vector<Vec3>& points) {
    double sum = 0;
    for (const Vec3& p : points) sum += std::hypot(std::hypot(p.x(), p.y()) - major, p.z());
    return sum / static_cast<double>(points.size());
  };
  const double square[] = {1.0, 0.729, 0.674, 0.661};
  TriMesh m = torus(sections, 4, major, 1);
  for (int level = 1; level <= 3; ++level) {
    m = loop_subdivide(m);
    const double r = mean_distance_from_axis(m.vertices);
    std::cout << "square, level " << level << ": mean distance from the axis " << r << "\n";
    EXPECT_NEAR(r, square[level], 0.01) << "level " << level;
  }
  // The limit surfaces, sampled at the limit points of the level-3 vertices (those of the control vertices
  // alone are the corners' only, which lie farther out than the mean): pipeline.cpp's radius scales.
  const double limit = mean_distance_from_axis(loop_limit(m).vertices);
  std::cout << "square, limit: mean distance from the axis " << limit << "\n";
  EXPECT_NEAR(limit, 1 / subdivision_radius_scale(4), 0.001);
  const double octagon = mean_distance_from_axis(loop_limit(loop_subdivide(torus(sections, 8, major, 1), 3)).vertices);
  std::cout << "octagon, limit: mean distance from the axis " << octagon << "\n";
  EXPECT_NEAR(octagon, 1 / subdivision_radius_scale(8), 0.001);
}

TEST(Loop, VertexPropertyEqualToXStaysEqualToX) {
  for (TriMesh mesh :
       {irregular_cube(), tilted_grid(4, 4, Vec3(0.5, 0, 0), Vec3(1, 1, 0).normalized(), Vec3::UnitZ())}) {
    VertexProperty x{"x", {}};
    for (const Vec3& p : mesh.vertices) x.values.push_back(static_cast<float>(p.x()));
    mesh.vertex_properties = {x};
    const TriMesh m = loop_subdivide(mesh, 3);
    ASSERT_EQ(m.vertex_properties.size(), 1u);
    EXPECT_EQ(m.vertex_properties[0].name, "x");
    ASSERT_EQ(m.vertex_properties[0].values.size(), m.vertices.size());
    for (size_t i = 0; i < m.vertices.size(); ++i)
      EXPECT_NEAR(m.vertex_properties[0].values[i], m.vertices[i].x(), 1e-6);
  }
}

TEST(Loop, NonManifoldOrInconsistentEdgeThrowsNamingTheEdge) {
  TriMesh fin;  // three triangles on edge (0, 1)
  fin.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  fin.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  TriMesh flipped;  // two triangles running the same way along edge (0, 1)
  flipped.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  flipped.faces = {{0, 1, 2}, {0, 1, 3}};
  for (const TriMesh& mesh : {fin, flipped}) {
    try {
      loop_subdivide(mesh);
      ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("edge (0, 1)"), std::string::npos) << e.what();
    }
    EXPECT_THROW(loop_limit(mesh), std::invalid_argument);
  }
}

TEST(Loop, PrintsTheTimeOfOneLevelOnAMillionTriangleClosedMesh) {
  const TriMesh mesh = torus(1000, 500, 10, 3);
  ASSERT_EQ(mesh.faces.size(), 1000000u);
  const auto start = std::chrono::steady_clock::now();
  const TriMesh m = loop_subdivide(mesh);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "one Loop level, 1,000,000 → " << m.faces.size() << " triangles: " << seconds << " s\n";
  EXPECT_EQ(m.faces.size(), 4000000u);
  EXPECT_EQ(m.vertices.size(), 2000000u);
}
