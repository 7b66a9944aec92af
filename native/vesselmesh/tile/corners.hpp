#pragma once
// Where a branch bends too sharply for a tube (a turn over 120° at one point or within two radii of
// one, a bend tighter than its squares' corners reach, or one the tube gets round only by dropping
// sections that stand over half a radius off it), the base mesh cuts it and tiles the point as a joint
// of its two pieces.

#include <vector>

#include "vesselmesh/graph/centerline_graph.hpp"
#include "vesselmesh/sample/sample.hpp"

namespace vesselmesh {

/// Branches per task where the tiling works on every core at once: each costs a sampling of the branch.
constexpr std::size_t kBranchesPerTask = 16;

struct CutBranches {
  std::vector<Branch> branches;  ///< the graph's branches, cut at the corners
  std::vector<char> corner;      ///< per point: a corner, tiled as a joint of two branches
};

/// The graph's branches cut at their sharp corners, and at the points in `also` (degree 2); closed rings of
/// degree-2 points are left whole. The branches are cut on every core at once (each marks only its own
/// inner points). Sections are sampled as `sampling` says, their corners at `scale` × radius.
CutBranches cut_at_corners(const CenterlineGraph& g, const SamplingOptions& sampling, double scale,
                           const std::vector<int32_t>& also = {});

}  // namespace vesselmesh
