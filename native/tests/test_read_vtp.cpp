#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "allocation_probe.hpp"
#include "test_support.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/read/read.hpp"

namespace vesselmesh {
namespace {

const std::string kSource = "fixture.vtp";

// ---------------------------------------------------------------------------------------------------
// Fixture writer: VTK XML PolyData in every encoding, laid out as VTK writes it.

struct Array {
  std::string name;
  std::string type;
  int components;
  std::vector<double> values;
};

struct Piece {
  Array points{"Points", "Float32", 3, {}};
  Array connectivity{"connectivity", "Int64", 1, {}};
  Array offsets{"offsets", "Int64", 1, {}};
  std::vector<Array> point_data;
  std::vector<Array> cell_data;
  int verts = 0;  ///< vertex cells, one per point from 0; cell data lists them before the lines
};

enum class Format { kAscii, kBinary, kAppended };

struct Encoding {
  const char* label;
  Format format = Format::kAscii;
  bool zlib = false;
  bool raw = false;  ///< appended data as raw bytes instead of base64
  bool uint64_header = false;
  bool big_endian = false;
  std::size_t block_size = 32768;  ///< uncompressed bytes per zlib block
};

const Encoding kAscii{"ascii"};
const Encoding kBinary{"binary", Format::kBinary};
const Encoding kBinaryZlib{"binary zlib", Format::kBinary, true};
const Encoding kAppendedRawZlib{"appended raw zlib", Format::kAppended, true, true};
const Encoding kBinaryZlibBigEndian64{
    "binary zlib BigEndian UInt64 header", Format::kBinary, true, false, true, true};
const Encoding kAppendedRawBigEndian64{
    "appended raw BigEndian UInt64 header", Format::kAppended, false, true, true, true};

const std::vector<Encoding> kEncodings = {
    kAscii,
    kBinary,
    kBinaryZlib,
    {"binary zlib UInt64 header", Format::kBinary, true, false, true},
    {"binary BigEndian", Format::kBinary, false, false, false, true},
    kBinaryZlibBigEndian64,
    {"binary zlib 16-byte blocks (partial last block)", Format::kBinary, true, false, false, false, 16},
    {"binary zlib 8-byte blocks (full last block)", Format::kBinary, true, false, false, false, 8},
    {"appended base64", Format::kAppended},
    {"appended base64 zlib", Format::kAppended, true},
    {"appended base64 UInt64 header", Format::kAppended, false, false, true},
    {"appended raw", Format::kAppended, false, true},
    kAppendedRawZlib,
    kAppendedRawBigEndian64,
    {"appended raw zlib 16-byte blocks BigEndian", Format::kAppended, true, true, false, true, 16},
};

std::size_t type_size(const std::string& type) {
  const std::string bits = type.substr(type.find_first_of("0123456789"));
  return std::stoul(bits) / 8;
}

std::string word_bytes(uint64_t value, std::size_t size, bool big_endian) {
  std::string out(size, '\0');
  for (std::size_t k = 0; k < size; ++k)
    out[big_endian ? size - 1 - k : k] = static_cast<char>(value >> (8 * k));
  return out;
}

/// `values` as binary `type` in the chosen byte order.
std::string pack(const std::string& type, const std::vector<double>& values, bool big_endian) {
  std::string out;
  for (double v : values) {
    uint64_t bits;
    if (type == "Float32") {
      const float f = static_cast<float>(v);
      uint32_t narrow;
      std::memcpy(&narrow, &f, sizeof narrow);
      bits = narrow;
    } else if (type == "Float64") {
      std::memcpy(&bits, &v, sizeof bits);
    } else {
      bits = static_cast<uint64_t>(static_cast<int64_t>(v));
    }
    out += word_bytes(bits, type_size(type), big_endian);
  }
  return out;
}

std::string header_words(const std::vector<uint64_t>& words, const Encoding& e) {
  std::string out;
  for (uint64_t w : words) out += word_bytes(w, e.uint64_header ? 8 : 4, e.big_endian);
  return out;
}

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t group = 0;
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    for (std::size_t k = 0; k < 3; ++k)
      group = group << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? digits[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::string deflate(const std::string& bytes) {
  uLongf size = compressBound(static_cast<uLong>(bytes.size()));
  std::string out(size, '\0');
  EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(&out[0]), &size, reinterpret_cast<const Bytef*>(bytes.data()),
                      static_cast<uLong>(bytes.size()), 6),
            Z_OK);
  out.resize(size);
  return out;
}

/// Data split into zlib blocks, with the compression header VTK writes before them.
struct Compressed {
  std::vector<uint64_t> header;  ///< blocks, block size, last block size (0: full), compressed sizes
  std::vector<std::string> blocks;
};

Compressed compress(const std::string& data, std::size_t block_size) {
  Compressed c;
  for (std::size_t at = 0; at < data.size(); at += block_size)
    c.blocks.push_back(deflate(data.substr(at, block_size)));
  c.header = {c.blocks.size(), block_size, data.size() % block_size};
  for (const std::string& block : c.blocks) c.header.push_back(block.size());
  return c;
}

/// Base64 text, except for raw appended data.
std::string encode(const std::string& bytes, const Encoding& e) {
  return e.format == Format::kAppended && e.raw ? bytes : base64(bytes);
}

std::string stored(const Compressed& c, const Encoding& e) {
  std::string blocks;
  for (const std::string& block : c.blocks) blocks += block;
  return encode(header_words(c.header, e), e) + encode(blocks, e);
}

/// An array's data as VTK stores it: [byte count][data] in one run, or compressed blocks.
std::string stored(const std::string& data, const Encoding& e) {
  if (e.zlib) return stored(compress(data, e.block_size), e);
  return encode(header_words({data.size()}, e) + data, e);
}

class Writer {
 public:
  explicit Writer(const Encoding& e) : e_(e) {}

  std::string file(const std::vector<Piece>& pieces) {
    std::string body;
    for (const Piece& p : pieces) body += piece(p);
    std::string out =
        std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"") +
        (e_.big_endian ? "BigEndian" : "LittleEndian") + "\" header_type=\"" +
        (e_.uint64_header ? "UInt64" : "UInt32") + "\"" +
        (e_.zlib ? " compressor=\"vtkZLibDataCompressor\"" : "") + ">\n  <PolyData>\n" + body +
        "  </PolyData>\n";
    if (!appended_.empty())
      out += std::string("  <AppendedData encoding=\"") + (e_.raw ? "raw" : "base64") + "\">\n   _" +
             appended_ + "\n  </AppendedData>\n";
    return out + "</VTKFile>\n";
  }

 private:
  std::string piece(const Piece& p) {
    const std::size_t points = p.points.values.size() / 3;
    std::string out = "    <Piece NumberOfPoints=\"" + std::to_string(points) + "\" NumberOfVerts=\"" +
                      std::to_string(p.verts) + "\" NumberOfLines=\"" +
                      std::to_string(p.offsets.values.size()) +
                      "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n      <PointData>\n";
    for (const Array& a : p.point_data) out += element(a);
    out += "      </PointData>\n      <CellData>\n";
    for (const Array& a : p.cell_data) out += element(a);
    out += "      </CellData>\n      <Points>\n";
    out += element(p.points);
    out += "      </Points>\n      <Verts>\n";
    Array vert_points{"connectivity", "Int64", 1, {}}, vert_ends{"offsets", "Int64", 1, {}};
    for (int v = 0; v < p.verts; ++v) {
      vert_points.values.push_back(v);
      vert_ends.values.push_back(v + 1);
    }
    // One element per statement: appended data must follow the order of the elements.
    out += element(vert_points);
    out += element(vert_ends);
    out += "      </Verts>\n      <Lines>\n";
    out += element(p.connectivity);
    out += element(p.offsets);
    return out + "      </Lines>\n    </Piece>\n";
  }

  std::string element(const Array& a) {
    static const char* formats[] = {"ascii", "binary", "appended"};
    std::string out = "        <DataArray type=\"" + a.type + "\" Name=\"" + a.name +
                      "\" NumberOfComponents=\"" + std::to_string(a.components) + "\" format=\"" +
                      formats[static_cast<int>(e_.format)] + "\"";
    const std::string data = pack(a.type, a.values, e_.big_endian);
    switch (e_.format) {
      case Format::kAscii: {
        out += ">\n";
        for (std::size_t i = 0; i < a.values.size(); ++i) {
          char number[32];
          std::snprintf(number, sizeof number, "%.17g", a.values[i]);
          out += (i % 6 == 0 ? "          " : " ") + std::string(number) + (i % 6 == 5 ? "\n" : "");
        }
        return out + "\n        </DataArray>\n";
      }
      case Format::kBinary:
        return out + ">\n          " + stored(data, e_) + "\n        </DataArray>\n";
      case Format::kAppended:
        out += " offset=\"" + std::to_string(appended_.size()) + "\"/>\n";
        appended_ += stored(data, e_);
        return out;
    }
    return out;
  }

  Encoding e_;
  std::string appended_;
};

/// Two poly-lines: 0-1-2-3 and 4-5, a point radius, and arrays the reader must ignore.
Piece sample() {
  Piece p;
  p.points.values = {0, 0, 0, 1, 0, 0, 2, 0.5, 0, 3, 1, 0.25, 0, 1, 0, 0, 2, -0.5};
  p.connectivity.values = {0, 1, 2, 3, 4, 5};
  p.offsets.values = {4, 6};
  p.point_data = {{"Radius", "Float64", 1, {1, 0.75, 0.5, 0.5, 0.25, 0.125}},
                  {"EdgeArray", "Int32", 2, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}}};
  p.cell_data = {{"GroupIds", "Int32", 1, {0, 1}}};
  return p;
}

CenterlineData sample_data() {
  CenterlineData d;
  d.points = {{0, 0, 0}, {1, 0, 0}, {2, 0.5, 0}, {3, 1, 0.25}, {0, 1, 0}, {0, 2, -0.5}};
  d.radius = {1, 0.75, 0.5, 0.5, 0.25, 0.125};
  d.edges = {{0, 1}, {1, 2}, {2, 3}, {4, 5}};
  return d;
}

std::string sample_file(const Encoding& e) { return Writer(e).file({sample()}); }

void expect_same(const CenterlineData& got, const CenterlineData& want) {
  ASSERT_EQ(got.points.size(), want.points.size());
  for (std::size_t i = 0; i < want.points.size(); ++i)
    EXPECT_EQ(got.points[i], want.points[i]) << "point " << i;
  EXPECT_EQ(got.radius, want.radius);
  EXPECT_EQ(got.edges, want.edges);
  EXPECT_EQ(got.edge_radius, want.edge_radius);
  EXPECT_TRUE(got.roots.empty());
}

CenterlineData parse(const std::string& text, const ReadOptions& options = {}) {
  return parse_vtp(text, kSource, options);
}

/// The message of the InputError that parsing `text` throws; a test failure when it does not throw.
std::string error_of(const std::string& text, const ReadOptions& options = {}) {
  try {
    parse(text, options);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "parse_vtp accepted:\n" << text;
  return "";
}

/// `message` starts with "fixture.vtp: <where>: " and contains `part`.
::testing::AssertionResult Says(const std::string& message, const std::string& where,
                                const std::string& part) {
  const std::string prefix = kSource + ": " + (where.empty() ? "" : where + ": ");
  if (message.rfind(prefix, 0) != 0)
    return ::testing::AssertionFailure() << "'" << message << "' lacks '" << prefix << "'";
  if (message.find(part) == std::string::npos)
    return ::testing::AssertionFailure() << "'" << message << "' lacks '" << part << "'";
  return ::testing::AssertionSuccess();
}

/// "byte N" for the first occurrence of `needle` at or after `from`.
std::string byte_of(const std::string& text, const std::string& needle, std::size_t from = 0) {
  const std::size_t at = text.find(needle, from);
  EXPECT_NE(at, std::string::npos) << "fixture lacks " << needle;
  return at_byte(at);
}

/// "byte N" for the first DataArray element after `after` whose attributes include `attribute`.
std::string array_at(const std::string& text, const std::string& attribute, const std::string& after = "") {
  const std::size_t at = text.find(attribute, text.find(after));
  EXPECT_NE(at, std::string::npos) << "fixture lacks " << attribute;
  return at_byte(text.rfind("<DataArray", at));
}

std::string line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "fixture lacks " << needle;
  return at_line(1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n')));
}

/// `text` with the first `from` after `after` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to,
                     const std::string& after = "") {
  const std::size_t at = text.find(from, text.find(after));
  EXPECT_NE(at, std::string::npos) << "fixture lacks " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// The sample in `e` (an inline binary encoding) with the stored text of its <Points> DataArray replaced.
std::string with_points_content(const std::string& content, const Encoding& e = kBinaryZlib) {
  const std::string text = sample_file(e);
  const std::size_t start = text.find('>', text.find("<DataArray", text.find("<Points>"))) + 1;
  const std::size_t end = text.find("</DataArray>", start);
  return text.substr(0, start) + content + text.substr(end);
}

/// The sample's points as little-endian Float32 bytes.
std::string sample_points_bytes() { return pack("Float32", sample().points.values, false); }

// ---------------------------------------------------------------------------------------------------
// Reading

TEST(ReadVtp, EveryEncodingGivesTheSameCenterline) {
  for (const Encoding& e : kEncodings) {
    SCOPED_TRACE(e.label);
    expect_same(parse(sample_file(e)), sample_data());
  }
}

TEST(ReadVtp, PolyLineOfKPointsGivesKMinusOneEdges) {
  Piece p = sample();
  p.points.values.insert(p.points.values.end(), {5, 5, 5});
  p.point_data[0].values.push_back(2);
  p.point_data[1].values.insert(p.point_data[1].values.end(), {13, 14});
  p.connectivity.values = {5, 4, 3, 2, 1, 6, 6, 0};  // a 5-point line, a lone point, a 2-point line
  p.offsets.values = {5, 6, 8};
  p.cell_data[0].values = {0, 1, 2};
  for (const Encoding& e : {kAscii, kAppendedRawZlib}) {
    SCOPED_TRACE(e.label);
    const CenterlineData d = parse(Writer(e).file({p}));
    EXPECT_EQ(d.edges, (std::vector<Edge>{{5, 4}, {4, 3}, {3, 2}, {2, 1}, {6, 0}}));
  }
}

TEST(ReadVtp, PiecesAreConcatenatedWithTheirPointIndicesOffset) {
  Piece second = sample();
  second.points.values = {9, 9, 9, 8, 8, 8, 7, 7, 7};
  second.point_data = {{"Radius", "Float64", 1, {3, 2, 1}}};
  second.connectivity.values = {2, 0, 1};
  second.offsets.values = {3};
  second.cell_data = {{"GroupIds", "Int32", 1, {4}}};
  CenterlineData want = sample_data();
  want.points.insert(want.points.end(), {{9, 9, 9}, {8, 8, 8}, {7, 7, 7}});
  want.radius.insert(want.radius.end(), {3, 2, 1});
  want.edges.insert(want.edges.end(), {{8, 6}, {6, 7}});
  for (const Encoding& e : kEncodings) {
    SCOPED_TRACE(e.label);
    expect_same(parse(Writer(e).file({sample(), Piece{}, second})), want);  // with an empty piece between
  }
}

TEST(ReadVtp, CellRadiusGivesEachEdgeItsLinesValueAfterTheVerts) {
  Piece p = sample();
  p.verts = 2;
  p.point_data.erase(p.point_data.begin());
  p.cell_data.push_back({"Radius", "Float32", 1, {9, 9, 1.5, 0.5}});  // two vertex cells, then the lines
  CenterlineData want = sample_data();
  want.radius.clear();
  want.edge_radius = {1.5, 1.5, 1.5, 0.5};
  for (const Encoding& e : kEncodings) {
    SCOPED_TRACE(e.label);
    expect_same(parse(Writer(e).file({p})), want);
  }
}

TEST(ReadVtp, DiameterArrayIsHalved) {
  Piece p = sample();
  p.point_data[0] = {"Diameter", "Float64", 1, {2, 1.5, 1, 1, 0.5, 0.25}};
  for (const Encoding& e : {kAscii, kBinaryZlib}) {
    SCOPED_TRACE(e.label);
    expect_same(parse(Writer(e).file({p})), sample_data());
  }
}

TEST(ReadVtp, RequestedArrayOverridesTheChoiceByName) {
  Piece p = sample();
  p.point_data.push_back({"Thickness", "Float32", 1, {4, 4, 4, 4, 4, 4}});
  ReadOptions options;
  options.radius_array = "Thickness";
  CenterlineData want = sample_data();
  want.radius.assign(6, 4.0);
  expect_same(parse(Writer(kAscii).file({p}), options), want);

  options.radius_array = "EdgeDiameter";  // a requested diameter is halved too
  p.cell_data.push_back({"EdgeDiameter", "UInt8", 1, {4, 2}});
  want.radius.clear();
  want.edge_radius = {2, 2, 2, 1};
  expect_same(parse(Writer(kAppendedRawZlib).file({p}), options), want);
}

TEST(ReadVtp, EveryNumericTypeIsRead) {
  const char* types[] = {"Int8",   "UInt8", "Int16",  "UInt16",  "Int32",
                         "UInt32", "Int64", "UInt64", "Float32", "Float64"};
  for (const char* type : types) {
    for (const Encoding& e : {kAscii, kBinaryZlibBigEndian64, kAppendedRawBigEndian64}) {
      SCOPED_TRACE(std::string(type) + ", " + e.label);
      Piece p = sample();
      p.point_data[0] = {"Radius", type, 1, {1, 2, 3, 4, 5, 6}};
      if (std::string(type).find("Float") == std::string::npos) {
        p.connectivity.type = type;
        p.offsets.type = type;
      } else {
        p.points.type = type;
      }
      CenterlineData want = sample_data();
      want.radius = {1, 2, 3, 4, 5, 6};
      expect_same(parse(Writer(e).file({p})), want);
    }
  }
}

TEST(ReadVtp, NegativeSignedValuesAreSignExtended) {
  Piece p = sample();
  p.points.type = "Int16";
  p.points.values = {-1, -2, -300, 1, 0, 0, 2, 0, 0, 3, 1, 0, 0, 1, 0, 0, 2, -32768};
  for (const Encoding& e : {kAscii, kBinaryZlibBigEndian64}) {
    SCOPED_TRACE(e.label);
    const CenterlineData d = parse(Writer(e).file({p}));
    EXPECT_EQ(d.points[0], Vec3(-1, -2, -300));
    EXPECT_EQ(d.points[5], Vec3(0, 2, -32768));
  }
}

TEST(ReadVtp, RawAppendedBytesThatLookLikeXmlAreData) {
  const std::string tricky("<\0>_</AppendedData></VTKFile>", 29);
  Array bytes{"Bytes", "UInt8", 1, {}};
  for (char c : tricky) bytes.values.push_back(static_cast<unsigned char>(c));
  Piece p = sample();
  p.points.values.resize(bytes.values.size() * 3, 0.0);
  p.point_data = {bytes, {"Radius", "Float64", 1, std::vector<double>(bytes.values.size(), 1.0)}};
  const std::string text = Writer({"appended raw", Format::kAppended, false, true}).file({p});
  ASSERT_NE(text.find(tricky), std::string::npos);
  const CenterlineData d = parse(text);
  EXPECT_EQ(d.points.size(), bytes.values.size());
  EXPECT_EQ(d.edges.size(), 4u);
}

TEST(ReadVtp, StripsAndPolysElementsAreIgnoredWhenTheirCountsAreZero) {
  // VTK writes <Strips> and <Polys> with arrays even when the piece has none of those cells.
  const std::string full = sample_file(kAscii);
  const std::size_t start = full.find("<Lines>") + 7;
  const std::string cells = full.substr(start, full.find("</Lines>") - start);
  const std::string text =
      replaced(full, "</Lines>", "</Lines>\n<Strips>" + cells + "</Strips><Polys>" + cells + "</Polys>");
  expect_same(parse(text), sample_data());
}

TEST(ReadVtp, ByteOrderMarkAndCrlfLineEndsAreAcceptedAndCounted) {
  std::string text = "\xEF\xBB\xBF";
  for (char c : sample_file(kAscii)) text += c == '\n' ? std::string("\r\n") : std::string(1, c);
  expect_same(parse(text), sample_data());
  const std::string bad = replaced(text, "1 0.25\r\n", "1 x\r\n");
  EXPECT_TRUE(
      Says(error_of(bad), line_of(bad, "1 x"), "expected a number for <Points> DataArray, found 'x'"));
  const std::string grid = replaced(text, "type=\"PolyData\"", "type=\"ImageData\"");
  EXPECT_TRUE(Says(error_of(grid), byte_of(grid, "<VTKFile"), "'ImageData'; expected PolyData"));
}

TEST(ReadVtp, ProjectFixtureOfTwoOverlappingLinesIsRead) {
  const CenterlineData d = read_centerline(test::test_data("two_lines.vtp"));
  EXPECT_EQ(d.points.size(), 8u);
  EXPECT_EQ(d.edges.size(), 6u);
  EXPECT_EQ(d.radius[7], 1.4);
  EXPECT_EQ(d.points[7], Vec3(-4, 0, 16));
}

void expect_aorta(const std::string& path, std::size_t points, std::size_t edges) {
  const CenterlineData d = read_centerline(path);
  EXPECT_EQ(d.points.size(), points);
  EXPECT_EQ(d.edges.size(), edges);
  ASSERT_EQ(d.radius.size(), points);
  EXPECT_TRUE(d.edge_radius.empty());
  const auto [min, max] = std::minmax_element(d.radius.begin(), d.radius.end());
  EXPECT_NEAR(*min, 2.77587, 2.77587 * 1e-5);
  EXPECT_NEAR(*max, 7.57802, 7.57802 * 1e-5);
  Vec3 low = d.points[0], high = d.points[0];
  for (const Vec3& p : d.points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  EXPECT_TRUE(low.isApprox(Vec3(210.2, 101.314, 21.6731), 1e-5)) << low.transpose();  // SOURCE.md's box
  EXPECT_TRUE(high.isApprox(Vec3(234.695, 175.87, 31.6877), 1e-5)) << high.transpose();
}

TEST(ReadVtp, VmtkAortaCenterlineHasItsKnownCountsAndRadii) {
  SHARED_DATA_OR_SKIP(path, "vmtk-aorta-centerline/aorta-centerline.vtp");
  expect_aorta(path, 409, 407);
}

TEST(ReadVtp, VmtkAortaBranchesCenterlineHasItsKnownCountsAndRadii) {
  SHARED_DATA_OR_SKIP(path, "vmtk-aorta-centerline/aorta-centerline-branches.vtp");
  expect_aorta(path, 417, 411);
}

// ---------------------------------------------------------------------------------------------------
// Rejected input: the file, where, and what was expected

TEST(ReadVtp, EmptyInputIsRejected) { EXPECT_TRUE(Says(error_of(""), "", "the file is empty")); }

TEST(ReadVtp, TextThatIsNotXmlIsRejected) {
  EXPECT_TRUE(Says(error_of("# vtk DataFile Version 3.0\nASCII\n"), "byte 0", "not XML"));
  EXPECT_TRUE(Says(error_of("  \n\t "), "byte 0", "not XML"));
}

TEST(ReadVtp, MalformedXmlIsRejectedWithItsOffset) {
  const std::string text = replaced(sample_file(kAscii), "</Points>", "</Pointz>");
  EXPECT_TRUE(Says(error_of(text), byte_of(text, "Pointz>"), "not valid XML"));
}

TEST(ReadVtp, DocumentOtherThanVtkFileIsRejected) {
  const std::string text = "<?xml version=\"1.0\"?>\n<svg width=\"3\"/>";
  EXPECT_TRUE(Says(error_of(text), byte_of(text, "<svg"), "expected a <VTKFile> element, found <svg>"));
}

TEST(ReadVtp, VtkFileOfAnotherTypeIsRejected) {
  const std::string text = replaced(sample_file(kAscii), "type=\"PolyData\"", "type=\"UnstructuredGrid\"");
  EXPECT_TRUE(Says(error_of(text), byte_of(text, "<VTKFile"), "'UnstructuredGrid'; expected PolyData"));
}

TEST(ReadVtp, UnknownByteOrderOrHeaderTypeIsRejected) {
  const std::string order = replaced(sample_file(kBinary), "LittleEndian", "MiddleEndian");
  EXPECT_TRUE(Says(error_of(order), byte_of(order, "<VTKFile"), "expected LittleEndian or BigEndian"));
  const std::string header = replaced(sample_file(kBinary), "UInt32", "UInt16");
  EXPECT_TRUE(Says(error_of(header), byte_of(header, "<VTKFile"), "expected UInt32 or UInt64"));
}

TEST(ReadVtp, UnknownCompressorIsRejected) {
  const std::string text =
      replaced(sample_file(kBinaryZlib), "vtkZLibDataCompressor", "vtkLZ4DataCompressor");
  EXPECT_TRUE(Says(error_of(text), byte_of(text, "<VTKFile"),
                   "unknown compressor 'vtkLZ4DataCompressor'; expected vtkZLibDataCompressor"));
}

TEST(ReadVtp, MissingPolyDataOrPieceIsRejected) {
  const std::string no_poly_data = "<VTKFile type=\"PolyData\">\n  <ImageData/>\n</VTKFile>";
  EXPECT_TRUE(Says(error_of(no_poly_data), "byte 0", "no <PolyData>"));
  const std::string no_piece = "<VTKFile type=\"PolyData\">\n  <PolyData>\n  </PolyData>\n</VTKFile>";
  EXPECT_TRUE(Says(error_of(no_piece), byte_of(no_piece, "<PolyData>"), "<PolyData> has no <Piece>"));
}

TEST(ReadVtp, MissingPointsIsRejected) {
  const std::string full = sample_file(kAscii);
  const std::size_t start = full.find("<Points>"), end = full.find("</Points>") + 9;
  const std::string text = full.substr(0, start) + full.substr(end);
  EXPECT_TRUE(
      Says(error_of(text), byte_of(text, "<Piece"), "NumberOfPoints=6 but the piece has no <Points>"));
}

TEST(ReadVtp, MissingLinesIsRejected) {
  const std::string full = sample_file(kAscii);
  const std::size_t start = full.find("<Lines>"), end = full.find("</Lines>") + 8;
  const std::string text = full.substr(0, start) + full.substr(end);
  EXPECT_TRUE(Says(error_of(text), byte_of(text, "<Piece"), "NumberOfLines=2 but the piece has no <Lines>"));
}

TEST(ReadVtp, MissingConnectivityOrOffsetsIsRejected) {
  const std::string text = replaced(sample_file(kAscii), "Name=\"connectivity\"", "Name=\"conn\"", "<Lines>");
  EXPECT_TRUE(
      Says(error_of(text), byte_of(text, "<Lines>"), "<Lines> has no DataArray named 'connectivity'"));
  const std::string offsets = replaced(sample_file(kAscii), "Name=\"offsets\"", "Name=\"ends\"", "<Lines>");
  EXPECT_TRUE(
      Says(error_of(offsets), byte_of(offsets, "<Lines>"), "<Lines> has no DataArray named 'offsets'"));
}

TEST(ReadVtp, FileWithoutLineCellsIsRejected) {
  Piece p = sample();
  p.connectivity.values.clear();
  p.offsets.values.clear();
  p.cell_data.clear();
  const std::string text = Writer(kAscii).file({p});
  EXPECT_TRUE(Says(error_of(text), byte_of(text, "<PolyData>"), "no line cells"));
}

TEST(ReadVtp, PolygonsAndStripsAreRejectedAsNotACenterline) {
  const std::string polys = replaced(sample_file(kAscii), "NumberOfPolys=\"0\"", "NumberOfPolys=\"3\"");
  EXPECT_TRUE(
      Says(error_of(polys), byte_of(polys, "<Piece"), "3 polygons and 0 triangle strips: not a centerline"));
  const std::string strips = replaced(sample_file(kAscii), "NumberOfStrips=\"0\"", "NumberOfStrips=\"1\"");
  EXPECT_TRUE(Says(error_of(strips), byte_of(strips, "<Piece"), "1 triangle strips"));
}

TEST(ReadVtp, MissingNegativeOrNonNumericCountIsRejected) {
  const std::string missing = replaced(sample_file(kAscii), "NumberOfPoints=\"6\"", "");
  EXPECT_TRUE(Says(error_of(missing), byte_of(missing, "<Piece"), "<Piece> has no NumberOfPoints attribute"));
  const std::string negative = replaced(sample_file(kAscii), "NumberOfLines=\"2\"", "NumberOfLines=\"-2\"");
  EXPECT_TRUE(Says(error_of(negative), byte_of(negative, "<Piece"), "NumberOfLines=-2 is out of range"));
  const std::string word = replaced(sample_file(kAscii), "NumberOfPoints=\"6\"", "NumberOfPoints=\"six\"");
  EXPECT_TRUE(
      Says(error_of(word), line_of(word, "<Piece"), "expected an integer for NumberOfPoints, found 'six'"));
}

TEST(ReadVtp, CountsBeyondThe32BitIndexRangeAreRejected) {
  const std::string text =
      replaced(sample_file(kAscii), "NumberOfPoints=\"6\"", "NumberOfPoints=\"3000000000\"");
  EXPECT_TRUE(Says(error_of(text), byte_of(text, "<Piece"), "NumberOfPoints=3000000000 is out of range"));
}

TEST(ReadVtp, PointsWithTwoComponentsAreRejected) {
  const std::string text = replaced(sample_file(kAscii), "Name=\"Points\" NumberOfComponents=\"3\"",
                                    "Name=\"Points\" NumberOfComponents=\"2\"");
  EXPECT_TRUE(Says(error_of(text), array_at(text, "Name=\"Points\""), "NumberOfComponents=2; points need 3"));
}

TEST(ReadVtp, AsciiArrayShorterOrLongerThanItsCountIsRejected) {
  const std::string shorter = replaced(sample_file(kAscii), "0.125", "");
  EXPECT_TRUE(
      Says(error_of(shorter), array_at(shorter, "Name=\"Radius\""),
           "<PointData> DataArray 'Radius' holds 5 values; expected 6 (one per point, NumberOfPoints=6)"));
  const std::string longer = replaced(sample_file(kAscii), "-0.5", "-0.5 7");
  EXPECT_TRUE(Says(error_of(longer), array_at(longer, "Name=\"Points\""),
                   "holds 19 values; expected 18 (3 per point, NumberOfPoints=6)"));
}

TEST(ReadVtp, BinaryArrayWhoseHeaderGivesAnotherSizeIsRejected) {
  for (uint64_t size : {60u, 84u}) {
    const std::string content = base64(header_words({size}, kBinary) + sample_points_bytes());
    const std::string text = with_points_content(content, kBinary);
    EXPECT_TRUE(Says(error_of(text), byte_of(text, content),
                     "the header gives " + std::to_string(size) + " bytes; expected 72 bytes (3 per point"));
  }
}

TEST(ReadVtp, CompressionHeaderGivingAnotherSizeIsRejected) {
  Compressed c = compress(sample_points_bytes(), 32768);
  c.header[2] = 64;
  const std::string content = stored(c, kBinaryZlib);
  const std::string text = with_points_content(content);
  EXPECT_TRUE(
      Says(error_of(text), byte_of(text, content), "the compression header gives 64 bytes; expected 72"));
}

TEST(ReadVtp, InlineBinaryDataLongerThanItsHeaderIsRejected) {
  const std::string content = base64(header_words({72}, kBinary) + sample_points_bytes()) + "AAAA";
  const std::string text = with_points_content(content, kBinary);
  EXPECT_TRUE(Says(error_of(text), at_byte(text.find(content) + content.size() - 4),
                   "more data follows the 72 bytes that its header gives"));
}

TEST(ReadVtp, InvalidBase64CharacterIsRejectedWithItsOffset) {
  std::string content = base64(header_words({72}, kBinary) + sample_points_bytes());
  content[21] = '!';
  const std::string text = with_points_content(content, kBinary);
  EXPECT_TRUE(Says(error_of(text), at_byte(text.find(content) + 21), "expected base64 data, found '!'"));
}

TEST(ReadVtp, TruncatedBase64IsRejectedWhereItEnds) {
  const std::string content = base64(header_words({72}, kBinary) + sample_points_bytes()).substr(0, 40);
  const std::string text = with_points_content(content, kBinary);
  EXPECT_TRUE(
      Says(error_of(text), at_byte(text.find(content) + 40), "the data ends here, short of the 76 bytes"));
}

TEST(ReadVtp, Base64PaddingBeforeTheEndIsRejected) {
  std::string content = base64(header_words({72}, kBinary) + sample_points_bytes());
  content.replace(24, 4, "AA==");
  const std::string text = with_points_content(content, kBinary);
  EXPECT_TRUE(
      Says(error_of(text), at_byte(text.find(content) + 24), "the base64 data ends ('=' padding) after 19"));
}

TEST(ReadVtp, Base64RunWithoutItsPaddingIsRejected) {
  // The compression header (4 words = 16 bytes) must end its own run with '=' padding.
  Compressed c = compress(sample_points_bytes(), 32768);
  std::string blocks;
  for (const std::string& block : c.blocks) blocks += block;
  const std::string content = base64(header_words(c.header, kBinaryZlib) + blocks);
  const std::string text = with_points_content(content);
  EXPECT_TRUE(Says(error_of(text), at_byte(text.find(content) + 24), "runs on past the 16 bytes expected"));
}

TEST(ReadVtp, CorruptZlibBlockIsRejectedWithItsOffset) {
  std::string text = sample_file(kAppendedRawZlib);
  const std::size_t points = text.find("offset=\"", text.find("<Points>")) + 8;
  const std::size_t block =
      text.find('_', text.find("<AppendedData")) + 1 + std::stoul(text.substr(points)) + 16;
  ASSERT_EQ(text[block], '\x78');  // the zlib header
  text[block] = '\0';
  EXPECT_TRUE(
      Says(error_of(text), at_byte(block), "<Points> DataArray: compressed block 0 is not valid zlib data"));
}

TEST(ReadVtp, CorruptZlibBlockInBase64IsLocatedByItsCharacterGroup) {
  Compressed c = compress(sample_points_bytes(), 32);  // blocks of 32, 32 and 8 bytes
  c.blocks[1][2] ^= 0x55;
  const std::string header = base64(header_words(c.header, kBinaryZlib));
  const std::string content = stored(c, kBinaryZlib);
  const std::string text = with_points_content(content);
  const std::size_t where = text.find(content) + header.size() + c.blocks[0].size() / 3 * 4;
  EXPECT_TRUE(Says(error_of(text), at_byte(where), "compressed block 1 "));
}

TEST(ReadVtp, ZlibBlockThatInflatesToAnotherSizeIsRejected) {
  const std::string bytes = sample_points_bytes();
  Compressed more = compress(bytes, 64);  // blocks of 64 and 8 bytes, declared as 40 and 32
  more.header[1] = 40;
  more.header[2] = 32;
  std::string content = stored(more, kBinaryZlib);
  std::string text = with_points_content(content);
  const std::size_t data = text.find(content) + base64(header_words(more.header, kBinaryZlib)).size();
  EXPECT_TRUE(Says(error_of(text), at_byte(data), "compressed block 0 inflates to more than the 40 bytes"));

  Compressed fewer;  // blocks of 60 and 12 bytes, declared as 64 and 8
  fewer.blocks = {deflate(bytes.substr(0, 60)), deflate(bytes.substr(60))};
  fewer.header = {2, 64, 8, fewer.blocks[0].size(), fewer.blocks[1].size()};
  content = stored(fewer, kBinaryZlib);
  text = with_points_content(content);
  const std::size_t fewer_data = text.find(content) + base64(header_words(fewer.header, kBinaryZlib)).size();
  EXPECT_TRUE(Says(error_of(text), at_byte(fewer_data),
                   "compressed block 0 inflates to 60 bytes; the header gives 64"));
}

TEST(ReadVtp, ZlibBlockWithBytesAfterItsStreamIsRejected) {
  Compressed c = compress(sample_points_bytes(), 32768);
  c.blocks[0] += "junk";
  c.header[3] += 4;
  const std::string content = stored(c, kBinaryZlib);
  const std::string text = with_points_content(content);
  const std::size_t data = text.find(content) + base64(header_words(c.header, kBinaryZlib)).size();
  EXPECT_TRUE(Says(error_of(text), at_byte(data), "compressed block 0 has 4 bytes after its zlib stream"));
}

TEST(ReadVtp, ZlibBlockCutShortIsRejected) {
  Compressed c = compress(sample_points_bytes(), 32768);
  c.blocks[0].resize(c.blocks[0].size() - 6);  // the Adler-32 check and the last bytes of data
  c.header[3] = c.blocks[0].size();
  const std::string content = stored(c, kBinaryZlib);
  const std::string text = with_points_content(content);
  const std::size_t data = text.find(content) + base64(header_words(c.header, kBinaryZlib)).size();
  EXPECT_TRUE(Says(error_of(text), at_byte(data), "compressed block 0 ends before its zlib stream does"));
}

TEST(ReadVtp, CompressedSizesPastTheEndOfTheDataAreRejected) {
  Compressed c = compress(sample_points_bytes(), 32768);
  c.header[3] += 1000;
  const std::string content = stored(c, kBinaryZlib);
  const std::string text = with_points_content(content);
  // The fourth header word, in the third group of base64 characters.
  EXPECT_TRUE(Says(error_of(text), at_byte(text.find(content) + 16), "runs past the end of the data"));
}

TEST(ReadVtp, AbsurdBlockCountIsRejectedBeforeAllocating) {
  Compressed c = compress(sample_points_bytes(), 32768);
  c.header[0] = 0xFFFFFFFFu;
  const std::string content = stored(c, kBinaryZlib);
  const std::string text = with_points_content(content);
  EXPECT_TRUE(Says(error_of(text), at_byte(text.find(content)),
                   "4294967295 blocks, more than the data could describe"));
}

TEST(ReadVtp, BlockClaimingMoreThanZlibCanProduceIsRejected) {
  Compressed c = compress(sample_points_bytes(), 32768);
  c.header[1] = c.header[2] = 4000000000u;
  const std::string content = stored(c, kBinaryZlib);
  const std::string text = with_points_content(content);
  EXPECT_TRUE(Says(error_of(text), at_byte(text.find(content) + 16), "more than zlib can produce"));
}

TEST(ReadVtp, AbsurdCountsMatchingAnAbsurdHeaderAreRejectedBeforeAllocating) {
  const Encoding e{"binary UInt64 header", Format::kBinary, false, false, true};
  const std::string content = base64(header_words({12000000000u}, e) + sample_points_bytes());
  const std::string text =
      replaced(with_points_content(content, e), "NumberOfPoints=\"6\"", "NumberOfPoints=\"1000000000\"");
  EXPECT_TRUE(Says(error_of(text), at_byte(text.find(content) + content.size()),
                   "the data ends here, short of the 12000000008 bytes"));
}

// Every count the reader sizes something by (NumberOfPoints, NumberOfLines, the last offset, byte
// counts in headers), set to hundreds of millions in a small file of each encoding: an
// InputError, and no allocation much beyond the file's own size.
TEST(ReadVtp, NoCountIsAllocatedBeforeTheBytesThatHoldItAreChecked) {
  std::vector<std::string> files;
  for (const Encoding& e : kEncodings) {
    const std::string text = sample_file(e);
    files.push_back(replaced(text, "NumberOfPoints=\"6\"", "NumberOfPoints=\"300000000\""));
    files.push_back(replaced(text, "NumberOfLines=\"2\"", "NumberOfLines=\"300000000\""));
  }
  files.push_back(replaced(sample_file(kAscii), "4 6\n", "4 300000000\n"));
  files.push_back(
      with_points_content(base64(header_words({3000000000u}, kBinary) + sample_points_bytes()), kBinary));
  Compressed c = compress(sample_points_bytes(), 32768);
  c.header[1] = c.header[2] = c.header[3] * 1032;  // as much as zlib could give: 72 bytes are there
  files.push_back(with_points_content(stored(c, kBinaryZlib)));
  for (const std::string& file : files) {
    SCOPED_TRACE(file.substr(0, 300));
    LargestAllocation largest;
    try {
      parse(file);
      ADD_FAILURE() << "accepted";
    } catch (const InputError&) {
    }
    EXPECT_LT(largest.bytes(), 64 * 1024 + 4 * file.size());
  }
}

TEST(ReadVtp, OffsetsThatDecreaseOrGoOutOfRangeAreRejected) {
  const std::string base = sample_file(kAscii);
  const std::string offsets = "Name=\"offsets\"";
  const std::string decreasing = replaced(base, "4 6\n", "4 3\n");
  EXPECT_TRUE(
      Says(error_of(decreasing), array_at(decreasing, offsets, "<Lines>"), "offsets entry 1 is 3, below 4"));
  const std::string negative = replaced(base, "4 6\n", "-1 6\n");
  EXPECT_TRUE(
      Says(error_of(negative), array_at(negative, offsets, "<Lines>"), "offsets entry 0 is -1, below 0"));
  const std::string huge = replaced(base, "4 6\n", "4 3000000000\n");
  EXPECT_TRUE(Says(error_of(huge), array_at(huge, offsets, "<Lines>"),
                   "the last offset, 3000000000, is out of range"));
  const std::string long_cell = replaced(base, "4 6\n", "4 7\n");
  EXPECT_TRUE(Says(error_of(long_cell), array_at(long_cell, "Name=\"connectivity\"", "<Lines>"),
                   "'connectivity' holds 6 values; expected 7 (the last offset)"));
}

TEST(ReadVtp, ConnectivityIndexOutOfRangeIsRejected) {
  const std::string text = replaced(sample_file(kAscii), "0 1 2 3 4 5\n", "0 1 2 3 4 6\n");
  EXPECT_TRUE(Says(error_of(text), array_at(text, "Name=\"connectivity\"", "<Lines>"),
                   "connectivity entry 5 is 6, outside the piece's points 0..5"));
  const std::string negative = replaced(sample_file(kAscii), "0 1 2 3 4 5\n", "0 -1 2 3 4 5\n");
  EXPECT_TRUE(Says(error_of(negative), array_at(negative, "Name=\"connectivity\"", "<Lines>"),
                   "connectivity entry 1 is -1"));
}

TEST(ReadVtp, UnknownTypeOrFloatIndicesAreRejected) {
  const std::string unknown =
      replaced(sample_file(kAscii), "type=\"Float64\" Name=\"Radius\"", "type=\"Float16\" Name=\"Radius\"");
  EXPECT_TRUE(
      Says(error_of(unknown), array_at(unknown, "Name=\"Radius\""), "unknown type 'Float16'; expected Int8"));
  const std::string float_indices =
      replaced(sample_file(kAscii), "type=\"Int64\"", "type=\"Float32\"", "<Lines>");
  EXPECT_TRUE(Says(error_of(float_indices), array_at(float_indices, "Name=\"connectivity\"", "<Lines>"),
                   "has type Float32; expected an integer type"));
}

TEST(ReadVtp, UnknownDataArrayFormatIsRejected) {
  const std::string text =
      replaced(sample_file(kAscii), "Name=\"Radius\" NumberOfComponents=\"1\" format=\"ascii\"",
               "Name=\"Radius\" NumberOfComponents=\"1\" format=\"hex\"");
  EXPECT_TRUE(Says(error_of(text), array_at(text, "Name=\"Radius\""),
                   "format 'hex'; expected ascii, binary or appended"));
}

TEST(ReadVtp, AppendedArraysNeedAnAppendedSectionThatHoldsTheirOffset) {
  const std::string full = sample_file(kAppendedRawZlib);
  const std::string no_section = full.substr(0, full.find("  <AppendedData")) + "</VTKFile>\n";
  EXPECT_TRUE(Says(error_of(no_section), array_at(no_section, "Name=\"Points\""),
                   "is appended but the file has no <AppendedData>"));
  const std::string past = replaced(full, "offset=\"0\"", "offset=\"100000\"");
  EXPECT_TRUE(Says(error_of(past), array_at(past, "offset=\"100000\""),
                   "offset=100000 is outside the appended data"));
  const std::string negative = replaced(full, "offset=\"0\"", "offset=\"-8\"");
  EXPECT_TRUE(Says(error_of(negative), array_at(negative, "offset=\"-8\""), "offset=-8 is outside"));
}

TEST(ReadVtp, AppendedSectionMustBeWellFormed) {
  const std::string full = sample_file(kAppendedRawZlib);
  const std::string no_mark = replaced(full, "\n   _", "\n   ");
  EXPECT_TRUE(Says(error_of(no_mark), at_byte(no_mark.find("encoding=\"raw\">") + 19),
                   "expected '_' where the appended data starts"));
  const std::string unclosed = full.substr(0, full.find("<AppendedData") + 20);
  EXPECT_TRUE(
      Says(error_of(unclosed), byte_of(unclosed, "<AppendedData"), "the <AppendedData> tag is not closed"));
  const std::string encoding = replaced(full, "encoding=\"raw\"", "encoding=\"hex\"");
  EXPECT_TRUE(
      Says(error_of(encoding), byte_of(encoding, "<AppendedData"), "encoding 'hex'; expected base64 or raw"));
}

TEST(ReadVtp, TruncatedRawAppendedDataIsRejectedWhereItEnds) {
  const std::string full = sample_file({"appended raw", Format::kAppended, false, true});
  const std::string text = full.substr(0, full.size() - 40);  // the closing tags and 10 bytes of data
  EXPECT_TRUE(Says(error_of(text), at_byte(text.size()), "the data ends here, short of the"));
}

TEST(ReadVtp, TruncatedCompressedDataIsRejectedAtTheSizeThatOverrunsIt) {
  const std::string full = sample_file(kAppendedRawZlib);
  const std::string text = full.substr(0, full.size() - 32);  // the closing tags and 2 bytes of data
  const std::size_t offsets = text.find("offset=\"", text.find("Name=\"offsets\"", text.find("<Lines>"))) + 8;
  const std::size_t size_word =
      text.find('_', text.find("<AppendedData")) + 1 + std::stoul(text.substr(offsets)) + 12;
  EXPECT_TRUE(Says(error_of(text), at_byte(size_word), "'offsets': compressed block 0 of "));
}

TEST(ReadVtp, NotANumberIsRejectedWithItsLineOrArray) {
  const std::string ascii = replaced(sample_file(kAscii), "1 0.25\n", "1 nan\n");
  EXPECT_TRUE(
      Says(error_of(ascii), line_of(ascii, "nan"), "<Points> DataArray is not a finite number ('nan')"));
  Piece p = sample();
  p.point_data[0].values[3] = std::numeric_limits<double>::infinity();
  const std::string binary = Writer(kBinaryZlib).file({p});
  EXPECT_TRUE(Says(error_of(binary), array_at(binary, "Name=\"Radius\""),
                   "<PointData> DataArray 'Radius': value 3 is not a finite number"));
}

TEST(ReadVtp, MissingRadiusArrayIsRejectedListingTheArrays) {
  const std::string text = replaced(sample_file(kAscii), "Name=\"Radius\"", "Name=\"Width\"");
  EXPECT_TRUE(Says(error_of(text), byte_of(text, "<Piece"),
                   "no radius array; found: Width, EdgeArray, GroupIds; name one with --radius-array"));
  ReadOptions options;
  options.radius_array = "Thickness";
  EXPECT_TRUE(Says(error_of(sample_file(kAscii), options), byte_of(text, "<Piece"),
                   "no array named 'Thickness'; found: Radius, EdgeArray, GroupIds"));
}

TEST(ReadVtp, RadiusWithTwoComponentsIsRejected) {
  ReadOptions options;
  options.radius_array = "EdgeArray";
  const std::string text = sample_file(kAscii);
  EXPECT_TRUE(Says(error_of(text, options), array_at(text, "Name=\"EdgeArray\""),
                   "'EdgeArray' has NumberOfComponents=2; a radius needs 1"));
}

TEST(ReadVtp, RadiusPerPointInOnePieceAndPerCellInAnotherIsRejected) {
  Piece per_cell = sample();
  per_cell.point_data.erase(per_cell.point_data.begin());
  per_cell.cell_data.push_back({"Radius", "Float32", 1, {1, 2}});
  const std::string text = Writer(kAscii).file({sample(), per_cell});
  const std::size_t second = text.find("<Piece", text.find("<Piece") + 1);
  EXPECT_TRUE(Says(error_of(text), at_byte(text.rfind("<DataArray", text.find("Name=\"Radius\"", second))),
                   "gives the radius per cell; an earlier piece gives it per point"));
}

// ---------------------------------------------------------------------------------------------------
// Compression headers that claim more than the data holds (a "zlib bomb"): the reader must report the
// bad block without first allocating what the header claims.

/// A Piece of `points` points whose <Points> array is appended raw, compressed as `blocks` zlib blocks
/// that each claim `block_size` bytes; the rest of the piece is ascii. Returns the file and sets
/// `data_at` to the byte offset of the first block's data.
std::string bomb_file(uint64_t points, const std::vector<std::string>& blocks, uint64_t block_size,
                      std::size_t& data_at) {
  std::vector<uint64_t> header = {blocks.size(), block_size, 0};
  std::string packed;
  for (const std::string& block : blocks) {
    header.push_back(block.size());
    packed += block;
  }
  const std::string head =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\">\n<PolyData>\n<Piece NumberOfPoints=\"" +
      std::to_string(points) +
      "\" NumberOfLines=\"1\">\n<PointData><DataArray type=\"Float32\" Name=\"Radius\" format=\"ascii\">1 1"
      "</DataArray></PointData>\n<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" "
      "format=\"appended\" offset=\"0\"/></Points>\n<Lines><DataArray type=\"Int64\" Name=\"connectivity\" "
      "format=\"ascii\">0 1</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">2"
      "</DataArray></Lines>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_";
  const std::string words = header_words(header, kAppendedRawZlib);
  data_at = head.size() + words.size();
  return head + words + packed + "\n</AppendedData>\n</VTKFile>\n";
}

// 240 blocks of 991 bytes, each claiming 1,000,000 (within zlib's 1032:1): 240 MB for 20 million points
// from a 240 kB file. The first block inflates to 1,000 bytes and ends.
TEST(ReadVtp, ZlibBombIsRejectedWithoutAllocatingWhatItsHeaderClaims) {
  constexpr uint64_t kClaimed = 1000000;
  const std::string first = deflate(std::string(1000, '\0'));
  std::vector<std::string> blocks(240, std::string(991, '\xff'));
  blocks[0] = first + std::string(991 - first.size(), '\0');
  std::size_t data_at = 0;
  const std::string text = bomb_file(20000000, blocks, kClaimed, data_at);
  LargestAllocation largest;
  EXPECT_TRUE(
      Says(error_of(text), at_byte(data_at),
           "<Points> DataArray: compressed block 0 inflates to 1000 bytes; the header gives 1000000"));
  EXPECT_LT(largest.bytes(), 4 * text.size()) << "the reader allocated what the header claims";
}

// The same header with four true blocks of a million zeros before a corrupt one: memory grows with the
// data that inflates (4 MB), not with the 240 MB claimed.
TEST(ReadVtp, ZlibBombMemoryGrowsOnlyWithTheDataThatInflates) {
  constexpr uint64_t kClaimed = 1000000;
  const std::string zeros = deflate(std::string(kClaimed, '\0'));
  ASSERT_LE(kClaimed, zeros.size() * 1032);
  std::vector<std::string> blocks(240, std::string(zeros.size(), '\xff'));
  for (int b = 0; b < 4; ++b) blocks[b] = zeros;
  std::size_t data_at = 0;
  const std::string text = bomb_file(20000000, blocks, kClaimed, data_at);
  LargestAllocation largest;
  EXPECT_TRUE(Says(error_of(text), at_byte(data_at + 4 * zeros.size()),
                   "<Points> DataArray: compressed block 4 is not valid zlib data"));
  EXPECT_LT(largest.bytes(), 16 * kClaimed) << "the reader allocated what the header claims";
}

// Blocks far larger than the reader's first 64 KiB of output room (1 MB and 200 kB) inflate whole and in
// order.
TEST(ReadVtp, BlocksOfAMegabyteInflateWhole) {
  Piece p = sample();
  p.points.values.assign(3 * 100000, 0.0);
  for (std::size_t i = 0; i < p.points.values.size(); i += 3) p.points.values[i] = static_cast<double>(i / 3);
  p.connectivity.values = {0, 99999};
  p.offsets.values = {2};
  p.point_data = {{"Radius", "Float32", 1, std::vector<double>(100000, 1.0)}};
  p.cell_data.clear();
  const Encoding e{"appended raw zlib, 1 MB blocks", Format::kAppended, true, true, false, false, 1000000};
  const CenterlineData data = parse(Writer(e).file({p}));
  ASSERT_EQ(data.points.size(), 100000u);
  EXPECT_EQ(data.points[99999].x(), 99999.0);
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 99999}}));
}

// ---------------------------------------------------------------------------------------------------
// Robustness: damaged files are read or rejected with an InputError, never anything else

TEST(ReadVtp, EveryTruncationIsReadOrRejectedCleanly) {
  for (const Encoding& e : kEncodings) {
    SCOPED_TRACE(e.label);
    const std::string full = sample_file(e);
    for (std::size_t n = 0; n < full.size(); ++n) {
      try {
        parse(full.substr(0, n));
      } catch (const InputError&) {
      }
    }
  }
}

TEST(ReadVtp, RandomByteDamageIsReadOrRejectedCleanly) {
  std::mt19937 random(12345);
  for (const Encoding& e : kEncodings) {
    SCOPED_TRACE(e.label);
    const std::string full = sample_file(e);
    std::uniform_int_distribution<std::size_t> position(0, full.size() - 1);
    std::uniform_int_distribution<int> value(0, 255);
    for (int trial = 0; trial < 400; ++trial) {
      std::string damaged = full;
      for (int k = 0; k < 1 + trial % 3; ++k) damaged[position(random)] = static_cast<char>(value(random));
      try {
        parse(damaged);
      } catch (const InputError&) {
      }
    }
  }
}

}  // namespace
}  // namespace vesselmesh
