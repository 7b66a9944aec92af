#pragma once
// What `vesselmesh info` tells about an input: the graph's counts, what normalisation changed, and the
// places where its tubes overlap (where the surface presses the two tubes flat against each other, or,
// where they cross, the separate stage moves them apart).

#include <string>

#include "vesselmesh/graph/centerline_graph.hpp"

namespace vesselmesh {

/// The figures `vesselmesh info` prints, as JSON text: points, edges, components, branches, joints,
/// terminals, max_degree, loops, radius {min, max, per}, bbox {min, max}, normalisation {...}, and
/// overlaps [{at, radius, edge_pairs, crossing_pairs}] (tube_overlaps; crossing_pairs: those that
/// cross, which the mesh's separate stage moves apart).
std::string summary_json(const CenterlineGraph& graph, int indent = 2);

}  // namespace vesselmesh
