#pragma once
// The base mesh: square cross-sections along every branch, joined into tubes, closed by flat caps at
// terminals and by a convex-hull patch around every joint. Each step is a gluing that keeps the
// surface a closed 2-manifold (a hull is a sphere; removing its square faces leaves one hole per tube;
// a tube is an annulus glued to two square loops; a cap is a disc), so the result has one component
// per centerline component and genus equal to the number of independent loops. A loop too short to
// part closes inside one patch as a tunnel: an annulus from one square hole of the hull to another,
// straight through the patch. A branch's sharp corner (a turn over 120° at one point, or within two
// radii either side of one) is tiled as a joint of its two pieces: its patch counts in `joints`, and
// its pieces count as branches in `absorbed_branches`.

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "vesselmesh/graph/centerline_graph.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"
#include "vesselmesh/sample/sample.hpp"

namespace vesselmesh {

enum class Caps { flat, open };

struct TileOptions {
  SamplingOptions sampling;
  Caps caps = Caps::flat;
  /// Square corners sit at radius_scale × r, so that the subdivided surface, which shrinks towards the
  /// axis, ends at radius r (see subdivision_radius_scale).
  double radius_scale = 1.0;
  /// Throws SizeLimitError rather than place more cross-sections than this in all.
  int64_t max_sections = std::numeric_limits<int64_t>::max();
  /// Every joint patch's squares small, not only those of a patch along a vessel (tile_detail::kSmallSquare),
  /// but for the patches with a joint or a branch within tile_detail::kNearCrossing radii of a place in
  /// `full_squares_near`: where a surface with small squares crossed itself or lost a loop (pipeline.cpp).
  bool small_squares = false;
  std::vector<Vec3> full_squares_near;
  /// Places where the surface crossed itself with full squares round them too: a tunnel whose hole passes
  /// within tile_detail::kNearCrossing of its loop's radii of one gives its loop up (pipeline.cpp).
  std::vector<Vec3> loops_closed_near;
};

/// Where a base vertex's tube is round: the axis point of its section, the radius the surface should have
/// there, and how much of the tube it is (1 for the sections of a tube, 0 for a joint patch's squares and a
/// terminal's end section, where the cap joins), which Loop subdivision blends like positions
/// (round/round.hpp). With them, the shape of the axis there, from which the tube's curvature is known
/// (curvature/tube_curvature.hpp): its direction, its bend and how fast the radius changes along it.
struct TubeAxis {
  Vec3 offset = Vec3::Zero();  ///< from the vertex to its section's (control) centre
  double radius = 0;
  double weight = 0;
  Vec3 tangent = Vec3::Zero();  ///< unit direction of the axis through the section centres
  Vec3 bend = Vec3::Zero();     ///< the axis's curvature vector (1/length, towards the centre of its bend)
  double slope = 0;             ///< dr/ds, the radius's change per unit of axis
};

/// The names of the vertex properties that carry TubeAxis through subdivision: offset x, y, z, radius,
/// weight, then tangent x, y, z, bend x, y, z and slope.
inline const std::array<std::string, 12> kTubeAxisNames = {
    "tube_axis_x",  "tube_axis_y",    "tube_axis_z", "tube_radius", "tube_weight", "tube_tangent_x",
    "tube_tangent_y", "tube_tangent_z", "tube_bend_x", "tube_bend_y", "tube_bend_z", "tube_slope"};

/// The axes as those vertex properties.
std::vector<VertexProperty> tube_axis_properties(const std::vector<TubeAxis>& axes);

/// How many of kTubeAxisNames, from the first, the round stage reads (offset, radius, weight); the rest,
/// the axis's shape, only the tube curvature reads.
constexpr std::size_t kRoundAxisProperties = 5;
/// Removes the mesh's tube properties from kTubeAxisNames[from] on (0: all of them, once the round stage has
/// read them; kRoundAxisProperties: the axis's shape, when no curvature is asked for).
void drop_tube_axis_properties(TriMesh& mesh, std::size_t from = 0);
/// A mesh's first `count` tube properties, in kTubeAxisNames' order (what round/ and curvature/ read), the
/// others null; all null unless it has every one of those.
std::array<const std::vector<float>*, kTubeAxisNames.size()> find_tube_axis_properties(
    const TriMesh& mesh, std::size_t count = kTubeAxisNames.size());

/// A loop of the centerline that the tile stage closed inside one joint patch: no handle of the surface
/// goes round it.
struct LostLoop {
  Vec3 at;                   ///< a joint of the patch
  std::array<Vec3, 2> ends;  ///< the joints of the loop's branch through the patch (its tunnel's)
  std::string why;           ///< in words, for reports
};

struct BaseMesh {
  std::vector<Vec3> vertices;
  std::vector<TubeAxis> axes;                 ///< one per vertex
  std::vector<std::array<int32_t, 4>> quads;  ///< tube pieces and caps, counter-clockwise from outside
  std::vector<Tri> triangles;                 ///< joint patches
  std::vector<std::array<int32_t, 4>> squares;  ///< every section's corners, counter-clockwise about it
  int64_t sections = 0;                       ///< cross-sections, joint squares included
  int64_t joints = 0;                         ///< joint patches (clusters of joints too close to part)
  int64_t absorbed_branches = 0;              ///< branches too short for a tube, inside a joint patch
  int64_t tunnels = 0;                        ///< of those, loops closed inside a patch, through it
  std::vector<LostLoop> lost_loops;           ///< the loops whose tunnels the patches gave up
};

BaseMesh tile_base_mesh(const CenterlineGraph& graph, const TileOptions& options);

}  // namespace vesselmesh
