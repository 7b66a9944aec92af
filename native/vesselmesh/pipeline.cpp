#include "vesselmesh/pipeline.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "vesselmesh/curvature/curvature.hpp"
#include "vesselmesh/curvature/tube_curvature.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/geometry/self_intersections.hpp"
#include "vesselmesh/round/round.hpp"
#include "vesselmesh/separate/hidden.hpp"
#include "vesselmesh/tile/octagons.hpp"
#include "vesselmesh/tile/patch_edges.hpp"
#include "vesselmesh/triangulate/triangulate.hpp"

namespace vesselmesh {

double subdivision_radius_scale(int sides) {
  // Mean distance from the axis of the Loop limit surface of a straight tube, relative to its control
  // section's corners (test_loop: TubesShrinkToTheKnownMeanRadius).
  return 1.0 / (sides == 8 ? 0.902 : 0.657);
}

void validate(const MeshOptions& options) {
  validate(options.sampling);
  validate(options.subdivision);
  if (options.sides != 4 && options.sides != 8)
    throw std::invalid_argument("sides must be 4 or 8, not " + std::to_string(options.sides));
  if (options.max_triangles < 1)
    throw std::invalid_argument("max_triangles must be at least 1, not " +
                                std::to_string(options.max_triangles));
}

std::string Verification::problem() const {
  std::vector<std::string> problems;
  const TopologyReport& t = topology;
  if (!t.closed_manifold())
    problems.push_back("it is not a closed manifold (" + std::to_string(t.boundary_edges) +
                       " boundary edges, " + std::to_string(t.non_manifold_edges) + " non-manifold edges, " +
                       std::to_string(t.non_manifold_vertices) + " non-manifold vertices, " +
                       std::to_string(t.inconsistent_edges) + " inconsistently oriented edges, " +
                       std::to_string(t.degenerate_faces) + " degenerate faces)");
  if (t.components != expected_components)
    problems.push_back("it has " + std::to_string(t.components) + " pieces for the centerline's " +
                       std::to_string(expected_components) + " components");
  if ((crossings_checked || crossings_checked_near_joints) && crossing_pairs > pairs_in_overlapping_tubes)
    problems.push_back("it crosses itself at " + std::to_string(crossing_pairs - pairs_in_overlapping_tubes) +
                       " triangle pairs where the input's tubes do not overlap");
  std::string out;
  for (const std::string& p : problems) out += (out.empty() ? "" : "; ") + p;
  return out;
}

namespace {

using FacePair = std::array<int32_t, 2>;  // two crossing faces (intersecting_face_pairs)

SizeLimitError too_large(int64_t triangles, bool at_least, int64_t sections, const MeshOptions& options) {
  return SizeLimitError("the surface would have " + std::string(at_least ? "more than " : "") +
                        std::to_string(triangles) + " triangles at level " +
                        std::to_string(options.subdivision.levels) + " (" +
                        std::string(at_least ? "over " : "") + std::to_string(sections) +
                        " cross-sections), beyond the limit of " + std::to_string(options.max_triangles) +
                        ": use fewer levels, a larger alpha (sections further apart), or raise max_triangles "
                        "(--max-triangles)");
}

/// How much of a surface of `faces` triangles is checked for crossings.
enum class CrossingCheck { none, near_joints, everywhere };
CrossingCheck crossing_check(int64_t faces, Verify how) {
  if (how == Verify::full || (how == Verify::automatic && faces <= kVerifyCrossingsUpTo))
    return CrossingCheck::everywhere;
  if (how == Verify::automatic && faces <= kVerifyNearJointsUpTo) return CrossingCheck::near_joints;
  return CrossingCheck::none;
}

/// The crossing counts of `v` from the crossing `pairs` of `mesh`.
void count_crossings(Verification& v, const TriMesh& mesh, const CenterlineGraph& centerline,
                     const std::vector<FacePair>& pairs) {
  const IntersectionReport x = intersection_report(mesh, &centerline, pairs);
  v.crossing_pairs = x.pairs;
  v.pairs_in_overlapping_tubes = x.pairs_in_overlapping_tubes;
}

/// `near_joints`: faces_near_joints of the mesh where only those are checked for crossings, else empty.
/// `pairs` receives the crossing pairs found (intersecting_face_pairs).
Verification verify(const TriMesh& mesh, const CenterlineGraph& centerline, Verify how,
                    const std::vector<char>& near_joints, std::vector<FacePair>& pairs) {
  Verification v;
  v.topology = check_topology(mesh);
  v.expected_components = centerline.components;
  v.loops = centerline.loops;
  const CrossingCheck check = crossing_check(static_cast<int64_t>(mesh.faces.size()), how);
  v.crossings_checked = check == CrossingCheck::everywhere;
  v.crossings_checked_near_joints = check == CrossingCheck::near_joints;
  pairs.clear();
  if (check != CrossingCheck::none) {
    pairs = intersecting_face_pairs(mesh, near_joints);
    count_crossings(v, mesh, centerline, pairs);
  }
  return v;
}

/// Whether the surface crosses itself where the input's tubes do not overlap.
bool crosses(const Verification& v) { return v.crossing_pairs > v.pairs_in_overlapping_tubes; }

/// About how many sections the tile stage places on the centerline: one a diameter along every edge, and a
/// quarter more for the joints' squares and the sections crowding in bends (the shared sets have 0.7 to 1.5
/// times as many as one a diameter, the cerebral trees 1.3).
double sections_estimate(const CenterlineGraph& g) {
  double sections = 0;
  for (const auto& [a, b] : g.edges)
    if (g.radius[a] + g.radius[b] > 0)
      sections += (g.points[a] - g.points[b]).norm() / (g.radius[a] + g.radius[b]);
  return 1.25 * sections;
}

Vec3 centroid(const TriMesh& mesh, int32_t f) {
  const Tri& t = mesh.faces[f];
  return (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3;
}

using Clock = std::chrono::steady_clock;

/// Adds a stage's time since `start` to `result`; a stage run again (another build, below) adds its time to
/// the first run's.
void record(MeshResult& result, const char* stage, Clock::time_point start, std::size_t vertices,
            std::size_t faces) {
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const auto same = std::find_if(result.stages.begin(), result.stages.end(),
                                 [&](const StageStats& s) { return s.stage == stage; });
  const StageStats now{stage, seconds, static_cast<int64_t>(vertices), static_cast<int64_t>(faces)};
  if (same == result.stages.end()) return result.stages.push_back(now);
  *same = {now.stage, same->seconds + seconds, now.vertices, now.faces};
}

/// What one build of the surface needs besides the options: the centerline it follows and its tubes (built
/// on first use).
struct Tubes {
  const CenterlineGraph& centerline;
  std::optional<RoundCones>& cones;
  const RoundCones& get() {
    if (!cones) cones.emplace(centerline);
    return *cones;
  }
};

/// What a build says of itself besides its surface and check.
struct Built {
  std::vector<char> near_joints;  ///< faces_near_joints where only those were checked for crossings
  std::vector<LostLoop> lost_loops;  ///< where the tile stage gave a loop's tunnel up (BaseMesh::lost_loops)
  std::vector<FacePair> crossing_pairs;  ///< where it crosses itself, as its check found
};

/// Builds the surface from the tile stage on into `result`: tiled, triangulated, subdivided, rounded,
/// fitted onto the tubes, rounded to float and checked, with the fit's moves taken back where it crosses
/// itself. With `tubes_curvature`, reads the tubes' own curvature into it before rounding.
Built build_surface(Tubes tubes, const TileOptions& tile, const MeshOptions& options,
                    TubeCurvature* tubes_curvature, MeshResult& result) {
  auto start = Clock::now();
  const int64_t per_base_triangle = int64_t{1} << (2 * options.subdivision.levels);
  BaseMesh base;
  try {
    base = tile_base_mesh(tubes.centerline, tile);
    if (options.sides == 8)
      base = split_long_patch_edges(
          octagonal_sections(std::move(base), subdivision_radius_scale(8) / subdivision_radius_scale(4)),
          tubes.get(), subdivision_radius_scale(8));
  } catch (const SizeLimitError&) {
    throw too_large(2 * options.sides * per_base_triangle * tile.max_sections, true, tile.max_sections,
                    options);
  }
  const auto base_triangles = static_cast<int64_t>(2 * base.quads.size() + base.triangles.size());
  if (base_triangles * per_base_triangle > options.max_triangles)
    throw too_large(base_triangles * per_base_triangle, false, base.sections, options);
  record(result, "tile", start, base.vertices.size(), base.quads.size() + base.triangles.size());
  result.sections = base.sections;
  result.joint_patches = base.joints;
  result.absorbed_branches = base.absorbed_branches;
  result.tunnels = base.tunnels;
  Built built{{}, std::move(base.lost_loops), {}};

  start = Clock::now();
  TriMesh& mesh = result.mesh;
  mesh = triangulate(base);
  // Only the curvature reads the axis's shape: without it, subdivision carries 5 properties instead of 12.
  if (!tubes_curvature) drop_tube_axis_properties(mesh, kRoundAxisProperties);
  record(result, "triangulate", start, mesh.vertices.size(), mesh.faces.size());

  start = Clock::now();
  SubdividedMesh subdivided = subdivide(mesh, options.subdivision);
  mesh = std::move(subdivided.mesh);
  result.transition = std::move(subdivided.transition);
  result.tagged = std::move(subdivided.tagged);
  record(result, "subdivide", start, mesh.vertices.size(), mesh.faces.size());

  start = Clock::now();
  const CrossingCheck check = crossing_check(static_cast<int64_t>(mesh.faces.size()), options.verify);
  if (check == CrossingCheck::near_joints) built.near_joints = faces_near_joints(mesh);
  const std::vector<char>& near_joints = built.near_joints;
  // The tubes' own curvature, read before rounding takes the tube properties off (tube_curvature.hpp).
  if (tubes_curvature) *tubes_curvature = tube_curvature(mesh);
  result.rounded_vertices = round_tubes(mesh).moved;
  record(result, "round", start, mesh.vertices.size(), mesh.faces.size());
  // Where the surface is checked for crossings, the fit's moves can be taken back where faces cross.
  const bool fits = options.fit != Fit::none;
  const std::vector<Vec3> before_fit =
      fits && check != CrossingCheck::none ? mesh.vertices : std::vector<Vec3>();
  if (fits) {
    start = Clock::now();
    const FitStats fit = fit_to_tubes(mesh, tubes.get(), options.fit);
    result.fitted_vertices = fit.moved;
    result.parted_vertices = fit.parted;
    record(result, "fit", start, mesh.vertices.size(), mesh.faces.size());
  }
  // Every file and Blender hold the coordinates as floats: rounded here, what the check passes is what
  // they hold.
  for (Vec3& p : mesh.vertices) p = rounded_to_float(p);
  start = Clock::now();
  std::vector<FacePair>& pairs = built.crossing_pairs;
  result.verification = verify(mesh, tubes.centerline, options.verify, near_joints, pairs);
  result.taken_back_vertices = 0;
  if (!before_fit.empty() && crosses(result.verification)) {
    // Moving vertices back changes no face: the rest of the check holds.
    result.taken_back_vertices = take_back_crossing_moves(mesh, before_fit, near_joints, pairs);
    if (result.taken_back_vertices > 0) count_crossings(result.verification, mesh, tubes.centerline, pairs);
  }
  record(result, "verify", start, mesh.vertices.size(), mesh.faces.size());
  return built;
}

}  // namespace

MeshResult mesh_centerline(const CenterlineGraph& graph, const MeshOptions& options) {
  validate(options);
  if (graph.edges.empty()) throw std::invalid_argument("the centerline has no edges");
  MeshResult result;
  const auto start = Clock::now();
  // The tubes the surface follows, built once for the separate stage and the fit, and again only where
  // the separate stage left terminal branches out or moved the centerline.
  std::optional<RoundCones> cones;
  const CenterlineGraph* centerline = &graph;
  CenterlineGraph unhidden;  // without its hidden terminal branches
  Separation separation;
  if (options.crossings == Crossings::separate) {
    cones.emplace(graph);
    result.hidden_terminals = drop_hidden_terminals(graph, cones, unhidden);
    if (result.hidden_terminals > 0) centerline = &unhidden;
    separation = separate_crossings(*centerline, *cones);
    result.crossings = separation.crossings;
    result.separated_points = separation.moved_points;
    result.largest_separation = separation.largest_move;
    result.crossings_left = separation.left;
    result.tangle = separation.tangle;
    if (separation.moved_points > 0) centerline = &separation.graph, cones.emplace(separation.graph);
    record(result, "separate", start, graph.points.size(), graph.edges.size());
  }
  Tubes tubes{*centerline, cones};

  TileOptions tile;
  tile.sampling = options.sampling;
  tile.caps = options.caps;
  tile.radius_scale = subdivision_radius_scale(4);  // octagons are tiled as squares (tile/octagons.hpp)
  // Every section brings at least two triangles a side, and each level four times as many.
  const int64_t per_section = 2 * options.sides * (int64_t{1} << (2 * options.subdivision.levels));
  tile.max_sections = std::max<int64_t>(2, options.max_triangles / per_section);
  // Small squares on every patch where the surface will be checked for crossings, everywhere or near its
  // joints (tile step 7 of docs/pipeline.md): where it crosses itself outside overlapping tubes, or the tile
  // stage gave a loop up, the patches near there are built again with full squares.
  tile.small_squares = crossing_check(static_cast<int64_t>(per_section * sections_estimate(*centerline)),
                                      options.verify) != CrossingCheck::none;
  TubeCurvature tube_curvature;
  int64_t genus_lost_at = -1;  // the genus of the last build that lost a loop
  for (int tries = 1;; ++tries) {
    const Built built =
        build_surface(tubes, tile, options, options.curvature ? &tube_curvature : nullptr, result);
    result.lost_loops = built.lost_loops;
    if (!tile.small_squares) break;
    const Verification& v = result.verification;
    const bool checked = v.crossings_checked || v.crossings_checked_near_joints;
    const bool lost = v.topology.genus < v.loops;
    if (!checked || (lost && (built.lost_loops.empty() || v.topology.genus <= genus_lost_at)) ||
        ((crosses(v) || lost) && tries == kSmallSquareTries)) {
      // Too large to be checked after all, a loop lost other than where the tile stage gave one up or
      // still lost with full squares there, or crossings that full squares round them did not part: small
      // squares only on patches along a vessel, as where the surface is never checked.
      tile.small_squares = false;
      // Where it still crosses itself round a tunnel (whose patch has full squares anyway), its loop is
      // closed: a loop of five voxels, its tubes filling its hole, crossed itself so (tile step 4).
      if (checked && crosses(v))
        for (const auto& pair : built.crossing_pairs)
          for (int32_t f : pair) tile.loops_closed_near.push_back(centroid(result.mesh, f));
    } else {
      if (!crosses(v) && !lost) break;
      if (crosses(v))
        for (const auto& pair : built.crossing_pairs)
          for (int32_t f : pair) tile.full_squares_near.push_back(centroid(result.mesh, f));
      // vesselgraph-demo at levels 0 and 1 lost a loop whose joints merged otherwise with small squares
      // round them, and whose tunnel then could not open.
      if (lost) {
        genus_lost_at = v.topology.genus;
        for (const LostLoop& loop : built.lost_loops) tile.full_squares_near.push_back(loop.at);
      }
    }
    ++result.full_square_tries;
  }
  result.small_squares = tile.small_squares;
  if (options.curvature) {
    const auto curvature_start = Clock::now();
    VertexCurvature curvature = estimate_curvature(result.mesh, needs_fit(tube_curvature));
    blend_tube_curvature(curvature, tube_curvature);
    for (VertexProperty& p : curvature_properties(curvature))
      result.mesh.vertex_properties.push_back(std::move(p));
    const std::vector<double> radius = local_radius(result.mesh.vertices, tubes.get());
    result.mesh.vertex_properties.push_back({"radius", std::vector<float>(radius.begin(), radius.end())});
    record(result, "curvature", curvature_start, result.mesh.vertices.size(), result.mesh.faces.size());
  }
  if (separation.moved_points > 0)
    result.separated = std::move(separation.graph);
  else if (result.hidden_terminals > 0)
    result.separated = std::move(unhidden);
  return result;
}

std::string stats_json(const MeshResult& result, int indent) {
  nlohmann::ordered_json j;
  j["vertices"] = result.mesh.vertices.size();
  j["triangles"] = result.mesh.faces.size();
  j["sections"] = result.sections;
  j["joint_patches"] = result.joint_patches;
  j["absorbed_branches"] = result.absorbed_branches;
  j["tunnels"] = result.tunnels;
  j["lost_loops"] = nlohmann::ordered_json::array();
  for (const LostLoop& loop : result.lost_loops)
    j["lost_loops"].push_back({{"joints",
                                {{loop.ends[0].x(), loop.ends[0].y(), loop.ends[0].z()},
                                 {loop.ends[1].x(), loop.ends[1].y(), loop.ends[1].z()}}},
                               {"why", loop.why}});
  j["crossings"] = result.crossings;
  j["hidden_terminals"] = result.hidden_terminals;
  j["separated_points"] = result.separated_points;
  j["largest_separation"] = result.largest_separation;
  j["crossings_left"] = result.crossings_left;
  j["tangle"] = result.tangle;
  j["rounded_vertices"] = result.rounded_vertices;
  j["fitted_vertices"] = result.fitted_vertices;
  j["parted_vertices"] = result.parted_vertices;
  j["taken_back_vertices"] = result.taken_back_vertices;
  j["full_square_tries"] = result.full_square_tries;
  j["small_squares"] = result.small_squares;
  j["transition_triangles"] = std::count(result.transition.begin(), result.transition.end(), 1);
  j["tagged_fraction"] = result.tagged;
  const Verification& v = result.verification;
  j["verified"] = {{"closed_manifold", v.topology.closed_manifold()},
                   {"components", v.topology.components},
                   {"expected_components", v.expected_components},
                   {"genus", v.topology.genus},
                   {"loops", v.loops},
                   {"crossings_checked", v.crossings_checked},
                   {"crossings_checked_near_joints", v.crossings_checked_near_joints},
                   {"crossing_pairs", v.crossing_pairs},
                   {"pairs_in_overlapping_tubes", v.pairs_in_overlapping_tubes},
                   {"problem", v.problem()}};
  double total = 0;
  for (const StageStats& s : result.stages) {
    j["stages"].push_back(
        {{"stage", s.stage}, {"seconds", s.seconds}, {"vertices", s.vertices}, {"faces", s.faces}});
    total += s.seconds;
  }
  j["seconds"] = total;
  return j.dump(indent);
}

}  // namespace vesselmesh
