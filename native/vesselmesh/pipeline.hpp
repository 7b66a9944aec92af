#pragma once
// The whole surface pipeline, stage by stage:
//   graph → separate (crossing vessels) → sample → frames → tile (base mesh of squares, then octagons) →
//   triangulate → subdivide (uniform or adaptive, onto the Loop limit surface) → round (tubes) → fit (onto
//   the input's tubes) [→ curvature] → verify
// with the time and the output size of each stage, for `vesselmesh mesh --stats-json` and the tests. Tile to
// verify run again, with the joint patches' full squares, round where the surface crossed itself (tile step 7
// of docs/pipeline.md).

#include <optional>
#include <string>
#include <vector>

#include "vesselmesh/check/check_mesh.hpp"
#include "vesselmesh/fit/fit.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"
#include "vesselmesh/separate/separate.hpp"
#include "vesselmesh/subdivide/adaptive.hpp"
#include "vesselmesh/tile/base_mesh.hpp"

namespace vesselmesh {

/// What the pipeline checks of its own surface before handing it out: `automatic` checks that it is a
/// closed manifold and, up to kVerifyCrossingsUpTo triangles (where the search costs about as much as
/// the meshing), that it does not cross itself; up to kVerifyNearJointsUpTo, that it does not cross itself
/// near its joints and caps (round/round.hpp, faces_near_joints), where the patches' shapes show; `full`
/// checks crossings everywhere whatever the size; `topology` never does.
enum class Verify { automatic, full, topology };
constexpr int64_t kVerifyCrossingsUpTo = 1'000'000;
constexpr int64_t kVerifyNearJointsUpTo = 16'000'000;

/// Builds of the surface with small squares, each with full squares round where the one before crossed itself
/// (MeshResult::full_square_tries); then one as where crossings are not checked, if it still crosses. Where
/// the surface is too large to be checked everywhere, they are checked near its joints and caps.
constexpr int kSmallSquareTries = 3;

struct MeshOptions {
  Crossings crossings = Crossings::separate;
  SamplingOptions sampling;
  Caps caps = Caps::flat;
  int sides = 8;  ///< round every base section: 8, or 4 (tile/octagons.hpp)
  SubdivisionOptions subdivision;
  Fit fit = Fit::onto;     ///< which vertices come onto the input's tubes (fit/fit.hpp)
  bool curvature = false;  ///< attach k1, k2, mean, gaussian, rms and the local tube radius as vertex properties
  /// Throw SizeLimitError, before the work, rather than build a surface with more triangles than this
  /// (counting every triangle of the last level, which the adaptive methods also compute).
  int64_t max_triangles = 50'000'000;
  Verify verify = Verify::automatic;
};

/// Throws std::invalid_argument naming the first option out of its range (NaN included).
void validate(const MeshOptions& options);

/// The pipeline's check of its own surface (check/check_mesh.hpp): what `vesselmesh check` would reject.
struct Verification {
  TopologyReport topology;
  int64_t expected_components = 0;  ///< the centerline's components
  int64_t loops = 0;                ///< the centerline's loops (a lost one is no failure: docs/pipeline.md)
  bool crossings_checked = false;              ///< everywhere
  bool crossings_checked_near_joints = false;  ///< only near the joints and caps (kVerifyNearJointsUpTo)
  int64_t crossing_pairs = 0;              ///< self-intersecting triangle pairs (when checked)
  int64_t pairs_in_overlapping_tubes = 0;  ///< of those, where the input's tubes themselves overlap
  /// Empty when the surface is a closed manifold with one piece per component and crosses itself only
  /// where the input's tubes overlap; else what is wrong, in words.
  std::string problem() const;
};

struct StageStats {
  std::string stage;
  double seconds = 0;
  int64_t vertices = 0, faces = 0;
};

struct MeshResult {
  TriMesh mesh;
  std::vector<uint8_t> transition;  ///< per face: 1 for a crack-closing triangle of adaptive subdivision
  std::vector<double> tagged;       ///< per level: the fraction of triangles it tagged for splitting
  std::vector<StageStats> stages;
  int64_t sections = 0, joint_patches = 0, absorbed_branches = 0, tunnels = 0;
  std::vector<LostLoop> lost_loops;  ///< the loops closed inside a joint patch: no handle goes round them
  int64_t hidden_terminals = 0;   ///< terminal branches dropped, hidden in other tubes (separate/hidden.hpp)
  int64_t crossings = 0;          ///< crossing edge pairs in the input (separate/separate.hpp)
  int64_t separated_points = 0;   ///< centerline points the separate stage moved
  double largest_separation = 0;  ///< its largest move, relative to the point's radius
  int64_t crossings_left = 0;     ///< crossing edge pairs it left
  bool tangle = false;            ///< it left them all: too dense to part (Separation::tangle)
  /// The centerline whose tubes the surface follows, where the separate stage moved vessels (with the
  /// points it added round the crossings) or dropped hidden terminal branches; empty when it did neither. Fidelity to the vessels as built is
  /// measured against it, to the file's vessels against the input.
  std::optional<CenterlineGraph> separated;
  int64_t rounded_vertices = 0;   ///< vertices the round stage moved onto their tube's circle
  int64_t fitted_vertices = 0;    ///< vertices the fit stage moved
  int64_t parted_vertices = 0;    ///< vertices it gave a move off another vessel's overlapping tube
  int64_t taken_back_vertices = 0;  ///< fit moves taken back where faces crossed (take_back_crossing_moves)
  /// Builds again from the tile stage (tile step 7 of docs/pipeline.md): with full squares round where the
  /// build with small squares crossed itself (at most kSmallSquareTries − 1 times), or with small squares only
  /// on patches along a vessel, as where crossings are not checked, where it lost a loop, still crossed after
  /// those tries, or came out too large to be checked.
  int64_t full_square_tries = 0;
  /// Whether every joint patch has small squares, but those near where a build crossed itself or lost a loop
  /// (tile step 7); false where only the patches along a vessel have them.
  bool small_squares = false;
  Verification verification;
};

/// Section corners sit at this multiple of the radius so that the subdivided surface, whose vertices
/// are finally moved to the Loop limit surface, is at the centerline radius: Loop pulls a tube of
/// `sides` (4 or 8) sides towards its axis (test_pipeline: RadiusScaleMakesSubdividedTubesFaithful).
double subdivision_radius_scale(int sides);

/// Throws std::invalid_argument for options validate() rejects, SizeLimitError (error.hpp) when the
/// surface would exceed options.max_triangles, and std::invalid_argument for a graph without edges.
MeshResult mesh_centerline(const CenterlineGraph& graph, const MeshOptions& options);

/// Counts and per-stage times as JSON text.
std::string stats_json(const MeshResult& result, int indent = 2);

}  // namespace vesselmesh
