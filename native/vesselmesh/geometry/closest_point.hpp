#pragma once
// Closest points, for distances between surfaces.

#include <utility>

#include "vesselmesh/centerline.hpp"

namespace vesselmesh {

/// Parameters in [0, 1] of the closest points of segments p0 → p1 and q0 → q1 (Ericson §5.1.9; for
/// parallel segments, one such pair).
std::pair<double, double> closest_parameters(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// The point of triangle (a, b, c) nearest to p (its interior, an edge or a corner; Ericson, Real-Time
/// Collision Detection §5.1.5). A degenerate triangle gives the nearest point of its edges.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace vesselmesh
