#include "vesselmesh/sample/sample.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "vesselmesh/error.hpp"

namespace vesselmesh {

namespace {

// Gentler corners are left to the sampling: moving sections onto them gained little on real tracings
// and made the tubes of smooth ones (human-brain-arteries) less even.
constexpr double kCornerDegrees = 30;
const double kCornerCosine = std::cos(kCornerDegrees * M_PI / 180);
// Such a corner takes a section only where it stands out a radius or more from the line between the
// points a diameter either side (its sphere stands out of a tube swept past it as far): the staircase of
// a voxel centerline turns at every point but stands out half a voxel, and sections snapped onto it zigzag.
constexpr double kCornerView = 2;  // radii along the polyline either side
constexpr double kCornerOut = 1;   // radii from the line between those points

/// How much wider than Eq. 1 the spacing may grow away from what limits it, per unit of arc: gaps then
/// grow at most by (1 + λ) / (1 − λ) = 5/3 from one to the next. Loop's limit runs along a tube as a
/// uniform B-spline through the sections, so uneven gaps bend its axis: at 0.5 (gaps tripling) the
/// vertices of brava-bg0003 were 2.15 % off their tubes at the median (1.8 % with Eq. 1 alone).
constexpr double kGrading = 0.25;
/// Pieces over more of the polyline's points than this are not tested (follows).
constexpr std::size_t kMostPointsPerPiece = 512;
/// At most this many field samples per edge of the polyline (at its points and between them).
constexpr int kSamplesPerEdge = 8;

/// ⌈x⌉ within [1, most], as an int: x, a length over a step, may be far beyond int (an edge of 1e98 radii,
/// a radius of 1e100 next to ordinary ones: a fuzz finding) or NaN.
int count_within(double x, int most) {
  const double n = std::ceil(x);
  return n > 1 ? static_cast<int>(std::min(n, static_cast<double>(most))) : 1;
}

struct Spacing {
  const BranchCurve& curve;
  double alpha, beta;
  std::vector<double> at{}, reach{};  ///< the straight-reach field (straight_reach), sampled
  double paper(double s) const {
    const double r = curve.radius_at(s);
    return std::max(alpha * r / (1.0 + beta * curve.kappa_at(s)), 0.25 * r);
  }
  double g(double s) const {
    double allowed = 0;
    if (!at.empty()) {
      const std::size_t i = std::upper_bound(at.begin(), at.end(), s) - at.begin();
      if (i == 0 || i == at.size()) {
        allowed = reach[i == 0 ? 0 : at.size() - 1];
      } else {
        const double f = (s - at[i - 1]) / (at[i] - at[i - 1]);
        allowed = (1 - f) * reach[i - 1] + f * reach[i];
      }
    }
    return std::max(paper(s), allowed);
  }
  /// How far `t` is from being the next section after `s`: ≥ 0 once it is far enough.
  double gap(double s, double t) const {
    return (curve.position(t) - curve.position(s)).norm() - g(s) - g(t);
  }
};

/// Whether a straight piece of tube from arc `a` to `b` (a < b) follows the input: every point of the
/// polyline between them lies within `tolerance` of its radius of the chord, its radius within as much of
/// the chord's (linear between the ends, as the round stage makes it), and the chord is at most
/// `max_step` times the mean of its ends' radii long.
bool follows(const BranchCurve& c, double a, double b, double tolerance, double max_step) {
  const Vec3 pa = c.position(a), chord = c.position(b) - pa;
  const double ra = c.radius_at(a), rb = c.radius_at(b), length2 = chord.squaredNorm();
  if (length2 > std::pow(max_step * 0.5 * (ra + rb), 2)) return false;
  const std::size_t first = std::upper_bound(c.arc.begin(), c.arc.end(), a) - c.arc.begin();
  // A piece over more points than this is left to Eq. 1, so that the work stays linear in the points
  // however densely they lie (a straight piece of 32 radii holds 128 of a voxel centerline's).
  if (first + kMostPointsPerPiece < c.arc.size() && c.arc[first + kMostPointsPerPiece] < b) return false;
  for (std::size_t j = first; j < c.arc.size() && c.arc[j] < b; ++j) {
    const double f = length2 > 0 ? std::clamp((c.points[j] - pa).dot(chord) / length2, 0.0, 1.0) : 0.0;
    const double limit = tolerance * c.radius[j];
    if ((pa + f * chord - c.points[j]).norm() > limit || std::abs(ra + f * (rb - ra) - c.radius[j]) > limit)
      return false;
  }
  return true;
}

/// The straight-reach field: at sample positions along the whole curve, the largest half-width h for
/// which a straight piece 2h long round s (s − h to s + h, shifted inside the curve near its ends) follows
/// the input, then limited to grow by at most kGrading per unit of arc away from where it is small (a
/// bend, a corner, a kink of the radius, the range's ends), so that Eq. 1's sections, spaced by it, come
/// to what limits them gradually. Samples at the curve's points and up to kSamplesPerEdge − 1 between,
/// about a radius apart on long edges.
void straight_reach(Spacing& sp, double tolerance, double max_step, double start, double end) {
  const BranchCurve& c = sp.curve;
  for (std::size_t i = 0; i + 1 < c.arc.size(); ++i) {
    const double edge = c.arc[i + 1] - c.arc[i];
    const double r = std::min(c.radius[i], c.radius[i + 1]);
    const int n = count_within(edge / r, kSamplesPerEdge);
    for (int k = 0; k < n; ++k) sp.at.push_back(c.arc[i] + edge * k / n);
  }
  sp.at.push_back(c.length());
  sp.reach.resize(sp.at.size());
  for (std::size_t i = 0; i < sp.at.size(); ++i) {
    const double s = sp.at[i], r = c.radius_at(s);
    // A window of 2h, shifted inside the curve near its ends: a one-sided window would allow twice the
    // spacing at an end (a joint's square or a ring's seam) of what it allows a step further in.
    auto ok = [&](double h) {
      const double a = std::clamp(s - h, 0.0, std::max(c.length() - 2 * h, 0.0));
      return follows(c, a, std::min(a + 2 * h, c.length()), tolerance, max_step);
    };
    // Doubling from a quarter radius to the first failure, then bisection: the field need not be exact,
    // and the work stays a few dozen tests a sample.
    double lo = 0, hi = 0.25 * r;
    while (hi < max_step * r && ok(hi)) lo = hi, hi *= 2;
    for (int it = 0; it < 8 && lo > 0; ++it) {
      const double mid = 0.5 * (lo + hi);
      (ok(mid) ? lo : hi) = mid;
    }
    sp.reach[i] = lo;
  }
  // The range's ends are where the tube meets a joint's patch or a cap: Eq. 1's spacing there, graded
  // away. Long pieces there drew a flat cap's rounding along them (a straight tube 3 % thin, its median,
  // away from the cap) and left a joint's squares long pieces to bulge and fold on (fixtures
  // u_bend_into_a_joint and siblings_side_by_side: 5.7 % and 1.3 % of the area off the tubes; 30 crossing
  // pairs on tests/data/crossing.swc) with only the first step from each end kept at Eq. 1's.
  for (std::size_t i = 0; i < sp.at.size(); ++i)
    sp.reach[i] = std::min(sp.reach[i], kGrading * std::min(std::abs(sp.at[i] - start), std::abs(sp.at[i] - end)));
  for (std::size_t i = 1; i < sp.at.size(); ++i)
    sp.reach[i] = std::min(sp.reach[i], sp.reach[i - 1] + kGrading * (sp.at[i] - sp.at[i - 1]));
  for (std::size_t i = sp.at.size() - 1; i-- > 0;)
    sp.reach[i] = std::min(sp.reach[i], sp.reach[i + 1] + kGrading * (sp.at[i + 1] - sp.at[i]));
}

Spacing spacing(const BranchCurve& curve, const SamplingOptions& options, double start, double end) {
  Spacing sp{curve, options.alpha, options.beta * curve.median_radius};
  if (options.tolerance > 0) straight_reach(sp, options.tolerance, options.max_step, start, end);
  return sp;
}

/// The next section from `s` towards `limit` (either direction): the first root of gap(s, ·), bracketed
/// by walking the curve's points, in strides of g(s) along long edges, then bisected. Nothing when no
/// admissible position precedes `limit`.
std::optional<double> step(const Spacing& sp, double s, double limit) {
  const BranchCurve& c = sp.curve;
  const bool forward = limit > s;
  double stride = forward ? sp.g(s) : -sp.g(s);
  double previous = s;
  // Candidate bracket ends: the curve's points strictly between s and limit, then limit itself; at most
  // a stride apart, the stride doubling each time, so that an edge thousands of radii long costs a few
  // strides, not a long bisection, and a radius that grows faster than the way along (no root there) a
  // few dozen, not one per radius of the start.
  std::size_t i = c.segment(s);
  auto next_knot = [&]() -> double {
    if (forward) {
      while (i + 1 < c.arc.size() && c.arc[i + 1] <= previous) ++i;
      return std::min({i + 1 < c.arc.size() ? c.arc[i + 1] : limit, limit, previous + stride});
    }
    while (i > 0 && c.arc[i] >= previous) --i;
    return std::max({c.arc[i] < previous ? c.arc[i] : limit, limit, previous + stride});
  };
  while (previous != limit) {
    const double t = next_knot();
    stride *= 2;
    if (sp.gap(s, t) >= 0.0) {
      double lo = previous, hi = t;  // gap(lo) < 0 ≤ gap(hi)
      for (int it = 0; it < 60 && std::abs(hi - lo) > 1e-12 * c.length(); ++it) {
        const double mid = 0.5 * (lo + hi);
        (sp.gap(s, mid) >= 0.0 ? hi : lo) = mid;
      }
      return hi;
    }
    previous = t;
  }
  return std::nullopt;
}

void check_count(std::size_t sections, int64_t max_sections) {
  if (static_cast<int64_t>(sections) > max_sections)
    throw SizeLimitError("a branch takes more than " + std::to_string(max_sections) + " sections");
}

std::vector<double> unidirectional(const Spacing& sp, double start, double end, int64_t max_sections) {
  std::vector<double> out{start};
  while (auto next = step(sp, out.back(), end)) {
    if (*next >= end) break;
    out.push_back(*next);
    check_count(out.size() + 1, max_sections);
  }
  out.push_back(end);
  return out;
}

std::vector<double> bidirectional(const Spacing& sp, double start, double end, double meet_min_ratio,
                                  int64_t max_sections) {
  std::vector<double> left{start}, right{end};
  while (true) {
    check_count(left.size() + right.size(), max_sections);
    const auto l = step(sp, left.back(), right.back());
    const auto r = step(sp, right.back(), left.back());
    if (!l || !r) break;
    if (*l >= *r) {
      // The fronts met or crossed: one section in the middle when the gap is too long for none.
      if (*l == *r)
        left.push_back(*l);
      else if (sp.gap(left.back(), right.back()) > 0.0)
        left.push_back(0.5 * (left.back() + right.back()));
      break;
    }
    left.push_back(*l);
    right.push_back(*r);
  }
  // A tiny middle gap would leave a thin, twisted tube piece: merge its two sections into one.
  const double xl = left.back(), xr = right.back();
  if (left.size() > 1 && right.size() > 1 && xr > xl) {
    const double desired = sp.g(xl) + sp.g(xr);
    if ((sp.curve.position(xr) - sp.curve.position(xl)).norm() < meet_min_ratio * desired) {
      left.back() = 0.5 * (xl + xr);
      right.pop_back();
    }
  }
  left.insert(left.end(), right.rbegin(), right.rend());
  left.erase(std::unique(left.begin(), left.end()), left.end());
  return left;
}

/// Moves sections onto the polyline's corners that turn by more than kCornerDegrees and stand out
/// kCornerOut radii from the line between the points kCornerView radii either side, sharpest first,
/// each onto the nearest section not moved yet, where both of its gaps stay at least meet_min_ratio of
/// their desired length. Sections a diameter apart cut such a corner, where the input's round cones
/// have a whole sphere: a section on the corner keeps the tube out to it (a 60° zigzag of points four
/// radii apart: 95th-percentile radius error 22 % → 13 %).
std::vector<char> snap_to_corners(const Spacing& sp, std::vector<double>& arcs, double meet_min_ratio) {
  const BranchCurve& c = sp.curve;
  std::vector<std::pair<double, std::size_t>> corners;  // (cosine of the turn, point)
  for (std::size_t j = 1; j + 1 < c.points.size(); ++j) {
    if (c.arc[j] <= arcs.front() || c.arc[j] >= arcs.back()) continue;
    const Vec3 in = c.points[j] - c.points[j - 1], out = c.points[j + 1] - c.points[j];
    const double cosine = in.dot(out) / (in.norm() * out.norm());
    if (cosine >= kCornerCosine) continue;
    const double view = kCornerView * c.radius[j];
    std::size_t i = j - 1, k = j + 1;
    while (i > 0 && c.arc[j] - c.arc[i] < view) --i;
    while (k + 1 < c.points.size() && c.arc[k] - c.arc[j] < view) ++k;
    const Vec3 chord = c.points[k] - c.points[i];
    const double t = chord.squaredNorm() > 0
                         ? std::clamp((c.points[j] - c.points[i]).dot(chord) / chord.squaredNorm(), 0.0, 1.0)
                         : 0.0;
    if ((c.points[i] + t * chord - c.points[j]).norm() >= kCornerOut * c.radius[j])
      corners.emplace_back(cosine, j);
  }
  std::sort(corners.begin(), corners.end());
  std::vector<char> snapped(arcs.size(), 0);
  auto fits = [&](double a, double b) {
    return (c.position(b) - c.position(a)).norm() >= meet_min_ratio * (sp.g(a) + sp.g(b));
  };
  for (const auto& [cosine, j] : corners) {
    const double at = c.arc[j];
    const std::size_t after = std::upper_bound(arcs.begin(), arcs.end(), at) - arcs.begin();
    const std::size_t i = at - arcs[after - 1] < arcs[after] - at ? after - 1 : after;
    if (i == 0 || i + 1 == arcs.size() || snapped[i]) continue;
    if (!fits(arcs[i - 1], at) || !fits(at, arcs[i + 1])) continue;
    arcs[i] = at;
    snapped[i] = 1;
  }
  return snapped;
}

/// Spreads the sections between consecutive fixed ones (the ends and the sections on corners) evenly in
/// desired spacings, τ(s) = ∫ ds / 2g(s), keeping their number. The sampling leaves one irregular gap
/// mid-branch, and Loop subdivision, whose limit runs along a tube as a uniform B-spline through the
/// sections, turns uneven spacing into a wiggling axis: a gap a third of its neighbours' put a ring's axis
/// 1 % of its radius off its circle.
void even_out(const Spacing& sp, std::vector<double>& arcs, const std::vector<char>& fixed) {
  const BranchCurve& c = sp.curve;
  // τ at the knots and at up to 16 points along each edge (trapezoids on 1/2g).
  std::vector<double> at{arcs.front()}, tau{0};
  std::vector<double> stops;
  for (double knot : c.arc)
    if (knot > arcs.front() && knot < arcs.back()) stops.push_back(knot);
  stops.push_back(arcs.back());
  for (double stop : stops) {
    const double from = at.back();
    const double least = 0.5 * std::min(sp.g(from), sp.g(stop));
    const int steps = count_within((stop - from) / least, 16);
    for (int k = 1; k <= steps; ++k) {
      const double s0 = at.back(), s1 = from + (stop - from) * k / steps;
      tau.push_back(tau.back() + 0.25 * (s1 - s0) * (1 / sp.g(s0) + 1 / sp.g(s1)));
      at.push_back(s1);
    }
  }
  auto tau_at = [&](double s) {
    const std::size_t i = std::min<std::size_t>(std::upper_bound(at.begin(), at.end(), s) - at.begin(), at.size() - 1);
    const std::size_t lo = i == 0 ? 0 : i - 1;
    return at[i] > at[lo] ? tau[lo] + (tau[i] - tau[lo]) * (s - at[lo]) / (at[i] - at[lo]) : tau[lo];
  };
  auto arc_at = [&](double t) {
    const std::size_t i = std::min<std::size_t>(std::upper_bound(tau.begin(), tau.end(), t) - tau.begin(), tau.size() - 1);
    const std::size_t lo = i == 0 ? 0 : i - 1;
    return tau[i] > tau[lo] ? at[lo] + (at[i] - at[lo]) * (t - tau[lo]) / (tau[i] - tau[lo]) : at[lo];
  };
  for (std::size_t a = 0, b = 1; b < arcs.size(); ++b) {
    if (!fixed[b] && b + 1 < arcs.size()) continue;
    const double ta = tau_at(arcs[a]), tb = tau_at(arcs[b]);
    for (std::size_t k = a + 1; k < b; ++k)
      arcs[k] = arc_at(ta + (tb - ta) * static_cast<double>(k - a) / static_cast<double>(b - a));
    a = b;
  }
}

}  // namespace

void validate(const SamplingOptions& options) {
  if (!(std::isfinite(options.alpha) && options.alpha > 0))
    throw std::invalid_argument("alpha (the section spacing) must be a positive number, not " +
                                number_text(options.alpha));
  if (!(std::isfinite(options.beta) && options.beta >= 0))
    throw std::invalid_argument("beta (the curvature weight) must be a number of at least 0, not " +
                                number_text(options.beta));
  if (!(std::isfinite(options.tolerance) && options.tolerance >= 0))
    throw std::invalid_argument("tolerance (of the sections' spacing) must be a number of at least 0, not " +
                                number_text(options.tolerance));
  if (!(std::isfinite(options.max_step) && options.max_step >= 2))
    throw std::invalid_argument("max_step (of the sections' spacing) must be a number of at least 2, not " +
                                number_text(options.max_step));
  if (!(options.meet_min_ratio >= 0 && options.meet_min_ratio <= 1))
    throw std::invalid_argument("meet_min_ratio must be in [0, 1], not " +
                                number_text(options.meet_min_ratio));
  if (options.max_sections < 2)
    throw std::invalid_argument("max_sections must be at least 2, not " +
                                std::to_string(options.max_sections));
}

namespace {

/// About how many sections lie on [start, end]: its length over the spacing, knot to knot.
double sections_between(const Spacing& sp, double start, double end) {
  double sections = 1, from = start;
  for (const double knot : sp.curve.arc)
    if (knot > start && knot < end) sections += (knot - from) / (sp.g(from) + sp.g(knot)), from = knot;
  return sections + (end - from) / (sp.g(from) + sp.g(end));
}

}  // namespace

double estimated_sections(const BranchCurve& curve, const SamplingOptions& options) {
  return sections_between(spacing(curve, options, 0, curve.length()), 0, curve.length());
}

std::vector<double> sample_branch(const BranchCurve& curve, double start, double end,
                                  const SamplingOptions& options) {
  validate(options);
  const Spacing sp = spacing(curve, options, start, end);
  if (end <= start) return {start, end};
  // Refused before the work when far beyond the limit (twice: the estimate follows the arc, the steps the
  // chords): near it, each step of a branch 1e10 radii long costs a bisection (8 s to reach 1.5 million).
  if (const double about = sections_between(sp, start, end); about > 2.0 * static_cast<double>(options.max_sections))
    throw SizeLimitError("a branch takes about " + std::to_string(static_cast<int64_t>(about)) + " sections");
  std::vector<double> arcs =
      options.method == Sampling::unidirectional
          ? unidirectional(sp, start, end, options.max_sections)
          : bidirectional(sp, start, end, options.meet_min_ratio, options.max_sections);
  std::vector<char> fixed = snap_to_corners(sp, arcs, options.meet_min_ratio);
  // The first step from each end is Eq. 1's, where the tube meets a joint's patch or a cap.
  if (arcs.size() > 3) fixed[1] = fixed[arcs.size() - 2] = 1;
  even_out(sp, arcs, fixed);
  return arcs;
}

}  // namespace vesselmesh
