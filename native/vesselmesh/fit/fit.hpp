#pragma once
// fit: the subdivided surface brought onto the input's tubes, the union of the centerline's round
// cones. A Loop limit surface is smooth: where the tubes it follows meet at an angle it bridges the
// concave side, webbing the crotch of a bifurcation (by up to half a radius on a narrow one) and
// filling the inner side of a bend, and on the convex side it cuts the corner, too thin where a coarse
// tracing turns sharply (the union has a whole sphere at the corner point). Each vertex moves towards
// the tubes' surface the shortest way, to within a small tolerance, so that the surface has the radius
// the file gives wherever it can. Where the file's tubes overlap side by side (a vessel traced along
// another, two vessels closer than their radii), each surface runs through the other's tube; there the
// two are pressed flat against each other instead, so that they no longer cross. Last, each vertex goes
// out a little along its normal, so that the flat faces between the vertices straddle the round tubes
// rather than cut inside them.

#include <array>
#include <cstdint>
#include <vector>

#include "vesselmesh/geometry/round_cones.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// Which vertices the fit moves.
enum class Fit {
  onto,    ///< every vertex: those outside the tubes come in, those inside go out (but never through
           ///< another tube: a vertex inside another vessel's tube is parted from it instead)
  inward,  ///< only the vertices outside the tubes: webs and filled bends come in, the rest keeps the
           ///< Loop surface's smooth shape (but for the parting of overlapping tubes)
  none,    ///< the Loop limit surface as it is
};

struct FitStats {
  int64_t moved = 0;      ///< vertices moved towards the tubes' surface, all or part of the way
  int64_t held_back = 0;  ///< vertices whose move was cut (halved, or dropped) as it would have folded or
                          ///< crossed a triangle, in the first round
  int64_t parted = 0;     ///< vertices given a move off another vessel's tube where the input's tubes
                          ///< overlap (some may then be held back)
};

/// Moves the vertices of `mesh` that `fit` chooses towards the surface of the union of `graph`'s round
/// cones, at their closest point on it: a vertex at signed distance d ends at τr·tanh(d/τr), within
/// τ = 1 % of the local radius r; one within 0.7 % stays. An outward move stops where its way enters
/// another cone. A vertex of one vessel in (or within 2 % of) another's tube, away from a joint the two
/// share, moves instead onto its own side of the radical plane of the two tubes' spheres there, 2 % of the
/// smaller radius from it. With Fit::onto each vertex fitted onto the tubes also goes out along its normal
/// by the depth of its faces' centroids below it (a third of its umbrella's depth: 1.7 % of the radius on a
/// ring of 16 sides), to at most 3 % off the tubes, so that the flat faces straddle the round tubes rather
/// than cut inside them; lifts below 0.2 % are not made, nor next to another vessel's tube. A move that
/// would fold a triangle over, or carry a triangle through another part of the surface, is halved, and
/// dropped after the sixth cut: the fit adds no folds, and no crossings by the moves long enough to make
/// one on their own (over a fifth of the local radius or half the vertex's shortest edge); shorter moves
/// together can add a few where surfaces already cross. A vertex whose move was cut and that is left over 5 %
/// of its radius inside the tubes of two branches (a narrow fork), away from other vessels' tubes, then
/// moves again from where it and its neighbours stand (one more round, each such move tested against the
/// triangles it passes).
FitStats fit_to_tubes(TriMesh& mesh, const CenterlineGraph& graph, Fit fit = Fit::onto);

/// The same onto the tubes `cones` holds (built once for both the separate stage and the fit).
FitStats fit_to_tubes(TriMesh& mesh, const RoundCones& cones, Fit fit = Fit::onto);

/// Rounds for take_back_crossing_moves: enough for the few faces a fold of the fit leaves crossing.
constexpr int kTakeBackRounds = 4;

/// Takes the fit's moves back where faces of `mesh` cross each other: the corners of every crossing face
/// that the fit moved go back to where they stood before it (`before`, one position per vertex, rounded to
/// float as the mesh's are), round after round until no face crosses, none of their corners moved, or
/// kTakeBackRounds are done. The fit's guard tests only its longer moves against other triangles; shorter
/// ones together can still make faces cross (guarded_moves.hpp). `pairs` holds the crossing pairs of the
/// mesh as it stands, with `among` (a flag per face) only those with a flagged face
/// (intersecting_face_pairs), and is left holding those of the mesh as it leaves it: the caller's check has
/// found the first, and needs the last. Returns how many vertices went back.
int64_t take_back_crossing_moves(TriMesh& mesh, const std::vector<Vec3>& before,
                                 const std::vector<char>& among, std::vector<std::array<int32_t, 2>>& pairs);

}  // namespace vesselmesh
