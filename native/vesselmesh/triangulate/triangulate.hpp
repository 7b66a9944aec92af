#pragma once
// Quads to triangles: every quad (a, b, c, d) is cut along the same diagonal, a–c. Tube quads are
// laid out alike, so a straight tube gets valence-6 vertices everywhere, which Loop subdivision treats
// as regular. Each vertex carries its tube's axis (TubeAxis) as vertex properties, which Loop
// subdivision carries along.

#include "vesselmesh/mesh/tri_mesh.hpp"
#include "vesselmesh/tile/base_mesh.hpp"

namespace vesselmesh {

TriMesh triangulate(const BaseMesh& base);

}  // namespace vesselmesh
