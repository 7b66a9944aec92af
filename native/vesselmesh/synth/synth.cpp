// Bit-identical output everywhere: the geometry uses only +, -, *, / and sqrt (all correctly rounded
// by IEEE 754), sums of products are written out in a fixed order, and no multiply-add may be fused,
// whatever the compiler's default (set before any header, so that Eigen's inline code obeys it too).
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "vesselmesh/synth/synth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vesselmesh {

namespace {

constexpr double kRootRadius = 1.5;  // mm; no point is thicker
constexpr double kSpacing = 0.5;     // point spacing, in local radii
constexpr double kClearance = 1.5;   // tubes keep (r_a + r_b) * kClearance apart...
constexpr double kJunction = 3.0;    // ...unless a path shorter than (r_a + r_b) * kJunction joins them
constexpr int kTries = 8;            // directions tried per child before it is cut short
constexpr int kMinStub = 3;          // fewest points of a child cut short by a collision
constexpr int kChunk = 8;            // consecutive samples checked with one grid query
constexpr int kEndMargin = 4;        // anastomoses attach at least this many points from a branch end
constexpr double kLoopReach = 16.0;  // anastomosis ends at most this many radii apart
constexpr int kLoopTries = 4;        // partners tried per anastomosis start point
constexpr int kLoopPoints = 30;      // points per anastomosis that the tree leaves room for
constexpr int kBezierSteps = 64;     // resolution of an anastomosis' arc-length table

// Eigen may sum a dot product in an order that depends on the SIMD width, so reductions are spelled out.
double dot(const Vec3& a, const Vec3& b) { return a.x() * b.x() + a.y() * b.y() + a.z() * b.z(); }

Vec3 cross(const Vec3& a, const Vec3& b) {
  return Vec3(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x());
}

Vec3 unit(const Vec3& v) { return v / std::sqrt(dot(v, v)); }

double distance2(const Vec3& a, const Vec3& b) {
  const Vec3 d = a - b;
  return dot(d, d);
}

// Newton's iteration from a fixed start, for x in [1, 2]: std::cbrt may differ in the last bit between
// C libraries.
double cube_root(double x) {
  double y = 1.25;
  for (int i = 0; i < 8; ++i) y = (2.0 * y + x / (y * y)) / 3.0;
  return y;
}

/// Cosine of the angle between the parent (radius r0) and the child of radius r1 that minimises the
/// work of the bifurcation (Murray 1926); r2 is the other child.
double murray_cos(double r0, double r1, double r2) {
  const double a = r0 * r0, b = r1 * r1, c = r2 * r2;
  return (a * a + b * b - c * c) / (2.0 * a * b);
}

// std::uniform_real_distribution is implementation-defined, so the bits are mapped to doubles here.
class Random {
 public:
  explicit Random(uint64_t seed) : bits_(seed) {}

  double uniform(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(bits_() >> 11) * 0x1.0p-53);
  }

  /// A random unit vector perpendicular to the unit vector `d` (uniform azimuth, drawn without trigonometry).
  Vec3 perpendicular(const Vec3& d) {
    const Vec3 helper = std::abs(d.x()) < 0.5 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 e1 = unit(cross(d, helper));
    const Vec3 e2 = cross(d, e1);
    for (;;) {
      const double a = uniform(-1.0, 1.0), b = uniform(-1.0, 1.0), q = a * a + b * b;
      if (q > 1e-4 && q <= 1.0) return (a * e1 + b * e2) / std::sqrt(q);
    }
  }

 private:
  std::mt19937_64 bits_;
};

/// Uniform grids over the placed points, one per octave of radius: level l holds radii in
/// (R 2^-l-1, R 2^-l] (R the root radius) in cells of 6 R 2^-l. Radii span two orders of magnitude, so
/// one cell size would make thin vessels scan crowds of points or thick ones scan crowds of cells; per
/// level, a query for a point of similar radius touches about 8 cells. Cells live in one open-addressing
/// hash table; each holds an intrusive list of its points.
class Grid {
 public:
  Grid(const std::vector<Vec3>& points, const std::vector<double>& radius)
      : points_(points), radius_(radius), slots_(1024) {}

  void insert(int32_t p) {
    if (2 * (used_ + 1) > slots_.size()) rehash();
    const int level = level_of(radius_[p]);
    if (level >= static_cast<int>(level_size_.size())) level_size_.resize(level + 1, 0);
    ++level_size_[level];
    const double cell = cell_size(level);
    const Vec3& x = points_[p];
    const int32_t i = index(x.x(), cell), j = index(x.y(), cell), k = index(x.z(), cell);
    Slot& slot = slots_[probe(level, i, j, k)];
    if (slot.level < 0) {
      slot = {level, i, j, k, -1};
      ++used_;
    }
    if (next_.size() <= static_cast<std::size_t>(p)) next_.resize(p + 1, -1);
    next_[p] = slot.head;
    slot.head = p;
  }

  /// Calls visit(q) for every point q in the cells of each level that overlap the box [lo, hi] grown by
  /// reach(largest radius of the level); a negative reach skips the level.
  template <class Reach, class Visit>
  void visit_box(const Vec3& lo, const Vec3& hi, Reach reach, Visit visit) const {
    for (int level = 0; level < static_cast<int>(level_size_.size()); ++level) {
      if (level_size_[level] == 0) continue;
      const double rho = reach(std::ldexp(kRootRadius, -level));
      if (rho < 0.0) continue;
      const double cell = cell_size(level);
      const int32_t i0 = index(lo.x() - rho, cell), i1 = index(hi.x() + rho, cell);
      const int32_t j0 = index(lo.y() - rho, cell), j1 = index(hi.y() + rho, cell);
      const int32_t k0 = index(lo.z() - rho, cell), k1 = index(hi.z() + rho, cell);
      for (int32_t i = i0; i <= i1; ++i)
        for (int32_t j = j0; j <= j1; ++j)
          for (int32_t k = k0; k <= k1; ++k)
            for (int32_t q = slots_[probe(level, i, j, k)].head; q >= 0; q = next_[q]) visit(q);
    }
  }

 private:
  struct Slot {
    int32_t level = -1;  // -1: empty
    int32_t i = 0, j = 0, k = 0;
    int32_t head = -1;  // the cell's latest point
  };

  static int level_of(double r) {
    int exponent = 0;
    std::frexp(kRootRadius / r, &exponent);
    return exponent - 1;
  }
  static double cell_size(int level) { return 6.0 * std::ldexp(kRootRadius, -level); }
  static int32_t index(double x, double cell) { return static_cast<int32_t>(std::floor(x / cell)); }

  /// The slot of the cell, or the empty slot where it would go.
  std::size_t probe(int level, int32_t i, int32_t j, int32_t k) const {
    uint64_t h = static_cast<uint32_t>(i) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<uint32_t>(j) * 0xC2B2AE3D27D4EB4Full;
    h ^= static_cast<uint32_t>(k) * 0x165667B19E3779F9ull;
    h ^= static_cast<uint64_t>(level) * 0x27D4EB2F165667C5ull;
    h ^= h >> 29;
    const std::size_t mask = slots_.size() - 1;
    std::size_t s = h & mask;
    while (slots_[s].level >= 0 &&
           !(slots_[s].level == level && slots_[s].i == i && slots_[s].j == j && slots_[s].k == k))
      s = (s + 1) & mask;
    return s;
  }

  void rehash() {
    std::vector<Slot> old(2 * slots_.size());
    old.swap(slots_);
    for (const Slot& slot : old)
      if (slot.level >= 0) slots_[probe(slot.level, slot.i, slot.j, slot.k)] = slot;
  }

  const std::vector<Vec3>& points_;
  const std::vector<double>& radius_;
  std::vector<Slot> slots_;  // size a power of two, at most half full
  std::size_t used_ = 0;
  std::vector<int64_t> level_size_;
  std::vector<int32_t> next_;  // per point: the previous point of its cell, or -1
};

/// One sample of a branch being traced; `s` is the arc length from the point the branch leaves.
struct Sample {
  Vec3 x;
  double r, s;
};

/// A branch before it is placed.
struct Shape {
  Vec3 start = Vec3::Zero();    // the point it leaves
  Vec3 dir = Vec3::UnitZ();     // its first direction
  Vec3 normal = Vec3::UnitX();  // its first curvature direction
  double r = 0.0;               // first radius
  double length = 0.0;          // arc length
  double bend = 0.0;            // bend radius, in local radii
  double twist = 0.0;           // turn of the curvature direction about the tangent per point (radians)
  double taper = 0.0;           // about this fraction of the radius is lost along the length
};

/// A branch of the tree: points first .. first + count - 1, leaving the last point of `parent`.
struct Branch {
  int32_t parent, depth, first, count;
};

/// A child chosen among several tries: `count` leading samples fit (0: none does), `full` when that is
/// the whole length.
struct Choice {
  Shape shape;
  Vec3 side = Vec3::UnitX();  // the azimuth it leaves towards
  int64_t count = 0;
  bool full = false;
};

/// The points near whose junctions a traced path may come close to other tubes: it leaves `from` and,
/// when `to` >= 0, arrives at `to` after arc length `length`.
struct Ends {
  int32_t from, to;
  double length;
};

/// A bifurcation waiting to grow: the end of tree branch `branch`. Thicker ends grow first; among
/// equals, earlier ones.
struct Pending {
  double radius;
  int64_t order;
  int32_t branch;
  bool operator<(const Pending& o) const {
    return radius < o.radius || (radius == o.radius && order > o.order);
  }
};

/// The growth state: the network so far, the grid over its points and the tree's branch structure.
class Network {
 public:
  explicit Network(uint64_t seed) : random_(seed), grid_(out_.points, out_.radius) {}

  /// The root trunk at the origin, heading along +z, of at most `target` points.
  void plant(int64_t target) {
    branches_.push_back({-1, 0, 0, 1});
    place(Vec3::Zero(), kRootRadius, 0, 0.0, -1);
    const Vec3 up = Vec3::UnitZ();
    const Shape trunk = random_shape(Vec3::Zero(), up, kRootRadius, random_.uniform(20.0, 30.0));
    trace(trunk, target - 1, samples_);
    append(0, 0, samples_);
    if (samples_.back().s >= trunk.length) pending_.push({out_.radius.back(), order_++, 0});
  }

  /// Grows the tree, thickest bifurcations first (breadth-first across vessel sizes, which keeps the radii
  /// of the growing front within a factor of about two), until the network has `target` points.
  void grow(int64_t target) {
    while (!pending_.empty() && size() + 2 <= target) {
      const int32_t branch = pending_.top().branch;
      pending_.pop();
      split(branch, target);
    }
  }

  /// `wanted` anastomoses, each between interior points of two branches of similar radius that are near
  /// in space but far apart in the tree. Thinnest branches are tried first: they are the most numerous.
  void add_loops(int wanted) {
    blocked_.assign(out_.points.size(), 0);
    int placed = 0;
    for (int32_t b = static_cast<int32_t>(branches_.size()) - 1; b >= 0 && placed < wanted; --b) {
      const Branch branch = branches_[b];
      for (int32_t a = branch.first + kEndMargin;
           a < branch.first + branch.count - kEndMargin && placed < wanted; a += kEndMargin)
        if (!blocked_[a] && connect(a)) ++placed;
    }
    if (placed < wanted)
      throw std::runtime_error(
          "synthesize_network: only " + std::to_string(placed) + " of the " + std::to_string(wanted) +
          " requested anastomoses could be placed in a network of " + std::to_string(out_.points.size()) +
          " points; ask for fewer loops or more sections");
  }

  CenterlineData take() {
    out_.roots = {0};
    return std::move(out_);
  }

 private:
  int64_t size() const { return static_cast<int64_t>(out_.points.size()); }

  void place(const Vec3& x, double r, int32_t owner, double arc, int32_t from) {
    const auto p = static_cast<int32_t>(out_.points.size());
    out_.points.push_back(x);
    out_.radius.push_back(r);
    if (from >= 0) out_.edges.push_back({from, p});
    owner_.push_back(owner);
    arc_.push_back(arc);
    grid_.insert(p);
  }

  /// Adds `samples` to tree branch `branch`, the first joined to point `from`.
  void append(int32_t branch, int32_t from, const std::vector<Sample>& samples) {
    for (const Sample& sample : samples) {
      place(sample.x, sample.r, branch, sample.s, from);
      from = static_cast<int32_t>(out_.points.size()) - 1;
    }
    branches_[branch].count += static_cast<int32_t>(samples.size());
  }

  /// A branch of the given start, direction, radius and length with random curvature, twist and taper.
  Shape random_shape(const Vec3& start, const Vec3& dir, double r, double length) {
    Shape shape;
    shape.start = start;
    shape.dir = dir;
    shape.normal = random_.perpendicular(dir);
    shape.r = r;
    shape.length = length;
    shape.bend = random_.uniform(12.0, 40.0);
    shape.twist = random_.uniform(-0.08, 0.08);
    shape.taper = random_.uniform(0.02, 0.08);
    return shape;
  }

  /// Up to `max_points` samples of a branch: points kSpacing local radii apart; the direction turns
  /// towards the curvature direction with the shape's bend radius, and the curvature direction slowly
  /// rotates about the tangent. The bend radius is at least 12 local radii and a branch turns by at most
  /// 2 radians, so a branch never comes back near itself.
  static void trace(const Shape& shape, int64_t max_points, std::vector<Sample>& samples) {
    samples.clear();
    Vec3 x = shape.start, d = shape.dir, n = shape.normal;
    double r = shape.r, s = 0.0;
    while (static_cast<int64_t>(samples.size()) < max_points && s < shape.length) {
      const double h = kSpacing * r;
      if (!samples.empty()) {  // the first step leaves along the branching direction itself
        d = unit(d + (kSpacing / shape.bend) * n);
        n = n + shape.twist * cross(d, n);
        n = unit(n - dot(n, d) * d);
      }
      x = x + h * d;
      s += h;
      samples.push_back({x, r, s});
      r *= 1.0 - shape.taper * h / shape.length;
    }
  }

  /// Whether the tree path between tree points p and q is shorter than `limit`: the deeper side climbs
  /// to its parent branch's end until both sides are on one branch. False when either is on an anastomosis.
  bool path_shorter(int32_t p, int32_t q, double limit) const {
    int32_t bp = owner_[p], bq = owner_[q];
    if (bp < 0 || bq < 0) return false;
    double ap = arc_[p], aq = arc_[q], walked = 0.0;
    while (bp != bq) {
      const bool climb_p = branches_[bp].depth >= branches_[bq].depth;
      int32_t& b = climb_p ? bp : bq;
      double& a = climb_p ? ap : aq;
      walked += a;
      if (walked >= limit) return false;
      b = branches_[b].parent;
      a = arc_[branches_[b].first + branches_[b].count - 1];
    }
    return walked + std::abs(ap - aq) < limit;
  }

  /// Whether `sample` overlaps the tube at point q: closer than kClearance (r_a + r_b), and not within
  /// kJunction (r_a + r_b) of it along a path through the ends.
  bool collides(const Sample& sample, int32_t q, const Ends& ends) const {
    const double rq = out_.radius[q];
    const double clearance = kClearance * (sample.r + rq);
    if (distance2(sample.x, out_.points[q]) >= clearance * clearance) return false;
    const double junction = kJunction * (sample.r + rq);
    return !path_shorter(ends.from, q, junction - sample.s) &&
           !(ends.to >= 0 && path_shorter(ends.to, q, junction - (ends.length - sample.s)));
  }

  /// The number of leading samples that keep clear of every placed point and of `sibling` (which leaves
  /// the same point), junctions apart.
  int64_t clear_prefix(const std::vector<Sample>& samples, const Ends& ends,
                       const std::vector<Sample>* sibling) const {
    const auto n = static_cast<int64_t>(samples.size());
    for (int64_t begin = 0; begin < n; begin += kChunk) {
      const int64_t end = std::min(n, begin + kChunk);
      Vec3 lo = samples[begin].x, hi = lo;
      double r_max = 0.0;
      for (int64_t k = begin; k < end; ++k) {
        lo = lo.cwiseMin(samples[k].x);
        hi = hi.cwiseMax(samples[k].x);
        r_max = std::max(r_max, samples[k].r);
      }
      int64_t first = end;  // the first colliding sample of the chunk
      grid_.visit_box(
          lo, hi, [&](double level_radius) { return kClearance * (r_max + level_radius); },
          [&](int32_t q) {
            for (int64_t k = begin; k < first; ++k)
              if (collides(samples[k], q, ends)) first = k;
          });
      if (sibling)
        for (int64_t k = begin; k < first; ++k)
          for (const Sample& other : *sibling) {
            const double sum = samples[k].r + other.r, clearance = kClearance * sum;
            if (distance2(samples[k].x, other.x) < clearance * clearance &&
                samples[k].s + other.s >= kJunction * sum) {
              first = k;
              break;
            }
          }
      if (first < end) return first;
    }
    return n;
  }

  /// Tries directions for a child of radius r leaving end point e along `axis`: first at `cos_angle`
  /// towards `side`, then at random azimuths and slightly changed angles. Takes the first that fits
  /// whole, else the one that runs furthest before a collision, cut there.
  Choice choose_child(int32_t e, const Vec3& axis, double r, double cos_angle, const Vec3& side,
                      int64_t max_points, const std::vector<Sample>* sibling) {
    Choice best;
    for (int t = 0; t < kTries; ++t) {
      Choice c;
      c.side = t == 0 ? side : random_.perpendicular(axis);
      const double cos_t = t == 0 ? cos_angle : std::clamp(cos_angle + random_.uniform(-0.1, 0.1), 0.2, 0.99);
      const Vec3 dir = unit(cos_t * axis + std::sqrt(1.0 - cos_t * cos_t) * c.side);
      c.shape = random_shape(out_.points[e], dir, r, random_.uniform(10.0, 20.0) * r);
      trace(c.shape, max_points, samples_);
      c.count = clear_prefix(samples_, {e, -1, 0.0}, sibling);
      if (c.count == static_cast<int64_t>(samples_.size())) {
        c.full = samples_.back().s >= c.shape.length;
        return c;
      }
      if (c.count > best.count) best = c;
    }
    if (best.count < kMinStub) best.count = 0;
    return best;
  }

  /// Grows the two children of tree branch `parent` from its end point (Murray's law for their radii
  /// and angles), both or neither, within `target` points in all.
  void split(int32_t parent, int64_t target) {
    const int32_t e = branches_[parent].first + branches_[parent].count - 1;
    const Vec3 axis = unit(out_.points[e] - out_.points[e - 1]);
    const double r0 = out_.radius[e];
    const double ratio = random_.uniform(0.5, 1.0);  // r_small / r_big
    const double r_big = r0 / cube_root(1.0 + ratio * ratio * ratio);
    const double r_small = ratio * r_big;
    const int64_t budget = target - size();
    const Vec3 side = random_.perpendicular(axis);
    const Choice big =
        choose_child(e, axis, r_big, murray_cos(r0, r_big, r_small), side, budget - 1, nullptr);
    if (big.count == 0) return;
    trace(big.shape, big.count, sibling_);
    // The smaller child first tries the same plane, on the other side.
    const Choice small = choose_child(e, axis, r_small, murray_cos(r0, r_small, r_big), -big.side,
                                      budget - big.count, &sibling_);
    if (small.count == 0) return;
    add_child(parent, e, sibling_, big.full);
    trace(small.shape, small.count, samples_);
    add_child(parent, e, samples_, small.full);
  }

  void add_child(int32_t parent, int32_t e, const std::vector<Sample>& samples, bool full) {
    const auto b = static_cast<int32_t>(branches_.size());
    branches_.push_back({parent, branches_[parent].depth + 1, static_cast<int32_t>(out_.points.size()), 0});
    append(b, e, samples);
    if (full) pending_.push({out_.radius.back(), order_++, b});
  }

  /// Tries to connect tree point a to a nearby partner by an anastomosis.
  bool connect(int32_t a) {
    const double ra = out_.radius[a], reach = kLoopReach * ra;
    const Vec3 xa = out_.points[a];
    candidates_.clear();
    grid_.visit_box(
        xa, xa,
        [&](double level_radius) {
          return level_radius >= ra / 2.0 && level_radius < 4.0 * ra ? reach : -1.0;
        },
        [&](int32_t q) {
          const int32_t b = owner_[q];
          if (b < 0 || b == owner_[a] || blocked_[q]) return;
          if (q - branches_[b].first < kEndMargin ||
              branches_[b].first + branches_[b].count - 1 - q < kEndMargin)
            return;
          if (out_.radius[q] < ra / 2.0 || out_.radius[q] > 2.0 * ra) return;  // of similar radius
          const double d2 = distance2(xa, out_.points[q]);
          if (d2 <= reach * reach) candidates_.push_back({d2, q});
        });
    std::sort(candidates_.begin(), candidates_.end());
    int tried = 0;
    for (const auto& [d2, q] : candidates_) {
      // A loop worth the name: the tree path is much longer than the shortcut.
      if (path_shorter(a, q, std::max(1.5 * std::sqrt(d2), 6.0 * (ra + out_.radius[q])))) continue;
      if (place_anastomosis(a, q)) return true;
      if (++tried == kLoopTries) break;
    }
    return false;
  }

  /// Places a vessel from tree point a to tree point b unless it would bend too sharply or collide: a
  /// cubic Bezier curve that meets each branch at 65 degrees or more, radius the smaller end radius,
  /// points evenly spaced along its arc.
  bool place_anastomosis(int32_t a, int32_t b) {
    const Vec3 xa = out_.points[a], xb = out_.points[b], chord = xb - xa;
    const double c = std::sqrt(dot(chord, chord));
    const Vec3 ta = unit(out_.points[a + 1] - out_.points[a - 1]);
    const Vec3 tb = unit(out_.points[b + 1] - out_.points[b - 1]);
    Vec3 da, db;
    if (!departure(chord / c, ta, da) || !departure(-chord / c, tb, db)) return false;
    const Vec3 pa = xa + (c / 3.0) * da, pb = xb + (c / 3.0) * db;
    const auto bezier = [&](double u) {
      const double v = 1.0 - u;
      return Vec3((v * v * v) * xa + (3.0 * v * v * u) * pa + (3.0 * v * u * u) * pb + (u * u * u) * xb);
    };
    std::array<double, kBezierSteps + 1> arc{};
    Vec3 previous = xa;
    for (int i = 1; i <= kBezierSteps; ++i) {
      const Vec3 x = bezier(static_cast<double>(i) / kBezierSteps);
      arc[i] = arc[i - 1] + std::sqrt(distance2(x, previous));
      previous = x;
    }
    const double length = arc[kBezierSteps], rv = std::min(out_.radius[a], out_.radius[b]);
    const auto segments = static_cast<int>(std::ceil(length / (kSpacing * rv)));
    samples_.clear();
    int i = 0;
    for (int k = 1; k < segments; ++k) {
      const double s = length * k / segments;
      while (arc[i + 1] < s) ++i;
      const double u = (i + (s - arc[i]) / (arc[i + 1] - arc[i])) / kBezierSteps;
      samples_.push_back({bezier(u), rv, s});
    }
    // Circumradius of each three consecutive points, ends included, at least 8 radii.
    for (std::size_t k = 0; k < samples_.size(); ++k) {
      const Vec3& p = k == 0 ? xa : samples_[k - 1].x;
      const Vec3& q = samples_[k].x;
      const Vec3& r = k + 1 == samples_.size() ? xb : samples_[k + 1].x;
      const double sides = std::sqrt(distance2(p, q) * distance2(q, r) * distance2(r, p));
      const Vec3 area = cross(q - p, r - p);
      if (sides < 2.0 * 8.0 * rv * std::sqrt(dot(area, area))) return false;
    }
    if (clear_prefix(samples_, {a, b, length}, nullptr) < static_cast<int64_t>(samples_.size())) return false;
    int32_t from = a;
    for (const Sample& sample : samples_) {
      place(sample.x, sample.r, -1, sample.s, from);
      from = static_cast<int32_t>(out_.points.size()) - 1;
    }
    out_.edges.push_back({from, b});
    block(a);
    block(b);
    return true;
  }

  /// The direction `d` in which a vessel leaves a branch of tangent t towards unit direction `toward`:
  /// that direction itself, or turned away from the branch just enough to meet it at 65 degrees (so that
  /// the two tubes part within the junction). False when `toward` is within 30 degrees of the branch.
  static bool departure(const Vec3& toward, const Vec3& t, Vec3& d) {
    const double along = dot(toward, t);
    const Vec3 across = toward - along * t;
    const double width = std::sqrt(dot(across, across)), most = 0.466 * width;  // tan 25 degrees
    if (width < 0.5) return false;
    d = std::abs(along) <= most ? toward : unit(across + std::copysign(most, along) * t);
    return true;
  }

  /// Keeps later anastomoses from attaching next to tree point p.
  void block(int32_t p) {
    const Branch& branch = branches_[owner_[p]];
    const int32_t lo = std::max(branch.first, p - kEndMargin);
    const int32_t hi = std::min(branch.first + branch.count - 1, p + kEndMargin);
    for (int32_t i = lo; i <= hi; ++i) blocked_[i] = 1;
  }

  Random random_;
  CenterlineData out_;
  Grid grid_;
  std::vector<int32_t> owner_;  // per point: its tree branch, or -1 on an anastomosis
  std::vector<double> arc_;     // per point: arc length from the point its branch leaves
  std::vector<Branch> branches_;
  std::priority_queue<Pending> pending_;
  int64_t order_ = 0;
  std::vector<char> blocked_;  // per tree point: no anastomosis may attach here
  std::vector<Sample> samples_, sibling_;
  std::vector<std::pair<double, int32_t>> candidates_;
};

}  // namespace

CenterlineData synthesize_network(const SynthOptions& options) {
  if (options.sections < 2 || options.sections > std::numeric_limits<int32_t>::max())
    throw std::invalid_argument("synthesize_network: sections must be between 2 and 2^31 - 1, not " +
                                std::to_string(options.sections));
  if (options.loops < 0)
    throw std::invalid_argument("synthesize_network: loops must not be negative, not " +
                                std::to_string(options.loops));
  // The anastomoses join the tree grown so far; the rest of the tree then grows around them.
  const int64_t reserve = std::min(options.sections / 2, int64_t{kLoopPoints} * options.loops);
  const int64_t first = std::max<int64_t>(2, options.sections - reserve);
  Network network(options.seed);
  network.plant(first);
  network.grow(first);
  network.add_loops(options.loops);
  network.grow(options.sections);
  return network.take();
}

}  // namespace vesselmesh
