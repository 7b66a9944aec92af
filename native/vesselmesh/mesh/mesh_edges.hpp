#pragma once
// The edges of a triangle mesh, for hosts that store them (Blender keeps an edge list and, per face
// corner, the edge to the next corner; handing both over spares it a hash of every edge).

#include <array>
#include <cstdint>
#include <vector>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

struct MeshEdges {
  std::vector<std::array<int32_t, 2>> edges;  ///< E undirected edges (lower vertex first), sorted
  std::vector<Tri> corner_edges;              ///< per face f and corner k: the edge from corner k to k+1
  std::vector<int32_t> corners;  ///< 3F corners (3·f + k, whose edge runs from corner k to k+1), by edge
  std::vector<int64_t> first;    ///< E + 1: edge e's corners are corners[first[e], first[e + 1])
};

/// Every distinct vertex pair that some face joins, in O(F) time. faces: (F,3) indices below
/// vertex_count; non-manifold and boundary edges are listed like the others.
MeshEdges mesh_edges(const std::vector<Tri>& faces, int32_t vertex_count);

}  // namespace vesselmesh
