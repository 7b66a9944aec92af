#include "vesselmesh/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "vesselmesh/curvature/curvature.hpp"
#include "vesselmesh/triangulate/triangulate.hpp"

namespace vesselmesh {

double subdivision_radius_scale() {
  // Mean distance from the axis of the Loop limit surface of a straight four-sided tube, relative to
  // its control square's corners (test_loop: SquareTubeShrinksToTheKnownMeanRadius).
  return 1.0 / 0.657;
}

MeshResult mesh_centerline(const CenterlineGraph& graph, const MeshOptions& options) {
  using Clock = std::chrono::steady_clock;
  MeshResult result;
  auto record = [&](const char* stage, Clock::time_point start, int64_t vertices, int64_t faces) {
    result.stages.push_back({stage, std::chrono::duration<double>(Clock::now() - start).count(), vertices, faces});
  };

  auto start = Clock::now();
  // The tubes the surface follows, built once for the separate stage and the fit, and again only where
  // the separate stage moved the centerline.
  std::optional<RoundCones> cones;
  const CenterlineGraph* centerline = &graph;
  Separation separation;
  if (options.crossings == Crossings::separate) {
    separation = separate_crossings(graph, cones.emplace(graph));
    result.crossings = separation.crossings;
    result.separated_points = separation.moved_points;
    result.largest_separation = separation.largest_move;
    result.crossings_left = separation.left;
    if (separation.moved_points > 0) centerline = &separation.graph, cones.emplace(separation.graph);
    record("separate", start, static_cast<int64_t>(graph.points.size()),
           static_cast<int64_t>(graph.edges.size()));
  }

  start = Clock::now();
  TileOptions tile;
  tile.sampling = options.sampling;
  tile.caps = options.caps;
  tile.radius_scale = subdivision_radius_scale();
  const BaseMesh base = tile_base_mesh(*centerline, tile);
  record("tile", start, static_cast<int64_t>(base.vertices.size()),
         static_cast<int64_t>(base.quads.size() + base.triangles.size()));
  result.sections = base.sections;
  result.joint_patches = base.joints;
  result.absorbed_branches = base.absorbed_branches;
  result.tunnels = base.tunnels;

  start = Clock::now();
  result.mesh = triangulate(base);
  record("triangulate", start, static_cast<int64_t>(result.mesh.vertices.size()),
         static_cast<int64_t>(result.mesh.faces.size()));

  start = Clock::now();
  SubdividedMesh subdivided = subdivide(result.mesh, options.subdivision);
  result.mesh = std::move(subdivided.mesh);
  result.transition = std::move(subdivided.transition);
  result.tagged = std::move(subdivided.tagged);
  record("subdivide", start, static_cast<int64_t>(result.mesh.vertices.size()),
         static_cast<int64_t>(result.mesh.faces.size()));
  if (options.fit != Fit::none) {
    start = Clock::now();
    if (!cones) cones.emplace(*centerline);
    const FitStats fit = fit_to_tubes(result.mesh, *cones, options.fit);
    result.fitted_vertices = fit.moved;
    result.parted_vertices = fit.parted;
    record("fit", start, static_cast<int64_t>(result.mesh.vertices.size()),
           static_cast<int64_t>(result.mesh.faces.size()));
  }
  if (options.curvature) {
    start = Clock::now();
    for (VertexProperty& p : curvature_properties(estimate_curvature(result.mesh)))
      result.mesh.vertex_properties.push_back(std::move(p));
    record("curvature", start, static_cast<int64_t>(result.mesh.vertices.size()),
           static_cast<int64_t>(result.mesh.faces.size()));
  }
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
  j["separated_points"] = result.separated_points;
  j["largest_separation"] = result.largest_separation;
  j["crossings_left"] = result.crossings_left;
  j["fitted_vertices"] = result.fitted_vertices;
  j["parted_vertices"] = result.parted_vertices;
  j["transition_triangles"] = std::count(result.transition.begin(), result.transition.end(), 1);
  j["tagged_fraction"] = result.tagged;
  double total = 0;
  for (const StageStats& s : result.stages) {
    j["stages"].push_back({{"stage", s.stage}, {"seconds", s.seconds}, {"vertices", s.vertices}, {"faces", s.faces}});
    total += s.seconds;
  }
  j["seconds"] = total;
  return j.dump(indent);
}

}  // namespace vesselmesh
