#include "vesselmesh/tile/corners.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "vesselmesh/parallel.hpp"
#include "vesselmesh/sample/branch_curve.hpp"
#include "vesselmesh/tile/tube_sections.hpp"

namespace vesselmesh {

namespace {

/// A point of a branch where it turns by more than this is tiled as a joint.
constexpr double kCornerJointDegrees = 120;
const double kCornerJointCosine = std::cos(kCornerJointDegrees * M_PI / 180);

/// Where the longest chain of a piece's sections that do not fold (fold_free_chains, `from`) drops
/// sections whose centres stand more than this many of their radii off the straight line between the
/// two it keeps either side, its tube would cut across the bend there, a straight prism inside the
/// vessels beside it (fixture hairpin_beside_the_vessel_it_leaves: 1.1 radii, 4.9 % of the area over
/// half a radius off the tubes); the bend is tiled as a corner instead. At half a radius, a bend of
/// brava-records BG10 (0.50) became a corner with a notch on its outer side where the tube had been
/// smooth, and one more of the cohort's trees had over 0.2 % of its area that far off (docs/pipeline.md).
constexpr double kCutBend = 0.75;

/// The index of the section after the dropped ones that stand furthest off the chain's chord, in radii,
/// and that distance (0 and 0 when no section is dropped).
std::pair<std::size_t, double> furthest_dropped(const std::vector<Section>& sections,
                                                const std::vector<std::size_t>& from) {
  std::pair<std::size_t, double> out{0, 0.0};
  for (std::size_t i = sections.size() - 1; i > 0; i = from[i]) {
    const Vec3 a = sections[from[i]].center, chord = sections[i].center - a;
    for (std::size_t j = from[i] + 1; j < i; ++j) {
      const Vec3 p = sections[j].center - a;
      const double f =
          chord.squaredNorm() > 0 ? std::clamp(p.dot(chord) / chord.squaredNorm(), 0.0, 1.0) : 0.0;
      const double off = (p - f * chord).norm() / sections[j].radius;
      if (off > out.second) out = {i, off};
    }
  }
  return out;
}

/// A point of `piece` to tile as a corner because the piece bends tighter than its squares' corners
/// reach: no chain of its sections (facing along the smoothed tangent) gets round the bend without one
/// reaching across the next one's plane, and a tube would fold there however its sections were
/// dropped (a U-bend of a thick vessel, its legs less than three radii apart: fixture
/// u_bend_into_a_joint); or the chain that gets round drops sections that stand more than kCutBend
/// off it. The point turning most within two radii either side, near where the chains break off or
/// the sections are dropped; −1 when they get through, or no point of the piece is there.
int32_t tight_bend(const CenterlineGraph& g, const Branch& piece, const SamplingOptions& sampling,
                   double scale) {
  const std::size_t k = piece.points.size() - 1;
  if (k < 2) return -1;
  const BranchCurve c = branch_curve(g, piece);
  const std::vector<double> arcs = sample_branch(c, 0, c.length(), sampling);
  std::vector<Section> sections(arcs.size());
  for (std::size_t i = 0; i < arcs.size(); ++i) {
    sections[i].center = c.position(arcs[i]);
    sections[i].radius = c.radius_at(arcs[i]);
    sections[i].normal = c.tangent(arcs[i]);
  }
  std::vector<std::size_t> from;
  const std::vector<int> count = fold_free_chains(sections, scale, from);
  std::size_t broken = std::find(count.begin(), count.end(), 0) - count.begin(), before = broken - 1;
  if (broken == count.size()) {
    const auto [after, off] = furthest_dropped(sections, from);
    if (off <= kCutBend) return -1;
    broken = after, before = from[after];
  }
  const double r = sections[broken].radius;
  const double lo = arcs[before] - 2 * scale * r, hi = arcs[broken] + 2 * r;
  auto at = [&](double s) { return c.position(std::clamp(s, 0.0, c.length())); };
  int32_t sharpest = -1;
  double lowest = 1;  // cosine of the turn
  for (std::size_t i = 1; i < k; ++i) {
    const double s = c.arc[i];
    if (s < lo || s > hi) continue;
    const double reach = 2 * g.radius[piece.points[i]];
    const Vec3 in = (c.points[i] - at(s - reach)).normalized(),
               out = (at(s + reach) - c.points[i]).normalized();
    if (in.dot(out) < lowest) lowest = in.dot(out), sharpest = piece.points[i];
  }
  return sharpest;
}

/// Marks the branch's sharp corners: its points where it turns by more than kCornerJointDegrees, from
/// one edge to the next and a radius either side along the vessel (vessel_arc: jitter turns edges, not the
/// tube), and where the branch turns that far two radii either side of a point (a hairpin drawn over
/// several short edges: bent tighter than its radius), the sharpest such point, none within two radii of
/// another corner.
void mark_corners(const CenterlineGraph& g, const Branch& b, std::vector<char>& corner) {
  const std::size_t k = b.points.size() - 1;
  auto point = [&](std::size_t i) { return g.points[b.points[i]]; };
  const std::vector<double> arc = vessel_arc(g, b);
  auto at = [&](double s) {  // the polyline at arc length s, clamped to the branch
    s = std::clamp(s, 0.0, arc[k]);
    const std::size_t i =
        std::min<std::size_t>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin(), k) - 1;
    const double f = arc[i + 1] > arc[i] ? (s - arc[i]) / (arc[i + 1] - arc[i]) : 0.0;
    return Vec3((1 - f) * point(i) + f * point(i + 1));
  };
  auto sharp = [](const Vec3& in, const Vec3& out) {
    return in.dot(out) < kCornerJointCosine * in.norm() * out.norm();
  };
  // The way into point i from `reach` back along the vessel and out to `reach` on; none within half a
  // radius of the branch's ends, where a way a jitter long has any direction.
  auto turn = [&](std::size_t i, double reach) {
    const Vec3 in = point(i) - at(arc[i] - reach), out = at(arc[i] + reach) - point(i);
    const double r = g.radius[b.points[i]];
    const bool known = in.norm() >= 0.5 * r && out.norm() >= 0.5 * r;
    return known ? std::pair{in, out} : std::pair{Vec3(Vec3::Zero()), Vec3(Vec3::Zero())};
  };
  std::vector<std::pair<double, std::size_t>> bends;  // (cosine of the turn within reach, point)
  for (std::size_t i = 1; i < k; ++i) {
    const double r = g.radius[b.points[i]];
    if (sharp(point(i) - point(i - 1), point(i + 1) - point(i))) {
      const auto [in, out] = turn(i, r);
      if (sharp(in, out)) {
        corner[b.points[i]] = 1;
        continue;
      }
    }
    const auto [in, out] = turn(i, 2 * r);
    if (sharp(in, out)) bends.push_back({in.normalized().dot(out.normalized()), i});
  }
  std::sort(bends.begin(), bends.end());
  for (const auto& [cosine, i] : bends) {
    const double reach = 2 * g.radius[b.points[i]];
    bool clear = true;
    for (std::size_t j = i; clear && j > 1 && arc[i] - arc[j - 1] <= reach; --j)
      clear = !corner[b.points[j - 1]];
    for (std::size_t j = i; clear && j + 1 < k && arc[j + 1] - arc[i] <= reach; ++j)
      clear = !corner[b.points[j + 1]];
    if (clear) corner[b.points[i]] = 1;
  }
}

/// Branch b cut at its corners, which it marks in `corner` (its inner points only).
std::vector<Branch> cut_branch(const CenterlineGraph& g, const Branch& b, const SamplingOptions& sampling,
                               double scale, std::vector<char>& corner) {
  const std::size_t k = b.points.size() - 1;
  if (b.points.front() == b.points.back() && g.degree(b.points.front()) < 3 && !corner[b.points.front()])
    return {b};
  mark_corners(g, b, corner);
  std::vector<Branch> pieces;
  for (bool cut = true; cut;) {
    pieces.clear();
    std::size_t from = 0;
    for (std::size_t i = 1; i <= k; ++i) {
      if (i < k && !corner[b.points[i]]) continue;
      Branch piece;
      piece.points.assign(b.points.begin() + from, b.points.begin() + i + 1);
      piece.edges.assign(b.edges.begin() + from, b.edges.begin() + i);
      pieces.push_back(std::move(piece));
      from = i;
    }
    cut = false;
    for (const Branch& piece : pieces) {
      const int32_t bend = tight_bend(g, piece, sampling, scale);
      if (bend >= 0) corner[bend] = 1, cut = true;
    }
  }
  return pieces;
}

}  // namespace

/// Cuts the branches at their sharp corners (mark_corners), which then join their two pieces like any
/// joint: a convex patch between two squares, pushed along each piece until they clear each other. A
/// tube swept round such a corner folds on its inner side (within a few radii its two legs overlap, and
/// the smoothed tangent, spanning the legs, leaves the sections near the corner leaning along them).
/// Closed rings of degree-2 points are left whole.
CutBranches cut_at_corners(const CenterlineGraph& g, const SamplingOptions& sampling, double scale,
                           const std::vector<int32_t>& also) {
  CutBranches out;
  std::vector<char>& corner = out.corner;
  corner.assign(g.points.size(), 0);
  for (int32_t v : also) corner[v] = 1;
  std::vector<std::vector<Branch>> pieces(g.branches.size());
  parallel_for(
      g.branches.size(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) pieces[i] = cut_branch(g, g.branches[i], sampling, scale, corner);
      },
      kBranchesPerTask);
  for (std::vector<Branch>& p : pieces)
    for (Branch& piece : p) out.branches.push_back(std::move(piece));
  return out;
}

}  // namespace vesselmesh
