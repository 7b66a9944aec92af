#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "test_support.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/read/read.hpp"

namespace vesselmesh {
namespace {

const std::string kVertices = "fixture_vertices.csv";
const std::string kEdges = "fixture_edges.csv";

CenterlineData parse(std::string_view vertices, std::string_view edges,
                     const std::string& radius_array = "") {
  return parse_csv_graph(vertices, kVertices, edges, kEdges, ReadOptions{radius_array});
}

/// The message of the InputError that parsing the tables throws; a test failure when it does not throw.
std::string error_of(std::string_view vertices, std::string_view edges,
                     const std::string& radius_array = "") {
  try {
    parse(vertices, edges, radius_array);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "parse_csv_graph accepted:\n" << vertices << "\n---\n" << edges;
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A small VesselGraph-style pair: three vertices, two edges, radius per edge among other radius columns.
constexpr const char* kVesselGraphVertices =
    "id;pos_x;pos_y;pos_z;degree;isAtSampleBorder\n"
    "0;-255.0;-37.0;0.0;1;1\n"
    "1;-163.0;-47.0;0.0;2;0\n"
    "2;-194.0;-63.0;4.5;1;0\n";
constexpr const char* kVesselGraphEdges =
    "id;node1id;node2id;length;minRadiusAvg;avgRadiusAvg;maxRadiusAvg\n"
    "0;0;1;38.5;3.5;4.5;5.5\n"
    "1;1;2;8.2;1.0;2.0;3.0\n";

// Vertices with a radius, for the per-vertex cases.
constexpr const char* kVerticesWithRadius =
    "id,x,y,z,radius\n"
    "0,0,0,0,1.5\n"
    "1,1,0,0,2.5\n"
    "2,2,0,0,3.5\n";
constexpr const char* kEdgesWithoutRadius =
    "source,target\n"
    "0,1\n"
    "1,2\n";

TEST(ReadCsv, ReadsVesselGraphTablesWithAvgRadiusAvgPerEdge) {
  const CenterlineData data = parse(kVesselGraphVertices, kVesselGraphEdges);
  ASSERT_EQ(data.points.size(), 3u);
  EXPECT_EQ(data.points[0], Vec3(-255, -37, 0));
  EXPECT_EQ(data.points[2], Vec3(-194, -63, 4.5));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}, {1, 2}}));
  EXPECT_EQ(data.edge_radius, (std::vector<double>{4.5, 2.0}));
  EXPECT_TRUE(data.radius.empty());
  EXPECT_TRUE(data.roots.empty());
  EXPECT_NO_THROW(validate(data, kVertices));
}

TEST(ReadCsv, DetectsTheCommaSeparatorFromTheHeader) {
  const CenterlineData data =
      parse("id,pos_x,pos_y,pos_z\n0,1,2,3\n1,4,5,6\n", "node1id,node2id,radius\n0,1,0.5\n");
  EXPECT_EQ(data.points[1], Vec3(4, 5, 6));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}}));
  EXPECT_EQ(data.edge_radius, (std::vector<double>{0.5}));
}

TEST(ReadCsv, SemicolonWinsWhenTheHeaderHasBothSeparators) {
  const CenterlineData data =
      parse("id;x;y;z;note,unit\n0;1;2;3;a,b\n1;4;5;6;c,d\n", "u;v;radius\n0;1;0.5\n");
  EXPECT_EQ(data.points[0], Vec3(1, 2, 3));
  EXPECT_EQ(data.points[1], Vec3(4, 5, 6));
}

TEST(ReadCsv, EachTableDetectsItsOwnSeparator) {
  const CenterlineData data = parse("id;x;y;z\n0;1;2;3\n1;4;5;6\n", "u,v,radius\n0,1,0.5\n");
  EXPECT_EQ(data.points[0], Vec3(1, 2, 3));
  EXPECT_EQ(data.edge_radius, (std::vector<double>{0.5}));
}

TEST(ReadCsv, AcceptsCrlfLineEndingsAndAByteOrderMark) {
  const CenterlineData data = parse("\xEF\xBB\xBFid;pos_x;pos_y;pos_z\r\n0;1;2;3\r\n1;4;5;6\r\n",
                                    "\xEF\xBB\xBFnode1id;node2id;avgRadiusAvg\r\n1;0;2.5\r\n");
  EXPECT_EQ(data.points[1], Vec3(4, 5, 6));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{1, 0}}));
  EXPECT_EQ(data.edge_radius, (std::vector<double>{2.5}));
}

TEST(ReadCsv, UnquotesQuotedHeaderNames) {
  const CenterlineData data =
      parse("\"id\",\"x\",\"y\",\"z\"\n0,1,2,3\n1,4,5,6\n", "\"source\", \"target\" ,\"radius\"\n0,1,0.5\n");
  EXPECT_EQ(data.points[1], Vec3(4, 5, 6));
  EXPECT_EQ(data.edge_radius, (std::vector<double>{0.5}));
}

TEST(ReadCsv, MatchesColumnNamesCaseInsensitively) {
  const CenterlineData data =
      parse("ID;POS_X;Pos_Y;pos_Z\n0;1;2;3\n1;4;5;6\n", "Node1Id;NODE2ID;Radius\n0;1;0.5\n");
  EXPECT_EQ(data.points[1], Vec3(4, 5, 6));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}}));
}

TEST(ReadCsv, AcceptsEveryEndpointColumnPair) {
  for (const char* pair :
       {"node1id,node2id", "source,target", "node1,node2", "from,to", "u,v", "Source,Target"}) {
    const CenterlineData data = parse(kVerticesWithRadius, std::string(pair) + "\n2,1\n1,0\n");
    EXPECT_EQ(data.edges, (std::vector<Edge>{{2, 1}, {1, 0}})) << pair;
  }
}

TEST(ReadCsv, IgnoresColumnsItDoesNotUseInAnyOrder) {
  const CenterlineData data = parse("z;comment;y;x;id\n3;a;2;1;10\n6;b;5;4;11\n",
                                    "weight;target;label;source;radius\n9;11;e;10;0.5\n");
  EXPECT_EQ(data.points[0], Vec3(1, 2, 3));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}}));
}

TEST(ReadCsv, UsesRowOrderAsTheIdWithoutAnIdColumn) {
  const CenterlineData data = parse("x;y;z\n0;0;0\n1;0;0\n2;0;0\n", "u;v;radius\n2;0;1\n0;1;2\n");
  EXPECT_EQ(data.edges, (std::vector<Edge>{{2, 0}, {0, 1}}));
}

TEST(ReadCsv, MapsUnsortedNonSequentialVertexIdsToRowIndices) {
  const CenterlineData data =
      parse("id,x,y,z\n500,5,0,0\n-3,0,0,0\n70,7,0,0\n", "source,target,radius\n-3,500,1\n500,70,2\n");
  EXPECT_EQ(data.edges, (std::vector<Edge>{{1, 0}, {0, 2}}));
  EXPECT_EQ(data.points[1], Vec3(0, 0, 0));
}

TEST(ReadCsv, UsesPerVertexRadiusWhenTheEdgesHaveNone) {
  const CenterlineData data = parse(kVerticesWithRadius, kEdgesWithoutRadius);
  EXPECT_EQ(data.radius, (std::vector<double>{1.5, 2.5, 3.5}));
  EXPECT_TRUE(data.edge_radius.empty());
  EXPECT_NO_THROW(validate(data, kVertices));
}

TEST(ReadCsv, PrefersPerEdgeRadiusWhenBothTablesHaveOne) {
  const CenterlineData data = parse(kVerticesWithRadius, "source,target,radius\n0,1,9\n1,2,8\n");
  EXPECT_EQ(data.edge_radius, (std::vector<double>{9, 8}));
  EXPECT_TRUE(data.radius.empty());
}

TEST(ReadCsv, HalvesADiameterColumn) {
  const CenterlineData data = parse("id,x,y,z\n0,0,0,0\n1,1,0,0\n", "u,v,diameter\n0,1,3\n");
  EXPECT_EQ(data.edge_radius, (std::vector<double>{1.5}));
}

TEST(ReadCsv, RequestedRadiusColumnIsTakenFromTheEdgesTable) {
  const CenterlineData data = parse(kVesselGraphVertices, kVesselGraphEdges, "maxRadiusAvg");
  EXPECT_EQ(data.edge_radius, (std::vector<double>{5.5, 3.0}));
}

TEST(ReadCsv, RequestedRadiusColumnIsLookedUpInTheEdgesTableFirst) {
  const CenterlineData data =
      parse("id,x,y,z,thickness\n0,0,0,0,1\n1,1,0,0,2\n", "u,v,thickness\n0,1,7\n", "thickness");
  EXPECT_EQ(data.edge_radius, (std::vector<double>{7}));
  EXPECT_TRUE(data.radius.empty());
}

TEST(ReadCsv, RequestedRadiusColumnFallsBackToTheVerticesTable) {
  const CenterlineData data =
      parse("id,x,y,z,thickness\n0,0,0,0,1\n1,1,0,0,2\n", "u,v,radius\n0,1,7\n", "Thickness");
  EXPECT_EQ(data.radius, (std::vector<double>{1, 2}));
  EXPECT_TRUE(data.edge_radius.empty());
}

TEST(ReadCsv, SkipsBlankLinesAndReadsALastRowWithoutNewline) {
  const CenterlineData data = parse("\nid;x;y;z\n\n0;0;0;0\n  \n1;1;0;0\n\n", "u;v;radius\n0;1;2");
  EXPECT_EQ(data.points.size(), 2u);
  EXPECT_EQ(data.edge_radius, (std::vector<double>{2}));
}

TEST(ReadCsv, AcceptsSpacesAroundFields) {
  const CenterlineData data = parse("id, x, y, z\n 0, 1.5 , 2, 3\n1 ,4,5,6\n", "u, v, radius\n0 , 1, 0.5 \n");
  EXPECT_EQ(data.points[0], Vec3(1.5, 2, 3));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}}));
}

// --- errors: each names the right file and line ---

TEST(ReadCsv, MissingPositionColumnsAreRejectedListingExpectedAndFound) {
  const std::string message = error_of("id;pos_x;pos_y;height\n0;1;2;3\n", kVesselGraphEdges);
  EXPECT_TRUE(contains(message,
                       "fixture_vertices.csv: line 1: expected columns pos_x,pos_y,pos_z or x,y,z; "
                       "found: id, pos_x, pos_y, height"))
      << message;
}

TEST(ReadCsv, MissingEndpointColumnsAreRejectedListingExpectedAndFound) {
  const std::string message = error_of(kVesselGraphVertices, "id;a;b;radius\n0;0;1;1\n");
  EXPECT_TRUE(
      contains(message, "fixture_edges.csv: line 1: expected columns node1id,node2id or source,target"))
      << message;
  EXPECT_TRUE(contains(message, "u,v; found: id, a, b, radius")) << message;
}

TEST(ReadCsv, MissingColumnsErrorNamesTheHeaderLineAfterBlankLines) {
  const std::string message = error_of("\n\nid,a,b,c\n0,1,2,3\n", kEdgesWithoutRadius);
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: line 3: expected columns")) << message;
}

TEST(ReadCsv, MissingRadiusIsRejectedListingTheColumnsOfBothTables) {
  const std::string message = error_of("id,x,y,z\n0,0,0,0\n1,1,0,0\n", kEdgesWithoutRadius);
  EXPECT_TRUE(contains(message, "fixture_edges.csv: no radius array; found: source, target")) << message;
  EXPECT_TRUE(
      contains(message, "the vertices table fixture_vertices.csv has none either (found: id, x, y, z)"))
      << message;
}

TEST(ReadCsv, RequestedRadiusColumnThatNeitherTableHasIsRejected) {
  const std::string message = error_of(kVesselGraphVertices, kVesselGraphEdges, "thickness");
  EXPECT_TRUE(contains(message, "fixture_edges.csv: no array named 'thickness'; found: id, node1id"))
      << message;
  EXPECT_TRUE(contains(message, "the vertices table fixture_vertices.csv has none either (found: id, pos_x"))
      << message;
}

TEST(ReadCsv, VertexRowWithTooFewFieldsIsRejectedNamingTheLine) {
  const std::string message = error_of("id;x;y;z\n0;0;0;0\n1;1;0\n", "u;v;radius\n0;1;1\n");
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: line 3: expected 4 fields as in the header, found 3"))
      << message;
}

TEST(ReadCsv, EdgeRowWithTooManyFieldsIsRejectedNamingTheLine) {
  const std::string message =
      error_of(kVesselGraphVertices, "node1id;node2id;radius\r\n0;1;2\r\n1;2;3;4\r\n");
  EXPECT_TRUE(contains(message, "fixture_edges.csv: line 3: expected 3 fields as in the header, found 4"))
      << message;
}

TEST(ReadCsv, RowSplitAtTheOtherSeparatorIsRejectedNamingTheLine) {
  const std::string message = error_of("id;x;y;z\n0;0;0;0\n1,1,0,0\n", "u;v;radius\n0;1;1\n");
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: line 3: expected 4 fields as in the header, found 1"))
      << message;
}

TEST(ReadCsv, NonNumericCoordinateIsRejectedNamingTheVerticesLine) {
  const std::string message = error_of("id;x;y;z\n0;0;0;0\n\n1;1;abc;0\n", "u;v;radius\n0;1;1\n");
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: line 4: expected a number for y, found 'abc'"))
      << message;
}

TEST(ReadCsv, NonFiniteCoordinateIsRejectedNamingTheVerticesLine) {
  const std::string message = error_of("id;x;y;z\n0;0;0;0\n1;nan;0;0\n", "u;v;radius\n0;1;1\n");
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: line 3: x is not a finite number")) << message;
}

TEST(ReadCsv, NonIntegerVertexIdIsRejectedNamingTheLine) {
  const std::string message = error_of("id;x;y;z\n0;0;0;0\nv1;1;0;0\n", "u;v;radius\n0;1;1\n");
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: line 3: expected an integer for the id, found 'v1'"))
      << message;
}

TEST(ReadCsv, NonNumericEndpointIsRejectedNamingTheEdgesLine) {
  const std::string message = error_of(kVesselGraphVertices, "node1id;node2id;radius\n0;1;1\n1;two;1\n");
  EXPECT_TRUE(contains(message, "fixture_edges.csv: line 3: expected an integer for node2id, found 'two'"))
      << message;
}

TEST(ReadCsv, NonNumericEdgeRadiusIsRejectedNamingTheEdgesLine) {
  const std::string message = error_of(kVesselGraphVertices, "node1id;node2id;radius\n0;1;1\n1;2;\n");
  EXPECT_TRUE(contains(message, "fixture_edges.csv: line 3: expected a number for the radius, found ''"))
      << message;
}

TEST(ReadCsv, NonPositiveEdgeRadiusIsRejectedNamingTheEdgesLine) {
  const std::string message = error_of(kVesselGraphVertices, "node1id;node2id;radius\n0;1;1\n1;2;0\n");
  EXPECT_TRUE(contains(message, "fixture_edges.csv: line 3: radius must be positive, found 0")) << message;
}

TEST(ReadCsv, NonPositiveVertexRadiusIsRejectedNamingTheVerticesLine) {
  const std::string message = error_of("id,x,y,z,radius\n0,0,0,0,1\n1,1,0,0,-2\n", kEdgesWithoutRadius);
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: line 3: radius must be positive, found -2"))
      << message;
}

TEST(ReadCsv, DuplicateVertexIdIsRejectedNamingBothLines) {
  const std::string message = error_of("id;x;y;z\n4;0;0;0\n5;1;0;0\n4;2;0;0\n", "u;v;radius\n4;5;1\n");
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: line 4: duplicate vertex id 4 (first on line 2)"))
      << message;
}

TEST(ReadCsv, EdgeToAnUnknownVertexIdIsRejectedNamingTheEdgesLine) {
  const std::string message = error_of(kVesselGraphVertices, "node1id;node2id;radius\n0;1;1\n7;2;1\n");
  EXPECT_TRUE(contains(message,
                       "fixture_edges.csv: line 3: node1id 7 is not an id in the vertices table "
                       "fixture_vertices.csv"))
      << message;
}

TEST(ReadCsv, EdgeToARowIndexPastTheEndIsRejectedWithoutAnIdColumn) {
  const std::string message = error_of("x;y;z\n0;0;0\n1;0;0\n", "u;v;radius\n0;1;1\n1;2;1\n");
  EXPECT_TRUE(contains(message, "fixture_edges.csv: line 3: v 2 is not an id")) << message;
}

TEST(ReadCsv, EmptyVerticesFileIsRejected) {
  const std::string message = error_of("", kVesselGraphEdges);
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: empty vertices table: no header row")) << message;
  EXPECT_TRUE(contains(error_of("\xEF\xBB\xBF\r\n\r\n", kVesselGraphEdges), "fixture_vertices.csv: empty"));
}

TEST(ReadCsv, EmptyEdgesFileIsRejected) {
  const std::string message = error_of(kVesselGraphVertices, "\n");
  EXPECT_TRUE(contains(message, "fixture_edges.csv: empty edges table: no header row")) << message;
}

TEST(ReadCsv, VerticesTableWithOnlyAHeaderIsRejected) {
  const std::string message = error_of("id;x;y;z\n\n", "u;v;radius\n0;1;1\n");
  EXPECT_TRUE(contains(message, "fixture_vertices.csv: no vertices")) << message;
}

TEST(ReadCsv, EdgesTableWithOnlyAHeaderIsRejected) {
  const std::string message = error_of(kVesselGraphVertices, "node1id;node2id;radius\r\n");
  EXPECT_TRUE(contains(message, "fixture_edges.csv: no edges")) << message;
}

TEST(ReadCsv, BinaryBytesAreRejectedWithAnInputError) {
  std::mt19937 random(2024);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 50; ++trial) {
    std::string bytes(1 + trial * 97, '\0');
    for (char& c : bytes) c = static_cast<char>(byte(random));
    bytes[0] = '\x01';  // not blank
    const std::string as_vertices = error_of(bytes, kVesselGraphEdges);
    EXPECT_TRUE(contains(as_vertices, "fixture_vertices.csv: ")) << as_vertices;
    const std::string as_edges = error_of(kVesselGraphVertices, bytes);
    EXPECT_TRUE(contains(as_edges, "fixture_edges.csv: ")) << as_edges;
  }
}

// --- the shared VesselGraph sample, read through read_centerline (pairing, dispatch, validation) ---

void expect_vesselgraph_demo(const CenterlineData& data) {
  EXPECT_EQ(data.points.size(), 3197u);
  EXPECT_EQ(data.edges.size(), 3249u);
  EXPECT_TRUE(data.radius.empty());
  ASSERT_EQ(data.edge_radius.size(), 3249u);
  const auto [min, max] = std::minmax_element(data.edge_radius.begin(), data.edge_radius.end());
  EXPECT_NEAR(*min, 1.0, 1e-5);
  EXPECT_NEAR(*max, 8.80404, 1e-5);
}

TEST(ReadCsvSharedData, VesselGraphDemoReadsFromTheVerticesFile) {
  SHARED_DATA_OR_SKIP(path, "vesselgraph-demo/vertices.csv");
  expect_vesselgraph_demo(read_centerline(path));
}

TEST(ReadCsvSharedData, VesselGraphDemoReadsFromTheEdgesFile) {
  SHARED_DATA_OR_SKIP(path, "vesselgraph-demo/edges.csv");
  expect_vesselgraph_demo(read_centerline(path));
}

TEST(ReadCsvSharedData, VesselGraphDemoReadsFromItsFolder) {
  SHARED_DATA_OR_SKIP(path, "vesselgraph-demo");
  expect_vesselgraph_demo(read_centerline(path));
}

}  // namespace
}  // namespace vesselmesh
