#pragma once
// The convex hull of the square corners around one joint, as outward triangles. Incremental, with an
// exact orientation test, so that the result is always a closed, consistently oriented surface.

#include <vector>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// Triangles (indices into `points`) facing outwards; empty when all points are coplanar. Exactly
/// coplanar points on the hull may come back as flat neighbouring triangles.
std::vector<Tri> convex_hull(const std::vector<Vec3>& points);

}  // namespace vesselmesh
