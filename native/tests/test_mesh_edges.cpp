#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "surfaces.hpp"
#include "vesselmesh/mesh/mesh_edges.hpp"

namespace vesselmesh {
namespace {

using surfaces::grid_faces;
using surfaces::torus;
using Pair = std::pair<int32_t, int32_t>;

Pair undirected(int32_t a, int32_t b) { return {std::min(a, b), std::max(a, b)}; }

/// Every property the host and the topology check rely on: each corner's edge joins that corner and the
/// next; every listed edge is some face's, lower vertex first, sorted and listed once; each edge's corners
/// are grouped under it.
void expect_edges_of(const std::vector<Tri>& faces, int32_t vertex_count) {
  const MeshEdges e = mesh_edges(faces, vertex_count);
  ASSERT_EQ(e.corner_edges.size(), faces.size());
  std::set<Pair> joined;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int32_t edge = e.corner_edges[f][k];
      ASSERT_GE(edge, 0);
      ASSERT_LT(edge, static_cast<int32_t>(e.edges.size()));
      EXPECT_EQ(Pair(e.edges[edge][0], e.edges[edge][1]), undirected(faces[f][k], faces[f][(k + 1) % 3]));
      joined.insert(undirected(faces[f][k], faces[f][(k + 1) % 3]));
    }
  std::vector<Pair> listed;
  for (const auto& edge : e.edges) listed.emplace_back(edge[0], edge[1]);
  EXPECT_EQ(listed, std::vector<Pair>(joined.begin(), joined.end()));  // sorted, distinct, nothing extra
  // Each edge's grouped corners are exactly the corners whose edge it is, every corner once.
  ASSERT_EQ(e.first.size(), e.edges.size() + 1);
  ASSERT_EQ(e.corners.size(), 3 * faces.size());
  EXPECT_EQ(e.first.front(), 0);
  EXPECT_EQ(e.first.back(), static_cast<int64_t>(3 * faces.size()));
  std::vector<int32_t> seen(3 * faces.size(), 0);
  for (std::size_t edge = 0; edge < e.edges.size(); ++edge) {
    ASSERT_LT(e.first[edge], e.first[edge + 1]);
    for (int64_t i = e.first[edge]; i < e.first[edge + 1]; ++i) {
      const int32_t c = e.corners[i];
      EXPECT_EQ(e.corner_edges[c / 3][c % 3], static_cast<int32_t>(edge));
      ++seen[c];
    }
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int32_t n) { return n == 1; }));
}

TEST(MeshEdges, ATorusHasThreeEdgesPerTwoFacesEachJoiningItsCorners) {
  const TriMesh t = torus(24, 12, 3.0, 1.0);
  expect_edges_of(t.faces, static_cast<int32_t>(t.vertices.size()));
  EXPECT_EQ(2 * mesh_edges(t.faces, static_cast<int32_t>(t.vertices.size())).edges.size(),
            3 * t.faces.size());
}

TEST(MeshEdges, BoundaryAndNonManifoldEdgesAreListedOnce) {
  // Three triangles on the edge 0-1 (a non-manifold fin), with boundary edges round them.
  const std::vector<Tri> fin = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  expect_edges_of(fin, 5);
  EXPECT_EQ(mesh_edges(fin, 5).edges.size(), 7u);
  expect_edges_of(grid_faces(7, 5), 8 * 6);
}

TEST(MeshEdges, UnusedVerticesAndNoFacesGiveNoEdges) {
  EXPECT_TRUE(mesh_edges({}, 4).edges.empty());
  expect_edges_of({{5, 7, 6}}, 10);
}

TEST(MeshEdges, AVertexIndexOutOfRangeIsRejectedNamingTheFace) {
  try {
    mesh_edges({{0, 1, 2}, {2, 1, 3}}, 3);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("face 1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(mesh_edges({{0, -1, 2}}, 3), std::invalid_argument);
}

}  // namespace
}  // namespace vesselmesh
