// The command-line tool as a user runs it: `vesselmesh info --json` reports the counts each shared data
// set's SOURCE.md gives, and bad input exits non-zero with a message naming the file.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "test_support.hpp"

namespace {

using vesselmesh::test::CliRun;
using vesselmesh::test::run_cli;

/// The --stats-json of `vesselmesh mesh` on the project's bifurcation with the given options.
nlohmann::json mesh_stats(const std::string& options, const std::string& input = "bifurcation.swc") {
  const std::string stats = vesselmesh::test::temp_path("stats.json");
  const CliRun run =
      run_cli("mesh '" + vesselmesh::test::test_data(input) + "' -o '" +
              vesselmesh::test::temp_path("m.ply") + "' " + options + " --stats-json '" + stats + "'");
  EXPECT_EQ(run.status, 0) << options << ": " << run.output;
  std::ifstream file(stats);
  return nlohmann::json::parse(file);
}

nlohmann::json info_json(const std::string& path) {
  const CliRun run = run_cli("info --json '" + path + "'");
  EXPECT_EQ(run.status, 0) << run.output;
  return nlohmann::json::parse(run.output);
}

struct Expected {
  const char* file;
  int points, edges, components, branches, joints, loops, max_degree;
};
void PrintTo(const Expected& x, std::ostream* os) { *os << x.file; }

// Counts after normalisation, from each set's SOURCE.md (for VMTK: "after merging exactly-coincident
// points"; for the mesentery: the simple graph, its one parallel duplicate segment dropped).
const Expected kSharedSets[] = {
    {"secomb-rat-cortex-50/network.vtk", 49, 50, 2, 26, 13, 3, 4},
    {"vmtk-aorta-centerline/aorta-centerline.vtp", 346, 345, 1, 3, 1, 0, 3},
    {"vmtk-aorta-centerline/aorta-centerline-branches.vtp", 350, 349, 1, 3, 1, 0, 3},
    {"vascpy-mouse-vessels/penetrating_artery.vtk", 1274, 1273, 1, 1, 0, 0, 2},
    {"vascpy-mouse-vessels/test_smaller_vasculature.vtk", 912, 897, 15, 27, 6, 0, 3},
    {"brava-bg0003/BG0003_ColorCoded.CNG.swc", 3470, 3469, 1, 219, 109, 0, 3},
    {"human-brain-arteries/arteries_smooth.vtk", 12709, 12708, 1, 291, 145, 0, 3},
    {"secomb-rat-mesentery/network.vtk", 972, 1129, 1, 543, 350, 158, 3},
    {"vesselgraph-demo/vertices.csv", 3197, 3249, 1, 3227, 1627, 53, 5},
    {"neuron-hemibrain-da1/1734350788.swc", 4465, 4464, 1, 1217, 599, 0, 5},
};

}  // namespace

class SharedSet : public testing::TestWithParam<Expected> {};

TEST_P(SharedSet, InfoJsonReportsTheCountsOfItsSourceMd) {
  const Expected& x = GetParam();
  SHARED_DATA_OR_SKIP(path, x.file);
  const nlohmann::json j = info_json(path);
  EXPECT_EQ(j["points"], x.points);
  EXPECT_EQ(j["edges"], x.edges);
  EXPECT_EQ(j["components"], x.components);
  EXPECT_EQ(j["branches"], x.branches);
  EXPECT_EQ(j["joints"], x.joints);
  EXPECT_EQ(j["loops"], x.loops);
  EXPECT_EQ(j["max_degree"], x.max_degree);
}

INSTANTIATE_TEST_SUITE_P(Cli, SharedSet, testing::ValuesIn(kSharedSets), [](const auto& info) {
  std::string name = info.param.file;
  for (char& c : name)
    if (!isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

TEST(Cli, VmtkOverlapIsReportedAsMergedPointsAndDroppedEdges) {
  SHARED_DATA_OR_SKIP(path, "vmtk-aorta-centerline/aorta-centerline.vtp");
  const nlohmann::json n = info_json(path)["normalisation"];
  EXPECT_EQ(n["input_points"], 409);
  EXPECT_EQ(n["merged_points"], 63);
  EXPECT_EQ(n["zero_length_edges"], 1);
  EXPECT_EQ(n["duplicate_edges"], 61);
}

TEST(Cli, MesenteryParallelSegmentIsReportedAsADuplicateEdge) {
  SHARED_DATA_OR_SKIP(path, "secomb-rat-mesentery/network.vtk");
  EXPECT_EQ(info_json(path)["normalisation"]["duplicate_edges"], 1);
}

TEST(Cli, InfoJsonOnTheProjectsOwnFixtureHasTheRequiredKeys) {
  const nlohmann::json j = info_json(vesselmesh::test::test_data("bifurcation.swc"));
  for (const char* key : {"points", "edges", "components", "branches", "joints", "loops"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["branches"], 3);
}

TEST(Cli, InfoTextNamesTheFile) {
  const std::string path = vesselmesh::test::test_data("ring_with_tail.vtk");
  const CliRun run = run_cli("info '" + path + "'");
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.output.find("ring_with_tail.vtk"), std::string::npos);
  EXPECT_NE(run.output.find("loops       1"), std::string::npos) << run.output;
}

TEST(Cli, InfoTellsWhereTheInputTubesOverlap) {
  // A vessel that turns back across its own start, 0.3 off its axis.
  const std::string path = vesselmesh::test::temp_path("crosses_itself.swc");
  std::ofstream(path) << "1 1 0 0 0 1 -1\n2 1 10 0 0 1 1\n3 1 20 0 0 1 2\n4 1 0 10 0 1 1\n5 1 10 10 0.3 1 4\n"
                         "6 1 10 -10 0.3 1 5\n";
  const CliRun run = run_cli("info '" + path + "'");
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.output.find("overlaps    1 place where"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("at 1 they cross, and mesh moves them apart"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("at (10, 0, 0.15), radius 1, 2 edge pairs, crossing"), std::string::npos)
      << run.output;
  const nlohmann::json j = info_json(path);
  ASSERT_EQ(j["overlaps"].size(), 1u);
  EXPECT_EQ(j["overlaps"][0]["edge_pairs"], 2);
  EXPECT_EQ(j["overlaps"][0]["crossing_pairs"], 2);
  EXPECT_TRUE(info_json(vesselmesh::test::test_data("ring_with_tail.vtk"))["overlaps"].empty());
}

TEST(Cli, InfoSaysWhichLoopsAQuickBuildClosesAndWhy) {
  const std::string fat = vesselmesh::test::test_data("extreme/fat_loop_round_a_thin_branch.vtk");
  const CliRun run = run_cli("info '" + fat + "'");
  EXPECT_NE(
      run.output.find("loops       1 (a level-0 build closes 1:\n              the loop through the branch "
                      "from (-3, 0, 0) to (0, 0, 0) closed inside a joint patch: the joint patch's hull "
                      "does not close round its hole)"),
      std::string::npos)
      << run.output;
  EXPECT_EQ(info_json(fat)["loops_closed_at_level_0"].size(), 1u);
  const std::string ring = vesselmesh::test::test_data("ring_with_tail.vtk");
  EXPECT_NE(
      run_cli("info '" + ring + "'").output.find("loops       1 (a level-0 build keeps each as a handle)"),
      std::string::npos);
  EXPECT_TRUE(info_json(ring)["loops_closed_at_level_0"].empty());
  EXPECT_FALSE(info_json(vesselmesh::test::test_data("bifurcation.swc")).contains("loops_closed_at_level_0"));
}

TEST(Cli, MalformedInputExitsNonZeroWithTheFileAndLine) {
  const std::string path = vesselmesh::test::temp_path("truncated.swc");
  std::ofstream(path) << "1 1 0 0 0 1 -1\n2 1 0 0 1\n";
  const CliRun run = run_cli("info '" + path + "'");
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("truncated.swc: line 2"), std::string::npos) << run.output;
}

TEST(Cli, MissingFileAndUnknownFormatExitNonZero) {
  EXPECT_NE(run_cli("info /nonexistent/file.swc").status, 0);
  const std::string path = vesselmesh::test::temp_path("network.xyz");
  std::ofstream(path) << "hello\n";
  const CliRun run = run_cli("info '" + path + "'");
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("unknown format"), std::string::npos) << run.output;
}

TEST(Cli, SynthWritesANetworkThatInfoReadsBack) {
  const std::string path = vesselmesh::test::temp_path("synth.vtk");
  for (const char* binary : {"", " --binary"}) {
    const CliRun run = run_cli("synth -o '" + path + "' --sections 3000 --loops 3 --seed 5" + binary);
    ASSERT_EQ(run.status, 0) << run.output;
    const nlohmann::json j = info_json(path);
    EXPECT_NEAR(j["points"].get<double>(), 3000, 300);
    EXPECT_EQ(j["loops"], 3);
    EXPECT_EQ(j["components"], 1);
  }
}

TEST(Cli, MeshWithCurvatureWritesTheFiveMeasuresIntoThePly) {
  const std::string out = vesselmesh::test::temp_path("bifurcation.ply");
  const CliRun run = run_cli("mesh '" + vesselmesh::test::test_data("bifurcation.swc") + "' -o '" + out +
                             "' --levels 2 --curvature");
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(out, std::ios::binary);
  std::string header;
  for (std::string line; std::getline(in, line) && line != "end_header";) header += line + "\n";
  for (const char* name : {"k1", "k2", "mean", "gaussian", "rms"})
    EXPECT_NE(header.find(std::string("property float ") + name + "\n"), std::string::npos) << name;
  const CliRun check = run_cli("check '" + out + "'");
  EXPECT_EQ(check.status, 0) << check.output;
}

TEST(Cli, MeshMethodsGiveFewerTrianglesThanUniformAndReportTheirTagging) {
  const auto triangles = [&](const std::string& options) {
    const nlohmann::json j = mesh_stats("--levels 2 " + options);
    EXPECT_EQ(j["tagged_fraction"].size(), 2u) << options;
    return j["triangles"].get<int64_t>();
  };
  const int64_t uniform = triangles("--method uniform");
  EXPECT_LT(triangles("--method curvature --uniform-levels 0 --threshold 0.9 --measure abs-gaussian"), uniform);
  EXPECT_LT(triangles("--method dihedral --uniform-levels 0 --angle 150"), uniform);
  EXPECT_EQ(triangles("--method curvature --threshold 0"), uniform);
}

TEST(Cli, MeshFitsTheSurfaceToTheTubesUnlessToldNotTo) {
  const auto fitted = [](const std::string& options) {
    return mesh_stats(options)["fitted_vertices"].get<int64_t>();
  };
  EXPECT_GT(fitted("--fit inward"), 0);
  EXPECT_LT(fitted("--fit inward"), fitted(""));
  EXPECT_EQ(fitted("--fit none"), 0);
  const auto stages = [](const std::string& options) {
    std::vector<std::string> names;
    const nlohmann::json stats = mesh_stats(options);
    for (const auto& stage : stats["stages"]) names.push_back(stage["stage"]);
    return names;
  };
  EXPECT_EQ(stages(""),
            (std::vector<std::string>{"separate", "tile", "triangulate", "subdivide", "round", "fit", "verify"}));
  EXPECT_EQ(stages("--fit none"),
            (std::vector<std::string>{"separate", "tile", "triangulate", "subdivide", "round", "verify"}));
}

TEST(Cli, MeshMovesCrossingVesselsApartUnlessToldToKeepThem) {
  const nlohmann::json separated = mesh_stats("", "crossing.swc");
  EXPECT_GT(separated["crossings"].get<int64_t>(), 0);
  EXPECT_GT(separated["separated_points"].get<int64_t>(), 0);
  EXPECT_EQ(separated["crossings_left"], 0);
  EXPECT_EQ(separated["stages"].front()["stage"], "separate");
  const nlohmann::json kept = mesh_stats("--crossings keep", "crossing.swc");
  EXPECT_EQ(kept["separated_points"], 0);
  EXPECT_EQ(kept["stages"].front()["stage"], "tile");
}

TEST(Cli, MeshWritesTheCenterlineItsSurfaceFollowsForCheck) {
  // Checked against the centerline as the separate stage left it, the surface lies on its tubes; against
  // the file's, the vessels it moved apart count as off them.
  const std::string in = vesselmesh::test::test_data("crossing.swc");
  const std::string out = vesselmesh::test::temp_path("m.ply"), moved = vesselmesh::test::temp_path("moved.vtk");
  const CliRun run = run_cli("mesh '" + in + "' -o '" + out + "' --centerline-out '" + moved + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto fidelity = [&](const std::string& centerline) {
    const CliRun checked = run_cli("check '" + out + "' --centerline '" + centerline + "' --json");
    EXPECT_EQ(checked.status, 0) << checked.output;
    return nlohmann::json::parse(checked.output)["fidelity"];
  };
  const nlohmann::json as_moved = fidelity(moved), as_filed = fidelity(in);
  EXPECT_EQ(as_moved["area_off_tubes"], 0.0);
  EXPECT_GT(as_filed["area_off_tubes"], 0.1);
  EXPECT_LT(as_moved["abs_relative_error"]["p95"], 0.03);
  // The same vessels, with the points added round where they crossed.
  const nlohmann::json a = info_json(moved), b = info_json(in);
  EXPECT_EQ(a["components"], b["components"]);
  EXPECT_EQ(a["branches"], b["branches"]);
  EXPECT_GT(a["points"], b["points"]);
}

TEST(Cli, MeshRejectsUnknownMethodsAndOutOfRangeOptions) {
  const std::string in = vesselmesh::test::test_data("bifurcation.swc");
  for (const char* options : {"--method sideways", "--measure colour", "--threshold 1.5", "--angle 200",
                              "--uniform-levels -1", "--fit outward", "--crossings merge"}) {
    const CliRun run =
        run_cli("mesh '" + in + "' -o '" + vesselmesh::test::temp_path("m.ply") + "' " + options);
    EXPECT_NE(run.status, 0) << options;
  }
}
