#pragma once
// Exact geometric predicates. Each sign is first computed in doubles with an error bound; only when
// the bound cannot vouch for it is the determinant evaluated exactly with expansion arithmetic (sums
// of non-overlapping doubles), so that touching and crossing are told apart without tolerance.
// Exact for all finite inputs whose products neither overflow nor underflow.

#include <Eigen/Core>
#include <array>

#include "vesselmesh/centerline.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

using Vec2 = Eigen::Vector2d;

/// Sign (+1, 0, −1) of (b − a) × (c − a): positive when a, b, c turn counter-clockwise.
int orient2d(const Vec2& a, const Vec2& b, const Vec2& c);

/// Sign (+1, 0, −1) of ((b − a) × (c − a)) · (d − a): positive when d lies on the side that the normal
/// of the counter-clockwise triangle a, b, c points to, zero when the four points are coplanar.
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

using Triangle = std::array<Vec3, 3>;

/// The corners of face `t` of a mesh with these vertices.
inline Triangle corners(const std::vector<Vec3>& vertices, const Tri& t) {
  return {vertices[t[0]], vertices[t[1]], vertices[t[2]]};
}

/// True when the three corners are collinear (or coincide): the triangle has no plane.
bool is_degenerate(const Triangle& t);

/// True when the relative interiors of two non-degenerate triangles meet: they cross, one passes
/// through the other, or they overlap in a common plane. Contact along edges or at vertices only
/// (touching, or sharing an edge or a vertex without folding over) is not an intersection. Decided
/// from orient3d signs (orient2d in the common plane), so the answer is exact.
bool triangle_interiors_meet(const Triangle& a, const Triangle& b);

}  // namespace vesselmesh
