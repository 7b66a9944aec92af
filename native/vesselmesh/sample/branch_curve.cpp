#include "vesselmesh/sample/branch_curve.hpp"

#include <algorithm>
#include <cmath>

namespace vesselmesh {

namespace {

/// Radius of the branch at each of its points (see BranchCurve::radius).
std::vector<double> branch_radii(const CenterlineGraph& g, const Branch& b) {
  const std::size_t k = b.edges.size();
  std::vector<double> r(k + 1);
  auto end_at = [&](int32_t e, int32_t v) { return g.end_radius[e][g.edges[e][0] == v ? 0 : 1]; };
  r[0] = end_at(b.edges[0], b.points[0]);
  r[k] = end_at(b.edges[k - 1], b.points[k]);
  for (std::size_t i = 1; i < k; ++i)
    r[i] = 0.5 * (end_at(b.edges[i - 1], b.points[i]) + end_at(b.edges[i], b.points[i]));
  return r;
}

/// The curve resampled every h, with `half` extra samples past each end: extended by point reflection
/// (which keeps an end fixed under symmetric smoothing), or wrapped around for a ring.
struct Resampled {
  std::vector<Vec3> x;  ///< x[i + half] is the curve at arc length i·h, i in −half..n+half
  double h = 0;
  int n = 0, half = 0;
};

Resampled resample(const BranchCurve& c, bool ring, double step, double reach) {
  Resampled r;
  const double length = c.length();
  r.n = std::max(2, static_cast<int>(std::ceil(length / step)));
  r.h = length / r.n;
  r.half = static_cast<int>(std::ceil(reach / r.h));
  r.x.resize(r.n + 1 + 2 * r.half);
  for (int i = -r.half; i <= r.n + r.half; ++i) {
    const double s = i * r.h;
    Vec3 p;
    if (ring)
      p = c.position(std::fmod(std::fmod(s, length) + length, length));
    else if (s < 0)
      p = 2.0 * c.points.front() - c.position(std::min(-s, length));
    else if (s > length)
      p = 2.0 * c.points.back() - c.position(std::max(2.0 * length - s, 0.0));
    else
      p = c.position(s);
    r.x[i + r.half] = p;
  }
  return r;
}

/// Linear interpolation of per-sample values back to the curve's points.
template <typename T>
std::vector<T> at_points(const BranchCurve& c, const Resampled& r, const std::vector<T>& uniform) {
  std::vector<T> out(c.points.size());
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    const double u = c.arc[i] / r.h;
    const int lo = std::clamp(static_cast<int>(std::floor(u)), 0, r.n - 1);
    const double f = std::clamp(u - lo, 0.0, 1.0);
    out[i] = (1 - f) * uniform[lo] + f * uniform[lo + 1];
  }
  return out;
}

/// Curvature and unit tangent at each point: the resampled curve convolved with Gaussian derivative
/// kernels, κ = |X' × X''| / |X'|³. At least a radius wide: a tube shows nothing of its centerline finer
/// than its radius, and at half a radius the staircase of a voxel centerline (points half a radius apart)
/// still reads as bends of radius r, crowding sections every half radius. At least one mean edge wide:
/// between sparse points the curve is unknown, and a polyline's corners are not bends of the vessel.
/// Samples go a quarter radius apart, or a 32nd of the width where that is wider (sparse tracings): the
/// kernel then has at most 257 taps and the branch at most 32 samples per mean edge, so the work is
/// linear in its points whatever its length in radii.
void smoothed_differentials(BranchCurve& c, bool ring) {
  const double mean_edge = c.length() / static_cast<double>(c.points.size() - 1);
  // No wider than the branch: a branch shorter than its radius has no bend to smooth, and a kernel wider
  // than the branch only reaches past its (reflected) ends.
  const double sigma = std::min(std::max(c.median_radius, mean_edge), c.length());
  const double step = std::max(std::min(mean_edge, 0.25 * c.median_radius), sigma / 32);
  const Resampled r = resample(c, ring, step, 4.0 * sigma);
  const int half = r.half;
  const double h = r.h;
  // Derivative-of-Gaussian kernels, applied as Σ_j g(j) x(i − j). g2 is shifted to sum to zero
  // (constants give no response); m1, m2 scale them to be exact on linear and quadratic curves.
  const int width = 2 * half + 1;
  std::vector<double> g1(width), g2(width);
  for (int j = -half; j <= half; ++j) {
    const double t = j * h, w = std::exp(-0.5 * t * t / (sigma * sigma));
    g1[j + half] = -t * w;
    g2[j + half] = (t * t / (sigma * sigma) - 1.0) * w;
  }
  double g2_mean = 0;
  for (double v : g2) g2_mean += v / width;
  double m1 = 0, m2 = 0;
  for (int j = -half; j <= half; ++j) {
    const double t = j * h;
    g2[j + half] -= g2_mean;
    m1 += g1[j + half] * -t;
    m2 += g2[j + half] * t * t / 2;
  }
  std::vector<double> kappa_uniform(r.n + 1);
  std::vector<Vec3> tangent_uniform(r.n + 1);
  for (int i = 0; i <= r.n; ++i) {
    Vec3 d1 = Vec3::Zero(), d2 = Vec3::Zero();
    for (int j = -half; j <= half; ++j) {
      d1 += g1[j + half] * r.x[i + half - j];
      d2 += g2[j + half] * r.x[i + half - j];
    }
    d1 /= m1, d2 /= m2;
    const double speed = d1.norm();
    kappa_uniform[i] = speed > 0 ? d1.cross(d2).norm() / (speed * speed * speed) : 0.0;
    tangent_uniform[i] = d1;
  }
  c.kappa = at_points(c, r, kappa_uniform);
  c.tangents = at_points(c, r, tangent_uniform);
  for (std::size_t i = 0; i < c.tangents.size(); ++i) {
    // A curve that doubles back within the kernel has no smoothed direction there: use the chord.
    const std::size_t a = std::min(i, c.points.size() - 2);
    const Vec3 chord = (c.points[a + 1] - c.points[a]).normalized();
    c.tangents[i] = c.tangents[i].norm() > 1e-12 ? c.tangents[i].normalized() : chord;
  }
}

/// Points of a jittered stretch, where vessel_arc counted the straight way (an edge's length along the
/// vessel under nine tenths of its own), moved to the mean of the points within a radius either side along
/// the vessel, the window no wider than the way to the nearer end (ends stay, and with them the joints): a
/// tube's sections stand round its axis, not round the jitter (a fork of vessels traced every twentieth of
/// a radius, jittered by up to a quarter: 0.4 % of its area in the crotch over half a radius inside the
/// tubes, where its joint's squares stood on jittered points). Elsewhere the points are the tracing's own.
void settle_jitter(BranchCurve& c) {
  const std::size_t n = c.points.size();
  auto jittered = [&](std::size_t e) {  // edge e, from point e to e + 1
    return c.arc[e + 1] - c.arc[e] < 0.9 * (c.points[e + 1] - c.points[e]).norm();
  };
  // Sums of the points from the first, which they are taken from: a window's mean costs the same however
  // many points it holds (thousands within a radius of one another).
  std::vector<Vec3> sum(n + 1, Vec3::Zero());
  for (std::size_t i = 0; i < n; ++i) sum[i + 1] = sum[i] + (c.points[i] - c.points[0]);
  std::vector<Vec3> settled = c.points;
  for (std::size_t i = 1, lo = 0, hi = 0; i + 1 < n; ++i) {
    if (!jittered(i - 1) && !jittered(i)) continue;
    const double half = std::min({c.radius[i], c.arc[i], c.length() - c.arc[i]});
    while (c.arc[lo] < c.arc[i] - half) ++lo;
    hi = std::max(hi, i);
    while (hi + 1 < n && c.arc[hi + 1] <= c.arc[i] + half) ++hi;
    settled[i] = c.points[0] + (sum[hi + 1] - sum[lo]) / static_cast<double>(hi - lo + 1);
  }
  c.points = std::move(settled);
}

}  // namespace

std::size_t BranchCurve::segment(double s) const {
  const auto it = std::upper_bound(arc.begin(), arc.end(), s);
  const std::size_t i = it == arc.begin() ? 0 : static_cast<std::size_t>(it - arc.begin()) - 1;
  return std::min(i, arc.size() - 2);
}

std::pair<std::size_t, double> BranchCurve::locate(double s) const {
  const std::size_t i = segment(s);
  const double len = arc[i + 1] - arc[i];
  return {i, len > 0 ? std::clamp((s - arc[i]) / len, 0.0, 1.0) : 0.0};
}

Vec3 BranchCurve::position(double s) const {
  const auto [i, f] = locate(s);
  return (1 - f) * points[i] + f * points[i + 1];
}

double BranchCurve::radius_at(double s) const {
  const auto [i, f] = locate(s);
  return (1 - f) * radius[i] + f * radius[i + 1];
}

double BranchCurve::kappa_at(double s) const {
  const auto [i, f] = locate(s);
  return (1 - f) * kappa[i] + f * kappa[i + 1];
}

Vec3 BranchCurve::tangent(double s) const {
  const auto [i, f] = locate(s);
  const Vec3 t = (1 - f) * tangents[i] + f * tangents[i + 1];
  return t.norm() > 1e-12 ? t.normalized() : tangents[i];
}

BranchCurve branch_curve(const CenterlineGraph& graph, const Branch& branch) {
  BranchCurve c;
  for (int32_t v : branch.points) c.points.push_back(graph.points[v]);
  c.radius = branch_radii(graph, branch);
  c.arc = vessel_arc(graph, branch);
  settle_jitter(c);
  std::vector<double> sorted = c.radius;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  c.median_radius = sorted[sorted.size() / 2];
  const bool ring = branch.points.front() == branch.points.back();
  smoothed_differentials(c, ring);
  return c;
}

}  // namespace vesselmesh
