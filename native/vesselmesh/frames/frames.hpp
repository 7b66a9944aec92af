#pragma once
// Section frames: each cross-section has a centre, a unit normal (the local tangent) and a unit
// up-vector perpendicular to it; its square's corners sit at ±up and ±(normal × up). Up-vectors are
// carried from section to section by the rotation-minimising frame, so tubes do not twist.

#include <vector>

#include "vesselmesh/centerline.hpp"

namespace vesselmesh {

struct Section {
  Vec3 center = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  ///< unit, along the direction of travel
  Vec3 up = Vec3::UnitX();      ///< unit, perpendicular to normal
  double radius = 0;

  /// Corner k (0..3) of the square at `scale` × radius: counter-clockwise about the normal, corner 0 at up.
  Vec3 corner(int k, double scale) const;
};

/// A unit vector perpendicular to unit `n`: `n` crossed with the world axis least aligned with it.
Vec3 any_perpendicular(const Vec3& n);

/// `v` rotated by `angle` (radians) about the unit `axis`.
Vec3 rotate(const Vec3& v, const Vec3& axis, double angle);

/// Signed angle from `a` to `b` about the unit `axis` (both taken in the plane perpendicular to it).
double signed_angle(const Vec3& a, const Vec3& b, const Vec3& axis);

/// Carries `from.up` to a section at `center` with `normal` by the double-reflection rotation-
/// minimising frame (Wang, Jüttler, Zheng, Liu 2008): fourth-order accurate, no twist.
Vec3 transport_up(const Section& from, const Vec3& center, const Vec3& normal);

/// Up-vectors for sections[1..]: transported from sections[0].up. When `target_up` is given, the last
/// section must end up on it modulo a quarter turn (a square looks the same every 90°): the residual
/// twist (at most 45°) is spread along the sections in proportion to arc length. Returns k in 0..3 such
/// that the last section's corner j lies on corner (j − k) mod 4 of a section with up = *target_up.
int transport_frames(std::vector<Section>& sections, const Vec3* target_up);

}  // namespace vesselmesh
