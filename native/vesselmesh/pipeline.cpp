#include "vesselmesh/pipeline.hpp"

#include <algorithm>
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
  if (crossings_checked && crossing_pairs > pairs_in_overlapping_tubes)
    problems.push_back("it crosses itself at " + std::to_string(crossing_pairs - pairs_in_overlapping_tubes) +
                       " triangle pairs where the input's tubes do not overlap");
  std::string out;
  for (const std::string& p : problems) out += (out.empty() ? "" : "; ") + p;
  return out;
}

namespace {

SizeLimitError too_large(int64_t triangles, bool at_least, int64_t sections, const MeshOptions& options) {
  return SizeLimitError("the surface would have " + std::string(at_least ? "more than " : "") +
                        std::to_string(triangles) + " triangles at level " +
                        std::to_string(options.subdivision.levels) + " (" +
                        std::string(at_least ? "over " : "") + std::to_string(sections) +
                        " cross-sections), beyond the limit of " + std::to_string(options.max_triangles) +
                        ": use fewer levels, a larger alpha (sections further apart), or raise max_triangles "
                        "(--max-triangles)");
}

bool checks_crossings(const TriMesh& mesh, Verify how) {
  return how == Verify::full ||
         (how == Verify::automatic && static_cast<int64_t>(mesh.faces.size()) <= kVerifyCrossingsUpTo);
}

Verification verify(const TriMesh& mesh, const CenterlineGraph& centerline, Verify how) {
  Verification v;
  v.topology = check_topology(mesh);
  v.expected_components = centerline.components;
  v.loops = centerline.loops;
  v.crossings_checked = checks_crossings(mesh, how);
  if (v.crossings_checked) {
    const IntersectionReport x = find_self_intersections(mesh, &centerline);
    v.crossing_pairs = x.pairs;
    v.pairs_in_overlapping_tubes = x.pairs_in_overlapping_tubes;
  }
  return v;
}

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

}  // namespace

MeshResult mesh_centerline(const CenterlineGraph& graph, const MeshOptions& options) {
  validate(options);
  if (graph.edges.empty()) throw std::invalid_argument("the centerline has no edges");
  using Clock = std::chrono::steady_clock;
  MeshResult result;
  // A stage run again (another try with full squares, below) adds its time to the first run's.
  auto record = [&](const char* stage, Clock::time_point start, int64_t vertices, int64_t faces) {
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const auto same = std::find_if(result.stages.begin(), result.stages.end(),
                                   [&](const StageStats& s) { return s.stage == stage; });
    if (same == result.stages.end()) return result.stages.push_back({stage, seconds, vertices, faces});
    same->seconds += seconds, same->vertices = vertices, same->faces = faces;
  };

  auto start = Clock::now();
  // The tubes the surface follows, built once for the separate stage and the fit, and again only where
  // the separate stage left terminal branches out or moved the centerline.
  std::optional<RoundCones> cones;
  const CenterlineGraph* centerline = &graph;
  HiddenTerminals hidden;
  Separation separation;
  if (options.crossings == Crossings::separate) {
    hidden = drop_hidden_terminals(graph, cones.emplace(graph));
    result.hidden_terminals = hidden.dropped;
    if (hidden.dropped > 0) centerline = &hidden.graph, cones.emplace(hidden.graph);
    separation = separate_crossings(*centerline, *cones);
    result.crossings = separation.crossings;
    result.separated_points = separation.moved_points;
    result.largest_separation = separation.largest_move;
    result.crossings_left = separation.left;
    result.tangle = separation.tangle;
    if (separation.moved_points > 0) centerline = &separation.graph, cones.emplace(separation.graph);
    record("separate", start, static_cast<int64_t>(graph.points.size()),
           static_cast<int64_t>(graph.edges.size()));
  }

  TileOptions tile;
  tile.sampling = options.sampling;
  tile.caps = options.caps;
  tile.radius_scale = subdivision_radius_scale(4);  // octagons are tiled as squares (tile/octagons.hpp)
  // Every section brings at least two triangles a side, and each level four times as many.
  const int64_t per_base_triangle = int64_t{1} << (2 * options.subdivision.levels);
  const int64_t per_section = 2 * options.sides * per_base_triangle;
  tile.max_sections = std::max<int64_t>(2, options.max_triangles / per_section);
  // Small squares on every patch where the surface will be checked for crossings (tile step 7 of
  // docs/pipeline.md): where it crosses itself outside overlapping tubes, the patches near the crossing
  // are tried again with full squares.
  tile.small_squares = options.verify == Verify::full ||
                       (options.verify == Verify::automatic &&
                        per_section * sections_estimate(*centerline) <= kVerifyCrossingsUpTo);
  TubeCurvature tubes;
  for (int tries = 1;; ++tries) {
    start = Clock::now();
    BaseMesh base;
    try {
      base = tile_base_mesh(*centerline, tile);
      if (options.sides == 8)
        base = octagonal_sections(std::move(base), subdivision_radius_scale(8) / subdivision_radius_scale(4));
    } catch (const SizeLimitError&) {
      throw too_large(per_section * tile.max_sections, true, tile.max_sections, options);
    }
    const auto base_triangles = static_cast<int64_t>(2 * base.quads.size() + base.triangles.size());
    if (base_triangles * per_base_triangle > options.max_triangles)
      throw too_large(base_triangles * per_base_triangle, false, base.sections, options);
    record("tile", start, static_cast<int64_t>(base.vertices.size()),
           static_cast<int64_t>(base.quads.size() + base.triangles.size()));
    result.sections = base.sections;
    result.joint_patches = base.joints;
    result.absorbed_branches = base.absorbed_branches;
    result.tunnels = base.tunnels;

    start = Clock::now();
    result.mesh = triangulate(base);
    // Only the curvature reads the axis's shape: without it, subdivision carries 5 properties instead of 12.
    if (!options.curvature) drop_tube_axis_properties(result.mesh, kRoundAxisProperties);
    record("triangulate", start, static_cast<int64_t>(result.mesh.vertices.size()),
           static_cast<int64_t>(result.mesh.faces.size()));

    start = Clock::now();
    SubdividedMesh subdivided = subdivide(result.mesh, options.subdivision);
    result.mesh = std::move(subdivided.mesh);
    result.transition = std::move(subdivided.transition);
    result.tagged = std::move(subdivided.tagged);
    record("subdivide", start, static_cast<int64_t>(result.mesh.vertices.size()),
           static_cast<int64_t>(result.mesh.faces.size()));
    // Small squares where the estimate let them through but the surface turned out too large to be checked:
    // built again as where it is never checked.
    if (tile.small_squares && !checks_crossings(result.mesh, options.verify)) {
      tile.small_squares = false;
      ++result.full_square_tries;
      continue;
    }
    start = Clock::now();
    // The tubes' own curvature, read before rounding takes the tube properties off (tube_curvature.hpp).
    if (options.curvature) tubes = tube_curvature(result.mesh);
    result.rounded_vertices = round_tubes(result.mesh).moved;
    record("round", start, static_cast<int64_t>(result.mesh.vertices.size()),
           static_cast<int64_t>(result.mesh.faces.size()));
    // Where the surface is checked for crossings, the fit's moves can be taken back where faces cross.
    const bool fits = options.fit != Fit::none;
    const std::vector<Vec3> before_fit =
        fits && checks_crossings(result.mesh, options.verify) ? result.mesh.vertices : std::vector<Vec3>();
    if (fits) {
      start = Clock::now();
      if (!cones) cones.emplace(*centerline);
      const FitStats fit = fit_to_tubes(result.mesh, *cones, options.fit);
      result.fitted_vertices = fit.moved;
      result.parted_vertices = fit.parted;
      record("fit", start, static_cast<int64_t>(result.mesh.vertices.size()),
             static_cast<int64_t>(result.mesh.faces.size()));
    }
    // Every file and Blender hold the coordinates as floats: rounded here, what the check passes is what
    // they hold.
    for (Vec3& p : result.mesh.vertices) p = p.cast<float>().cast<double>();
    start = Clock::now();
    result.verification = verify(result.mesh, *centerline, options.verify);
    const auto crosses = [&] {
      return result.verification.crossing_pairs > result.verification.pairs_in_overlapping_tubes;
    };
    result.taken_back_vertices = 0;
    if (!before_fit.empty() && crosses()) {
      result.taken_back_vertices = take_back_crossing_moves(result.mesh, before_fit);
      if (result.taken_back_vertices > 0)
        result.verification = verify(result.mesh, *centerline, options.verify);
    }
    record("verify", start, static_cast<int64_t>(result.mesh.vertices.size()),
           static_cast<int64_t>(result.mesh.faces.size()));
    if (!tile.small_squares) break;
    const bool lost_a_loop = result.verification.topology.genus < result.verification.loops;
    if (lost_a_loop || (crosses() && tries == kSmallSquareTries)) {
      // A loop lost (vesselgraph-demo at level 0), or crossings that full squares round them did not part:
      // small squares only where the surface is never checked, on patches along a vessel.
      tile.small_squares = false;
    } else {
      if (!crosses()) break;
      for (const auto& pair : intersecting_face_pairs(result.mesh))
        for (int32_t f : pair) tile.full_squares_near.push_back(centroid(result.mesh, f));
    }
    ++result.full_square_tries;
  }
  if (options.curvature) {
    start = Clock::now();
    VertexCurvature curvature = estimate_curvature(result.mesh, needs_fit(tubes));
    blend_tube_curvature(curvature, tubes);
    for (VertexProperty& p : curvature_properties(curvature)) result.mesh.vertex_properties.push_back(std::move(p));
    if (!cones) cones.emplace(*centerline);
    const std::vector<double> radius = local_radius(result.mesh.vertices, *cones);
    result.mesh.vertex_properties.push_back({"radius", std::vector<float>(radius.begin(), radius.end())});
    record("curvature", start, static_cast<int64_t>(result.mesh.vertices.size()),
           static_cast<int64_t>(result.mesh.faces.size()));
  }
  if (separation.moved_points > 0)
    result.separated = std::move(separation.graph);
  else if (hidden.dropped > 0)
    result.separated = std::move(hidden.graph);
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
  j["transition_triangles"] = std::count(result.transition.begin(), result.transition.end(), 1);
  j["tagged_fraction"] = result.tagged;
  const Verification& v = result.verification;
  j["verified"] = {{"closed_manifold", v.topology.closed_manifold()},
                   {"components", v.topology.components},
                   {"expected_components", v.expected_components},
                   {"genus", v.topology.genus},
                   {"loops", v.loops},
                   {"crossings_checked", v.crossings_checked},
                   {"crossing_pairs", v.crossing_pairs},
                   {"pairs_in_overlapping_tubes", v.pairs_in_overlapping_tubes},
                   {"problem", v.problem()}};
  double total = 0;
  for (const StageStats& s : result.stages) {
    j["stages"].push_back({{"stage", s.stage}, {"seconds", s.seconds}, {"vertices", s.vertices}, {"faces", s.faces}});
    total += s.seconds;
  }
  j["seconds"] = total;
  return j.dump(indent);
}

}  // namespace vesselmesh
