#pragma once
// round: tubes made round. The Loop limit of a four-sided tube is not round (its radius ripples ±2 %
// four times round, which reads as a ±20 % ripple of the mean curvature). Every base vertex knows the
// axis point and radius of its section (TubeAxis); Loop subdivision carries them along with the
// positions, so each vertex of the subdivided surface knows the point of the tube's smooth axis at its
// place and the radius there. A tube's vertices then move radially onto that circle, those near a joint
// patch as far as their weight says (1 along a tube, falling to 0 at the joint's squares).

#include <vector>

#include "vesselmesh/geometry/guarded_moves.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"
#include "vesselmesh/tile/base_mesh.hpp"

namespace vesselmesh {

/// Moves every vertex with a tube weight w > 0 the share w of the way to the point at its radius from its
/// axis point, along the line from the axis point through it (move_without_folding: never folding the
/// surface nor passing it through itself), and takes the axis properties off the mesh. A mesh without the
/// properties is left as it is.
GuardedMoves round_tubes(TriMesh& mesh);

/// Per face, 1 where a corner is not wholly on a tube (its tube weight is below 1: a joint's patch, a cap and
/// the pieces of tube next to them), where the patches' shapes show; 0 elsewhere. Empty for a mesh without
/// the tube properties.
std::vector<char> faces_near_joints(const TriMesh& mesh);

}  // namespace vesselmesh
