#pragma once
// The whole surface pipeline, stage by stage:
//   graph → separate (crossing vessels) → sample → frames → tile (base mesh) → triangulate → subdivide
//   (uniform or adaptive, onto the Loop limit surface) → fit (onto the input's tubes) [→ curvature]
// with the time and the output size of each stage, for `vesselmesh mesh --stats-json` and the tests.

#include <string>
#include <vector>

#include "vesselmesh/fit/fit.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"
#include "vesselmesh/separate/separate.hpp"
#include "vesselmesh/subdivide/adaptive.hpp"
#include "vesselmesh/tile/base_mesh.hpp"

namespace vesselmesh {

struct MeshOptions {
  Crossings crossings = Crossings::separate;
  SamplingOptions sampling;
  Caps caps = Caps::flat;
  SubdivisionOptions subdivision;
  Fit fit = Fit::onto;     ///< which vertices come onto the input's tubes (fit/fit.hpp)
  bool curvature = false;  ///< attach k1, k2, mean, gaussian, rms as vertex properties
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
  int64_t crossings = 0;          ///< crossing edge pairs in the input (separate/separate.hpp)
  int64_t separated_points = 0;   ///< centerline points the separate stage moved
  double largest_separation = 0;  ///< its largest move, relative to the point's radius
  int64_t crossings_left = 0;     ///< crossing edge pairs it left
  int64_t fitted_vertices = 0;  ///< vertices the fit stage moved
  int64_t parted_vertices = 0;  ///< vertices it gave a move off another vessel's overlapping tube
};

/// Square corners sit at this multiple of the radius so that the subdivided surface, whose vertices
/// are finally moved to the Loop limit surface, is at the centerline radius: Loop pulls a four-sided
/// tube towards its axis (test_pipeline: RadiusScaleMakesSubdividedTubesFaithful).
double subdivision_radius_scale();

MeshResult mesh_centerline(const CenterlineGraph& graph, const MeshOptions& options);

/// Counts and per-stage times as JSON text.
std::string stats_json(const MeshResult& result, int indent = 2);

}  // namespace vesselmesh
