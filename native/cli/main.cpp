// vesselmesh: the command-line front end of the core.
//   vesselmesh info FILE [--json] [--radius-array NAME]
//   vesselmesh synth -o FILE --sections N [--loops K] [--seed S] [--binary]
//   vesselmesh mesh IN -o OUT.{ply,obj,stl} [--levels N] [--sampling ...] [--alpha A] [--beta B]
//                   [--tolerance T] [--max-step S] [--caps flat|open] [--crossings separate|keep] [--fit onto|inward|none]
//                   [--stats-json FILE] [--curvature]
//   vesselmesh check MESH [--centerline IN] [--json]
#include <CLI/CLI.hpp>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "vesselmesh/check/check_mesh.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"
#include "vesselmesh/mesh/mesh_files.hpp"
#include "vesselmesh/option_names.hpp"
#include "vesselmesh/pipeline.hpp"
#include "vesselmesh/read/read.hpp"
#include "vesselmesh/summary.hpp"
#include "vesselmesh/synth/synth.hpp"
#include "vesselmesh/write/centerline_vtk.hpp"

using namespace vesselmesh;

namespace {

std::string point_text(const Vec3& p) {
  std::ostringstream text;
  text << std::setprecision(6) << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return text.str();
}

/// A loop the surface closed, and why, in words (MeshResult::lost_loops).
std::string lost_loop_text(const LostLoop& loop) {
  return "the loop through the branch from " + point_text(loop.ends[0]) + " to " + point_text(loop.ends[1]) +
         " closed inside a joint patch: " + loop.why;
}

/// The loops a quick build of a centerline (level 0, otherwise the default settings) closes, and why: a
/// loop whose tubes fill its hole may close inside a joint patch (docs/pipeline.md, tile step 4).
struct QuickBuild {
  std::vector<LostLoop> closed;
  std::string not_built;  ///< why there was none: over 100,000 points or a million triangles, or its error
};

QuickBuild loops_a_quick_build_closes(const CenterlineGraph& g) {
  if (g.loops == 0) return {};
  if (g.points.size() > 100'000) return {{}, "over 100,000 points"};
  MeshOptions quick;
  quick.subdivision.levels = 0;
  quick.max_triangles = 1'000'000;  // a second or two on two cores
  try {
    return {mesh_centerline(g, quick).lost_loops, ""};
  } catch (const SizeLimitError&) {
    return {{}, "over a million triangles at level 0"};
  } catch (const std::exception& e) {
    return {{}, e.what()};
  }
}

/// What `info` says of the loops a quick build closes.
std::string loops_text(const QuickBuild& quick, int64_t loops) {
  if (loops == 0) return "";
  if (!quick.not_built.empty())
    return " (no quick build: " + quick.not_built + "; `vesselmesh mesh` names the loops it closes)";
  if (quick.closed.empty()) return " (a level-0 build keeps each as a handle)";
  std::string text = " (a level-0 build closes " + std::to_string(quick.closed.size()) + ":";
  for (const LostLoop& loop : quick.closed) text += "\n              " + lost_loop_text(loop);
  return text + ")";
}

void print_info(const CenterlineGraph& g, const std::string& file) {
  const auto j = nlohmann::json::parse(summary_json(g));
  const auto& n = j["normalisation"];
  std::cout << file << "\n"
            << "  points      " << j["points"] << "\n"
            << "  edges       " << j["edges"] << "\n"
            << "  components  " << j["components"] << "\n"
            << "  branches    " << j["branches"] << "\n"
            << "  joints      " << j["joints"] << " (max degree " << j["max_degree"] << ")\n"
            << "  terminals   " << j["terminals"] << "\n"
            << "  loops       " << j["loops"] << loops_text(loops_a_quick_build_closes(g), g.loops) << "\n"
            << "  radius      " << j["radius"]["min"] << " .. " << j["radius"]["max"] << " (per "
            << j["radius"]["per"].get<std::string>() << ")\n"
            << "  bbox        " << j["bbox"]["min"].dump() << " .. " << j["bbox"]["max"].dump() << "\n"
            << "  normalised  " << n["input_points"] << " points, " << n["input_edges"]
            << " edges read; merged " << n["merged_points"] << " coincident points, dropped "
            << n["zero_length_edges"] << " zero-length edges, merged " << n["duplicate_edges"]
            << " duplicate edges, dropped " << n["isolated_points"] << " isolated points, set "
            << n["snapped_coordinates"] << " coordinates next to zero to zero\n";
  // Where the input's tubes overlap, the surface cannot follow both without crossing itself, pressing
  // them flat against each other or moving them apart: worth knowing before meshing.
  const auto& overlaps = j["overlaps"];
  const auto crossing = std::count_if(overlaps.begin(), overlaps.end(), [](const auto& o) {
    return o["crossing_pairs"].template get<int>() > 0;
  });
  std::cout << "  overlaps    " << overlaps.size() << (overlaps.size() == 1 ? " place" : " places")
            << " where tubes overlap away from their joints (vessels crossing, touching or traced along "
               "each other)";
  if (crossing > 0) std::cout << "; at " << crossing << " they cross, and mesh moves them apart";
  std::cout << "\n";
  constexpr std::size_t kShown = 10;
  std::ostringstream places;
  places << std::setprecision(4);
  for (std::size_t i = 0; i < std::min(overlaps.size(), kShown); ++i) {
    const auto& o = overlaps[i];
    places << "              at (" << o["at"][0].get<double>() << ", " << o["at"][1].get<double>() << ", "
           << o["at"][2].get<double>() << "), radius " << o["radius"].get<double>() << ", " << o["edge_pairs"]
           << (o["edge_pairs"] == 1 ? " edge pair" : " edge pairs")
           << (o["crossing_pairs"] > 0 ? ", crossing" : "") << "\n";
  }
  std::cout << places.str();
  if (overlaps.size() > kShown) std::cout << "              ... (all of them: --json)\n";
}

/// The mark of a lost loop's line in a surface file's comments, for `vesselmesh check` to name it.
constexpr std::string_view kLostLoopComment = "lost loop: ";

/// Which loops the surface closed and why (MeshResult::lost_loops), the first ten.
void print_lost_loops(const std::vector<LostLoop>& loops) {
  for (std::size_t i = 0; i < loops.size() && i < 10; ++i)
    std::cerr << "  " << lost_loop_text(loops[i]) << "\n";
  if (loops.size() > 10) std::cerr << "  and " << loops.size() - 10 << " more (--stats-json lists them)\n";
}

/// `closed`: the loops the surface closed, in words, as `source` says (the file's lost-loop comments, or a
/// quick build of the centerline).
void print_check(const CheckReport& r, const std::string& file, const CenterlineGraph* graph,
                 const std::vector<std::string>& closed, const std::string& source) {
  const TopologyReport& t = r.topology;
  std::cout << file << "\n"
            << "  closed manifold      " << (t.closed_manifold() ? "yes" : "no") << " (" << t.boundary_edges
            << " boundary edges, " << t.non_manifold_edges << " non-manifold edges, "
            << t.non_manifold_vertices << " non-manifold vertices, " << t.inconsistent_edges
            << " inconsistently oriented edges, " << t.degenerate_faces << " degenerate faces)\n"
            << "  size                 " << t.vertices << " vertices, " << t.faces << " triangles\n"
            << "  components, genus    " << t.components << ", " << t.genus << " (Euler characteristic "
            << t.euler_characteristic << ")\n";
  if (graph && graph->loops != t.genus)
    std::cout << "  loops                " << graph->loops << " in the centerline, genus " << t.genus
              << (graph->loops > t.genus
                      ? ": " + std::to_string(graph->loops - t.genus) +
                            (closed.empty() ? " closed (`vesselmesh mesh` names the loops it closes, and why)"
                                            : " closed; " + source + ":")
                      : ": handles no loop goes round")
              << "\n";
  if (graph && graph->loops > t.genus)
    for (const std::string& loop : closed) std::cout << "                       " << loop << "\n";
  std::cout << "  self-intersections   " << r.intersections.pairs << " triangle pairs ("
            << r.intersections.pairs_in_overlapping_tubes << " where the input tubes overlap)\n"
            << "  radius ratio R/r     median " << r.quality.radius_ratio.median << ", max "
            << r.quality.radius_ratio.max << "\n"
            << "  minimum angle        median " << r.quality.min_angle.median << ", min "
            << r.quality.min_angle.min << " degrees\n";
  if (r.fidelity)
    std::cout << "  radius error         median " << 100 * r.fidelity->abs_relative_error.median
              << " %, 95th " << 100 * r.fidelity->abs_relative_error.p95 << " % of the local radius\n"
              << "  between the vertices median " << 100 * r.fidelity->centroid_error.median << " %, 95th "
              << 100 * r.fidelity->centroid_error.p95 << " %, 99th " << 100 * r.fidelity->centroid_error.p99
              << " % (face centroids off the tubes, by area)\n"
              << "  area off the tubes   " << 100 * r.fidelity->area_off_tubes
              << " % (faces centred over half a radius off them)\n"
              << "  furthest face        " << r.fidelity->largest_centroid_offset
              << " local radii off the tubes, at " << point_text(r.fidelity->largest_centroid_offset_at)
              << "\n"
              << "  longest edge         " << r.fidelity->longest_edge << " local radii ("
              << r.fidelity->longest_edge_length << "), at " << point_text(r.fidelity->longest_edge_at)
              << "\n"
              << "  longest edge off     " << r.fidelity->longest_edge_off_tubes
              << " local radii (its middle over half a radius off the tubes), at "
              << point_text(r.fidelity->longest_edge_off_tubes_at) << "\n"
              << "  axis with no surface " << r.fidelity->missing_axis
              << " local radii (outside the surface by over a radius)"
              << (r.fidelity->missing_axis > 0 ? ", first at " + point_text(r.fidelity->missing_axis_at) : "")
              << "\n";
}

}  // namespace

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // The core's big arrays come and go stage by stage. By default glibc maps each one larger than a few MiB
  // afresh and unmaps it when freed, so every stage pays a page fault per 4 KiB it touches; kept in the
  // heap instead (no mapping at all), freed memory is reused (brava-bg0003 at level 2: 1.7 s → 1.1 s here;
  // a million sections about 2 s of 31, for a tenth more peak memory). The process is short-lived: what it
  // keeps goes back when it exits.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
#endif
  CLI::App app{"VesselMesh: smooth, closed, adaptive vessel surfaces from centerline graphs"};
  app.require_subcommand(1);

  std::string info_file, radius_array;
  bool json = false;
  CLI::App* info = app.add_subcommand("info", "Read a centerline file and describe its graph");
  info->add_option("FILE", info_file, "centerline file: .swc .vtk .vtp, or a vertices/edges .csv pair")
      ->required();
  info->add_flag("--json", json, "print JSON instead of text");
  info->add_option("--radius-array", radius_array, "name of the array or column holding the radius");

  std::string synth_out;
  SynthOptions synth_options;
  bool binary = false;
  CLI::App* synth = app.add_subcommand("synth", "Write a deterministic synthetic arterial network (legacy VTK)");
  synth->add_option("-o,--output", synth_out, "output .vtk file")->required();
  synth->add_option("--sections", synth_options.sections, "about this many cross-sections")
      ->check(CLI::Range(int64_t{2}, int64_t{100000000}));
  synth->add_option("--loops", synth_options.loops, "anastomosis loops to add")->check(CLI::NonNegativeNumber);
  synth->add_option("--seed", synth_options.seed, "random seed (same seed, same network)");
  synth->add_flag("--binary", binary, "write binary VTK (smaller and faster for large networks)");

  std::string mesh_in, mesh_out, stats_file, centerline_out;
  MeshOptions mesh_options;
  CLI::App* mesh = app.add_subcommand("mesh", "Build the vessel surface of a centerline");
  mesh->add_option("IN", mesh_in, "centerline file")->required();
  mesh->add_option("-o,--output", mesh_out, "surface file: .ply, .obj or .stl")->required();
  SubdivisionOptions& subdivision = mesh_options.subdivision;
  mesh->add_option("--levels", subdivision.levels, "Loop subdivision levels")->check(CLI::Range(0, 4));
  mesh->add_option("--method", subdivision.method, "which triangles each level splits")
      ->transform(CLI::CheckedTransformer(refinement_names()));
  mesh->add_option("--uniform-levels", subdivision.uniform_levels,
                   "the first levels split every triangle (adaptive methods)")
      ->check(CLI::NonNegativeNumber);
  mesh->add_option("--threshold", subdivision.threshold,
                   "curvature method: split triangles with a vertex at or above this equalised curvature")
      ->check(CLI::Range(0.0, 1.0));
  mesh->add_option("--measure", subdivision.measure, "curvature method: the measure to equalise and threshold")
      ->transform(CLI::CheckedTransformer(measure_names()));
  mesh->add_option("--angle", subdivision.angle_degrees,
                   "dihedral method: split triangles with an interior dihedral angle below this, in degrees")
      ->check(CLI::Range(0.0, 180.0));
  mesh->add_option("--sampling", mesh_options.sampling.method, "cross-section sampling")
      ->transform(CLI::CheckedTransformer(sampling_names()));
  mesh->add_option("--alpha", mesh_options.sampling.alpha, "spacing scale (1: about one diameter)")
      ->check(CLI::PositiveNumber);
  mesh->add_option("--beta", mesh_options.sampling.beta, "curvature weight, in median radii")
      ->check(CLI::NonNegativeNumber);
  mesh->add_option("--tolerance", mesh_options.sampling.tolerance,
                   "sections further apart than --alpha's where a straight piece of tube stays within this "
                   "fraction of the local radius of the centerline (0: --alpha's spacing alone)")
      ->check(CLI::NonNegativeNumber);
  mesh->add_option("--max-step", mesh_options.sampling.max_step, "the longest such piece, in radii")
      ->check(CLI::Range(2.0, std::numeric_limits<double>::max()));
  mesh->add_option("--sides", mesh_options.sides, "sides round every base section: 4 or 8")
      ->check(CLI::IsMember({4, 8}));
  mesh->add_option("--caps", mesh_options.caps, "terminal ends")
      ->transform(CLI::CheckedTransformer(caps_names()));
  mesh->add_option("--stats-json", stats_file, "write counts and per-stage times here");
  mesh->add_option("--centerline-out", centerline_out,
                   "write the centerline the surface follows here (legacy VTK): the input with its crossing "
                   "vessels moved apart, as the separate stage left it; for vesselmesh check --centerline");
  mesh->add_option("--crossings", mesh_options.crossings,
                   "vessels whose tubes cross away from a joint: move them apart (separate) or keep them")
      ->transform(CLI::CheckedTransformer(crossings_names()));
  mesh->add_option("--fit", mesh_options.fit,
                   "which vertices come onto the input's tubes: all (onto), those outside (inward), none")
      ->transform(CLI::CheckedTransformer(fit_names()));
  mesh->add_flag("--curvature", mesh_options.curvature,
                 "per-vertex curvature (the tubes' own along the vessels, a 2-ring fit at joints and caps); PLY gets "
                 "k1, k2, mean, gaussian, rms and the local "
                 "tube radius");
  mesh->add_option("--radius-array", radius_array, "name of the array or column holding the radius");
  mesh->add_option("--max-triangles", mesh_options.max_triangles,
                   "refuse, before the work, a surface with more triangles than this")
      ->check(CLI::Range(int64_t{1}, std::numeric_limits<int64_t>::max()));
  mesh->add_option(
          "--verify", mesh_options.verify,
          "check the surface before reporting success: closed manifold, and crossings up to a million "
          "triangles, near the joints and caps up to 16 million (auto), everywhere whatever its size "
          "(full), or never (topology); where crossings are checked, joint patches hug their branches "
          "closer, built again as before round a crossing")
      ->transform(CLI::CheckedTransformer(verify_names()));

  std::string check_in, check_centerline;
  CLI::App* check = app.add_subcommand("check", "Check a surface: closed, manifold, intersections, quality");
  check->add_option("MESH", check_in, "surface file: .ply, .obj or .stl")->required();
  check->add_option("--centerline", check_centerline, "centerline it was made from, for radius fidelity");
  check->add_flag("--json", json, "print JSON");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*info) {
      ReadOptions options;
      options.radius_array = radius_array;
      const CenterlineGraph graph = build_graph(read_centerline(info_file, options), info_file);
      if (json) {
        nlohmann::ordered_json j = nlohmann::ordered_json::parse(summary_json(graph));
        const QuickBuild quick = loops_a_quick_build_closes(graph);
        if (graph.loops > 0 && quick.not_built.empty()) {
          j["loops_closed_at_level_0"] = nlohmann::ordered_json::array();
          for (const LostLoop& loop : quick.closed)
            j["loops_closed_at_level_0"].push_back(lost_loop_text(loop));
        }
        std::cout << j.dump(2) << "\n";
      } else {
        print_info(graph, info_file);
      }
    } else if (*synth) {
      const auto start = std::chrono::steady_clock::now();
      const CenterlineData data = synthesize_network(synth_options);
      write_centerline_vtk(data, synth_out, binary);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::cerr << "wrote " << synth_out << ": " << data.points.size() << " points, " << data.edges.size()
                << " edges in " << seconds << " s\n";
    } else if (*mesh) {
      ReadOptions options;
      options.radius_array = radius_array;
      const CenterlineGraph graph = build_graph(read_centerline(mesh_in, options), mesh_in);
      const MeshResult result = mesh_centerline(graph, mesh_options);
      WriteOptions written;
      for (const LostLoop& loop : result.lost_loops)
        written.comments.push_back(std::string(kLostLoopComment) + lost_loop_text(loop));
      write_mesh(result.mesh, mesh_out, written);
      if (!centerline_out.empty())
        write_centerline_vtk(centerline_data(result.separated ? *result.separated : graph), centerline_out, false);
      const Verification& v = result.verification;
      std::cerr << "wrote " << mesh_out << ": " << result.mesh.vertices.size() << " vertices, "
                << result.mesh.faces.size() << " triangles";
      const std::string where = v.crossings_checked ? "" : " near its joints and caps";
      if (v.problem().empty())
        std::cerr << "; checked: a closed manifold of genus " << v.topology.genus << ", "
                  << (!v.crossings_checked && !v.crossings_checked_near_joints
                          ? std::string(mesh_options.verify == Verify::topology
                                            ? "crossings not checked (--verify topology)"
                                            : "crossings not checked above 16 million triangles "
                                              "(--verify full, or vesselmesh check)")
                      : v.crossing_pairs == 0
                          ? "crossing itself nowhere" + where
                          : "crossing itself" + where + " only where the input's tubes overlap (" +
                                std::to_string(v.crossing_pairs) + " triangle pairs)");
      if (v.problem().empty() && v.crossings_checked_near_joints)
        std::cerr << " (only there above a million triangles: --verify full, or vesselmesh check)";
      std::cerr << "\n";
      if (v.topology.closed_manifold() && v.topology.genus != v.loops) {
        std::cerr << "note: the centerline has " << v.loops << (v.loops == 1 ? " loop" : " loops")
                  << " and the surface genus " << v.topology.genus
                  << " (docs/pipeline.md, tile: where a loop closes)\n";
        print_lost_loops(result.lost_loops);
      }
      if (result.hidden_terminals > 0)
        std::cerr << "note: " << result.hidden_terminals
                  << " terminal branches lie wholly inside other vessels' tubes and were left out: the vessel's "
                     "shape is the same (docs/pipeline.md, separate)\n";
      if (result.tangle)
        std::cerr << "note: " << result.crossings
                  << " pairs of crossing vessels lie in a tangle too dense to part, and were left as they are "
                     "(docs/pipeline.md, separate)\n";
      if (!stats_file.empty()) {
        std::ofstream out(stats_file);
        out << stats_json(result) << "\n";
        if (!out) throw std::runtime_error("cannot write " + stats_file);
      }
      if (!v.problem().empty()) {
        std::cerr << "error: the surface written to " << mesh_out << " fails its check: " << v.problem()
                  << " (where: vesselmesh check " << mesh_out << " --centerline " << mesh_in << ")\n";
        return 2;
      }
    } else if (*check) {
      const TriMesh surface = read_mesh(check_in);
      std::optional<CenterlineGraph> graph;
      if (!check_centerline.empty()) graph = build_graph(read_centerline(check_centerline), check_centerline);
      const CheckReport report = check_mesh(surface, graph ? &*graph : nullptr);
      // The loops the surface closed: as the file says, or else as a quick build of the centerline closes
      // them.
      std::vector<std::string> closed;
      for (const std::string& line : read_mesh_comments(check_in))
        if (line.rfind(kLostLoopComment, 0) == 0) closed.push_back(line.substr(kLostLoopComment.size()));
      std::string source = "as the file says", key = "closed_loops";
      if (closed.empty() && graph && report.topology.closed_manifold() &&
          report.topology.genus < graph->loops) {
        for (const LostLoop& loop : loops_a_quick_build_closes(*graph).closed)
          closed.push_back(lost_loop_text(loop));
        source = "the file does not say which, a level-0 build of the centerline closes";
        key = "loops_closed_at_level_0";
      }
      if (json && closed.empty()) {
        std::cout << report_json(report) << "\n";
      } else if (json) {
        nlohmann::ordered_json j = nlohmann::ordered_json::parse(report_json(report));
        j[key] = closed;
        std::cout << j.dump(2) << "\n";
      } else {
        print_check(report, check_in, graph ? &*graph : nullptr, closed, source);
      }
      // Status 2 when the surface is not a closed manifold or intersects itself where the tubes do not.
      const auto& x = report.intersections;
      return report.topology.closed_manifold() && x.pairs == x.pairs_in_overlapping_tubes ? 0 : 2;
    }
  } catch (const std::exception& e) {  // InputError names the file and place; others say what failed
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
