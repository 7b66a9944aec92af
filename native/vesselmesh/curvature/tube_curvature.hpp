#pragma once
// The curvature of the round tubes themselves. The round stage puts each tube vertex on the circle of its
// radius about its axis (round/), so along a tube the surface is a canal surface whose curvature is known
// from the axis: 1/r round it (less where the radius changes, cos φ/r with tan φ = dr/ds) and, along it,
// −cos φ (b·u) / (1 − r (b·u)) with b the axis's curvature vector and u the unit direction from the axis
// to the vertex (on a torus: κ cos θ / (1 + κ r cos θ), the closed form). A quadric fitted to a vertex's
// 2-ring reads that too, but only where the ring is fine: a tube left at level 1 has 8 vertices round it,
// and its fit missed a torus's mean curvature by 6 to 11 % at the 95th percentile (docs/pipeline.md).
// Blended with the fit by the tube weight, which falls to 0 at the joints' squares and the caps.

#include <vector>

#include "vesselmesh/curvature/curvature.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// Per vertex (V values each): the principal curvatures of the round tube the vertex is rounded onto and
/// their directions, and how much of it the vertex follows (the tube weight; 0 where it has no tube).
struct TubeCurvature {
  std::vector<double> around, along;        ///< 1/length, convex positive
  std::vector<Vec3> around_dir, along_dir;  ///< unit
  std::vector<double> weight;               ///< in [0, 1]
};

/// Reads the tube properties (kTubeAxisNames) the tile stage gave the base mesh and subdivision carried;
/// call it before round_tubes takes them off. Empty for a mesh without them.
TubeCurvature tube_curvature(const TriMesh& mesh);

/// Which vertices the blend reads a fit for (V flags; empty for an empty `tube`): those not wholly on a
/// tube. Along the tubes, most of a surface's vertices, the fit would be thrown away (estimate_curvature's
/// `fitted`).
std::vector<char> needs_fit(const TubeCurvature& tube);

/// Each vertex's principal curvatures become w·(the tube's) + (1 − w)·(the fit's), with w its tube
/// weight (1 where needs_fit says no fit is needed), and the measures made of them follow; its directions
/// are the tube's where w ≥ ½. An empty `tube` changes nothing.
void blend_tube_curvature(VertexCurvature& curvature, const TubeCurvature& tube);

}  // namespace vesselmesh
