#pragma once
// Who is next to whom in a triangle mesh, in compressed rows: the faces round each vertex and each
// vertex's 1-ring, for the stages that walk the surface (curvature, fit).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// Compressed rows: row i holds items[offsets[i]] .. items[offsets[i + 1] − 1].
struct Csr {
  std::vector<size_t> offsets;
  std::vector<int32_t> items;
  const int32_t* begin(int32_t i) const { return items.data() + offsets[i]; }
  const int32_t* end(int32_t i) const { return items.data() + offsets[i + 1]; }
};

/// The faces around each vertex (a counting sort of the 3F corners). Throws std::invalid_argument for a
/// face that refers to a vertex the mesh does not have.
Csr vertex_faces(const TriMesh& mesh);

/// The 1-ring of each vertex, sorted: the other corners of its faces.
Csr vertex_neighbours(const TriMesh& mesh, const Csr& faces);

}  // namespace vesselmesh
