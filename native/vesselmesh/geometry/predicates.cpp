#include "vesselmesh/geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesselmesh {

namespace {

// --- expansion arithmetic -------------------------------------------------------------------------
// A value held exactly as the sum of up to N doubles that do not overlap bit-wise, in increasing
// magnitude, zeros dropped; its sign is the sign of the largest component.

template <int N>
struct Expansion {
  std::array<double, N> c;
  int n = 0;
  int sign() const { return n == 0 ? 0 : (c[n - 1] > 0 ? 1 : -1); }
};

// s + e == a + b exactly, s the rounded sum.
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double b_virtual = s - a;
  e = (a - (s - b_virtual)) + (b - b_virtual);
}

// p + e == a · b exactly: fma rounds once, so it returns the rounding error of the product.
inline void two_product(double a, double b, double& p, double& e) {
  p = a * b;
  e = std::fma(a, b, -p);
}

Expansion<2> difference(double a, double b) {
  Expansion<2> x;
  double s, e;
  two_sum(a, -b, s, e);
  if (e != 0) x.c[x.n++] = e;
  if (s != 0) x.c[x.n++] = s;
  return x;
}

// x += b, in place (the grow step: carry b up through the components, keeping the errors).
template <int N>
void grow(Expansion<N>& x, double b) {
  double q = b;
  int k = 0;
  for (int i = 0; i < x.n; ++i) {
    double s, e;
    two_sum(q, x.c[i], s, e);
    q = s;
    if (e != 0) x.c[k++] = e;
  }
  if (q != 0) x.c[k++] = q;
  x.n = k;
}

template <int M, int N>
Expansion<M + N> sum(const Expansion<M>& x, const Expansion<N>& y) {
  Expansion<M + N> h;
  std::copy(x.c.begin(), x.c.begin() + x.n, h.c.begin());
  h.n = x.n;
  for (int j = 0; j < y.n; ++j) grow(h, y.c[j]);
  return h;
}

template <int N>
Expansion<N> negated(Expansion<N> x) {
  for (int i = 0; i < x.n; ++i) x.c[i] = -x.c[i];
  return x;
}

// x · b (the scale step: each component's product and its error, carried upwards).
template <int N>
Expansion<2 * N> scaled(const Expansion<N>& x, double b) {
  Expansion<2 * N> h;
  if (x.n == 0 || b == 0) return h;
  double q, e;
  two_product(x.c[0], b, q, e);
  if (e != 0) h.c[h.n++] = e;
  for (int i = 1; i < x.n; ++i) {
    double p, pe, s, t;
    two_product(x.c[i], b, p, pe);
    two_sum(q, pe, s, t);
    if (t != 0) h.c[h.n++] = t;
    two_sum(p, s, q, t);
    if (t != 0) h.c[h.n++] = t;
  }
  if (q != 0) h.c[h.n++] = q;
  return h;
}

template <int M, int N>
Expansion<2 * M * N> product(const Expansion<M>& x, const Expansion<N>& y) {
  Expansion<2 * M * N> h;
  for (int j = 0; j < y.n; ++j) {
    const Expansion<2 * M> part = scaled(x, y.c[j]);
    for (int i = 0; i < part.n; ++i) grow(h, part.c[i]);
  }
  return h;
}

// xa · yb − xb · ya for two-component differences.
Expansion<16> cross_term(const Expansion<2>& xa, const Expansion<2>& yb, const Expansion<2>& xb,
                         const Expansion<2>& ya) {
  return sum(product(xa, yb), negated(product(xb, ya)));
}

int sign_of(double x) { return (x > 0) - (x < 0); }

// Error bounds of the double evaluations below (relative to the permanent: the same expression with
// absolute values), for round-to-nearest doubles.
constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;
constexpr double kOrient2dBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEps) * kEps;

int orient2d_exact(const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross_term(difference(b.x(), a.x()), difference(c.y(), a.y()), difference(b.y(), a.y()),
                    difference(c.x(), a.x()))
      .sign();
}

int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  std::array<Expansion<2>, 3> u, v, w;
  for (int i = 0; i < 3; ++i) {
    u[i] = difference(b[i], a[i]);
    v[i] = difference(c[i], a[i]);
    w[i] = difference(d[i], a[i]);
  }
  // ((b − a) × (c − a)) · (d − a) = u · (v × w) by the cyclic symmetry of the triple product.
  const Expansion<16> vw_x = cross_term(v[1], w[2], v[2], w[1]);
  const Expansion<16> vw_y = cross_term(v[2], w[0], v[0], w[2]);
  const Expansion<16> vw_z = cross_term(v[0], w[1], v[1], w[0]);
  return sum(sum(product(u[0], vw_x), product(u[1], vw_y)), product(u[2], vw_z)).sign();
}

// The plane a triangle projects onto without loss when its coordinate `axis` is dropped.
Vec2 drop(const Vec3& p, int axis) {
  return axis == 0 ? Vec2(p.y(), p.z()) : axis == 1 ? Vec2(p.z(), p.x()) : Vec2(p.x(), p.y());
}

// Coordinate axes to drop, best-conditioned first (the one along which the normal is largest). The
// normal is only a hint; every decision is made by exact orient2d signs.
std::array<int, 3> projection_order(const Triangle& t) {
  const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
  std::array<int, 3> axes = {0, 1, 2};
  std::sort(axes.begin(), axes.end(), [&](int i, int j) { return std::abs(n[i]) > std::abs(n[j]); });
  return axes;
}

using Triangle2 = std::array<Vec2, 3>;

// True when an edge line of counter-clockwise `p` has all of `q` on its outer side or on it.
bool edge_separates(const Triangle2& p, const Triangle2& q) {
  for (int i = 0; i < 3; ++i) {
    const Vec2& s = p[i];
    const Vec2& t = p[(i + 1) % 3];
    if (orient2d(s, t, q[0]) <= 0 && orient2d(s, t, q[1]) <= 0 && orient2d(s, t, q[2]) <= 0) return true;
  }
  return false;
}

// Two coplanar triangles: projected onto a coordinate plane where `a` keeps its area (an affine
// bijection of their common plane), their open interiors are disjoint exactly when an edge line of
// one of them separates the two.
bool coplanar_interiors_meet(const Triangle& a, const Triangle& b) {
  for (int axis : projection_order(a)) {
    Triangle2 p = {drop(a[0], axis), drop(a[1], axis), drop(a[2], axis)};
    const int orientation = orient2d(p[0], p[1], p[2]);
    if (orientation == 0) continue;
    Triangle2 q = {drop(b[0], axis), drop(b[1], axis), drop(b[2], axis)};
    if (orientation < 0) std::swap(p[1], p[2]);
    if (orient2d(q[0], q[1], q[2]) < 0) std::swap(q[1], q[2]);
    return !edge_separates(p, q) && !edge_separates(q, p);
  }
  return false;  // `a` is degenerate
}

// Signs of the corners of `t` relative to the plane of `plane`. A corner that is one of the plane's
// own corners (a shared vertex) is on it without asking.
std::array<int, 3> sides(const Triangle& plane, const Triangle& t) {
  std::array<int, 3> s;
  for (int i = 0; i < 3; ++i) {
    const bool shared = t[i] == plane[0] || t[i] == plane[1] || t[i] == plane[2];
    s[i] = shared ? 0 : orient3d(plane[0], plane[1], plane[2], t[i]);
  }
  return s;
}

bool straddles(const std::array<int, 3>& s) {
  return std::count(s.begin(), s.end(), 1) > 0 && std::count(s.begin(), s.end(), -1) > 0;
}

// The corner alone on its side of the other plane (the others on the opposite side or on the plane).
int lone_corner(const std::array<int, 3>& s) {
  const int positive = static_cast<int>(std::count(s.begin(), s.end(), 1));
  const int wanted = positive == 1 ? 1 : -1;
  return static_cast<int>(std::find(s.begin(), s.end(), wanted) - s.begin());
}

}  // namespace

int orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (b.x() - a.x()) * (c.y() - a.y());
  const double right = (b.y() - a.y()) * (c.x() - a.x());
  const double det = left - right;
  const double permanent = std::abs(left) + std::abs(right);
  const double bound = kOrient2dBound * permanent;
  if (det > bound || -det > bound) return sign_of(det);
  if (permanent == 0) return 0;  // both products vanished, so both exact terms are zero
  return orient2d_exact(a, b, c);
}

int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double vywz = v.y() * w.z(), vzwy = v.z() * w.y();
  const double vzwx = v.z() * w.x(), vxwz = v.x() * w.z();
  const double vxwy = v.x() * w.y(), vywx = v.y() * w.x();
  const double det = u.x() * (vywz - vzwy) + u.y() * (vzwx - vxwz) + u.z() * (vxwy - vywx);
  const double permanent = (std::abs(vywz) + std::abs(vzwy)) * std::abs(u.x()) +
                           (std::abs(vzwx) + std::abs(vxwz)) * std::abs(u.y()) +
                           (std::abs(vxwy) + std::abs(vywx)) * std::abs(u.z());
  const double bound = kOrient3dBound * permanent;
  if (det > bound || -det > bound) return sign_of(det);
  if (permanent == 0) return 0;  // every product vanished, so every term of the exact sum is zero
  return orient3d_exact(a, b, c, d);
}

bool is_degenerate(const Triangle& t) {
  for (int axis : projection_order(t))
    if (orient2d(drop(t[0], axis), drop(t[1], axis), drop(t[2], axis)) != 0) return false;
  return true;
}

bool triangle_interiors_meet(const Triangle& a_in, const Triangle& b_in) {
  Triangle a = a_in, b = b_in;
  const std::array<int, 3> sb = sides(a, b);
  if (sb == std::array<int, 3>{0, 0, 0}) return coplanar_interiors_meet(a, b);
  // A triangle that keeps to one side of the other's plane meets that plane only along its boundary.
  if (!straddles(sb)) return false;
  const std::array<int, 3> sa = sides(b, a);
  if (!straddles(sa)) return false;
  // Each triangle now cuts the line where the planes meet in a segment whose inside lies inside the
  // triangle. Put the lone corners first, on the positive side of the other plane (swapping two
  // corners of one triangle flips the other triangle's signs only); then the segments overlap in
  // more than a point exactly when the two orientations below say so.
  const int ka = lone_corner(sa), kb = lone_corner(sb);
  std::rotate(a.begin(), a.begin() + ka, a.end());
  std::rotate(b.begin(), b.begin() + kb, b.end());
  if (sa[ka] < 0) std::swap(b[1], b[2]);
  if (sb[kb] < 0) std::swap(a[1], a[2]);
  return orient3d(a[0], a[1], b[0], b[1]) < 0 && orient3d(a[0], a[2], b[0], b[2]) > 0;
}

}  // namespace vesselmesh
