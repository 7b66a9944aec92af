#pragma once
// Closest points, for distances between surfaces.

#include "vesselmesh/centerline.hpp"

namespace vesselmesh {

/// The point of triangle (a, b, c) nearest to p (its interior, an edge or a corner; Ericson, Real-Time
/// Collision Detection §5.1.5). A degenerate triangle gives the nearest point of its edges.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace vesselmesh
