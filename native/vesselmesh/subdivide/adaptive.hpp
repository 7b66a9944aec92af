#pragma once
// Adaptive Loop subdivision (paper §2.5): at each level only the triangles that need it are split, the
// others stay, and the cracks between them are closed by splitting the unsplit side in two or three
// (paper Fig. 6). Uniform refinement and the dihedral-angle criterion (the paper's baseline) run through
// the same code.
//
// How it is built, and why:
//  - The refined triangles form a forest over the base triangles: a leaf is a triangle of some uniform
//    Loop level, and splitting it gives its four children of the next level (loop_subdivide's numbering).
//    Neighbouring leaves differ by at most one level, and a leaf with all three edges split is split too,
//    so every crack is a single midpoint on one or two edges of a leaf.
//  - Transition ("green") triangles exist only in the output: at the next level a tagged green triangle
//    splits its whole parent leaf instead (the red–green rule of Bank, Sherman and Weiser), so thin
//    transition triangles never split again into thinner ones.
//  - Every vertex is placed at its Loop limit position, which does not depend on the level it was made
//    at: refined and unrefined parts meet without steps in the radius, and every vertex of an adaptive
//    mesh is also a vertex of the uniform mesh of the same level, at the same place.

#include <cstdint>
#include <vector>

#include "vesselmesh/curvature/curvature.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// Which triangles a level splits.
enum class Refinement {
  uniform,    ///< all of them
  curvature,  ///< those with a vertex whose equalised curvature measure reaches the threshold (paper §2.5)
  dihedral,   ///< those with an interior dihedral angle to a neighbour below the angle (the paper's baseline)
};

struct SubdivisionOptions {
  int levels = 1;          ///< 0..4 (one level on the pipeline's octagons rounds tubes to 16 sides)
  Refinement method = Refinement::curvature;
  int uniform_levels = 1;  ///< the first levels split everything: a base mesh's octagons are too coarse
                           ///< for its curvature to say where detail is (paper §2.5 step 1)
  CurvatureMeasure measure = CurvatureMeasure::tube_departure;  ///< ranks vessels of every size alike
  /// curvature: in [0, 1], on the scaled and equalised measure. At level 2 on octagons, 0.72 keeps 57 % of
  /// uniform's triangles on brava-bg0003 and human-brain-arteries with face centroids 0.8 % and 0.4 % of the
  /// radius further off at the 95th percentile (test_adaptive; 0.7: 60.1 % on human-brain-arteries).
  double threshold = 0.72;
  double angle_degrees = 160;    ///< dihedral: interior angle, 180 for coplanar triangles
};

struct SubdividedMesh {
  TriMesh mesh;                      ///< every vertex on the Loop limit surface of the base mesh
  std::vector<uint8_t> face_level;   ///< per face: the uniform level of the leaf it comes from
  std::vector<uint8_t> transition;   ///< per face: 1 for a triangle that closes a crack (green)
  std::vector<double> tagged;        ///< per level: the fraction of the triangles before it that it tagged
};

/// Throws std::invalid_argument naming the option for levels outside 0..4, a negative uniform_levels, a
/// threshold outside [0, 1] and an angle outside [0, 180] (NaN included).
void validate(const SubdivisionOptions& options);

/// `options.levels` levels of (adaptive) Loop subdivision of a closed or open triangle mesh, with every
/// vertex moved to the limit surface. Refinement::uniform gives loop_limit(loop_subdivide(base, levels)).
/// The base mesh's vertex properties are carried with the same masks as the positions.
///
/// Throws std::invalid_argument for the options validate() rejects and for the meshes loop_subdivide
/// rejects.
SubdividedMesh subdivide(const TriMesh& base, const SubdivisionOptions& options);

}  // namespace vesselmesh
