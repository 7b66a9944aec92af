#pragma once
// Which triangles of a surface cross each other.

#include <array>
#include <cstdint>
#include <vector>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// Every pair of faces (f < g, in ascending order) whose relative interiors meet (triangle_interiors_meet,
/// exact): the pairs a bounding-volume hierarchy of their boxes proposes, tested on every core. Faces that
/// repeat a vertex or have no plane are left out. With `among` (a flag per face), only the pairs with a
/// flagged face: the cost then grows with the flagged faces. The faces' indices must be valid.
std::vector<std::array<int32_t, 2>> intersecting_face_pairs(const TriMesh& mesh,
                                                            const std::vector<char>& among = {});

}  // namespace vesselmesh
