#include "vesselmesh/frames/frames.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace vesselmesh {

Vec3 Section::corner(int k, double scale) const {
  const Vec3 side = normal.cross(up);
  const Vec3 dirs[4] = {up, side, -up, -side};
  return center + scale * radius * dirs[k & 3];
}

Vec3 any_perpendicular(const Vec3& n) {
  int axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  return n.cross(Vec3::Unit(axis)).normalized();
}

Vec3 rotate(const Vec3& v, const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis) * v; }

double signed_angle(const Vec3& a, const Vec3& b, const Vec3& axis) {
  const Vec3 pa = a - a.dot(axis) * axis, pb = b - b.dot(axis) * axis;
  return std::atan2(axis.dot(pa.cross(pb)), pa.dot(pb));
}

Vec3 transport_up(const Section& from, const Vec3& center, const Vec3& normal) {
  const Vec3 v1 = center - from.center;
  const double c1 = v1.squaredNorm();
  Vec3 up = from.up, tangent = from.normal;
  if (c1 > 0) {
    up -= (2.0 / c1) * v1.dot(up) * v1;
    tangent -= (2.0 / c1) * v1.dot(tangent) * v1;
  }
  const Vec3 v2 = normal - tangent;
  const double c2 = v2.squaredNorm();
  if (c2 > 1e-20) up -= (2.0 / c2) * v2.dot(up) * v2;
  up -= up.dot(normal) * normal;
  // Only when the section turns by nearly 180° can the projection vanish; any perpendicular will do.
  return up.norm() > 1e-12 ? up.normalized() : any_perpendicular(normal);
}

int transport_frames(std::vector<Section>& sections, const Vec3* target_up) {
  for (std::size_t i = 1; i < sections.size(); ++i)
    sections[i].up = transport_up(sections[i - 1], sections[i].center, sections[i].normal);
  if (!target_up) return 0;
  Section& last = sections.back();
  const double psi = signed_angle(last.up, *target_up, last.normal);
  const double quarter = M_PI / 2;
  // k quarter turns plus a residual δ in (−45°, 45°].
  int k = static_cast<int>(std::ceil(psi / quarter - 0.5));
  const double delta = psi - k * quarter;
  double total = 0;
  std::vector<double> arc(sections.size(), 0.0);
  for (std::size_t i = 1; i < sections.size(); ++i)
    arc[i] = total += (sections[i].center - sections[i - 1].center).norm();
  for (std::size_t i = 1; i < sections.size(); ++i)
    sections[i].up = rotate(sections[i].up, sections[i].normal, total > 0 ? delta * arc[i] / total : delta);
  // Now target_up is our up turned by k quarter turns, so our corner j is the target's corner j − k.
  return ((k % 4) + 4) % 4;
}

}  // namespace vesselmesh
