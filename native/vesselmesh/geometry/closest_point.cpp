#include "vesselmesh/geometry/closest_point.hpp"

#include <algorithm>
#include <utility>

namespace vesselmesh {

std::pair<double, double> closest_parameters(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  auto unit = [](double x) { return std::clamp(x, 0.0, 1.0); };
  if (a == 0) return {0.0, e == 0 ? 0.0 : unit(f / e)};
  const double c = d1.dot(r);
  if (e == 0) return {unit(-c / a), 0.0};
  const double b = d1.dot(d2), denominator = a * e - b * b;
  double s = denominator > 0 ? unit((b * f - c * e) / denominator) : 0.0;  // parallel: any s will do
  const double t = (b * s + f) / e;
  if (t < 0) return {unit(-c / a), 0.0};
  if (t > 1) return {unit((b - c) / a), 1.0};
  return {s, t};
}

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Voronoi regions of the corners, then of the edges, else the face (barycentric coordinates).
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double sum = va + vb + vc;
  if (!(sum > 0)) {
    // No area: the nearest of the three edges' nearest points.
    Vec3 best = a;
    for (const auto& [s, t] : {std::pair<Vec3, Vec3>{a, b}, {b, c}, {c, a}}) {
      const double length2 = (t - s).squaredNorm();
      const double u = length2 > 0 ? std::clamp((p - s).dot(t - s) / length2, 0.0, 1.0) : 0.0;
      const Vec3 q = s + u * (t - s);
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    }
    return best;
  }
  return a + (vb / sum) * ab + (vc / sum) * ac;
}

}  // namespace vesselmesh
