#pragma once
// separate: the input's crossing vessels moved apart before the surface is built. Where two vessels'
// tubes overlap away from any joint the graph gives them (two vessels crossing like an X, a terminal
// traced back along another vessel, a branch looping back through its parent), the union of the tubes
// has a handle that the graph lacks: a closed surface of the graph's genus that follows both tubes must
// cross itself there. Real vessels do not pass through each other; the tracing put them too close. So
// the centerline points there move apart, each vessel by the same share of its own radius, each move
// spread smoothly along its branch, until the two tubes lie a little apart. Tubes that overlap where
// they leave a joint they share (a fork at a small angle) are no crossing within the joint's reach
// (kJointReach times the sum of their radii from it): they stay, and the fit presses the two surfaces
// flat against each other there. Beyond it they are parted like any others: two vessels that run on
// side by side from a joint, their tubes overlapping all along (a child traced back along its parent),
// would otherwise leave the joint's squares no place where each clears the other, and the joint's
// patch would span both, a fin along them.

#include <array>
#include <cstdint>
#include <vector>

#include "vesselmesh/geometry/round_cones.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"

namespace vesselmesh {

/// How the pipeline treats the input's crossing vessels.
enum class Crossings {
  separate,  ///< move them apart (separate_crossings)
  keep,      ///< leave the centerline as it is: the surface crosses itself where they do
};

/// The pairs of edges (e < f) of `g` (whose round cones `cones` holds) whose tubes cross: they overlap,
/// or come within `gap` of each other (RoundCones::overlapping_edges), their closest axis points lie
/// more than kJointReach times the sum of their radii apart along the graph, and the two do not overlap
/// all the way back to a joint their branches share that lies within that distance of both along their
/// branches.
std::vector<std::array<int32_t, 2>> crossing_edges(const CenterlineGraph& g, const RoundCones& cones,
                                                   double gap = 0);

struct Separation {
  CenterlineGraph graph;     ///< the input, the vessels moved apart (with points added where they were)
  int64_t crossings = 0;     ///< edge pairs to move apart in the input: crossing, or passing close by a joint
                             ///< (where the input is a tangle already, its overlapping pairs, counted up to
                             ///< just past the tangle's)
  int64_t moved_points = 0;  ///< points moved
  double largest_move = 0;   ///< the largest move, relative to the moved point's radius
  int64_t left = 0;          ///< such pairs left when the rounds ran out (0 but in a tangle)
  bool tangle = false;       ///< the vessels were too dense to part (every piece of tube overlapping dozens
                             ///< of others), and were left as they were
};

/// Moves the crossing vessels of `g` (whose round cones `cones` holds) apart, and those passing within the
/// gap below of the tubes round a joint of another vessel that they do not share. First each such edge
/// gets points a quarter of the two radii apart round where it crosses (the tubes stay the same), so that
/// a coarse tracing bends there rather than shifts whole edges. Then, in rounds until no edges cross (at
/// most 8), each crossing pair's two tubes move apart along the line between their closest axis points,
/// each by the same share of its own radius, until they lie about a fifth of the sum of their radii apart;
/// each move fades along its branch as a cosine over kJointReach times the sum of the radii either side. A
/// point asked to move by several pairs in one round takes the largest move, and then each round's moves
/// are averaged along their branch over a Gaussian of arc length, σ two radii, so that the axis does not
/// zigzag; joints stay where they are (their patches with them). Vessels too dense to part (after the
/// points are added, each edge's tube overlapping dozens of others on average: a tangle) are left as they
/// are, with `tangle` set. The topology and the radii are kept; a graph without crossings comes back as it
/// is.
Separation separate_crossings(const CenterlineGraph& g, const RoundCones& cones);

}  // namespace vesselmesh
