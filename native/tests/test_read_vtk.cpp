// Legacy VTK reader and writer: every layout the reader takes, every error it reports (with the file and the
// line or byte offset), robustness against damaged input, writer round trips and the shared real data sets.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "allocation_probe.hpp"
#include "test_support.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/read/read.hpp"
#include "vesselmesh/read/text.hpp"
#include "vesselmesh/write/centerline_vtk.hpp"

namespace vesselmesh {
namespace {

const std::string kSource = "fixture.vtk";

CenterlineData parse(const std::string& bytes, const std::string& radius_array = "") {
  ReadOptions options;
  options.radius_array = radius_array;
  return parse_vtk(bytes, kSource, options);
}

/// Passes when parsing throws an InputError whose message starts with the file name and contains every
/// fragment (the location, such as "line 9:" or "byte 120:", and what was expected).
::testing::AssertionResult FailsWith(const std::string& bytes, std::initializer_list<std::string> fragments,
                                     const std::string& radius_array = "") {
  std::string message;
  try {
    parse(bytes, radius_array);
    return ::testing::AssertionFailure() << "no InputError was thrown";
  } catch (const InputError& e) {
    message = e.what();
  }
  if (message.rfind(kSource + ": ", 0) != 0)
    return ::testing::AssertionFailure() << "'" << message << "' does not start with the file name";
  for (const std::string& fragment : fragments)
    if (message.find(fragment) == std::string::npos)
      return ::testing::AssertionFailure() << "'" << message << "' lacks '" << fragment << "'";
  return ::testing::AssertionSuccess() << message;
}

/// `text` with its one occurrence of `from` replaced by `to`.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos)
    throw std::logic_error("fixture edit: '" + from + "' is not in the fixture exactly once");
  return text.replace(at, from.size(), to);
}

/// Byte offset just past `line` in `bytes`: where BINARY data after that keyword line starts.
std::size_t data_after(const std::string& bytes, const std::string& line) {
  return bytes.find(line) + line.size();
}

/// Lines 1 to 4 of a fixture: header, title, format and dataset.
std::string header(const std::string& version = "3.0", const std::string& format = "ASCII",
                   const std::string& dataset = "POLYDATA") {
  return "# vtk DataFile Version " + version + "\ntest fixture\n" + format + "\nDATASET " + dataset + "\n";
}

/// Builds BINARY fixtures: text, and values in big-endian byte order.
class Bytes {
 public:
  Bytes& text(std::string_view s) {
    bytes_ += s;
    return *this;
  }
  template <class T>
  Bytes& be(std::initializer_list<T> values) {
    for (T value : values) {
      std::array<char, sizeof(T)> raw;
      std::memcpy(raw.data(), &value, sizeof value);
      if (little_endian()) std::reverse(raw.begin(), raw.end());
      bytes_.append(raw.data(), raw.size());
    }
    return *this;
  }
  std::size_t size() const { return bytes_.size(); }
  const std::string& str() const { return bytes_; }

 private:
  static bool little_endian() {
    const uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
  }
  std::string bytes_;
};

// An ASCII 3.0 POLYDATA: one poly-line of three points, radius per point. Lines 5 to 13.
std::string ascii_lines() {
  return header() +
         "POINTS 3 float\n"        // 5
         "0 0 0 1 0 0\n"           // 6
         "2 0 0\n"                 // 7
         "LINES 1 4\n"             // 8
         "3 0 1 2\n"               // 9
         "POINT_DATA 3\n"          // 10
         "SCALARS radius float\n"  // 11
         "LOOKUP_TABLE default\n"  // 12
         "0.5 0.25 0.125\n";       // 13
}

// An ASCII 5.1 POLYDATA with OFFSETS and CONNECTIVITY, radius per cell. Lines 5 to 15.
std::string ascii_offsets() {
  return header("5.1") +
         "POINTS 4 double\n"            // 5
         "0 0 0 1 0 0 2 0 0 2 1 0\n"    // 6
         "LINES 3 5\n"                  // 7
         "OFFSETS vtktypeint64\n"       // 8
         "0 3 5\n"                      // 9
         "CONNECTIVITY vtktypeint64\n"  // 10
         "0 1 2 2 3\n"                  // 11
         "CELL_DATA 2\n"                // 12
         "FIELD FieldData 1\n"          // 13
         "radius 1 2 double\n"          // 14
         "1.5 2.5\n";                   // 15
}

// An ASCII 3.0 UNSTRUCTURED_GRID: a vertex, a line and a poly-line, radius per cell. Lines 5 to 18.
std::string ascii_grid() {
  return header("3.0", "ASCII", "UNSTRUCTURED_GRID") +
         "POINTS 4 float\n"           // 5
         "0 0 0 1 0 0 2 0 0 3 0 0\n"  // 6
         "CELLS 3 9\n"                // 7
         "1 3\n"                      // 8
         "2 0 1\n"                    // 9
         "3 1 2 3\n"                  // 10
         "CELL_TYPES 3\n"             // 11
         "1\n"                        // 12
         "3\n"                        // 13
         "4\n"                        // 14
         "CELL_DATA 3\n"              // 15
         "SCALARS r double\n"         // 16
         "LOOKUP_TABLE default\n"     // 17
         "9 1 2\n";                   // 18
}

/// A BINARY 3.0 POLYDATA (the layout of vascpy's files) and where its data blocks start.
struct BinaryFixture {
  std::string bytes;
  std::size_t points_at, cells_at, radius_at;
};

BinaryFixture binary_lines() {
  Bytes b;
  BinaryFixture f;
  b.text(header("3.0", "BINARY") + "POINTS 3 float\n");
  f.points_at = b.size();
  b.be<float>({0, 0, 0, 1, 0, 0, 2, 0, 0}).text("\nLINES 2 6\n");
  f.cells_at = b.size();
  b.be<int32_t>({2, 0, 1, 2, 1, 2}).text("\nCELL_DATA 2\nFIELD FieldData 1\nradius 1 2 float\n");
  f.radius_at = b.size();
  b.be<float>({1.5f, 2.5f}).text("\n");
  f.bytes = b.str();
  return f;
}

/// A BINARY 5.1 UNSTRUCTURED_GRID (the layout of the human brain arteries file), with METADATA after the
/// points.
BinaryFixture binary_grid() {
  Bytes b;
  BinaryFixture f;
  b.text(header("5.1", "BINARY", "UNSTRUCTURED_GRID") + "POINTS 3 float\n");
  f.points_at = b.size();
  b.be<float>({0, 0, 0, 1, 0, 0, 2, 0, 0})
      .text("\nMETADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 2\n\n")
      .text("CELLS 3 4\nOFFSETS vtktypeint64\n");
  f.cells_at = b.size();
  b.be<int64_t>({0, 2, 4})
      .text("\nCONNECTIVITY vtktypeint64\n")
      .be<int64_t>({0, 1, 1, 2})
      .text("\nCELL_TYPES 2\n")
      .be<int32_t>({3, 3})
      .text("\nPOINT_DATA 3\nSCALARS radius float\nLOOKUP_TABLE default\n");
  f.radius_at = b.size();
  b.be<float>({0.5f, 0.25f, 0.125f})
      .text("\nFIELD FieldData 1\nroot 1 3 vtktypeint64\n")
      .be<int64_t>({2, 0, 1});
  b.text("\n");
  f.bytes = b.str();
  return f;
}

const std::vector<Edge> kChain = {Edge{0, 1}, Edge{1, 2}};

// ---------------------------------------------------------------------------------------------------------
// Layouts

TEST(ReadVtk, AsciiPolyDataLinesGiveEdgesAndPointRadius) {
  const CenterlineData data = parse(ascii_lines());
  ASSERT_EQ(data.points.size(), 3u);
  EXPECT_EQ(data.points[1], Vec3(1, 0, 0));
  EXPECT_EQ(data.points[2], Vec3(2, 0, 0));
  EXPECT_EQ(data.edges, kChain);
  EXPECT_EQ(data.radius, (std::vector<double>{0.5, 0.25, 0.125}));
  EXPECT_TRUE(data.edge_radius.empty());
  EXPECT_NO_THROW(validate(data, kSource));
}

TEST(ReadVtk, PolyLineCellOfKPointsGivesKMinusOneEdges) {
  const std::string text = header() +
                           "POINTS 4 float\n0 0 0 1 0 0 2 0 0 3 0 0\n"
                           "LINES 3 10\n4 0 1 2 3\n1 3\n2 3 0\n"
                           "POINT_DATA 4\nSCALARS radius float\nLOOKUP_TABLE default\n1 1 1 1\n";
  EXPECT_EQ(parse(text).edges, (std::vector<Edge>{{0, 1}, {1, 2}, {2, 3}, {3, 0}}));
}

TEST(ReadVtk, Version51OffsetsAndConnectivityInPolyData) {
  const CenterlineData data = parse(ascii_offsets());
  EXPECT_EQ(data.points.size(), 4u);
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}, {1, 2}, {2, 3}}));
  EXPECT_TRUE(data.radius.empty());
  EXPECT_EQ(data.edge_radius, (std::vector<double>{1.5, 1.5, 2.5}));
}

TEST(ReadVtk, UnstructuredGridLinesAndPolyLinesBecomeEdgesAndVerticesAreSkipped) {
  const CenterlineData data = parse(ascii_grid());
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}, {1, 2}, {2, 3}}));
  // Cell 0 is the vertex; its CELL_DATA value 9 belongs to no edge.
  EXPECT_EQ(data.edge_radius, (std::vector<double>{1, 2, 2}));
}

TEST(ReadVtk, Version51UnstructuredGridWithOffsetsAndPolyVertexCells) {
  const std::string text = header("5.1", "ASCII", "UNSTRUCTURED_GRID") +
                           "POINTS 3 float\n0 0 0 1 0 0 2 0 0\n"
                           "CELLS 3 5\nOFFSETS vtktypeint64\n0 2 5\nCONNECTIVITY vtktypeint64\n0 2 0 1 2\n"
                           "CELL_TYPES 2\n2 4\n"
                           "POINT_DATA 3\nSCALARS radius double 1\nLOOKUP_TABLE default\n1 2 3\n";
  const CenterlineData data = parse(text);
  EXPECT_EQ(data.edges, kChain);
  EXPECT_EQ(data.radius, (std::vector<double>{1, 2, 3}));
}

TEST(ReadVtk, Binary30PolyDataWithCellFieldRadius) {
  const CenterlineData data = parse(binary_lines().bytes);
  ASSERT_EQ(data.points.size(), 3u);
  EXPECT_EQ(data.points[2], Vec3(2, 0, 0));
  EXPECT_EQ(data.edges, kChain);
  EXPECT_EQ(data.edge_radius, (std::vector<double>{1.5, 2.5}));
}

TEST(ReadVtk, Binary51UnstructuredGridWithInt64OffsetsMetadataAndPointScalars) {
  const CenterlineData data = parse(binary_grid().bytes);
  EXPECT_EQ(data.points.size(), 3u);
  EXPECT_EQ(data.edges, kChain);
  EXPECT_EQ(data.radius, (std::vector<double>{0.5, 0.25, 0.125}));
}

TEST(ReadVtk, PolyDataCellDataNumbersVerticesBeforeLines) {
  // LINES comes first in the file, but VTK numbers the VERTICES cells first.
  const std::string text = header() +
                           "POINTS 3 float\n0 0 0 1 0 0 2 0 0\n"
                           "LINES 1 3\n2 1 2\n"
                           "VERTICES 2 4\n1 0\n1 2\n"
                           "CELL_DATA 3\nSCALARS radius float\nLOOKUP_TABLE default\n7 8 4\n";
  const CenterlineData data = parse(text);
  EXPECT_EQ(data.edges, (std::vector<Edge>{{1, 2}}));
  EXPECT_EQ(data.edge_radius, (std::vector<double>{4}));
}

TEST(ReadVtk, DiameterArrayIsHalved) {
  const CenterlineData data = parse(with(ascii_lines(), "SCALARS radius float", "SCALARS Diameter float"));
  EXPECT_EQ(data.radius, (std::vector<double>{0.25, 0.125, 0.0625}));
}

TEST(ReadVtk, RequestedArrayNameOverridesTheDefaultChoice) {
  const std::string text =
      ascii_lines() + "FIELD FieldData 2\nthickness 1 3 double\n4 5 6\nvessel_diam 1 3 double\n2 2 2\n";
  EXPECT_EQ(parse(text).radius, (std::vector<double>{0.5, 0.25, 0.125}));
  EXPECT_EQ(parse(text, "thickness").radius, (std::vector<double>{4, 5, 6}));
  EXPECT_EQ(parse(text, "THICKNESS").radius, (std::vector<double>{4, 5, 6}));
  EXPECT_EQ(parse(text, "vessel_diam").radius, (std::vector<double>{1, 1, 1}));
}

TEST(ReadVtk, AsciiSkipsVectorsNormalsTensorsTextureCoordinatesColorScalarsAndLookupTables) {
  const std::string text = header() +
                           "POINTS 2 float\n0 0 0 1 0 0\nLINES 1 3\n2 0 1\n"
                           "LOOKUP_TABLE colors 2\n0 0 0 1 1 1 1 1\n"
                           "POINT_DATA 2\n"
                           "VECTORS velocity float\n1 2 3 4 5 6\n"
                           "NORMALS normals double\n0 0 1 0 0 1\n"
                           "TENSORS stress float\n1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 1\n"
                           "TEXTURE_COORDINATES uv 2 float\n0 0 1 1\n"
                           "COLOR_SCALARS rgb 3\n0.1 0.2 0.3 0.4 0.5 0.6\n"
                           "SCALARS radius float\nLOOKUP_TABLE colors\n2 3\n"
                           "LOOKUP_TABLE colors 1\n0.5 0.5 0.5 1\n";
  EXPECT_EQ(parse(text).radius, (std::vector<double>{2, 3}));
}

TEST(ReadVtk, BinarySkipsColorScalarsAsBytesAndOtherBlocks) {
  Bytes b;
  b.text(header("3.0", "BINARY") + "POINTS 2 float\n")
      .be<float>({0, 0, 0, 1, 0, 0})
      .text("\nLINES 1 3\n")
      .be<int32_t>({2, 0, 1})
      .text("\nPOINT_DATA 2\nCOLOR_SCALARS rgba 4\n")
      .be<uint8_t>({10, 20, 30, 255, 40, 50, 60, 255})
      .text("\nLOOKUP_TABLE table 1\n")
      .be<uint8_t>({1, 2, 3, 4})
      .text("\nVECTORS v double\n")
      .be<double>({1, 2, 3, 4, 5, 6})
      .text("\nSCALARS radius double\nLOOKUP_TABLE default\n")
      .be<double>({0.75, 1.25})
      .text("\n");
  EXPECT_EQ(parse(b.str()).radius, (std::vector<double>{0.75, 1.25}));
}

TEST(ReadVtk, Version51MetadataAndInformationBlocksAreSkipped) {
  const std::string text = header("5.1") +
                           "POINTS 3 float\n0 0 0 1 0 0 2 0 0\n"
                           "METADATA\nINFORMATION 2\n"
                           "NAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 2\n"
                           "NAME L2_NORM_FINITE_RANGE LOCATION vtkDataArray\nDATA 2 0 2\n\n"
                           "LINES 2 3\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n0 1 2\n"
                           "POINT_DATA 3\n"
                           "FIELD FieldData 2\n"
                           "flow 2 3 double\n1 2 3 4 5 6\n"
                           "METADATA\nCOMPONENT_NAMES\nX\nY\n\n"
                           "radius 1 3 float\n1 2 3\n"
                           "METADATA\nINFORMATION 1\nNAME UNITS_LABEL LOCATION vtkDataArray\nDATA mm\n\n";
  const CenterlineData data = parse(text);
  EXPECT_EQ(data.edges, kChain);
  EXPECT_EQ(data.radius, (std::vector<double>{1, 2, 3}));
}

TEST(ReadVtk, NullArraysInFieldAreSkipped) {
  const std::string text =
      with(ascii_offsets(), "FIELD FieldData 1\n", "FIELD FieldData 3\nNULL_ARRAY\nNULL_ARRAY\n");
  EXPECT_EQ(parse(text).edge_radius, (std::vector<double>{1.5, 1.5, 2.5}));
}

TEST(ReadVtk, DatasetFieldDataIsNotARadiusCandidate) {
  const std::string text =
      with(ascii_lines(), "POINTS 3 float\n", "FIELD FieldData 1\nradius 1 1 double\n99\nPOINTS 3 float\n");
  EXPECT_EQ(parse(text).radius, (std::vector<double>{0.5, 0.25, 0.125}));
}

TEST(ReadVtk, SectionsMayComeInAnyOrder) {
  const std::string text = header() +
                           "CELL_DATA 2\nSCALARS radius double\nLOOKUP_TABLE default\n3 4\n"
                           "LINES 2 6\n2 0 1\n2 1 2\n"
                           "POINTS 3 double\n0 0 0 1 0 0 2 0 0\n";
  const CenterlineData data = parse(text);
  EXPECT_EQ(data.edges, kChain);
  EXPECT_EQ(data.edge_radius, (std::vector<double>{3, 4}));
}

TEST(ReadVtk, AsciiNumbersMaySpanLinesWithTabsAndCrlf) {
  const std::string text =
      "# vtk DataFile Version 4.2\r\ntitle\r\nascii\r\ndataset polydata\r\n\r\n"
      "points 3 double\r\n0\t0 0\r\n1 0\r\n0 2 0 0 lines 1 4 3\r\n0 1\r\n2\r\n"
      "point_data 3 scalars radius double lookup_table default 1\t2\r\n3\r\n";
  const CenterlineData data = parse(text);
  EXPECT_EQ(data.points[2], Vec3(2, 0, 0));
  EXPECT_EQ(data.edges, kChain);
  EXPECT_EQ(data.radius, (std::vector<double>{1, 2, 3}));
}

TEST(ReadVtk, AsciiIntegerTypedArraysAreRead) {
  const std::string text = with(with(ascii_lines(), "SCALARS radius float", "SCALARS radius vtkIdType"),
                                "0.5 0.25 0.125", "2 3 4");
  EXPECT_EQ(parse(text).radius, (std::vector<double>{2, 3, 4}));
}

/// A BINARY fixture whose point radius array has `type`, holding the values 3 and 7.
template <class T>
std::string binary_radius_of_type(const std::string& type) {
  Bytes b;
  b.text(header("3.0", "BINARY") + "POINTS 2 float\n")
      .be<float>({0, 0, 0, 1, 0, 0})
      .text("\nLINES 1 3\n")
      .be<int32_t>({2, 0, 1})
      .text("\nPOINT_DATA 2\nSCALARS radius " + type + "\nLOOKUP_TABLE default\n")
      .be<T>({T(3), T(7)})
      .text("\n");
  return b.str();
}

TEST(ReadVtk, EveryBinaryDataTypeDecodes) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"unsigned_char", binary_radius_of_type<uint8_t>("unsigned_char")},
      {"char", binary_radius_of_type<int8_t>("char")},
      {"signed_char", binary_radius_of_type<int8_t>("signed_char")},
      {"unsigned_short", binary_radius_of_type<uint16_t>("unsigned_short")},
      {"short", binary_radius_of_type<int16_t>("short")},
      {"unsigned_int", binary_radius_of_type<uint32_t>("unsigned_int")},
      {"int", binary_radius_of_type<int32_t>("int")},
      {"unsigned_long", binary_radius_of_type<uint64_t>("unsigned_long")},
      {"long", binary_radius_of_type<int64_t>("long")},
      {"float", binary_radius_of_type<float>("float")},
      {"double", binary_radius_of_type<double>("double")},
      {"vtkIdType", binary_radius_of_type<int32_t>("vtkIdType")},
      {"vtktypeint8", binary_radius_of_type<int8_t>("vtktypeint8")},
      {"vtktypeuint8", binary_radius_of_type<uint8_t>("vtktypeuint8")},
      {"vtktypeint16", binary_radius_of_type<int16_t>("vtktypeint16")},
      {"vtktypeuint16", binary_radius_of_type<uint16_t>("vtktypeuint16")},
      {"vtktypeint32", binary_radius_of_type<int32_t>("vtktypeint32")},
      {"vtktypeuint32", binary_radius_of_type<uint32_t>("vtktypeuint32")},
      {"vtktypeint64", binary_radius_of_type<int64_t>("vtktypeint64")},
      {"vtktypeuint64", binary_radius_of_type<uint64_t>("vtktypeuint64")},
      {"vtktypefloat32", binary_radius_of_type<float>("vtktypefloat32")},
      {"vtktypefloat64", binary_radius_of_type<double>("vtktypefloat64")},
  };
  for (const auto& [type, bytes] : cases) {
    SCOPED_TRACE(type);
    EXPECT_EQ(parse(bytes).radius, (std::vector<double>{3, 7}));
  }
}

TEST(ReadVtk, BinarySignedIntegersAreSignExtended) {
  Bytes b;
  b.text(header("3.0", "BINARY") + "POINTS 2 short\n")
      .be<int16_t>({-2, 0, 0, 300, -1, 0})
      .text("\nLINES 1 3\n")
      .be<int32_t>({2, 0, 1})
      .text("\nPOINT_DATA 2\nSCALARS radius char\nLOOKUP_TABLE default\n")
      .be<int8_t>({1, 2})
      .text("\n");
  const CenterlineData data = parse(b.str());
  EXPECT_EQ(data.points[0], Vec3(-2, 0, 0));
  EXPECT_EQ(data.points[1], Vec3(300, -1, 0));
}

// ---------------------------------------------------------------------------------------------------------
// Errors: header and structure

TEST(ReadVtk, EmptyFileIsRejected) { EXPECT_TRUE(FailsWith("", {"line 1:", "the file is empty"})); }

TEST(ReadVtk, MissingHeaderIsRejectedOnLineOne) {
  EXPECT_TRUE(FailsWith("vtk output\nASCII\nDATASET POLYDATA\n",
                        {"line 1:", "not a legacy VTK file", "# vtk DataFile Version"}));
  EXPECT_TRUE(FailsWith("\n\n", {"line 1:", "not a legacy VTK file"}));
}

TEST(ReadVtk, GarbledVersionIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "Version 3.0", "Version x.y"),
                        {"line 1:", "expected a number for the version, found 'x.y'"}));
}

TEST(ReadVtk, VersionOutsideThreeToFivePointOneIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "Version 3.0", "Version 2.0"),
                        {"line 1:", "unsupported version 2.0; expected 3.0 to 5.1"}));
  EXPECT_TRUE(
      FailsWith(with(ascii_lines(), "Version 3.0", "Version 6.0"), {"line 1:", "unsupported version 6.0"}));
}

TEST(ReadVtk, MissingTitleLineIsRejected) {
  EXPECT_TRUE(FailsWith("# vtk DataFile Version 3.0\n", {"line 2:", "expected a title line, found the end"}));
}

TEST(ReadVtk, FormatOtherThanAsciiOrBinaryIsRejected) {
  EXPECT_TRUE(
      FailsWith(with(ascii_lines(), "ASCII", "ASCI"), {"line 3:", "expected ASCII or BINARY, found 'ASCI'"}));
  EXPECT_TRUE(FailsWith("# vtk DataFile Version 3.0\ntitle\n",
                        {"line 3:", "expected ASCII or BINARY, found the end"}));
}

TEST(ReadVtk, MissingDatasetKeywordIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "DATASET POLYDATA", "POINTS POLYDATA"),
                        {"line 4:", "expected DATASET, found 'POINTS'"}));
}

TEST(ReadVtk, UnknownDatasetTypeIsRejected) {
  EXPECT_TRUE(
      FailsWith(with(ascii_lines(), "DATASET POLYDATA", "DATASET STRUCTURED_POINTS"),
                {"line 4:", "unknown dataset type 'STRUCTURED_POINTS'", "POLYDATA or UNSTRUCTURED_GRID"}));
}

TEST(ReadVtk, UnknownKeywordNamesTheLine) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "POINT_DATA 3\n", "GARBAGE 3\nPOINT_DATA 3\n"),
                        {"line 10:", "unknown keyword 'GARBAGE'"}));
}

TEST(ReadVtk, UnknownKeywordInBinaryNamesTheByteOffset) {
  const BinaryFixture f = binary_lines();
  const std::size_t at = f.bytes.find("CELL_DATA");
  EXPECT_TRUE(FailsWith(with(f.bytes, "CELL_DATA", "CELL_DATUM"),
                        {"byte " + std::to_string(at) + ":", "unknown keyword 'CELL_DATUM'"}));
}

TEST(ReadVtk, WrongBinaryCountLandsOnRawBytesAndIsReportedAsUnknownKeyword) {
  // Two points fewer than written: the reader stops inside the coordinates and shows them escaped.
  const BinaryFixture f = binary_lines();
  EXPECT_TRUE(FailsWith(with(f.bytes, "POINTS 3 float", "POINTS 1 float"), {"byte ", "unknown keyword '"}));
}

TEST(ReadVtk, PolygonsAndTriangleStripsAreNotACenterline) {
  const std::string polygons = with(ascii_lines(), "LINES 1 4", "POLYGONS 1 4");
  EXPECT_TRUE(FailsWith(polygons, {"line 8:", "POLYGONS describe a surface, not a centerline"}));
  const std::string strips = with(ascii_lines(), "LINES 1 4", "TRIANGLE_STRIPS 1 4");
  EXPECT_TRUE(FailsWith(strips, {"line 8:", "TRIANGLE_STRIPS describe a surface"}));
}

TEST(ReadVtk, LinesInAnUnstructuredGridAreAnUnknownKeyword) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "DATASET POLYDATA", "DATASET UNSTRUCTURED_GRID"),
                        {"line 8:", "unknown keyword 'LINES' in UNSTRUCTURED_GRID"}));
}

TEST(ReadVtk, RepeatedSectionIsRejected) {
  EXPECT_TRUE(FailsWith(ascii_lines() + "POINTS 1 float\n0 0 0\n", {"line 14:", "a second POINTS section"}));
  EXPECT_TRUE(FailsWith(ascii_lines() + "LINES 1 3\n2 0 1\n", {"line 14:", "a second LINES section"}));
}

TEST(ReadVtk, MissingPointsOrLinesIsRejected) {
  const std::string no_points = header() + "LINES 1 3\n2 0 1\n";
  EXPECT_TRUE(FailsWith(no_points, {"no POINTS section"}));
  const std::string no_lines = header() + "POINTS 1 float\n0 0 0\n";
  EXPECT_TRUE(FailsWith(no_lines, {"no LINES section"}));
  const std::string no_cells = header("3.0", "ASCII", "UNSTRUCTURED_GRID") + "POINTS 1 float\n0 0 0\n";
  EXPECT_TRUE(FailsWith(no_cells, {"no CELLS section"}));
}

TEST(ReadVtk, CellsWithoutCellTypesAreRejected) {
  const std::string text = with(ascii_grid(), "CELL_TYPES 3\n1\n3\n4\n", "");
  EXPECT_TRUE(FailsWith(text, {"CELLS without CELL_TYPES"}));
}

// ---------------------------------------------------------------------------------------------------------
// Errors: counts and data

TEST(ReadVtk, NegativeCountIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "POINTS 3 float", "POINTS -3 float"),
                        {"line 5:", "the number of points -3 is negative"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "LINES 1 4", "LINES 1 -4"), {"line 8:", "is negative"}));
}

TEST(ReadVtk, GarbledCountNamesTheLine) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "POINTS 3 float", "POINTS three float"),
                        {"line 5:", "expected an integer for the number of points, found 'three'"}));
}

TEST(ReadVtk, AbsurdAsciiCountIsRejectedBeforeAllocating) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "POINTS 3 float", "POINTS 1000000000 float"),
                        {"line 5:", "cannot fit in the"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "LINES 1 4", "LINES 1 4000000000000000000"),
                        {"line 8:", "cannot fit in the"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "POINTS 3 float", "POINTS 3000000000 float"),
                        {"line 5:", "more than a centerline can index"}));
}

TEST(ReadVtk, AbsurdBinaryCountIsRejectedBeforeAllocating) {
  const BinaryFixture f = binary_lines();
  const std::string points = with(f.bytes, "POINTS 3 float", "POINTS 2000000000 double");
  EXPECT_TRUE(
      FailsWith(points, {"byte " + std::to_string(data_after(points, "POINTS 2000000000 double\n")) + ":",
                         "truncated point coordinate: 6000000000 values of 8 bytes"}));
  const std::string lines = with(f.bytes, "LINES 2 6", "LINES 2 4000000000000000000");
  EXPECT_TRUE(
      FailsWith(lines, {"byte " + std::to_string(data_after(lines, "LINES 2 4000000000000000000\n")) + ":",
                        "truncated LINES cell list"}));
  // tuples x components overflows 64 bits.
  EXPECT_TRUE(
      FailsWith(with(f.bytes, "radius 1 2 float", "radius 9000000000000000000 2 float"), {"truncated"}));
}

// Every count the reader sizes something by (points, cells, cell list, offsets, connectivity, cell types,
// point and cell data, FIELD arrays and their tuples and components, lookup tables), set to hundreds of
// millions in a file of a few hundred bytes: an InputError, and no allocation of more than a few kB.
TEST(ReadVtk, NoCountIsAllocatedBeforeTheBytesThatHoldItAreChecked) {
  const std::string binary = binary_lines().bytes, grid = binary_grid().bytes;
  const std::vector<std::string> files = {
      with(ascii_lines(), "POINTS 3 float", "POINTS 300000000 float"),
      with(ascii_lines(), "LINES 1 4", "LINES 100000000 4"),
      with(ascii_lines(), "LINES 1 4", "LINES 1 400000000"),
      with(ascii_lines(), "POINT_DATA 3", "POINT_DATA 300000000"),
      ascii_lines() + "LOOKUP_TABLE big 100000000\n",
      with(ascii_offsets(), "LINES 3 5", "LINES 300000000 5"),
      with(ascii_offsets(), "LINES 3 5", "LINES 3 500000000"),
      with(with(ascii_offsets(), "CELL_DATA 2", "CELL_DATA 200000000"), "radius 1 2", "radius 1 200000000"),
      with(ascii_offsets(), "radius 1 2", "radius 100000000 2"),
      with(ascii_offsets(), "FIELD FieldData 1", "FIELD FieldData 100000000"),
      with(ascii_grid(), "CELLS 3 9", "CELLS 3 900000000"),
      with(ascii_grid(), "CELL_TYPES 3", "CELL_TYPES 300000000"),
      with(binary, "POINTS 3 float", "POINTS 300000000 float"),
      with(binary, "LINES 2 6", "LINES 2 600000000"),
      with(binary, "radius 1 2 float", "radius 1 200000000 float"),
      with(grid, "CELLS 3 4", "CELLS 300000000 4"),
      with(grid, "CELLS 3 4", "CELLS 3 400000000"),
      with(grid, "CELL_TYPES 2", "CELL_TYPES 200000000"),
      with(grid, "POINT_DATA 3", "POINT_DATA 300000000"),
  };
  for (const std::string& file : files) {
    SCOPED_TRACE(file.substr(0, 200));
    LargestAllocation largest;
    EXPECT_THROW(parse(file), InputError);
    EXPECT_LT(largest.bytes(), 4096u);
  }
}

TEST(ReadVtk, TruncatedAsciiPointsNameTheLineWhereTheFileEnds) {
  const std::string text =
      header() + "POINTS 3 double\n0.000000000 0.000000000 0.000000000\n1.000000 0.0000 0.0000\n";
  EXPECT_TRUE(FailsWith(text, {"line 7:", "point coordinate: the file ends after 6 of 9 values"}));
}

TEST(ReadVtk, AsciiPointsCutShortByAKeywordNameThatLine) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "POINTS 3 float", "POINTS 4 float"),
                        {"line 8:", "expected a number for point coordinate, found 'LINES'"}));
}

TEST(ReadVtk, TruncatedBinaryPointsNameTheByteOffset) {
  const BinaryFixture f = binary_lines();
  const std::string text = f.bytes.substr(0, f.points_at + 20);
  EXPECT_TRUE(FailsWith(text, {"byte " + std::to_string(f.points_at) + ":", "truncated point coordinate",
                               "9 values of 4 bytes", "20 bytes left"}));
}

TEST(ReadVtk, TruncatedBinaryCellsNameTheByteOffset) {
  const BinaryFixture f = binary_lines();
  EXPECT_TRUE(FailsWith(f.bytes.substr(0, f.cells_at + 10),
                        {"byte " + std::to_string(f.cells_at) + ":", "truncated LINES cell list"}));
  const BinaryFixture g = binary_grid();
  EXPECT_TRUE(FailsWith(g.bytes.substr(0, g.cells_at + 23),
                        {"byte " + std::to_string(g.cells_at) + ":", "truncated CELLS OFFSETS"}));
}

TEST(ReadVtk, TruncatedBinaryRadiusNamesTheByteOffset) {
  const BinaryFixture f = binary_lines();
  EXPECT_TRUE(FailsWith(f.bytes.substr(0, f.radius_at + 7),
                        {"byte " + std::to_string(f.radius_at) + ":", "truncated array 'radius'"}));
}

TEST(ReadVtk, LegacyCellLengthRunningPastTheListIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "LINES 1 4", "LINES 1 3"),
                        {"line 9:", "LINES cell 0 has 3 points, but the list has 2 values left"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "3 0 1 2", "-3 0 1 2"), {"line 9:", "has -3 points"}));
}

TEST(ReadVtk, LegacyListSizeDisagreeingWithCellLengthsIsRejected) {
  const BinaryFixture f = binary_lines();
  std::string text = with(f.bytes, "LINES 2 6", "LINES 1 6");
  EXPECT_TRUE(FailsWith(text, {"byte " + std::to_string(f.cells_at - 10) + ":",
                               "LINES says its list has 6 values, but its 1 cells use 3"}));
  text = with(f.bytes, "LINES 2 6", "LINES 3 6");
  EXPECT_TRUE(FailsWith(text, {"LINES: the list of 6 values ends inside cell 2 of 3"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "LINES 1 4", "LINES 5 4"),
                        {"line 8:", "5 cells cannot fit in a list of 4 values"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "LINES 1 4", "LINES 1 5"),
                        {"line 8:", "LINES says its list has 5 values, but its 1 cells use 4"}));
}

TEST(ReadVtk, OffsetsMustStartAtZero) {
  EXPECT_TRUE(FailsWith(with(ascii_offsets(), "0 3 5\n", "1 3 5\n"),
                        {"line 9:", "LINES OFFSETS must start at 0, found 1"}));
}

TEST(ReadVtk, OffsetsMustNotDecrease) {
  EXPECT_TRUE(FailsWith(with(ascii_offsets(), "0 3 5\n", "0 3\n2\n"),
                        {"line 10:", "must not decrease: 2 follows 3"}));
}

TEST(ReadVtk, OffsetsPastTheEndOfConnectivityAreRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_offsets(), "0 3 5\n", "0 3 6\n"),
                        {"line 9:", "offset 6 is past the end of CONNECTIVITY (5 values)"}));
}

TEST(ReadVtk, OffsetsEndingBeforeConnectivityEndsAreRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_offsets(), "0 3 5\n", "0 2 4\n"),
                        {"line 8:", "LINES OFFSETS end at 4, but CONNECTIVITY has 5 values"}));
}

TEST(ReadVtk, Version5CellsWithoutOffsetsBlockAreRejected) {
  const std::string text = with(ascii_offsets(), "OFFSETS vtktypeint64\n0 3 5\n", "");
  EXPECT_TRUE(FailsWith(text, {"line 8:", "expected OFFSETS, found 'CONNECTIVITY'"}));
  EXPECT_TRUE(FailsWith(with(ascii_offsets(), "CONNECTIVITY vtktypeint64", "CONNECT vtktypeint64"),
                        {"line 10:", "expected CONNECTIVITY, found 'CONNECT'"}));
}

TEST(ReadVtk, OffsetsOfARealTypeAreRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_offsets(), "OFFSETS vtktypeint64", "OFFSETS float"),
                        {"line 8:", "LINES OFFSETS must have an integer type, found 'float'"}));
}

TEST(ReadVtk, UnsignedIndexBeyondInt64IsRejected) {
  const BinaryFixture g = binary_grid();
  std::string text = with(g.bytes, "CONNECTIVITY vtktypeint64", "CONNECTIVITY vtktypeuint64");
  const std::size_t ids_at = data_after(text, "CONNECTIVITY vtktypeuint64\n");
  text.replace(ids_at + 8, 8, std::string(8, '\xff'));
  EXPECT_TRUE(FailsWith(
      text, {"byte " + std::to_string(ids_at + 8) + ":", "value 18446744073709551615 is out of range"}));
}

TEST(ReadVtk, CellTypesCountDisagreeingWithCellsIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_grid(), "CELL_TYPES 3\n1\n3\n4\n", "CELL_TYPES 2\n3\n4\n"),
                        {"line 11:", "CELL_TYPES has 2 entries for 3 CELLS"}));
}

TEST(ReadVtk, UnsupportedCellTypeNamesTheCellAndType) {
  EXPECT_TRUE(FailsWith(with(ascii_grid(), "1\n3\n4\n", "1\n3\n5\n"),
                        {"line 14:", "cell 2 has type 5", "lines (3), poly-lines (4)"}));
  const BinaryFixture g = binary_grid();
  const std::size_t types_at = data_after(g.bytes, "CELL_TYPES 2\n");
  std::string text = g.bytes;
  text[types_at + 7] = 10;  // second cell: tetrahedron
  EXPECT_TRUE(FailsWith(text, {"byte " + std::to_string(types_at + 4) + ":", "cell 1 has type 10"}));
}

TEST(ReadVtk, PointDataCountDisagreeingWithPointsIsRejected) {
  const std::string text =
      with(with(ascii_lines(), "POINT_DATA 3", "POINT_DATA 4"), "0.5 0.25", "0.5 0.5 0.25");
  EXPECT_TRUE(FailsWith(text, {"line 10:", "POINT_DATA has 4 values for 3 points"}));
}

TEST(ReadVtk, CellDataCountDisagreeingWithCellsIsRejected) {
  const std::string text =
      with(with(ascii_offsets(), "CELL_DATA 2", "CELL_DATA 3"), "radius 1 2", "radius 1 3");
  EXPECT_TRUE(FailsWith(with(text, "1.5 2.5", "1 2 3"), {"line 12:", "CELL_DATA has 3 values for 2 cells"}));
}

TEST(ReadVtk, FieldArrayTupleCountDisagreeingWithItsSectionIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_offsets(), "radius 1 2 double", "radius 1 3 double"),
                        {"line 14:", "FIELD array 'radius' has 3 tuples, but CELL_DATA has 2"}));
}

TEST(ReadVtk, PointIndexOutOfRangeNamesTheLine) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "3 0 1 2", "3 0 1\n7"),
                        {"line 10:", "LINES refers to point 7, but there are 3 points"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "3 0 1 2", "3 0 -1 2"), {"line 9:", "refers to point -1"}));
  EXPECT_TRUE(FailsWith(with(ascii_grid(), "3 1 2 3", "3 1 2 4"), {"line 10:", "CELLS refers to point 4"}));
}

TEST(ReadVtk, PointIndexOutOfRangeNamesTheByteOffset) {
  const BinaryFixture f = binary_lines();
  std::string text = f.bytes;
  text[f.cells_at + 23] = 9;  // last id of the second cell
  EXPECT_TRUE(FailsWith(text, {"byte " + std::to_string(f.cells_at + 20) + ":", "LINES refers to point 9"}));
}

TEST(ReadVtk, NonIntegerPointIndexIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "3 0 1 2", "3 0 1.5 2"),
                        {"line 9:", "expected an integer for LINES cell list, found '1.5'"}));
}

TEST(ReadVtk, NonFiniteCoordinateNamesTheLine) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "2 0 0\n", "2 nan 0\n"),
                        {"line 7:", "point coordinate is not a finite number"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "2 0 0\n", "2 0 inf\n"), {"line 7:", "not a finite number"}));
}

TEST(ReadVtk, NonFiniteCoordinateNamesTheByteOffset) {
  const BinaryFixture f = binary_lines();
  std::string text = f.bytes;
  const float infinity = std::numeric_limits<float>::infinity();
  Bytes value;
  value.be<float>({infinity});
  text.replace(f.points_at + 16, 4, value.str());
  EXPECT_TRUE(FailsWith(
      text, {"byte " + std::to_string(f.points_at + 16) + ":", "point coordinate is not a finite"}));
}

TEST(ReadVtk, NonFiniteRadiusIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "0.5 0.25 0.125", "0.5 NaN 0.125"),
                        {"line 13:", "array 'radius' is not a finite number"}));
  const BinaryFixture f = binary_lines();
  std::string text = f.bytes;
  Bytes value;
  value.be<float>({std::numeric_limits<float>::quiet_NaN()});
  text.replace(f.radius_at + 4, 4, value.str());
  EXPECT_TRUE(
      FailsWith(text, {"byte " + std::to_string(f.radius_at + 4) + ":", "array 'radius' is not a finite"}));
}

TEST(ReadVtk, NanInAnArrayThatIsNotTheRadiusIsIgnored) {
  const std::string text = ascii_lines() + "FIELD FieldData 1\nflow 1 3 double\nnan inf -inf\n";
  EXPECT_EQ(parse(text).radius, (std::vector<double>{0.5, 0.25, 0.125}));
}

TEST(ReadVtk, UnknownDataTypeIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "POINTS 3 float", "POINTS 3 quaternion"),
                        {"line 5:", "unknown data type 'quaternion'"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "SCALARS radius float", "SCALARS radius string"),
                        {"line 11:", "unknown data type 'string'"}));
}

TEST(ReadVtk, BitArraysAreRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "SCALARS radius float", "SCALARS radius bit"),
                        {"line 11:", "bit arrays are not supported"}));
}

TEST(ReadVtk, ScalarsWithoutLookupTableAreRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "LOOKUP_TABLE default\n", ""),
                        {"line 12:", "expected an integer for the number of components, found '0.5'"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "LOOKUP_TABLE default\n", "1 TABLE default\n"),
                        {"line 12:", "expected LOOKUP_TABLE, found 'TABLE'"}));
}

TEST(ReadVtk, AttributeBlockOutsidePointOrCellDataIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "POINT_DATA 3\n", ""),
                        {"line 10:", "SCALARS outside POINT_DATA or CELL_DATA"}));
  EXPECT_TRUE(FailsWith(with(ascii_lines(), "POINT_DATA 3\n", "VECTORS v float\n"),
                        {"line 10:", "VECTORS outside POINT_DATA or CELL_DATA"}));
}

TEST(ReadVtk, MultiComponentRadiusIsRejected) {
  const std::string text = with(with(ascii_lines(), "SCALARS radius float", "SCALARS radius float 2"),
                                "0.5 0.25 0.125", "1 1 2 2 3 3");
  EXPECT_TRUE(FailsWith(text, {"line 11:", "array 'radius' has 2 components; a radius has 1"}));
  const std::string cells =
      with(with(ascii_offsets(), "radius 1 2 double", "radius 2 2 double"), "1.5 2.5", "1 1 2 2");
  EXPECT_TRUE(FailsWith(cells, {"line 14:", "has 2 components"}));
}

TEST(ReadVtk, ZeroComponentArrayIsRejected) {
  EXPECT_TRUE(FailsWith(with(ascii_offsets(), "radius 1 2 double", "radius 0 2 double"),
                        {"line 14:", "array 'radius' has 0 components"}));
}

TEST(ReadVtk, MissingRadiusArrayListsTheArraysFound) {
  const std::string text = with(ascii_lines(), "SCALARS radius float", "SCALARS flow float") +
                           "FIELD FieldData 1\npressure 1 3 float\n1 2 3\n";
  EXPECT_TRUE(FailsWith(text, {"no radius array; found: flow, pressure"}));
  EXPECT_TRUE(FailsWith(ascii_lines(), {"no array named 'thickness'; found: radius"}, "thickness"));
}

// ---------------------------------------------------------------------------------------------------------
// Damaged input: whatever the damage, an InputError or a usable result, never a crash or a read past the end.

void expect_clean_outcome(const std::string& bytes) {
  try {
    const CenterlineData data = parse(bytes);
    for (const Edge& e : data.edges)
      for (int32_t v : e) ASSERT_TRUE(v >= 0 && static_cast<std::size_t>(v) < data.points.size());
    ASSERT_TRUE(data.radius.size() == data.points.size() || data.edge_radius.size() == data.edges.size());
  } catch (const InputError&) {
  }
}

TEST(ReadVtk, EveryTruncationFailsCleanly) {
  for (const std::string& full : {binary_lines().bytes, binary_grid().bytes, ascii_grid(), ascii_offsets()})
    for (std::size_t n = 0; n < full.size(); ++n) {
      SCOPED_TRACE(n);
      expect_clean_outcome(full.substr(0, n));
    }
}

TEST(ReadVtk, EveryCorruptedByteFailsCleanly) {
  for (const std::string& full : {binary_lines().bytes, binary_grid().bytes, ascii_grid(), ascii_offsets()})
    for (std::size_t i = 0; i < full.size(); ++i)
      for (char c : {'\0', '\xff', '\x7f', '9', '-', '\n', ' '}) {
        std::string damaged = full;
        damaged[i] = c;
        SCOPED_TRACE(i);
        expect_clean_outcome(damaged);
      }
}

// ---------------------------------------------------------------------------------------------------------
// Writer

/// A file in a scratch folder, removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("vesselmesh_test_read_vtk_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    path_ = (dir / name).string();
  }
  ~TempFile() { std::filesystem::remove(path_); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// Values that only survive a round trip when every digit is kept.
CenterlineData awkward_centerline(bool per_edge) {
  CenterlineData data;
  data.points = {Vec3(0.1, 1.0 / 3.0, -2.5e-300), Vec3(123456.789e10, -0.0, 5e-324), Vec3(1, 2, 3),
                 Vec3(std::nextafter(1.0, 2.0), 1e308, -7.0 / 9.0)};
  data.edges = {Edge{0, 1}, Edge{1, 2}, Edge{1, 3}};
  if (per_edge)
    data.edge_radius = {0.1 + 0.2, 1.0 / 7.0, 3e10};
  else
    data.radius = {0.1, 1.0 / 3.0, 2.5e-7, 123456.789};
  return data;
}

void expect_round_trip(bool binary, bool per_edge) {
  const CenterlineData original = awkward_centerline(per_edge);
  const TempFile file(std::string(binary ? "binary" : "ascii") + (per_edge ? "_edge" : "_point") + ".vtk");
  write_centerline_vtk(original, file.path(), binary);
  const CenterlineData back = parse_vtk(read_file(file.path()), file.path(), {});
  ASSERT_EQ(back.points.size(), original.points.size());
  for (std::size_t i = 0; i < original.points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(back.points[i][k], original.points[i][k]) << "point " << i << "." << k;
  EXPECT_EQ(back.edges, original.edges);
  EXPECT_EQ(back.radius, original.radius);
  EXPECT_EQ(back.edge_radius, original.edge_radius);
}

TEST(WriteVtk, AsciiRoundTripOfPointRadiusKeepsEveryDigit) { expect_round_trip(false, false); }
TEST(WriteVtk, AsciiRoundTripOfEdgeRadiusKeepsEveryDigit) { expect_round_trip(false, true); }
TEST(WriteVtk, BinaryRoundTripOfPointRadiusIsExact) { expect_round_trip(true, false); }
TEST(WriteVtk, BinaryRoundTripOfEdgeRadiusIsExact) { expect_round_trip(true, true); }

TEST(WriteVtk, AsciiOutputIsVersion42PolyDataWithRadiusScalars) {
  const TempFile file("layout.vtk");
  write_centerline_vtk(awkward_centerline(true), file.path(), false);
  const std::string text = read_file(file.path());
  EXPECT_EQ(text.rfind("# vtk DataFile Version 4.2\n", 0), 0u);
  EXPECT_NE(text.find("\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n0.10000000000000001 "), std::string::npos);
  EXPECT_NE(text.find("\nLINES 3 9\n2 0 1\n2 1 2\n2 1 3\n"), std::string::npos);
  EXPECT_NE(text.find("\nCELL_DATA 3\nSCALARS radius double 1\nLOOKUP_TABLE default\n"), std::string::npos);
  EXPECT_EQ(text.find("POINT_DATA"), std::string::npos);
}

TEST(WriteVtk, BinaryOutputIsBigEndian) {
  CenterlineData data;
  data.points = {Vec3(1, 0, 0), Vec3(2, 0, 0)};
  data.edges = {Edge{0, 1}};
  data.radius = {1, 1};
  const TempFile file("endian.vtk");
  write_centerline_vtk(data, file.path(), true);
  const std::string bytes = read_file(file.path());
  const std::size_t at = data_after(bytes, "POINTS 2 double\n");
  EXPECT_EQ(bytes.substr(at, 8), std::string("\x3f\xf0\0\0\0\0\0\0", 8));  // 1.0
  const std::size_t cells_at = data_after(bytes, "\nLINES 1 3\n");
  EXPECT_EQ(bytes.substr(cells_at, 12), std::string("\0\0\0\x02\0\0\0\0\0\0\0\x01", 12));
}

TEST(WriteVtk, MillionPointsRoundTripInBothFormats) {
  constexpr int32_t kPoints = 1000000;
  CenterlineData data;
  data.points.reserve(kPoints);
  for (int32_t i = 0; i < kPoints; ++i) data.points.emplace_back(i * 1e-3, std::sin(i * 1e-2), 1.0 / (i + 1));
  for (int32_t i = 0; i + 1 < kPoints; ++i) data.edges.push_back({i, i + 1});
  data.radius.assign(kPoints, 0.25);
  for (bool binary : {true, false}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const TempFile file(binary ? "million_binary.vtk" : "million_ascii.vtk");
    write_centerline_vtk(data, file.path(), binary);
    const CenterlineData back = parse_vtk(read_file(file.path()), file.path(), {});
    ASSERT_EQ(back.points.size(), data.points.size());
    EXPECT_EQ(back.edges.size(), data.edges.size());
    EXPECT_EQ(back.points[777777], data.points[777777]);
    EXPECT_EQ(back.radius.back(), 0.25);
  }
}

TEST(WriteVtk, UnwritablePathIsReportedWithThePath) {
  const std::string path = "/nonexistent-folder/out.vtk";
  try {
    write_centerline_vtk(awkward_centerline(false), path, false);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------------------
// Real data sets

std::pair<double, double> range(const std::vector<double>& values) {
  const auto [min, max] = std::minmax_element(values.begin(), values.end());
  return {*min, *max};
}

TEST(ReadVtkRealData, HumanBrainArteries51BinaryUnstructuredGrid) {
  SHARED_DATA_OR_SKIP(path, "human-brain-arteries/arteries_smooth.vtk");
  const CenterlineData data = read_centerline(path);
  EXPECT_EQ(data.points.size(), 12709u);
  EXPECT_EQ(data.edges.size(), 12708u);
  ASSERT_EQ(data.radius.size(), 12709u);
  const auto [min, max] = range(data.radius);
  EXPECT_NEAR(min, 0.000491071, 0.000491071 * 1e-5);
  EXPECT_NEAR(max, 0.00139568, 0.00139568 * 1e-5);
}

TEST(ReadVtkRealData, PenetratingArtery30AsciiCellFieldRadius) {
  SHARED_DATA_OR_SKIP(path, "vascpy-mouse-vessels/penetrating_artery.vtk");
  const CenterlineData data = read_centerline(path);
  EXPECT_EQ(data.points.size(), 1274u);
  EXPECT_EQ(data.edges.size(), 1273u);
  ASSERT_EQ(data.edge_radius.size(), 1273u);
  const auto [min, max] = range(data.edge_radius);
  EXPECT_NEAR(min, 10.4489, 10.4489 * 1e-5);
  EXPECT_NEAR(max, 14.0789, 14.0789 * 1e-5);
}

TEST(ReadVtkRealData, SmallerVasculature30BinaryCellFieldRadius) {
  SHARED_DATA_OR_SKIP(path, "vascpy-mouse-vessels/test_smaller_vasculature.vtk");
  const CenterlineData data = read_centerline(path);
  EXPECT_EQ(data.points.size(), 912u);
  EXPECT_EQ(data.edges.size(), 897u);
  ASSERT_EQ(data.edge_radius.size(), 897u);
  const auto [min, max] = range(data.edge_radius);
  EXPECT_NEAR(min, 0.764439, 0.764439 * 1e-5);
  EXPECT_NEAR(max, 3.78865, 3.78865 * 1e-5);
}

TEST(ReadVtkRealData, SecombCortex42AsciiCellScalars) {
  SHARED_DATA_OR_SKIP(path, "secomb-rat-cortex-50/network.vtk");
  const CenterlineData data = read_centerline(path);
  EXPECT_EQ(data.points.size(), 49u);
  EXPECT_EQ(data.edges.size(), 50u);
  EXPECT_EQ(data.edge_radius.size(), 50u);
}

TEST(ReadVtkRealData, SecombMesentery42AsciiCellScalars) {
  SHARED_DATA_OR_SKIP(path, "secomb-rat-mesentery/network.vtk");
  const CenterlineData data = read_centerline(path);
  EXPECT_EQ(data.points.size(), 972u);
  EXPECT_EQ(data.edges.size(), 1130u);
  EXPECT_EQ(data.edge_radius.size(), 1130u);
}

}  // namespace
}  // namespace vesselmesh
