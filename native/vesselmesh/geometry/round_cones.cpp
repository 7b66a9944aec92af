#include "vesselmesh/geometry/round_cones.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "vesselmesh/frames/frames.hpp"
#include "vesselmesh/geometry/closest_point.hpp"
#include "vesselmesh/graph/union_find.hpp"
#include "vesselmesh/parallel.hpp"

namespace vesselmesh {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNearTube = 1.5;    // a point is near a centerline edge within this many local radii
constexpr double kCrowd = 0.5;       // radii between two tubes that count as crowding each other
// Tubes within this fraction of their radii of touching count as touching: where a tracing has two
// vessels exactly touching, rounding (of where the data set lies, say) must not decide whether they do.
constexpr double kTouch = 1e-9;

struct Ball {
  Vec3 centre;
  double radius;
};

using Pieces = std::vector<std::array<double, 2>>;  // parameter intervals of a segment

// The parameter interval of segment c0 → c1 inside the ball (empty: lo ≥ hi).
std::array<double, 2> inside(const Vec3& c0, const Vec3& c1, const Ball& ball) {
  const Vec3 d = c1 - c0;
  const Vec3 m = c0 - ball.centre;
  const double a = d.squaredNorm(), b = d.dot(m),
               discriminant = b * b - a * (m.squaredNorm() - ball.radius * ball.radius);
  if (a == 0 || discriminant <= 0) return {1.0, 0.0};
  return {(-b - std::sqrt(discriminant)) / a, (-b + std::sqrt(discriminant)) / a};
}

// The parts of a segment's parameters [0, 1] outside every one of `holes`.
Pieces outside(const Pieces& holes) {
  Pieces pieces = {{0.0, 1.0}};
  for (const auto& [enter, leave] : holes) {
    if (enter >= leave) continue;
    Pieces kept;
    for (const auto& [lo, hi] : pieces) {
      if (std::min(hi, enter) > lo) kept.push_back({lo, std::min(hi, enter)});
      if (hi > std::max(lo, leave)) kept.push_back({std::max(lo, leave), hi});
    }
    pieces = std::move(kept);
  }
  return pieces;
}

std::vector<RoundCone> round_cones(const CenterlineGraph& g) {
  std::vector<RoundCone> cones(g.edges.size());
  for (std::size_t b = 0; b < g.branches.size(); ++b)
    for (std::size_t i = 0; i < g.branches[b].edges.size(); ++i) {
      const int32_t e = g.branches[b].edges[i];
      cones[e] = {g.points[g.edges[e][0]], g.points[g.edges[e][1]], g.end_radius[e][0],
                  g.end_radius[e][1],      static_cast<int32_t>(b), static_cast<int32_t>(i)};
    }
  return cones;
}

// Each cone's box: round each end, the larger of its own radius and `reach` times the cone's larger
// radius (0 for the cone itself; more to hold the neighbourhood that counts as near it).
std::vector<Box> boxes(const std::vector<RoundCone>& cones, double reach) {
  std::vector<Box> out(cones.size());
  for (std::size_t e = 0; e < cones.size(); ++e) {
    const RoundCone& k = cones[e];
    const double r = reach * std::max(k.r0, k.r1), r0 = (1 + kTouch) * std::max(k.r0, r),
                 r1 = (1 + kTouch) * std::max(k.r1, r);
    out[e].extend(k.c0 - Vec3::Constant(r0));
    out[e].extend(k.c0 + Vec3::Constant(r0));
    out[e].extend(k.c1 - Vec3::Constant(r1));
    out[e].extend(k.c1 + Vec3::Constant(r1));
  }
  return out;
}

std::vector<TerminalCap> terminal_caps(const CenterlineGraph& g) {
  std::vector<TerminalCap> caps;
  for (int32_t v = 0; v < static_cast<int32_t>(g.points.size()); ++v) {
    if (g.degree(v) != 1) continue;
    const int32_t e = g.incident[g.offsets[v]];
    const Vec3 axis = (g.points[v] - g.points[g.other(e, v)]).normalized();
    caps.push_back({g.points[v], axis, g.end_radius[e][g.edges[e][0] == v ? 0 : 1]});
  }
  return caps;
}

std::vector<Box> cap_boxes(const std::vector<TerminalCap>& caps) {
  std::vector<Box> boxes(caps.size());
  for (std::size_t i = 0; i < caps.size(); ++i) {
    boxes[i].extend(caps[i].centre - Vec3::Constant(2 * caps[i].radius));
    boxes[i].extend(caps[i].centre + Vec3::Constant(2 * caps[i].radius));
  }
  return boxes;
}

}  // namespace

ConeDistance cone_distance(const RoundCone& k, const Vec3& p) {
  auto from_sphere = [&](const Vec3& centre, double r) {
    const Vec3 d = p - centre;
    const double n = d.norm();
    return ConeDistance{n - r, r, n > 0 ? Vec3(d / n) : any_perpendicular(k.c1 - k.c0)};
  };
  const double length = (k.c1 - k.c0).norm();
  if (length <= std::abs(k.r0 - k.r1))  // one end sphere holds the other
    return k.r0 >= k.r1 ? from_sphere(k.c0, k.r0) : from_sphere(k.c1, k.r1);
  // In the half-plane of p and the axis, with t along the axis from c0 and ρ away from it, the side
  // of the cone is the segment from r0·n to (L, 0) + r1·n with outward normal n = (sinφ, cosφ).
  const Vec3 axis = (k.c1 - k.c0) / length;
  const Vec3 d = p - k.c0;
  const double t = d.dot(axis);
  const Vec3 off_axis = d - t * axis;
  const double rho = off_axis.norm();
  const double sin_phi = (k.r0 - k.r1) / length;
  const double cos_phi = std::sqrt(1.0 - sin_phi * sin_phi);
  const double along = t * cos_phi - rho * sin_phi;  // position along the side, 0 where it leaves sphere 0
  const double side_length = length * cos_phi;
  if (along <= 0) return from_sphere(k.c0, k.r0);
  if (along >= side_length) return from_sphere(k.c1, k.r1);
  const Vec3 radial = rho > 0 ? Vec3(off_axis / rho) : any_perpendicular(axis);
  return {t * sin_phi + rho * cos_phi - k.r0, k.radius_at(along / side_length),
          sin_phi * axis + cos_phi * radial};
}

RoundCones::RoundCones(const CenterlineGraph& g)
    : graph_(g),
      cones_(round_cones(g)),
      tight_(boxes(cones_, 0.0)),
      near_(boxes(cones_, kNearTube)),
      caps_(terminal_caps(g)),
      cap_bvh_(cap_boxes(caps_)),
      crowded_(cones_.size(), 0),
      leads_out_(cones_.size(), {-1.0, -1.0}),
      arc_(cones_.size(), {0.0, 0.0}) {
  // A branch's edges from each of its ends for as long as they start within the end's reach, with how
  // far from the end the branch has been up to there.
  const std::vector<double> length = vessel_lengths(g);
  for (const Branch& b : g.branches) {
    const std::size_t n = b.edges.size();
    const int32_t first = b.points.front(), last = b.points.back();
    double farthest = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double from_first = (g.points[b.points[i]] - g.points[first]).norm();
      if (from_first >= kJointReach * g.radius[first]) break;
      farthest = std::max(farthest, from_first);
      leads_out_[b.edges[i]][0] = farthest;
    }
    farthest = 0;
    for (std::size_t i = n; i > 0; --i) {
      const double from_last = (g.points[b.points[i]] - g.points[last]).norm();
      if (from_last >= kJointReach * g.radius[last]) break;
      farthest = std::max(farthest, from_last);
      leads_out_[b.edges[i - 1]][1] = farthest;
    }
    double arc = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const int32_t e = b.edges[i];
      const double next = arc + length[e];
      arc_[e] =
          g.edges[e][0] == b.points[i] ? std::array<double, 2>{arc, next} : std::array<double, 2>{next, arc};
      arc = next;
    }
  }
  near_.for_each_overlapping_pair([&](int32_t e, int32_t f) {
    const RoundCone& k = cones_[e];
    const RoundCone& l = cones_[f];
    if (k.branch != l.branch && overlap(e, f, kCrowd * std::max({k.r0, k.r1, l.r0, l.r1})) != Overlap::none)
      crowded_[e] = crowded_[f] = any_crowded_ = 1;
  });
}

ConeDistance RoundCones::nearest(const Vec3& p, int32_t* hint, bool exact_inside) const {
  ConeDistance best{kInf, 0.0, Vec3::Zero()};
  int32_t best_cone = -1;
  // A cone near the last point's is likely near this one: it bounds the search from the start.
  if (hint != nullptr && *hint >= 0 && *hint < static_cast<int32_t>(cones_.size()))
    best = cone_distance(cones_[*hint], p), best_cone = *hint, best.branch = cones_[*hint].branch;
  double limit = exact_inside || best.distance >= 0 ? best.distance : -kInf;
  // A cone inside a box is no nearer than the box's signed distance.
  tight_.search([&](const Box& b) { return b.signed_distance(p); }, limit,
                [&](int32_t e) {
                  const ConeDistance d = cone_distance(cones_[e], p);
                  if (d.distance < best.distance) best = d, best_cone = e, best.branch = cones_[e].branch;
                  // Inside one cone is inside the union: the sign is all that is asked.
                  limit = exact_inside || best.distance >= 0 ? best.distance : -kInf;
                });
  if (hint != nullptr) *hint = best_cone;
  return best;
}

std::vector<double> local_radius(const std::vector<Vec3>& points, const RoundCones& cones) {
  std::vector<double> radius(points.size(), 0.0);
  if (cones.size() == 0) return radius;
  parallel_for(points.size(), [&](std::size_t begin, std::size_t end) {
    int32_t hint = -1;  // consecutive points are mostly near each other
    for (std::size_t i = begin; i < end; ++i) radius[i] = cones.nearest(points[i], &hint).radius;
  });
  return radius;
}

ConeDistance RoundCones::deepest(const Vec3& p, double depth) const {
  ConeDistance best{kInf, 0.0, Vec3::Zero()};
  double limit = -depth;
  tight_.search([&](const Box& b) { return b.signed_distance(p); }, limit,
                [&](int32_t e) {
                  const ConeDistance d = cone_distance(cones_[e], p);
                  if (d.distance < limit) best = d, best.branch = cones_[e].branch, limit = d.distance;
                });
  return best;
}

std::vector<ConeDistance> RoundCones::within(const Vec3& p, double margin) const {
  std::vector<ConeDistance> out;
  tight_.search([&](const Box& b) { return b.signed_distance(p); }, margin,
                [&](int32_t e) {
                  ConeDistance d = cone_distance(cones_[e], p);
                  d.branch = cones_[e].branch;
                  d.cone = e;
                  if (d.distance < margin) out.push_back(d);
                });
  return out;
}

bool RoundCones::leads_out_of(int32_t e, int32_t joint) const {
  const Branch& b = graph_.branches[cones_[e].branch];
  return (b.points.front() == joint && leads_out_[e][0] >= 0) ||
         (b.points.back() == joint && leads_out_[e][1] >= 0);
}

void RoundCones::coming_back(int32_t e, int32_t joint, const std::array<double, 2>& in_ball,
                             std::vector<std::array<double, 2>>& back) const {
  const Branch& b = graph_.branches[cones_[e].branch];
  const RoundCone& k = cones_[e];
  for (int end : {0, 1}) {
    if ((end == 0 ? b.points.front() : b.points.back()) != joint) continue;
    const double nearer = leads_out_[e][end] - graph_.radius[joint];  // negative where e does not lead out
    if (nearer <= 0) continue;
    const std::array<double, 2> in = inside(k.c0, k.c1, {graph_.points[joint], nearer});
    const double lo = std::max({in[0], in_ball[0], 0.0}), hi = std::min({in[1], in_ball[1], 1.0});
    if (lo < hi) back.push_back({lo, hi});
  }
}

bool RoundCones::meet_near(int32_t a, int32_t b, const Vec3& p) const {
  for (int32_t j : shared_joints(a, b))
    if ((graph_.points[j] - p).norm() < kJointReach * graph_.radius[j]) return true;
  return false;
}

std::vector<int32_t> RoundCones::shared_joints(int32_t a, int32_t b) const {
  const Branch& x = graph_.branches[a];
  const Branch& y = graph_.branches[b];
  std::vector<int32_t> joints;
  const std::array<int32_t, 2> ends = {x.points.front(), x.points.back()};  // the same point for a ring
  for (int i = 0; i < (ends[1] == ends[0] ? 1 : 2); ++i)
    if (ends[i] == y.points.front() || ends[i] == y.points.back()) joints.push_back(ends[i]);
  return joints;
}

bool RoundCones::inside_other_branch(const Vec3& p, int32_t branch) const {
  bool inside = false;
  double limit = 0.0;  // only the boxes that hold p can hold a cone that holds it
  tight_.search([&](const Box& b) { return b.signed_distance(p); }, limit,
                [&](int32_t e) {
                  if (cones_[e].branch != branch && cone_distance(cones_[e], p).distance < 0 &&
                      !meet_near(branch, cones_[e].branch, p))
                    inside = true, limit = -kInf;
                });
  return inside;
}

bool RoundCones::near_cap(const Vec3& p) const {
  bool near = false;
  cap_bvh_.search([&](const Box& b) { return b.signed_distance(p); }, 0.0,
                  [&](int32_t i) {
                    const Vec3 d = p - caps_[i].centre;
                    near =
                        near || (d.norm() < 2 * caps_[i].radius && d.dot(caps_[i].axis) > -caps_[i].radius);
                  });
  return near;
}

bool RoundCones::in_overlapping_tubes(const Vec3& p, const Vec3& q) const {
  const std::vector<int32_t> near_p = near_edges(p), near_q = near_edges(q);
  for (int32_t e : near_p)
    for (int32_t f : near_q)
      if (cones_[e].branch != cones_[f].branch ? overlap(e, f) != Overlap::none : folds_onto(e, f))
        return true;
  return false;
}

// Whether two edges of one branch overlap where the branch comes back onto itself: parts of them that lie
// more than kJointReach radii (of each) apart along the branch come within the sum of their radii. Parts
// nearer along it merely turn together, as two branches merely meet within that reach of their joint.
// Each edge is cut into at most 8 pieces, compared pairwise by their nearest points. With `margin`,
// parts that come within it of each other count too.
bool RoundCones::folds_onto(int32_t e, int32_t f, double margin) const {
  if (e == f) return false;
  const Branch& b = graph_.branches[cones_[e].branch];
  const bool ring = b.points.front() == b.points.back();
  const double length = branch_length(cones_[e].branch);
  const RoundCone& k = cones_[e];
  const RoundCone& l = cones_[f];
  // Edges whose points all lie within the smallest reach of each other along the branch only turn
  // together (most pairs of neighbouring edges of a densely sampled branch): no piece needs a look.
  double farthest = 0;
  for (double x : arc_[e])
    for (double y : arc_[f]) farthest = std::max(farthest, std::abs(x - y));
  if (farthest <= kJointReach * (std::min(k.r0, k.r1) + std::min(l.r0, l.r1))) return false;
  constexpr int kPieces = 8;
  for (int i = 0; i < kPieces; ++i)
    for (int j = 0; j < kPieces; ++j) {
      const double s0 = double(i) / kPieces, s1 = double(i + 1) / kPieces;
      const double t0 = double(j) / kPieces, t1 = double(j + 1) / kPieces;
      const auto [u, v] = closest_parameters(k.point_at(s0), k.point_at(s1), l.point_at(t0), l.point_at(t1));
      const double s = s0 + u * (s1 - s0), t = t0 + v * (t1 - t0);
      const double rs = k.radius_at(s), rt = l.radius_at(t);
      if ((k.point_at(s) - l.point_at(t)).norm() >= (1 + kTouch) * (rs + rt) + margin) continue;
      const double apart = std::abs(arc_at(e, s) - arc_at(f, t));
      if (std::min(apart, ring ? length - apart : apart) > kJointReach * (rs + rt)) return true;
    }
  return false;
}

std::vector<int32_t> RoundCones::near_edges(const Vec3& p) const {
  std::vector<int32_t> near;
  near_.search([&](const Box& b) { return b.signed_distance(p); }, 0.0,
               [&](int32_t e) {
                 const RoundCone& k = cones_[e];
                 const double s = closest_parameters(k.c0, k.c1, p, p).first;
                 if ((p - k.point_at(s)).norm() < kNearTube * k.radius_at(s)) near.push_back(e);
               });
  return near;
}

// Whether the tubes of edges e and f (of different branches) overlap, or come within `margin` of each
// other, away from the joints their branches share: near a shared joint they meet by design, which is no
// overlap of the input. Only edges that both lead out of the joint meet there: a branch that has left
// the joint's reach and comes back through its neighbour's tube overlaps it, and so does one that comes
// back within the reach, over a joint radius nearer the joint than it has been (fixture
// `thin_hook_through_its_fat_joint`).
RoundCones::Overlap RoundCones::overlap(int32_t e, int32_t f, double margin) const {
  const RoundCone& k = cones_[e];
  const RoundCone& l = cones_[f];
  Pieces in_e, in_f, back_e, back_f;  // in the joints' balls; of those, coming back
  for (int32_t j : shared_joints(k.branch, l.branch))
    if (leads_out_of(e, j) && leads_out_of(f, j)) {
      const Ball ball{graph_.points[j], kJointReach * graph_.radius[j]};
      in_e.push_back(inside(k.c0, k.c1, ball));
      in_f.push_back(inside(l.c0, l.c1, ball));
      coming_back(e, j, in_e.back(), back_e);
      coming_back(f, j, in_f.back(), back_f);
    }
  auto meet = [&](const Pieces& ps, const Pieces& qs) {
    for (const auto& [s0, s1] : ps)
      for (const auto& [t0, t1] : qs) {
        const auto [u, v] =
            closest_parameters(k.point_at(s0), k.point_at(s1), l.point_at(t0), l.point_at(t1));
        const double s = s0 + u * (s1 - s0), t = t0 + v * (t1 - t0);
        if ((k.point_at(s) - l.point_at(t)).norm() <
            (1 + kTouch) * (k.radius_at(s) + l.radius_at(t)) + margin)
          return true;
      }
    return false;
  };
  const Pieces whole = {{0.0, 1.0}};
  if (meet(outside(in_e), outside(in_f))) return Overlap::apart_from_joints;
  if (meet(back_e, whole)) return Overlap::first_comes_back;
  if (meet(whole, back_f)) return Overlap::second_comes_back;
  return Overlap::none;
}

std::vector<std::array<int32_t, 2>> RoundCones::overlapping_edges(double gap, std::size_t most) const {
  std::vector<std::array<int32_t, 2>> out;
  // Boxes widened by kNearTube radii hold every pair within half the sum of their radii of each other.
  (gap > 0 ? near_ : tight_).for_each_overlapping_pair([&](int32_t e, int32_t f) {
    if (out.size() <= most && tubes_overlap(e, f, gap)) out.push_back({std::min(e, f), std::max(e, f)});
  });
  std::sort(out.begin(), out.end());
  return out;
}

double RoundCones::gap_margin(int32_t e, int32_t f, double gap) const {
  return gap * (std::max(cones_[e].r0, cones_[e].r1) + std::max(cones_[f].r0, cones_[f].r1));
}

bool RoundCones::tubes_overlap(int32_t e, int32_t f, double gap) const {
  const double margin = gap_margin(e, f, gap);
  return cones_[e].branch != cones_[f].branch ? overlap(e, f, margin) != Overlap::none
                                              : folds_onto(e, f, margin);
}

int32_t RoundCones::coming_back_of(int32_t e, int32_t f, double gap) const {
  if (cones_[e].branch == cones_[f].branch) return -1;
  switch (overlap(e, f, gap_margin(e, f, gap))) {
    case Overlap::first_comes_back:
      return e;
    case Overlap::second_comes_back:
      return f;
    default:
      return -1;
  }
}

std::vector<TubeOverlap> tube_overlaps(const CenterlineGraph& g) { return tube_overlaps(g, RoundCones(g)); }

std::vector<TubeOverlap> tube_overlaps(const CenterlineGraph& g, const RoundCones& cones,
                                       const std::vector<std::array<int32_t, 2>>& crossing) {
  const std::vector<std::array<int32_t, 2>> pairs = cones.overlapping_edges();
  // Edges of overlapping pairs, joined across each pair and to their neighbours along the graph that
  // overlap too: two vessels side by side along many edges make one place.
  std::vector<char> overlapping(g.edges.size(), 0);
  UnionFind places(g.edges.size());
  for (const auto& [e, f] : pairs) overlapping[e] = overlapping[f] = 1, places.unite(e, f);
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    if (overlapping[e])
      for (int32_t v : g.edges[e])
        for (int32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k)
          if (overlapping[g.incident[k]]) places.unite(static_cast<int32_t>(e), g.incident[k]);
  std::vector<TubeOverlap> out;
  std::vector<int32_t> slot(g.edges.size(), -1);  // per place representative: its index in out
  for (const auto& [e, f] : pairs) {
    int32_t& i = slot[places.find(e)];
    if (i < 0) {
      i = static_cast<int32_t>(out.size());
      out.push_back({Vec3::Zero(), 0.0, 0});
    }
    const RoundCone& k = cones.cone(e);
    const RoundCone& l = cones.cone(f);
    const auto [s, t] = closest_parameters(k.c0, k.c1, l.c0, l.c1);
    TubeOverlap& o = out[i];
    o.at += 0.5 * (k.point_at(s) + l.point_at(t));  // a sum until the end
    o.edge_pairs += 1;
    o.crossing_pairs += std::binary_search(crossing.begin(), crossing.end(), std::array<int32_t, 2>{e, f});
    o.radius = std::max({o.radius, k.radius_at(s), l.radius_at(t)});
  }
  for (TubeOverlap& o : out) o.at /= static_cast<double>(o.edge_pairs);
  return out;
}

}  // namespace vesselmesh
