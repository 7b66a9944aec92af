#pragma once
// Moving a surface's vertices without folding it or passing it through itself: each stage that moves
// vertices after subdivision (round, fit) hands its moves here.

#include <cstdint>
#include <vector>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

struct GuardedMoves {
  int64_t moved = 0;      ///< vertices moved, all or part of the way
  int64_t held_back = 0;  ///< vertices whose move was cut (halved, or dropped) as it would have folded or
                          ///< crossed a triangle
  std::vector<char> cut;  ///< per vertex, 1 where its move was cut
};

/// How far each vertex of `mesh` may move before its move is long (move_without_folding): half its shortest
/// edge, and at most a fifth of `radius[v]` (the local vessel radius). Shape: one per vertex, in the mesh's
/// units.
std::vector<double> long_move_reach(const TriMesh& mesh, const std::vector<double>& radius);

/// Moves every vertex v of `mesh` by move[v], except where that would fold a triangle over (its normal
/// turning by more than a right angle) or carry a triangle through another part of the surface: there the
/// moves of the triangles' corners are halved, round after round, and dropped after the sixth cut. Only
/// moves longer than `reach[v]` (long_move_reach) are tested against other triangles (exactly, against
/// every triangle their swept box meets); shorter ones only bend the triangles round them, which the fold
/// test watches, though together they can add a few crossings where two surfaces already cross.
/// Every position it leaves is rounded to float, as files and Blender hold it, and the tests are made on
/// those: rounding can turn over a triangle that a move left almost flat.
GuardedMoves move_without_folding(TriMesh& mesh, std::vector<Vec3> move, const std::vector<double>& reach);

/// The cross product of triangle t's edges (its normal, twice its area long).
Vec3 face_normal(const std::vector<Vec3>& vertices, const Tri& t);

}  // namespace vesselmesh
