#pragma once
// The input's tubes: every centerline edge as a round cone (spheres of the end radii round its two
// points and the cone tangent to both), gathered in a bounding-volume hierarchy. Their union is the
// vessel the file describes, but for its ends, where the surface is capped instead: the fit stage brings
// the surface onto it, and the checker measures radius fidelity against it, both away from the caps.

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "vesselmesh/geometry/bvh.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"

namespace vesselmesh {

/// Two branches merely meet within this many joint radii of the joint they share; parts of one branch
/// nearer each other than this many radii along it merely turn together.
constexpr double kJointReach = 3.0;

/// One centerline edge: spheres of radius r0, r1 round c0, c1 and the cone tangent to both.
struct RoundCone {
  Vec3 c0, c1;
  double r0, r1;
  int32_t branch;  ///< the cone is edges[index] of branches[branch]
  int32_t index = 0;
  double radius_at(double s) const { return r0 + s * (r1 - r0); }
  Vec3 point_at(double s) const { return c0 + s * (c1 - c0); }
};

struct ConeDistance {
  double distance;      ///< signed: negative inside
  double radius;        ///< of the sphere of the cone's family (centres on the axis, radii linear) touching
                        ///< the surface where the point is closest
  Vec3 direction;       ///< unit, from the closest surface point towards the point when it is outside (the
                        ///< gradient of the distance)
  int32_t branch = -1;  ///< of the cone (RoundCones::nearest)
  int32_t cone = -1;    ///< the cone itself (RoundCones::within)
};

/// The end of a terminal, where the surface is capped rather than round: the terminal point, the axis
/// pointing out of the tube, and the radius there.
struct TerminalCap {
  Vec3 centre, axis;
  double radius;
};

class RoundCones;

/// A place where the input's tubes overlap (two vessels crossing, touching, or traced along each other;
/// a branch looping back onto itself): the union of the tubes has a handle there that the graph lacks, so
/// a surface of the graph's genus cannot follow both tubes there. The fit presses the two surfaces flat
/// against each other where it can; where it cannot (one tube mostly inside the other), they cross.
struct TubeOverlap {
  Vec3 at;                     ///< mean of the overlapping edges' closest axis points
  double radius;               ///< the largest radius there
  int64_t edge_pairs;          ///< overlapping edge pairs it gathers
  int64_t crossing_pairs = 0;  ///< of those, the ones in tube_overlaps' `crossing` list
};

/// The places where the tubes of `cones`' graph `g` overlap (RoundCones::overlapping_edges), overlapping
/// edge pairs joined into one place where they share an edge or their edges are neighbours along the
/// graph; ordered by position in the file (their first edge). Each counts its pairs that are in
/// `crossing` (sorted, as crossing_edges gives them).
std::vector<TubeOverlap> tube_overlaps(const CenterlineGraph& g, const RoundCones& cones,
                                       const std::vector<std::array<int32_t, 2>>& crossing = {});
/// The same with the graph's own round cones.
std::vector<TubeOverlap> tube_overlaps(const CenterlineGraph& g);

/// Signed distance from `p` to the surface of round cone `k`.
ConeDistance cone_distance(const RoundCone& k, const Vec3& p);

/// The radius of the tubes at each point: that of the nearest cone's sphere touching the tubes' surface
/// where the point is closest (ConeDistance::radius); 0 without cones. What curvature is multiplied by to
/// show a vessel's shape whatever its size: a straight tube has mean curvature × radius 1/2.
std::vector<double> local_radius(const std::vector<Vec3>& points, const RoundCones& cones);

class RoundCones {
 public:
  explicit RoundCones(const CenterlineGraph& g);

  /// The signed distance from `p` to the union of the cones (the smallest over the cones, exact
  /// outside the union), with the nearest cone's local radius and direction; distance +inf without cones.
  /// `hint`, when given, is a cone to try first (the nearest to a point close by: much faster for a
  /// sequence of nearby points), and receives the nearest cone. Without `exact_inside`, the search
  /// stops at the first cone that holds `p`: the distance is then only known to be negative.
  ConeDistance nearest(const Vec3& p, int32_t* hint = nullptr, bool exact_inside = true) const;

  /// Of the cones that hold `p` deeper than `depth` (> 0), the one that holds it deepest, with its
  /// (negative) distance; distance +inf when none does. Cheap when few do.
  ConeDistance deepest(const Vec3& p, double depth) const;

  /// The cones closer to `p` than `margin` (those that hold it, and for margin > 0 those just outside),
  /// each with its distance and branch.
  std::vector<ConeDistance> within(const Vec3& p, double margin) const;

  /// True when branches `a` and `b` share a joint within the reach of the joint round `p` (3 joint radii),
  /// where their tubes merely meet.
  bool meet_near(int32_t a, int32_t b, const Vec3& p) const;

  const RoundCone& cone(int32_t e) const { return cones_[e]; }
  std::size_t size() const { return cones_.size(); }

  /// Arc length along cone `e`'s branch (measured along the vessel: vessel_lengths), from the branch's first
  /// point, at parameter `s` of the cone (0 at c0, 1 at c1).
  double arc_at(int32_t e, double s) const { return arc_[e][0] + s * (arc_[e][1] - arc_[e][0]); }
  /// Arc length at point `i` of branch `b` (branches[b].points[i]).
  double arc_at_point(int32_t b, int32_t i) const {
    const std::vector<int32_t>& edges = graph_.branches[b].edges;
    return i == 0 ? 0.0 : std::max(arc_[edges[i - 1]][0], arc_[edges[i - 1]][1]);
  }
  /// The length of branch `b`'s axis.
  double branch_length(int32_t b) const {
    return arc_at_point(b, static_cast<int32_t>(graph_.branches[b].edges.size()));
  }

  /// True when cone `e`'s tube comes within half a radius of a tube of another branch, away from the
  /// joints the two share: only near such a cone can a point on its surface lie in another vessel's tube
  /// where the two do not merely meet.
  bool crowded(int32_t e) const { return crowded_[e]; }
  /// True when some cone is crowded.
  bool any_crowded() const { return any_crowded_; }

  /// True when `p` lies inside a cone of a branch other than `branch`, one that does not merely meet it
  /// at a joint near `p` (inside a joint's sphere, a soma's, every branch there holds the point).
  bool inside_other_branch(const Vec3& p, int32_t branch) const;

  /// True when `p` and `q` are near edges of two different branches whose tubes overlap, or of one
  /// branch that comes back onto itself (folds_onto).
  bool in_overlapping_tubes(const Vec3& p, const Vec3& q) const;

  /// True near a terminal's end, where the surface is capped rather than round: within 2 radii of the
  /// terminal point and less than a radius behind its section (or beyond it).
  bool near_cap(const Vec3& p) const;

  /// The pairs of edges (e < f) whose tubes overlap as in_overlapping_tubes() counts it: of two branches
  /// away from the joints they share, or of one branch that comes back onto itself. With `gap` > 0 (at
  /// most 0.5), also those whose tubes come within `gap` times the sum of their larger radii of each other.
  /// Past `most` pairs it tests no more (a caller asking whether there are that many: a tangle).
  std::vector<std::array<int32_t, 2>> overlapping_edges(
      double gap = 0, std::size_t most = std::numeric_limits<std::size_t>::max()) const;
  /// True when overlapping_edges(gap) holds the pair (e, f).
  bool tubes_overlap(int32_t e, int32_t f, double gap = 0) const;

  /// Of a pair that tubes_overlap(e, f, gap) holds, on branches sharing a joint: the edge (e or f) whose
  /// branch overlaps the other only where it comes back towards that joint (a hook through the joint's
  /// own tubes), or −1.
  int32_t coming_back_of(int32_t e, int32_t f, double gap = 0) const;

 private:
  std::vector<int32_t> near_edges(const Vec3& p) const;
  /// How the tubes of e and f (of different branches) overlap, see overlapping_edges: away from the joints
  /// their branches share, or only where one of them comes back towards such a joint.
  enum class Overlap { none, apart_from_joints, first_comes_back, second_comes_back };
  Overlap overlap(int32_t e, int32_t f, double margin = 0) const;
  bool folds_onto(int32_t e, int32_t f, double margin = 0) const;
  /// The margin tubes_overlap(e, f, gap) allows: gap times the sum of the two widest radii.
  double gap_margin(int32_t e, int32_t f, double gap) const;
  std::vector<int32_t> shared_joints(int32_t a, int32_t b) const;
  bool leads_out_of(int32_t e, int32_t joint) const;
  /// Adds to `back` the part of `in_ball` (edge e's parameters in the reach of `joint`) where e's branch
  /// comes back over a joint radius nearer the joint than it has been.
  void coming_back(int32_t e, int32_t joint, const std::array<double, 2>& in_ball,
                   std::vector<std::array<double, 2>>& back) const;

  const CenterlineGraph& graph_;
  std::vector<RoundCone> cones_;
  Bvh tight_;  ///< over each cone's box, for nearest()
  Bvh near_;   ///< over each cone's box widened to what counts as near it, for near_edges()
  std::vector<TerminalCap> caps_;
  Bvh cap_bvh_;  ///< over each cap's neighbourhood, for near_cap()
  std::vector<char> crowded_;  ///< per cone, see crowded()
  bool any_crowded_ = false;
  /// Per cone: for the edges leading out of its branch's first (0) or last (1) point, those that start
  /// within the point's joint reach, the farthest from that point the branch has been at the edge's
  /// start; −1 for the others.
  std::vector<std::array<double, 2>> leads_out_;
  std::vector<std::array<double, 2>> arc_;  ///< per cone: arc length along its branch at c0 and c1 (arc_at)
};

}  // namespace vesselmesh
