#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "test_support.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/mesh/mesh_files.hpp"

namespace vesselmesh {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------------
// Meshes and checks

/// A closed octahedron, outward-facing, at coordinates that float cannot hold exactly.
TriMesh octahedron() {
  TriMesh mesh;
  const Vec3 center(0.1, -2.3, 7.7);
  const double r = 1.3;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) mesh.vertices.push_back(center + sign * r * Vec3::Unit(axis));
  for (int sx : {0, 1})
    for (int sy : {0, 1})
      for (int sz : {0, 1}) {
        const int32_t a = sx, b = 2 + sy, c = 4 + sz;
        // An odd number of negative axes mirrors the octant, which flips the winding.
        if ((sx + sy + sz) % 2 == 0) {
          mesh.faces.push_back({a, b, c});
        } else {
          mesh.faces.push_back({a, c, b});
        }
      }
  return mesh;
}

/// A closed cube as 12 outward-facing triangles; vertex i is the corner (i & 1, i >> 1 & 1, i >> 2 & 1).
TriMesh cube() {
  TriMesh mesh;
  const Vec3 origin(-0.35, 1.7, 2.9);
  for (int i = 0; i < 8; ++i) mesh.vertices.push_back(origin + 0.6 * Vec3(i & 1, i >> 1 & 1, i >> 2 & 1));
  mesh.faces = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return mesh;
}

/// Every directed edge once, each with its reverse: closed and consistently oriented.
bool closed_and_oriented(const TriMesh& mesh) {
  std::map<std::pair<int32_t, int32_t>, int> directed;
  for (const Tri& f : mesh.faces)
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) return false;
  }
  return !mesh.faces.empty();
}

/// A position as the writers store it. Compared as floats: GCC 12 at -O2 may drop the rounding of a
/// double → float → double round trip, so a Vec3 of float-rounded values is not a reliable reference.
std::array<float, 3> as_float(const Vec3& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Binary data in a chosen byte order, for hand-made PLY and STL files.
class Bytes {
 public:
  explicit Bytes(bool big_endian) : big_endian_(big_endian) {}

  Bytes& text(const std::string& s) {
    data_ += s;
    return *this;
  }

  template <class T>
  Bytes& put(T value) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    const uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    if ((first == 1) == big_endian_) std::reverse(raw, raw + sizeof(T));
    data_.append(reinterpret_cast<const char*>(raw), sizeof(T));
    return *this;
  }

  const std::string& str() const { return data_; }

 private:
  bool big_endian_;
  std::string data_;
};

// ---------------------------------------------------------------------------------------------------
// Fixture: a fresh folder per test

class MeshFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / ("vesselmesh-mesh-files-" + std::string(info->name()) + "-" +
                                             std::to_string(std::random_device{}()));
    fs::create_directories(dir_);
  }

  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// Writes `bytes` to a file `name` in the test's folder and returns its path. An existing file is removed
  /// first: rewriting one in place makes ext4 flush it on close, which slows the many rewrites down.
  std::string file(const std::string& name, const std::string& bytes) const {
    const std::string p = path(name);
    fs::remove(p);
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }

  TriMesh round_trip(const TriMesh& mesh, const std::string& name) const {
    write_mesh(mesh, path(name));
    return read_mesh(path(name));
  }

  TriMesh round_trip_with(const TriMesh& mesh, const std::string& name, const WriteOptions& options) const {
    write_mesh(mesh, path(name), options);
    return read_mesh(path(name));
  }

 private:
  fs::path dir_;
};

/// read_mesh(path) must throw an InputError "path: where: ..." whose message contains `what`.
void expect_input_error(const std::string& path, const std::string& where, const std::string& what) {
  try {
    read_mesh(path);
    ADD_FAILURE() << "no error reading " << path;
  } catch (const InputError& e) {
    const std::string message = e.what();
    const std::string prefix = path + ": " + (where.empty() ? "" : where + ": ");
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << "expected the prefix '" << prefix << "' in: " << message;
    EXPECT_NE(message.find(what), std::string::npos) << "expected '" << what << "' in: " << message;
  }
}

// ---------------------------------------------------------------------------------------------------
// Round trips

/// Hand-written ascii PLY: CRLF, comments, a blank line, extra vertex properties (one a list), an edge
/// element with a list between the vertices and faces, a quad, and a scalar after the face list.
const std::string kQuadPly =
    "ply\r\n"
    "format ascii 1.0\r\n"
    "comment made by hand\r\n"
    "obj_info nothing\r\n"
    "element vertex 5\r\n"
    "property float32 x\r\n"
    "property float32 y\r\n"
    "property float32 z\r\n"
    "property uchar red\r\n"
    "property list uchar float texcoord\r\n"
    "property double quality\r\n"
    "element edge 2\r\n"
    "property int vertex1\r\n"
    "property list int int path\r\n"
    "element face 2\r\n"
    "property list uchar int vertex_index\r\n"
    "property ushort flags\r\n"
    "end_header\r\n"
    "0 0 0 255 2 0.5 0.5 1.5\r\n"
    "1 0 0 0 0 2.5\r\n"
    "1 1 0 7 4 0 0 1 1 -3\r\n"
    "0 1 0 1 0 4e-3\r\n"
    "\r\n"
    "0.5 0.5 1 2 1 9 1e3\r\n"
    "0 3 0 1 2\r\n"
    "1 0\r\n"
    "4 0 1 2 3 17\r\n"
    "3 0 1 4 0\r\n";

/// Hand-written ascii STL: two facets sharing an edge, the shared corners spelled differently.
const std::string kTwoFacetStl =
    "solid two\n"
    "  facet normal 0 0 1\n    outer loop\n"
    "      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n"
    "    endloop\n  endfacet\n"
    "  facet normal 0 0 1\n    outer loop\n"
    "      vertex -0 0 0\n      vertex 1.0 1 0\n      vertex 0 1e0 0\n"
    "    endloop\n  endfacet\n"
    "endsolid two\n";

TEST(RoundedToFloat, EveryCoordinateIsTheFloatTheFilesHold) {
  // Many points in a loop, as the pipeline rounds them: that is where GCC 12 vectorises x and y together.
  std::vector<Vec3> points;
  for (int i = 0; i < 1000; ++i) points.emplace_back(139.230488123 + 1e-3 * i, -39.76613 - 1e-3 * i, 0.1 * i);
  std::vector<Vec3> rounded(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    rounded[i] = rounded_to_float(points[i] + Vec3(1e-7, 1e-7, 0));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::array<float, 3> expected = as_float(points[i] + Vec3(1e-7, 1e-7, 0));
    for (int k = 0; k < 3; ++k) ASSERT_EQ(rounded[i][k], static_cast<double>(expected[k])) << i << ", " << k;
  }
}

TEST_F(MeshFiles, PlyRoundTripKeepsFloatPositionsAndIdenticalFaces) {
  for (const TriMesh& mesh : {octahedron(), cube()}) {
    const TriMesh read = round_trip(mesh, "mesh.ply");
    ASSERT_EQ(read.vertices.size(), mesh.vertices.size());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      EXPECT_EQ(as_float(read.vertices[v]), as_float(mesh.vertices[v]));
    EXPECT_EQ(read.faces, mesh.faces);
    EXPECT_TRUE(read.vertex_properties.empty());
    EXPECT_TRUE(closed_and_oriented(read));
  }
}

TEST_F(MeshFiles, ObjRoundTripKeepsExactPositionsAndIdenticalFaces) {
  for (const TriMesh& mesh : {octahedron(), cube()}) {
    const TriMesh read = round_trip(mesh, "mesh.obj");
    EXPECT_EQ(read.vertices, mesh.vertices);
    EXPECT_EQ(read.faces, mesh.faces);
  }
}

TEST_F(MeshFiles, StlRoundTripWeldsBackToTheSameVerticesAndAClosedMesh) {
  for (const TriMesh& mesh : {octahedron(), cube()}) {
    const TriMesh read = round_trip(mesh, "mesh.stl");
    EXPECT_EQ(read.vertices.size(), mesh.vertices.size());
    ASSERT_EQ(read.faces.size(), mesh.faces.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(as_float(read.vertices[read.faces[f][k]]), as_float(mesh.vertices[mesh.faces[f][k]]));
    EXPECT_TRUE(closed_and_oriented(read));
  }
}

TEST_F(MeshFiles, StlNormalIsTheUnitNormalOfTheVertexOrder) {
  write_mesh(cube(), path("cube.stl"));
  const std::string bytes = read_bytes(path("cube.stl"));
  ASSERT_EQ(bytes.size(), 84u + 50u * 12u);
  EXPECT_NE(bytes.substr(0, 5), "solid");
  float normal[3];
  std::memcpy(normal, bytes.data() + 84, sizeof normal);  // little-endian hosts only; the test runs on one
  EXPECT_EQ(normal[0], 0.0f);
  EXPECT_EQ(normal[1], 0.0f);
  EXPECT_EQ(normal[2], -1.0f);  // face {0, 2, 3} is the bottom
}

TEST_F(MeshFiles, PlyVertexPropertiesRoundTripByNameAndValue) {
  TriMesh mesh = octahedron();
  mesh.vertex_properties = {{"mean_curvature", {0.5f, -1.25f, 3e-8f, 0, 1e30f, -7}},
                            {"gauss", {1, 2, 3, 4, 5, 6}}};
  const TriMesh read = round_trip(mesh, "curvature.ply");
  ASSERT_EQ(read.vertex_properties.size(), 2u);
  for (std::size_t p = 0; p < 2; ++p) {
    EXPECT_EQ(read.vertex_properties[p].name, mesh.vertex_properties[p].name);
    EXPECT_EQ(read.vertex_properties[p].values, mesh.vertex_properties[p].values);
  }
  EXPECT_EQ(read.faces, mesh.faces);
}

TEST_F(MeshFiles, CommentsRoundTripInPlyAndObjOneLineEachAndStlHasNone) {
  WriteOptions options;
  options.comments = {"lost loop: the branch from (0, 0, 1) to (1, 0, 0)", "two\nlines"};
  for (const std::string name : {"mesh.ply", "mesh.obj", "mesh.PLY"}) {
    write_mesh(octahedron(), path(name), options);
    EXPECT_EQ(read_mesh_comments(path(name)),
              (std::vector<std::string>{"lost loop: the branch from (0, 0, 1) to (1, 0, 0)", "two lines"}))
        << name;
    EXPECT_EQ(read_mesh(path(name)).faces, octahedron().faces) << name;
  }
  write_mesh(octahedron(), path("mesh.stl"), options);
  EXPECT_TRUE(read_mesh_comments(path("mesh.stl")).empty());
  write_mesh(octahedron(), path("plain.ply"));
  EXPECT_TRUE(read_mesh_comments(path("plain.ply")).empty());
}

TEST_F(MeshFiles, WriterIsChosenByTheLowerCaseExtension) {
  write_mesh(cube(), path("CUBE.PLY"));
  EXPECT_EQ(read_bytes(path("CUBE.PLY")).substr(0, 4), "ply\n");
  EXPECT_EQ(read_mesh(path("CUBE.PLY")).faces, cube().faces);
}

TEST_F(MeshFiles, WriteRejectsAnUnknownExtensionNamingThePath) {
  const std::string target = path("mesh.vtk");
  try {
    write_mesh(cube(), target);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(target));
}

TEST_F(MeshFiles, WriteRejectsAVertexPropertyOfTheWrongLength) {
  TriMesh mesh = cube();
  mesh.vertex_properties = {{"k", {1, 2, 3}}};
  for (const char* name : {"mesh.ply", "mesh.obj", "mesh.stl"}) {
    try {
      write_mesh(mesh, path(name));
      ADD_FAILURE() << "no error for " << name;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path(name)), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("'k' has 3 values for 8 vertices"), std::string::npos) << e.what();
    }
  }
}

TEST_F(MeshFiles, WriteRejectsAFaceIndexOutOfRange) {
  TriMesh mesh = cube();
  mesh.faces[5][1] = 8;
  EXPECT_THROW(write_mesh(mesh, path("mesh.stl")), std::runtime_error);
}

// ---------------------------------------------------------------------------------------------------
// Far from the origin: what single precision would do, and how each format keeps the mesh

/// A 20 × 20 grid of size 10 (spacing 0.5, a gentle bump), moved `offset` along every axis.
TriMesh far_grid(double offset) {
  TriMesh mesh;
  constexpr int32_t kSide = 20;
  for (int32_t r = 0; r <= kSide; ++r)
    for (int32_t c = 0; c <= kSide; ++c)
      mesh.vertices.push_back(Vec3(offset, offset, offset) +
                              Vec3(0.5 * c, 0.5 * r, 0.3 * std::sin(0.4 * c) * std::cos(0.3 * r)));
  for (int32_t r = 0; r < kSide; ++r)
    for (int32_t c = 0; c < kSide; ++c) {
      const int32_t v = r * (kSide + 1) + c;
      mesh.faces.push_back({v, v + 1, v + kSide + 2});
      mesh.faces.push_back({v, v + kSide + 2, v + kSide + 1});
    }
  return mesh;
}

std::string ply_header(const std::string& path) {
  const std::string bytes = read_bytes(path);
  return bytes.substr(0, bytes.find("end_header"));
}

TEST_F(MeshFiles, FloatRoundingCountsMergedVerticesAndFacesThatLoseTheirArea) {
  EXPECT_FALSE(float_rounding(far_grid(0)).changes_mesh());
  EXPECT_FALSE(float_rounding(far_grid(1e3)).changes_mesh());
  const FloatRounding at_1e7 = float_rounding(far_grid(1e7));  // float steps of 1 there
  EXPECT_GT(at_1e7.degenerate_faces, 0);
  EXPECT_GT(at_1e7.merged_vertices, 0);
  const FloatRounding at_1e9 = float_rounding(far_grid(1e9));  // steps of 64: one point
  EXPECT_EQ(at_1e9.degenerate_faces, 800);
  EXPECT_EQ(at_1e9.merged_vertices, 21 * 21 - 1);
}

TEST_F(MeshFiles, FloatRoundingCountsFacesFlattenedByAFarOffsetAlongOneAxis) {
  TriMesh mesh = octahedron();  // of radius 1.3: float steps of 64 at 1e9 flatten it onto x = 1e9
  for (Vec3& p : mesh.vertices) p.x() += 1e9;
  const FloatRounding rounding = float_rounding(mesh);
  EXPECT_EQ(rounding.degenerate_faces, 8);
  EXPECT_THROW(write_mesh(mesh, path("flat.stl")), std::runtime_error);
}

TEST_F(MeshFiles, PlyStoresDoublePositionsOnlyWhereFloatWouldChangeTheMesh) {
  write_mesh(far_grid(0), path("near.ply"));
  EXPECT_NE(ply_header(path("near.ply")).find("property float x\n"), std::string::npos);
  for (double offset : {1e7, 1e9}) {
    const TriMesh mesh = far_grid(offset);
    const TriMesh read = round_trip(mesh, "far.ply");
    EXPECT_NE(ply_header(path("far.ply")).find("property double x\n"), std::string::npos) << offset;
    EXPECT_EQ(read.vertices, mesh.vertices) << offset;
    EXPECT_EQ(read.faces, mesh.faces) << offset;
  }
}

TEST_F(MeshFiles, ObjKeepsFarPositionsExactly) {
  for (double offset : {1e7, 1e9}) {
    const TriMesh mesh = far_grid(offset);
    const TriMesh read = round_trip(mesh, "far.obj");
    EXPECT_EQ(read.vertices, mesh.vertices) << offset;
    EXPECT_FALSE(float_rounding(read).changes_mesh() && !float_rounding(mesh).changes_mesh());
  }
}

TEST_F(MeshFiles, StlRefusesAMeshThatFloatWouldChangeAndSaysToWritePlyOrObj) {
  EXPECT_NO_THROW(write_mesh(far_grid(1e3), path("near.stl")));
  for (double offset : {1e7, 1e9}) {
    const std::string target = path("far.stl");
    try {
      write_mesh(far_grid(offset), target);
      ADD_FAILURE() << "no error at " << offset;
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(target), std::string::npos) << message;
      EXPECT_NE(message.find("write PLY or OBJ instead"), std::string::npos) << message;
      EXPECT_NE(message.find("of 800 triangles degenerate, turned over or tilted"), std::string::npos) << message;
    }
    EXPECT_FALSE(fs::exists(target));
  }
}

TEST_F(MeshFiles, PlyColoursAreUcharRedGreenBlueAndOptionalAlphaBeforeTheFloatProperties) {
  TriMesh mesh = octahedron();
  mesh.vertex_properties = {{"mean", {0.5f, -1.25f, 3e-8f, 0, 1e30f, -7}}};
  WriteOptions options;
  for (uint8_t v = 0; v < 6; ++v) options.colors.push_back({uint8_t(40 * v), uint8_t(255 - v), 7, uint8_t(200 + v)});
  for (bool alpha : {false, true}) {
    options.alpha = alpha;
    write_mesh(mesh, path("colours.ply"), options);
    const std::string header = ply_header(path("colours.ply"));
    EXPECT_NE(header.find("property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n" +
                          std::string(alpha ? "property uchar alpha\n" : "") + "property float mean\n"),
              std::string::npos)
        << header;
    const TriMesh read = read_mesh(path("colours.ply"));
    ASSERT_EQ(read.vertex_properties.size(), alpha ? 5u : 4u);
    for (int c = 0; c < (alpha ? 4 : 3); ++c) {
      EXPECT_EQ(read.vertex_properties[c].name, (std::array{"red", "green", "blue", "alpha"}[c]));
      for (std::size_t v = 0; v < 6; ++v) EXPECT_EQ(read.vertex_properties[c].values[v], options.colors[v][c]);
    }
    EXPECT_EQ(read.vertex_properties.back().name, "mean");
    EXPECT_EQ(read.vertex_properties.back().values, mesh.vertex_properties[0].values);
    EXPECT_EQ(read.faces, mesh.faces);
  }
}

TEST_F(MeshFiles, ObjColoursFollowEachVertexAndTheMaterialGoesToItsMtlTwin) {
  WriteOptions options;
  for (uint8_t v = 0; v < 8; ++v) options.colors.push_back({uint8_t(30 * v), 0, 255, 255});
  options.material = "VesselMesh_curvature";
  const TriMesh read = round_trip_with(cube(), "coloured.obj", options);
  EXPECT_EQ(read.vertices, cube().vertices);
  EXPECT_EQ(read.faces, cube().faces);
  const std::string obj = read_bytes(path("coloured.obj"));
  EXPECT_NE(obj.find("mtllib coloured.mtl\n"), std::string::npos);
  EXPECT_NE(obj.find("usemtl VesselMesh_curvature\nf "), std::string::npos);
  EXPECT_NE(obj.find(" 0.4706 0 1\n"), std::string::npos) << obj;  // vertex 4: 120/255
  EXPECT_NE(read_bytes(path("coloured.mtl")).find("newmtl VesselMesh_curvature\n"), std::string::npos);
}

TEST_F(MeshFiles, WriteRejectsColoursThatAreNotOnePerVertex) {
  WriteOptions options;
  options.colors.resize(3);
  for (const char* name : {"mesh.ply", "mesh.obj", "mesh.stl"})
    EXPECT_THROW(write_mesh(cube(), path(name), options), std::runtime_error) << name;
}

// ---------------------------------------------------------------------------------------------------
// PLY from other writers

TEST_F(MeshFiles, AsciiPlyQuadIsFanTriangulatedAndExtraElementsAreSkipped) {
  const std::string p = file("quad.ply", kQuadPly);
  const TriMesh mesh = read_mesh(p);
  ASSERT_EQ(mesh.vertices.size(), 5u);
  EXPECT_EQ(mesh.vertices[2], Vec3(1, 1, 0));
  EXPECT_EQ(mesh.vertices[4], Vec3(0.5, 0.5, 1));
  EXPECT_EQ(mesh.faces, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}}));
  ASSERT_EQ(mesh.vertex_properties.size(), 2u);
  EXPECT_EQ(mesh.vertex_properties[0].name, "red");
  EXPECT_EQ(mesh.vertex_properties[0].values, (std::vector<float>{255, 0, 7, 1, 2}));
  EXPECT_EQ(mesh.vertex_properties[1].name, "quality");
  EXPECT_EQ(mesh.vertex_properties[1].values, (std::vector<float>{1.5f, 2.5f, -3, 4e-3f, 1e3f}));
}

/// A binary PLY with every kind of thing other writers put in: coordinates of three types, a colour,
/// a list on the vertices, an edge element before the faces, faces with a flag before a uint-counted
/// ushort index list (a quad and a pentagon), and a material element after them.
std::string mixed_binary_ply(bool big_endian) {
  Bytes b(big_endian);
  b.text(std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
         " 1.0\n"
         "element vertex 5\n"
         "property float64 x\nproperty short y\nproperty float z\n"
         "property list uint8 float32 texcoord\nproperty uchar red\nproperty int8 bias\n"
         "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
         "element face 2\nproperty uchar flags\nproperty list uint ushort vertex_indices\n"
         "element material 1\nproperty list int uchar name\nproperty double shine\n"
         "end_header\n");
  const double x[] = {0.1, 1.1, 1.1, 0.1, -0.4};
  const int16_t y[] = {0, 0, -300, -300, -150};
  for (int v = 0; v < 5; ++v) {
    b.put(x[v]).put(y[v]).put(2.5f);
    b.put<uint8_t>(static_cast<uint8_t>(v % 2 * 2));
    for (int t = 0; t < v % 2 * 2; ++t) b.put(0.25f);
    b.put<uint8_t>(static_cast<uint8_t>(200 + v)).put<int8_t>(static_cast<int8_t>(-v));
  }
  b.put<int32_t>(0).put<int32_t>(4);
  b.put<uint8_t>(1).put<uint32_t>(4).put<uint16_t>(0).put<uint16_t>(1).put<uint16_t>(2).put<uint16_t>(3);
  b.put<uint8_t>(0).put<uint32_t>(5);
  for (uint16_t v : {4, 3, 2, 1, 0}) b.put(v);
  b.put<int32_t>(3).text("abc").put(0.75);
  return b.str();
}

TEST_F(MeshFiles, BinaryPlyOfEitherByteOrderWithMixedTypesReads) {
  for (bool big_endian : {false, true}) {
    SCOPED_TRACE(big_endian ? "big-endian" : "little-endian");
    const TriMesh mesh = read_mesh(file("mixed.ply", mixed_binary_ply(big_endian)));
    ASSERT_EQ(mesh.vertices.size(), 5u);
    EXPECT_EQ(mesh.vertices[0], Vec3(0.1, 0, 2.5));
    EXPECT_EQ(mesh.vertices[2], Vec3(1.1, -300, 2.5));
    EXPECT_EQ(mesh.vertices[4], Vec3(-0.4, -150, 2.5));
    EXPECT_EQ(mesh.faces, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {4, 3, 2}, {4, 2, 1}, {4, 1, 0}}));
    ASSERT_EQ(mesh.vertex_properties.size(), 2u);
    EXPECT_EQ(mesh.vertex_properties[0].name, "red");
    EXPECT_EQ(mesh.vertex_properties[0].values, (std::vector<float>{200, 201, 202, 203, 204}));
    EXPECT_EQ(mesh.vertex_properties[1].name, "bias");
    EXPECT_EQ(mesh.vertex_properties[1].values, (std::vector<float>{0, -1, -2, -3, -4}));
  }
}

TEST(MeshFilesSharedData, HemibrainPlyReadsWithItsVertexAndTriangleCounts) {
  SHARED_DATA_OR_SKIP(path, "neuron-hemibrain-da1/1734350788.ply");
  const TriMesh mesh = read_mesh(path);
  EXPECT_EQ(mesh.vertices.size(), 17369u);
  EXPECT_EQ(mesh.faces.size(), 35106u);
  EXPECT_TRUE(mesh.vertex_properties.empty());
}

// ---------------------------------------------------------------------------------------------------
// OBJ and STL from other writers

TEST_F(MeshFiles, ObjWithSlashesAndNegativeIndicesReads) {
  const std::string p = file("slashes.obj",
                             "# exported\nmtllib a.mtl\no thing\ng group\ns 1\nusemtl red\n"
                             "v 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.2 0.3 0.4\n"
                             "vt 0 0\nvt 1 0\nvn 0 0 1\n"
                             "f 1/1 2/2 3/1\n"
                             "v 0 1 0\n"
                             "f -4//1 -2//1 -1//1  # relative to the four vertices so far\n"
                             "f 1/1/1 3/2/1 4/1/1\n");
  const TriMesh mesh = read_mesh(p);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.vertices[1], Vec3(1, 0, 0));
  EXPECT_EQ(mesh.vertices[2], Vec3(1, 1, 0));
  EXPECT_EQ(mesh.faces, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {0, 2, 3}}));
}

TEST_F(MeshFiles, ObjPolygonsAreFanTriangulated) {
  const std::string p =
      file("pentagon.obj", "v 0 0 0\r\nv 1 0 0\r\nv 2 1 0\r\nv 1 2 0\r\nv 0 1 0\r\nf 1 2 3 4 5\r\n");
  EXPECT_EQ(read_mesh(p).faces, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
}

TEST_F(MeshFiles, AsciiStlReadsWithCoincidentVerticesWelded) {
  const std::string p = file("two.stl", kTwoFacetStl);
  const TriMesh mesh = read_mesh(p);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.faces, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(mesh.vertices[3], Vec3(0, 1, 0));
}

TEST_F(MeshFiles, BinaryStlWhoseHeaderStartsWithSolidIsReadAsBinary) {
  Bytes b(false);
  b.text("solid but binary" + std::string(64, ' ')).put<uint32_t>(1);
  for (float value : {0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) b.put(value);
  b.put<uint16_t>(0);
  const TriMesh mesh = read_mesh(file("solid.stl", b.str()));
  EXPECT_EQ(mesh.vertices.size(), 3u);
  EXPECT_EQ(mesh.faces, (std::vector<Tri>{{0, 1, 2}}));
}

// ---------------------------------------------------------------------------------------------------
// Errors: each names the file and where

TEST_F(MeshFiles, EmptyFileIsRejectedNamingTheFile) {
  for (const char* name : {"empty.ply", "empty.obj", "empty.stl"})
    expect_input_error(file(name, ""), "", "empty");
}

TEST_F(MeshFiles, MissingFileAndUnknownExtensionAreRejectedNamingTheFile) {
  expect_input_error(path("absent.ply"), "", "cannot open");
  expect_input_error(file("mesh.off", "OFF\n"), "", "unknown mesh extension '.off'");
}

TEST_F(MeshFiles, PlyHeaderErrorsNameTheLine) {
  expect_input_error(file("magic.ply", "solid x\n"), "line 1", "expected 'ply'");
  expect_input_error(file("format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"), "line 2",
                     "unknown format 'binary_middle_endian'");
  expect_input_error(file("type.ply",
                          "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                          "property quad y\nend_header\n"),
                     "line 5", "unknown property type 'quad'");
  expect_input_error(file("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"),
                     "line 4", "without 'end_header'");
  expect_input_error(file("keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 0\nend_header\n"), "line 3",
                     "unknown header keyword 'elemnt'");
  expect_input_error(file("no_z.ply",
                          "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                          "property float y\nend_header\n0 0\n"),
                     "line 3", "no scalar 'z' property");
  expect_input_error(file("no_list.ply",
                          "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                          "property float y\nproperty float z\nelement face 0\n"
                          "property list uchar int corners\nend_header\n"),
                     "line 7", "no vertex_indices list");
  expect_input_error(file("float_count.ply",
                          "ply\nformat ascii 1.0\nelement face 0\n"
                          "property list float int vertex_indices\nend_header\n"),
                     "line 4", "not an integer type");
}

TEST_F(MeshFiles, PlyCountsLargerThanTheFileCanHoldAreRejectedBeforeAllocating) {
  const std::string vertices = "property float x\nproperty float y\nproperty float z\n";
  expect_input_error(
      file("vertices.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\n" + vertices +
                               "end_header\n" + std::string(12, '\0')),
      "line 3", "declares 2000000000 entries, more than the 12 bytes");
  expect_input_error(
      file("faces.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 0\n" + vertices +
                            "element face 1000000000000000\nproperty list uchar int vertex_indices\n"
                            "end_header\n"),
      "line 7", "declares 1000000000000000 entries");
  expect_input_error(
      file("ascii.ply", "ply\nformat ascii 1.0\nelement vertex 1000\n" + vertices + "end_header\n0 0 0\n"),
      "line 3", "declares 1000 entries");
  expect_input_error(
      file("too_many.ply", "ply\nformat ascii 1.0\nelement vertex 3000000000\n" + vertices + "end_header\n"),
      "line 3", "more than 32-bit face indices can address");
}

/// A little-endian PLY with `vertices` vertices at the origin and the given face bytes.
std::string binary_ply(int vertices, int faces, const std::string& face_bytes) {
  Bytes b(false);
  b.text("ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nproperty int tag\nend_header\n");
  for (int i = 0; i < 3 * vertices; ++i) b.put(0.0f);
  return b.text(face_bytes).str();
}

std::size_t header_size(const std::string& ply) { return ply.find("end_header\n") + 11; }

TEST_F(MeshFiles, PlyTruncatedBinaryDataIsRejectedAtItsByteOffset) {
  // The list says three indices but the file ends after two.
  const std::string short_list =
      binary_ply(3, 1, Bytes(false).put<uint8_t>(3).put<int32_t>(0).put<int32_t>(1).str());
  const std::size_t list_count = header_size(short_list) + 36;
  expect_input_error(file("short_list.ply", short_list), "byte " + std::to_string(list_count),
                     "list 'vertex_indices' of face 0 has 3 items, but only 8 bytes remain");
  // The list is whole but the tag after it is cut short.
  const std::string short_tag = binary_ply(
      3, 1, Bytes(false).put<uint8_t>(3).put<int32_t>(0).put<int32_t>(1).put<int32_t>(2).text("ab").str());
  expect_input_error(file("short_tag.ply", short_tag), "byte " + std::to_string(list_count + 13),
                     "the file ends inside face 0 ('tag')");
}

TEST_F(MeshFiles, PlyTruncatedAsciiDataIsRejectedAtTheLine) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  expect_input_error(file("short.ply", header + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n"), "line 15",
                     "expected face 1 of 2, found the end of the file");
  expect_input_error(file("short_line.ply", header + "0 0 0\n1 0 0\n1 1\n0 1 0\n3 0 1 2\n3 0 2 3\n"),
                     "line 12", "expected a value for 'z' of vertex 2");
  expect_input_error(file("long_line.ply", header + "0 0 0\n1 0 0\n1 1 0 1\n0 1 0\n3 0 1 2\n3 0 2 3\n"),
                     "line 12", "more values on the line of vertex 2");
  expect_input_error(file("long_list.ply", header + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 2 3\n"),
                     "line 15", "has 4 items, but the line holds 3 more values");
}

TEST_F(MeshFiles, PlyFaceIndexOutOfRangeIsRejected) {
  const std::string binary = binary_ply(
      3, 1,
      Bytes(false).put<uint8_t>(3).put<int32_t>(0).put<int32_t>(3).put<int32_t>(1).put<int32_t>(0).str());
  expect_input_error(file("binary.ply", binary), "byte " + std::to_string(header_size(binary) + 36 + 5),
                     "face 0: vertex index 3 is out of range for 3 vertices");
  const std::string negative = binary_ply(
      3, 1,
      Bytes(false).put<uint8_t>(3).put<int32_t>(-1).put<int32_t>(1).put<int32_t>(2).put<int32_t>(0).str());
  expect_input_error(file("negative.ply", negative), "byte " + std::to_string(header_size(negative) + 36 + 1),
                     "vertex index -1 is out of range");
  expect_input_error(file("ascii.ply",
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                          "property float y\nproperty float z\nelement face 1\n"
                          "property list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
                     "line 13", "face 0: vertex index 7 is out of range for 3 vertices");
}

TEST_F(MeshFiles, PlyFaceWithFewerThanThreeVerticesIsRejected) {
  const std::string binary =
      binary_ply(3, 1, Bytes(false).put<uint8_t>(2).put<int32_t>(0).put<int32_t>(1).str());
  expect_input_error(file("binary.ply", binary), "byte " + std::to_string(header_size(binary) + 36),
                     "face 0 has 2 vertices; a face needs at least 3");
  expect_input_error(file("ascii.ply",
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                          "property float y\nproperty float z\nelement face 1\n"
                          "property list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
                     "line 13", "face 0 has 2 vertices");
}

TEST_F(MeshFiles, PlyNonFiniteCoordinateIsRejected) {
  std::string binary = binary_ply(3, 0, "");
  const std::size_t y_of_vertex_1 = header_size(binary) + 16;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&binary[y_of_vertex_1], &nan, sizeof nan);  // little-endian hosts only
  expect_input_error(file("nan.ply", binary), "byte " + std::to_string(y_of_vertex_1),
                     "vertex 1: y is not a finite number");
  expect_input_error(file("inf.ply",
                          "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n0 0 0\n1 inf 0\n"),
                     "line 9", "y is not a finite number");
}

TEST_F(MeshFiles, ObjErrorsNameTheLine) {
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_input_error(file("range.obj", vertices + "f 1 2 4\n"), "line 4",
                     "vertex index 4 is out of range: 3 vertices are defined before this line");
  expect_input_error(file("zero.obj", vertices + "f 0 1 2\n"), "line 4", "vertex index 0 is out of range");
  expect_input_error(file("negative.obj", vertices + "f -1 -2 -4\n"), "line 4",
                     "vertex index -4 is out of range");
  expect_input_error(file("forward.obj", "f 1 2 3\n" + vertices), "line 1", "vertex index 1 is out of range");
  expect_input_error(file("two.obj", vertices + "f 1 2\n"), "line 4", "a face needs at least 3");
  expect_input_error(file("nan.obj", "v 0 nan 0\n"), "line 1", "y is not a finite number");
  expect_input_error(file("text.obj", vertices + "v 1 2 three\n"), "line 4", "expected a number for z");
  expect_input_error(file("short.obj", "v 1 2\n"), "line 1", "expected 'v x y z'");
  expect_input_error(file("slash.obj", vertices + "f /1 2 3\n"), "line 4",
                     "expected an integer for a vertex index");
  expect_input_error(file("none.obj", "# nothing but comments\nvn 0 0 1\n"), "", "no vertices");
}

TEST_F(MeshFiles, StlErrorsNameTheLineOrByte) {
  write_mesh(cube(), path("cube.stl"));
  std::string binary = read_bytes(path("cube.stl"));
  expect_input_error(file("truncated.stl", binary.substr(0, binary.size() - 1)), "byte 0",
                     "not 84 + 50·n bytes for the 12 triangles");
  expect_input_error(file("tiny.stl", "VesselMesh"), "byte 0", "shorter than the 84 bytes");
  const std::size_t x_of_triangle_2_vertex_1 = 84 + 2 * 50 + 12 + 12;
  const float inf = std::numeric_limits<float>::infinity();
  std::memcpy(&binary[x_of_triangle_2_vertex_1], &inf, sizeof inf);  // little-endian hosts only
  expect_input_error(file("inf.stl", binary), "byte " + std::to_string(x_of_triangle_2_vertex_1),
                     "triangle 2: vertex 1 is not a finite number");

  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
  expect_input_error(file("two.stl", "solid s\n" + facet + "endloop\nendfacet\nendsolid s\n"), "line 7",
                     "the facet has 2 vertices; a facet needs at least 3");
  expect_input_error(file("nan.stl", "solid s\n" + facet + "vertex 0 nan 1\nendloop\nendfacet\n"), "line 6",
                     "y is not a finite number");
  expect_input_error(file("keyword.stl", "solid s\n" + facet + "vertx 0 1 0\n"), "line 6",
                     "unexpected 'vertx' inside a facet");
  expect_input_error(file("outside.stl", "solid s\nvertex 0 1 0\n"), "line 2",
                     "unexpected 'vertex' outside a facet");
  expect_input_error(file("open.stl", "solid s\n" + facet + "vertex 0 1 0\n"), "line 6",
                     "the file ends inside the facet that starts at line 2");
}

/// Reads `path`: either a mesh whose indices, coordinates and properties are all usable, or an InputError.
void expect_valid_mesh_or_input_error(const std::string& path) {
  TriMesh mesh;
  try {
    mesh = read_mesh(path);
  } catch (const InputError&) {
    return;
  }
  for (const Vec3& p : mesh.vertices) ASSERT_TRUE(p.allFinite());
  for (const Tri& f : mesh.faces)
    for (int32_t v : f) ASSERT_TRUE(v >= 0 && static_cast<std::size_t>(v) < mesh.vertices.size());
  for (const VertexProperty& property : mesh.vertex_properties)
    ASSERT_EQ(property.values.size(), mesh.vertices.size());
}

TEST_F(MeshFiles, DamagedFilesReadAsValidMeshesOrFailWithInputError) {
  std::vector<std::pair<std::string, std::string>> samples = {{"quad.ply", kQuadPly},
                                                              {"mixed_le.ply", mixed_binary_ply(false)},
                                                              {"mixed_be.ply", mixed_binary_ply(true)},
                                                              {"two.stl", kTwoFacetStl}};
  TriMesh with_property = cube();
  with_property.vertex_properties = {{"k", {1, 2, 3, 4, 5, 6, 7, 8}}};
  for (const char* name : {"cube.ply", "cube.obj", "cube.stl"}) {
    write_mesh(with_property, path(name));
    samples.emplace_back(name, read_bytes(path(name)));
  }
  std::mt19937 random(12345);
  for (const auto& [name, bytes] : samples) {
    SCOPED_TRACE(name);
    const std::string damaged = "damaged" + fs::path(name).extension().string();
    for (std::size_t size = 0; size < bytes.size(); ++size) {
      ASSERT_NO_FATAL_FAILURE(expect_valid_mesh_or_input_error(file(damaged, bytes.substr(0, size))))
          << "first " << size << " bytes";
    }
    for (int trial = 0; trial < 300; ++trial) {
      std::string changed = bytes;
      changed[random() % changed.size()] = static_cast<char>(random() % 256);
      ASSERT_NO_FATAL_FAILURE(expect_valid_mesh_or_input_error(file(damaged, changed))) << "trial " << trial;
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// Size

/// A 500 × 1000 quad grid: 501,501 vertices, 1,000,000 triangles.
TriMesh grid_mesh() {
  constexpr int32_t kColumns = 500, kRows = 1000;
  TriMesh mesh;
  mesh.vertices.reserve((kColumns + 1) * (kRows + 1));
  for (int32_t r = 0; r <= kRows; ++r)
    for (int32_t c = 0; c <= kColumns; ++c)
      mesh.vertices.emplace_back(0.01 * c, 0.01 * r, 0.001 * ((c * r) % 7));
  mesh.faces.reserve(2 * kColumns * kRows);
  for (int32_t r = 0; r < kRows; ++r)
    for (int32_t c = 0; c < kColumns; ++c) {
      const int32_t v = r * (kColumns + 1) + c;
      mesh.faces.push_back({v, v + 1, v + kColumns + 2});
      mesh.faces.push_back({v, v + kColumns + 2, v + kColumns + 1});
    }
  return mesh;
}

TEST_F(MeshFiles, MillionTriangleGridRoundTripsInEveryFormat) {
  const TriMesh mesh = grid_mesh();
  ASSERT_EQ(mesh.faces.size(), 1000000u);
  for (const char* name : {"grid.ply", "grid.obj", "grid.stl"}) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    write_mesh(mesh, path(name));
    const auto written = Clock::now();
    const TriMesh read = read_mesh(path(name));
    const auto done = Clock::now();
    std::printf("[ timing   ] %s: write %.0f ms, read %.0f ms (%ju bytes)\n", name,
                std::chrono::duration<double, std::milli>(written - start).count(),
                std::chrono::duration<double, std::milli>(done - written).count(),
                static_cast<uintmax_t>(fs::file_size(path(name))));
    EXPECT_EQ(read.vertices.size(), mesh.vertices.size()) << name;
    EXPECT_EQ(read.faces.size(), mesh.faces.size()) << name;
    if (std::string(name) != "grid.stl") EXPECT_TRUE(read.faces == mesh.faces) << name;
  }
}

}  // namespace
}  // namespace vesselmesh
