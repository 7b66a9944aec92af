#pragma once
// fit: the subdivided surface pulled into the input's tubes. A Loop limit surface is smooth, so where
// the tubes it follows meet at an angle it bridges the concave side: it webs the crotch of a
// bifurcation (by up to half a radius on a narrow one) and fills the inner side of a sharp bend,
// outside the union of the centerline's round cones. Each vertex outside that union moves onto its
// surface the shortest way; vertices inside it stay, so that no vertex is pushed towards another vessel.

#include <cstdint>

#include "vesselmesh/graph/centerline_graph.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

struct FitStats {
  int64_t moved = 0;      ///< vertices moved onto the tubes' surface (part of the way for those held back)
  int64_t held_back = 0;  ///< of those, vertices whose full move would have turned a triangle over
};

/// Moves every vertex of `mesh` that lies outside the union of `graph`'s round cones onto that union's
/// surface: to within τ = 3 % of the local radius, at its closest point (stopping where the way there
/// enters another cone). A move that would fold a triangle over, or carry a triangle through another part
/// of the surface, is halved, and dropped after the sixth cut: the fit adds no folds and no crossings.
FitStats fit_to_tubes(TriMesh& mesh, const CenterlineGraph& graph);

}  // namespace vesselmesh
