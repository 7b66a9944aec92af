#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "vesselmesh/error.hpp"
#include "vesselmesh/read/radius_array.hpp"
#include "vesselmesh/read/read.hpp"
#include "vesselmesh/read/text.hpp"

namespace vesselmesh {

namespace {

/// Point indices are int32 (centerline.hpp), so no count may exceed this.
constexpr int64_t kMaxCount = std::numeric_limits<int32_t>::max();

/// Deflate expands at most 1032:1, so a block that claims more than this many bytes per compressed
/// byte is a lie, rejected before anything is inflated. A claim within the ratio may still be a lie:
/// the inflated data is what the output buffer grows with (inflate_block).
constexpr uint64_t kMaxInflateRatio = 1032;

/// Offsets of pugixml nodes must be byte offsets of the file: no end-of-line conversion.
constexpr unsigned kParseOptions = pugi::parse_default & ~pugi::parse_eol;

struct Type {
  const char* name;
  std::size_t size;
  enum Kind { kSigned, kUnsigned, kFloat } kind;
};

constexpr Type kTypes[] = {
    {"Int8", 1, Type::kSigned},     {"UInt8", 1, Type::kUnsigned},  {"Int16", 2, Type::kSigned},
    {"UInt16", 2, Type::kUnsigned}, {"Int32", 4, Type::kSigned},    {"UInt32", 4, Type::kUnsigned},
    {"Int64", 8, Type::kSigned},    {"UInt64", 8, Type::kUnsigned}, {"Float32", 4, Type::kFloat},
    {"Float64", 8, Type::kFloat},
};

int64_t sign_extended(uint64_t bits, std::size_t size) {
  const unsigned shift = static_cast<unsigned>(64 - 8 * size);
  return static_cast<int64_t>(bits << shift) >> shift;
}

double as_double(uint64_t bits, const Type& type) {
  switch (type.kind) {
    case Type::kSigned:
      return static_cast<double>(sign_extended(bits, type.size));
    case Type::kUnsigned:
      return static_cast<double>(bits);
    case Type::kFloat:
      break;
  }
  if (type.size == 4) {
    const auto narrow = static_cast<uint32_t>(bits);
    float value;
    std::memcpy(&value, &narrow, sizeof value);
    return value;
  }
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// An integer element (callers reject float types first). UInt64 values past INT64_MAX are clamped:
/// every integer read here is an index or offset, and the range checks then reject them.
int64_t as_int(uint64_t bits, const Type& type) {
  if (type.kind == Type::kSigned) return sign_extended(bits, type.size);
  return static_cast<int64_t>(std::min<uint64_t>(bits, std::numeric_limits<int64_t>::max()));
}

int base64_digit(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

/// A character for a message: itself when printable, else its code.
std::string shown(char c) {
  const auto code = static_cast<unsigned char>(c);
  if (code > ' ' && code < 127) return std::string("'") + c + "'";
  const char* hex = "0123456789ABCDEF";
  return std::string("byte 0x") + hex[code >> 4] + hex[code & 15];
}

/// Inflates one zlib block that must give exactly `size` bytes and appends them to `out`. The buffer
/// grows with what the block really gives, at most doubling `out` (or by 64 KiB) at a time, so a block
/// whose header claims more than its data holds costs no more memory than that data. Returns "" or what
/// is wrong with the block.
std::string inflate_block(std::string_view block, uint64_t size, std::string& out) {
  constexpr uint64_t kFirstChunk = 64 * 1024;
  constexpr uint64_t kMaxPass = std::numeric_limits<uInt>::max();  // zlib counts in uInt
  z_stream z{};
  if (inflateInit(&z) != Z_OK) throw std::bad_alloc();
  struct End {
    z_stream& z;
    ~End() { inflateEnd(&z); }
  } end{z};
  std::size_t fed = 0;  // bytes of `block` handed to zlib
  const auto feed = [&] {
    if (z.avail_in != 0 || fed == block.size()) return;
    const auto n = static_cast<uInt>(std::min<uint64_t>(block.size() - fed, kMaxPass));
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(block.data() + fed));
    z.avail_in = n;
    fed += n;
  };
  const auto unread = [&] { return block.size() - fed + z.avail_in; };
  const std::size_t start = out.size();
  uint64_t produced = 0;
  int rc = Z_OK;
  while (produced < size) {
    feed();
    const uint64_t room = std::min({size - produced, std::max<uint64_t>(kFirstChunk, out.size()), kMaxPass});
    out.resize(start + static_cast<std::size_t>(produced + room));
    z.next_out = reinterpret_cast<Bytef*>(&out[start + static_cast<std::size_t>(produced)]);
    z.avail_out = static_cast<uInt>(room);
    rc = inflate(&z, Z_NO_FLUSH);
    produced += room - z.avail_out;
    out.resize(start + static_cast<std::size_t>(produced));
    if (rc == Z_STREAM_END) break;
    if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT) return "is not valid zlib data";
    if (rc == Z_MEM_ERROR) throw std::bad_alloc();
    if (rc == Z_BUF_ERROR && unread() == 0) return "ends before its zlib stream does";
    if (rc != Z_OK) return "cannot be inflated (zlib error " + std::to_string(rc) + ")";
  }
  while (rc != Z_STREAM_END) {  // all `size` bytes are out: the stream must end without giving more
    feed();
    unsigned char extra;
    z.next_out = &extra;
    z.avail_out = 1;
    rc = inflate(&z, Z_NO_FLUSH);
    if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT) return "is not valid zlib data";
    if (z.avail_out == 0)
      return "inflates to more than the " + std::to_string(size) + " bytes that the header gives";
    if (rc == Z_BUF_ERROR && unread() == 0) return "ends before its zlib stream does";
    if (rc != Z_OK && rc != Z_STREAM_END) return "cannot be inflated (zlib error " + std::to_string(rc) + ")";
  }
  if (produced != size)
    return "inflates to " + std::to_string(produced) + " bytes; the header gives " + std::to_string(size);
  if (unread() != 0) return "has " + std::to_string(unread()) + " bytes after its zlib stream";
  return "";
}

/// Where an array's binary data lies: base64 text (inline, or appended with encoding="base64") or raw
/// appended bytes. `text` runs from the array's first character to the end of what holds it.
struct Stored {
  std::string_view text;
  std::size_t at;  ///< byte offset of text[0] in the file
  bool base64;
};

/// An array's data bytes and the position in Stored::text just past them.
struct Decoded {
  std::string bytes;
  std::size_t end;
};

class VtpReader {
 public:
  VtpReader(std::string_view bytes, const std::string& source, const ReadOptions& options)
      : bytes_(bytes), source_(source), options_(options) {}

  CenterlineData read() {
    if (bytes_.empty()) throw InputError(source_, "", "the file is empty");
    const std::size_t bom = bytes_.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
    const std::size_t first = bytes_.find_first_not_of(" \t\r\n", bom);
    if (first == std::string_view::npos || bytes_[first] != '<')
      fail(first == std::string_view::npos ? 0 : first, "not XML: a VTK XML file starts with '<'");

    const std::string xml = xml_part();
    for (std::size_t i = 0; i < xml.size(); ++i)
      if (xml[i] == '\n') newlines_.push_back(i);
    pugi::xml_document doc;
    const pugi::xml_parse_result parsed =
        doc.load_buffer(xml.data(), xml.size(), kParseOptions, pugi::encoding_utf8);
    if (!parsed)  // the offset may lie in the closing tags that xml_part adds
      fail(std::min(static_cast<std::size_t>(parsed.offset), bytes_.size()),
           std::string("not valid XML: ") + parsed.description());
    const pugi::xml_node file = doc.document_element();
    if (std::string_view(file.name()) != "VTKFile")
      fail(offset(file), std::string("expected a <VTKFile> element, found <") + file.name() + ">");
    read_file_attributes(file);

    const pugi::xml_node poly_data = file.child("PolyData");
    if (!poly_data) fail(offset(file), "the VTKFile has no <PolyData> element");
    if (!poly_data.child("Piece")) fail(offset(poly_data), "<PolyData> has no <Piece>");
    CenterlineData data;
    int64_t lines = 0;
    for (const pugi::xml_node piece : poly_data.children("Piece")) lines += read_piece(piece, data);
    if (lines == 0)
      fail(offset(poly_data),
           "no line cells (NumberOfLines is 0 or absent in every piece): a centerline is "
           "made of lines");
    return data;
  }

 private:
  [[noreturn]] void fail(std::size_t at, const std::string& what) const {
    throw InputError(source_, at_byte(at), what);
  }

  /// Byte offset of a node in the file: the '<' of an element, the first character of text.
  static std::size_t offset(pugi::xml_node node) {
    const std::ptrdiff_t at = node.offset_debug();  // an element's offset is that of its name
    if (at <= 0) return 0;
    return static_cast<std::size_t>(node.type() == pugi::node_element ? at - 1 : at);
  }

  std::size_t line_at(std::size_t at) const {
    return 1 + static_cast<std::size_t>(std::lower_bound(newlines_.begin(), newlines_.end(), at) -
                                        newlines_.begin());
  }

  /// The XML before the appended data, with the elements that the cut leaves open closed again. Raw
  /// appended bytes may hold anything ('<', NUL), so they never reach the XML parser.
  std::string xml_part() {
    const std::size_t tag = bytes_.find("<AppendedData");
    if (tag == std::string_view::npos) return std::string(bytes_);
    const std::size_t close = bytes_.find('>', tag);
    if (close == std::string_view::npos) fail(tag, "the <AppendedData> tag is not closed");
    const std::size_t mark = bytes_.find_first_not_of(" \t\r\n", close + 1);
    if (mark == std::string_view::npos || bytes_[mark] != '_')
      fail(mark == std::string_view::npos ? bytes_.size() : mark,
           "expected '_' where the appended data starts");
    appended_at_ = mark + 1;
    std::size_t end = bytes_.rfind("</AppendedData>");
    if (end == std::string_view::npos || end < appended_at_) end = bytes_.size();
    appended_ = bytes_.substr(appended_at_, end - appended_at_);
    has_appended_ = true;
    return std::string(bytes_.substr(0, close + 1)) + "</AppendedData></VTKFile>";
  }

  void read_file_attributes(pugi::xml_node file) {
    const std::string_view type = file.attribute("type").value();
    if (type != "PolyData")
      fail(offset(file), "the VTKFile type is '" + std::string(type) + "'; expected PolyData (a centerline)");

    const std::string_view order = file.attribute("byte_order").as_string("LittleEndian");
    if (order != "LittleEndian" && order != "BigEndian")
      fail(offset(file), "byte_order '" + std::string(order) + "'; expected LittleEndian or BigEndian");
    big_endian_ = order == "BigEndian";

    const std::string_view header = file.attribute("header_type").as_string("UInt32");
    if (header != "UInt32" && header != "UInt64")
      fail(offset(file), "header_type '" + std::string(header) + "'; expected UInt32 or UInt64");
    header_size_ = header == "UInt64" ? 8 : 4;

    const std::string_view compressor = file.attribute("compressor").value();
    if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
      fail(offset(file),
           "unknown compressor '" + std::string(compressor) + "'; expected vtkZLibDataCompressor or none");
    compressed_ = !compressor.empty();

    if (has_appended_) {
      const pugi::xml_node appended = file.child("AppendedData");
      const std::string_view encoding = appended.attribute("encoding").value();
      if (encoding != "base64" && encoding != "raw")
        fail(offset(appended),
             "<AppendedData> encoding '" + std::string(encoding) + "'; expected base64 or raw");
      appended_base64_ = encoding == "base64";
    }
  }

  /// A non-negative count attribute; `fallback` when absent, an error when absent without one.
  int64_t count(pugi::xml_node node, const char* name, std::optional<int64_t> fallback) const {
    const pugi::xml_attribute attribute = node.attribute(name);
    if (!attribute) {
      if (fallback) return *fallback;
      fail(offset(node), std::string("<") + node.name() + "> has no " + name + " attribute");
    }
    const int64_t value = parse_int(attribute.value(), source_, line_at(offset(node)), name);
    if (value < 0 || value > kMaxCount)
      fail(offset(node), std::string(name) + "=" + std::to_string(value) +
                             " is out of range: expected 0 to " + std::to_string(kMaxCount));
    return value;
  }

  /// Reads one <Piece> into `data`, numbering its points after those already there; returns its line count.
  int64_t read_piece(pugi::xml_node piece, CenterlineData& data) {
    const int64_t points = count(piece, "NumberOfPoints", std::nullopt);
    const int64_t verts = count(piece, "NumberOfVerts", 0);
    const int64_t lines = count(piece, "NumberOfLines", 0);
    const int64_t strips = count(piece, "NumberOfStrips", 0);
    const int64_t polys = count(piece, "NumberOfPolys", 0);
    if (strips > 0 || polys > 0)
      fail(offset(piece), "the piece has " + std::to_string(polys) + " polygons and " +
                              std::to_string(strips) +
                              " triangle strips: not a centerline, which holds only lines");
    if (points == 0 && lines == 0) return 0;  // parallel writers emit empty pieces
    if (static_cast<int64_t>(data.points.size()) + points > kMaxCount)
      fail(offset(piece), "more than " + std::to_string(kMaxCount) + " points in all pieces together");

    const auto first = static_cast<int32_t>(data.points.size());
    read_points(piece, points, data);
    const std::vector<int64_t> edge_lines = read_lines(piece, points, lines, first, data);
    read_radius(piece, points, verts, lines, edge_lines, data);
    return lines;
  }

  void read_points(pugi::xml_node piece, int64_t points, CenterlineData& data) const {
    if (points == 0) return;
    const pugi::xml_node array = piece.child("Points").child("DataArray");
    if (!array)
      fail(offset(piece),
           "NumberOfPoints=" + std::to_string(points) + " but the piece has no <Points> DataArray");
    const int64_t components = count(array, "NumberOfComponents", 1);
    if (components != 3)
      fail(offset(array),
           "<Points> DataArray has NumberOfComponents=" + std::to_string(components) + "; points need 3");
    const std::vector<double> xyz =
        values<double>(array, 3 * static_cast<uint64_t>(points), "<Points> DataArray",
                       "3 per point, NumberOfPoints=" + std::to_string(points));
    for (std::size_t i = 0; i < xyz.size(); i += 3) data.points.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  }

  /// Appends the edges of the piece's poly-lines (a cell of k points gives k-1 edges) and returns, for
  /// each new edge, the index of its line within the piece.
  std::vector<int64_t> read_lines(pugi::xml_node piece, int64_t points, int64_t lines, int32_t first,
                                  CenterlineData& data) const {
    if (lines == 0) return {};
    const pugi::xml_node cells = piece.child("Lines");
    if (!cells)
      fail(offset(piece), "NumberOfLines=" + std::to_string(lines) + " but the piece has no <Lines>");

    const pugi::xml_node offsets_array = named_array(cells, "offsets");
    const std::vector<int64_t> offsets =
        values<int64_t>(offsets_array, static_cast<uint64_t>(lines), "<Lines> DataArray 'offsets'",
                        "one per line, NumberOfLines=" + std::to_string(lines));
    int64_t previous = 0;
    for (std::size_t i = 0; i < offsets.size(); previous = offsets[i++])
      if (offsets[i] < previous)
        fail(offset(offsets_array), "offsets entry " + std::to_string(i) + " is " +
                                        std::to_string(offsets[i]) + ", below " + std::to_string(previous) +
                                        ": offsets count up from 0, each the end of a line's points");
    if (offsets.back() > kMaxCount)
      fail(offset(offsets_array), "the last offset, " + std::to_string(offsets.back()) +
                                      ", is out of range: expected at most " + std::to_string(kMaxCount));

    const pugi::xml_node connectivity_array = named_array(cells, "connectivity");
    const std::vector<int64_t> connectivity =
        values<int64_t>(connectivity_array, static_cast<uint64_t>(offsets.back()),
                        "<Lines> DataArray 'connectivity'", "the last offset");
    for (std::size_t k = 0; k < connectivity.size(); ++k)
      if (connectivity[k] < 0 || connectivity[k] >= points)
        fail(offset(connectivity_array),
             "connectivity entry " + std::to_string(k) + " is " + std::to_string(connectivity[k]) +
                 (points == 0 ? ", but the piece has no points"
                              : ", outside the piece's points 0.." + std::to_string(points - 1)));

    std::vector<int64_t> edge_lines;
    int64_t start = 0;
    for (std::size_t line = 0; line < offsets.size(); start = offsets[line++])
      for (int64_t k = start + 1; k < offsets[line]; ++k) {
        data.edges.push_back({first + static_cast<int32_t>(connectivity[k - 1]),
                              first + static_cast<int32_t>(connectivity[k])});
        edge_lines.push_back(static_cast<int64_t>(line));
      }
    return edge_lines;
  }

  pugi::xml_node named_array(pugi::xml_node parent, const char* name) const {
    const pugi::xml_node array = parent.find_child_by_attribute("DataArray", "Name", name);
    if (!array)
      fail(offset(parent), std::string("<") + parent.name() + "> has no DataArray named '" + name + "'");
    return array;
  }

  /// The radius from a point array (data.radius) or a cell array (data.edge_radius, each edge taking
  /// its line's value; cell data lists the verts before the lines).
  void read_radius(pugi::xml_node piece, int64_t points, int64_t verts, int64_t lines,
                   const std::vector<int64_t>& edge_lines, CenterlineData& data) {
    std::vector<pugi::xml_node> arrays;
    std::vector<std::string> names;
    const auto collect = [&](const char* section) {
      for (const pugi::xml_node array : piece.child(section).children("DataArray")) {
        arrays.push_back(array);
        names.emplace_back(array.attribute("Name").value());
      }
    };
    collect("PointData");
    const std::size_t point_arrays = arrays.size();
    collect("CellData");
    const std::optional<RadiusArray> choice = find_radius_array(names, options_.radius_array);
    if (!choice) fail(offset(piece), missing_radius_message(names, options_.radius_array));
    const pugi::xml_node array = arrays[choice->index];
    const bool per_point = choice->index < point_arrays;
    const std::string what =
        std::string(per_point ? "<PointData>" : "<CellData>") + " DataArray '" + names[choice->index] + "'";
    if (radius_per_point_ && *radius_per_point_ != per_point)
      fail(offset(array), what + " gives the radius per " + (per_point ? "point" : "cell") +
                              "; an earlier piece gives it per " + (per_point ? "cell" : "point"));
    radius_per_point_ = per_point;
    const int64_t components = count(array, "NumberOfComponents", 1);
    if (components != 1)
      fail(offset(array),
           what + " has NumberOfComponents=" + std::to_string(components) + "; a radius needs 1");

    if (per_point) {
      for (double r : values<double>(array, static_cast<uint64_t>(points), what,
                                     "one per point, NumberOfPoints=" + std::to_string(points)))
        data.radius.push_back(r * choice->scale);
      return;
    }
    const std::vector<double> cell_radius =
        values<double>(array, static_cast<uint64_t>(verts + lines), what,
                       "one per cell, NumberOfVerts + NumberOfLines = " + std::to_string(verts + lines));
    for (int64_t line : edge_lines) data.edge_radius.push_back(cell_radius[verts + line] * choice->scale);
  }

  const Type& type_of(pugi::xml_node array, const std::string& what) const {
    const std::string_view name = array.attribute("type").value();
    for (const Type& type : kTypes)
      if (name == type.name) return type;
    fail(offset(array),
         what + " has unknown type '" + std::string(name) +
             "'; expected Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32 or Float64");
  }

  /// The `n` values of a DataArray in any format, as doubles (NaN and infinity rejected) or as integers
  /// (float types rejected). `reason` says where `n` comes from, for the message when the array differs.
  template <class T>
  std::vector<T> values(pugi::xml_node array, uint64_t n, const std::string& what,
                        const std::string& reason) const {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, int64_t>);
    const Type& type = type_of(array, what);
    if (std::is_same_v<T, int64_t> && type.kind == Type::kFloat)
      fail(offset(array), what + " has type " + type.name + "; expected an integer type");

    const std::string_view format = array.attribute("format").value();
    if (format == "ascii") return ascii<T>(array, n, what, reason);
    const uint64_t size = n * type.size;
    std::string bytes;
    if (format == "binary") {
      const auto [text, at] = text_of(array);
      const std::string_view trimmed = trim(text);
      const Stored stored{trimmed, at + static_cast<std::size_t>(trimmed.data() - text.data()), true};
      Decoded decoded = binary(stored, size, what, reason);
      if (decoded.end != trimmed.size())
        fail(stored.at + decoded.end,
             what + ": more data follows the " + std::to_string(size) + " bytes that its header gives");
      bytes = std::move(decoded.bytes);
    } else if (format == "appended") {
      if (!has_appended_) fail(offset(array), what + " is appended but the file has no <AppendedData>");
      const int64_t at =
          parse_int(array.attribute("offset").value(), source_, line_at(offset(array)), "offset");
      if (at < 0 || static_cast<uint64_t>(at) > appended_.size())
        fail(offset(array), what + ": offset=" + std::to_string(at) + " is outside the appended data (" +
                                std::to_string(appended_.size()) + " bytes)");
      const auto start = static_cast<std::size_t>(at);
      bytes =
          binary(Stored{appended_.substr(start), appended_at_ + start, appended_base64_}, size, what, reason)
              .bytes;
    } else {
      fail(offset(array),
           what + " has format '" + std::string(format) + "'; expected ascii, binary or appended");
    }

    std::vector<T> out;
    out.reserve(n);
    for (std::size_t i = 0; i < bytes.size(); i += type.size) {
      const uint64_t bits = load(bytes.data() + i, type.size);
      if constexpr (std::is_same_v<T, double>) {
        const double value = as_double(bits, type);
        if (!std::isfinite(value))
          fail(offset(array), what + ": value " + std::to_string(i / type.size) + " is not a finite number");
        out.push_back(value);
      } else {
        out.push_back(as_int(bits, type));
      }
    }
    return out;
  }

  template <class T>
  std::vector<T> ascii(pugi::xml_node array, uint64_t n, const std::string& what,
                       const std::string& reason) const {
    const auto [text, at] = text_of(array);
    const std::vector<std::string_view> tokens = split(text, " \t\r\n", true);
    if (tokens.size() != n)
      fail(offset(array), what + " holds " + std::to_string(tokens.size()) + " values; expected " +
                              std::to_string(n) + " (" + reason + ")");
    std::vector<T> out;
    out.reserve(tokens.size());
    std::size_t line = line_at(at);
    const char* counted = text.data();  // newlines before here are in `line`
    for (const std::string_view token : tokens) {
      for (; counted < token.data(); ++counted) line += *counted == '\n';
      if constexpr (std::is_same_v<T, double>)
        out.push_back(parse_double(token, source_, line, what.c_str()));
      else
        out.push_back(parse_int(token, source_, line, what.c_str()));
    }
    return out;
  }

  /// The element's character data and its byte offset in the file.
  static std::pair<std::string_view, std::size_t> text_of(pugi::xml_node element) {
    for (const pugi::xml_node child : element.children())
      if (child.type() == pugi::node_pcdata) return {child.value(), offset(child)};
    return {{}, offset(element)};
  }

  /// An unsigned integer of `size` bytes in the file's byte order.
  uint64_t load(const char* p, std::size_t size) const {
    uint64_t bits = 0;
    for (std::size_t k = 0; k < size; ++k)
      bits = bits << 8 | static_cast<unsigned char>(p[big_endian_ ? k : size - 1 - k]);
    return bits;
  }

  /// Characters (base64) or bytes (raw) that `n` stored bytes take.
  static std::size_t span(const Stored& s, uint64_t n) {
    return static_cast<std::size_t>(s.base64 ? (n + 2) / 3 * 4 : n);
  }

  /// The most bytes that the stored data from `pos` on could hold.
  static uint64_t capacity(const Stored& s, std::size_t pos) {
    const std::size_t left = pos < s.text.size() ? s.text.size() - pos : 0;
    return s.base64 ? left / 4 * 3 : left;
  }

  /// Byte offset in the file of decoded byte `byte` of the run that starts at `pos`.
  static std::size_t file_offset(const Stored& s, std::size_t pos, uint64_t byte) {
    return s.at + pos + static_cast<std::size_t>(s.base64 ? byte / 3 * 4 : byte);
  }

  /// The `n` bytes stored from `pos` on. In base64 they are a run of whole 4-character groups; with
  /// `whole_run` the run must end there, with the '=' padding that its length calls for.
  std::string take(const Stored& s, std::size_t pos, uint64_t n, bool whole_run,
                   const std::string& what) const {
    if (n > capacity(s, pos))
      fail(s.at + s.text.size(), what + ": the data ends here, short of the " + std::to_string(n) +
                                     " bytes expected from byte " + std::to_string(s.at + pos));
    if (!s.base64) return std::string(s.text.substr(pos, static_cast<std::size_t>(n)));

    std::string out;
    out.reserve(static_cast<std::size_t>(n) + 2);
    const std::size_t end = pos + span(s, n);
    for (std::size_t group = pos; group < end; group += 4) {
      uint32_t bits = 0;
      int padding = 0;
      for (std::size_t i = group; i < group + 4; ++i) {
        const char c = s.text[i];
        const int digit = base64_digit(c);
        if (c == '=' && i >= group + 2) {
          ++padding;
        } else if (digit < 0 || padding > 0) {
          fail(s.at + i, what + ": expected base64 data, found " + shown(c) + " (after " +
                             std::to_string(out.size()) + " of the " + std::to_string(n) +
                             " bytes expected)");
        }
        bits = bits << 6 | static_cast<uint32_t>(digit < 0 ? 0 : digit);
      }
      for (int b = 0; b < 3 - padding; ++b) out.push_back(static_cast<char>(bits >> (16 - 8 * b)));
      if (padding > 0 && out.size() < n)
        fail(s.at + group, what + ": the base64 data ends ('=' padding) after " + std::to_string(out.size()) +
                               " of the " + std::to_string(n) + " bytes expected");
    }
    if (whole_run && out.size() != n)
      fail(s.at + end, what + ": the base64 data runs on past the " + std::to_string(n) +
                           " bytes expected (no '=' padding where they end)");
    out.resize(static_cast<std::size_t>(n));
    return out;
  }

  /// The `n` data bytes of an array stored as VTK writes binary data: uncompressed, one run of
  /// [byte count][data]; compressed, a run of [blocks, block size, last block size, compressed sizes...]
  /// and then a run of the zlib blocks.
  Decoded binary(const Stored& s, uint64_t n, const std::string& what, const std::string& reason) const {
    const std::size_t word = header_size_;
    const std::string expected = std::to_string(n) + " bytes (" + reason + ")";
    if (!compressed_) {
      const uint64_t stated = load(take(s, 0, word, false, what).data(), word);
      if (stated != n)
        fail(s.at, what + ": the header gives " + std::to_string(stated) + " bytes; expected " + expected);
      return {take(s, 0, word + n, true, what).substr(word), span(s, word + n)};
    }

    const uint64_t blocks = load(take(s, 0, word, false, what).data(), word);
    if (blocks > capacity(s, 0) / word)
      fail(s.at, what + ": the compression header gives " + std::to_string(blocks) +
                     " blocks, more than the data could describe");
    const uint64_t header_bytes = (3 + blocks) * word;
    const std::string header = take(s, 0, header_bytes, true, what);
    const auto header_word = [&](uint64_t i) { return load(header.data() + i * word, word); };
    const std::size_t data_pos = span(s, header_bytes);
    const uint64_t room = capacity(s, data_pos);
    const uint64_t block_size = header_word(1);
    const uint64_t last_size = header_word(2);  // 0: the last block is a full one

    std::vector<uint64_t> packed_sizes, sizes;
    uint64_t packed_total = 0, total = 0;
    for (uint64_t b = 0; b < blocks; ++b) {
      const uint64_t packed = header_word(3 + b);
      const uint64_t size = b + 1 == blocks && last_size != 0 ? last_size : block_size;
      const std::size_t at = file_offset(s, 0, (3 + b) * word);
      if (packed > room - packed_total)
        fail(at, what + ": compressed block " + std::to_string(b) + " of " + std::to_string(packed) +
                     " bytes runs past the end of the data");
      if (size > packed * kMaxInflateRatio)
        fail(at, what + ": block " + std::to_string(b) + " claims " + std::to_string(size) + " bytes from " +
                     std::to_string(packed) + " compressed bytes, more than zlib can produce");
      packed_total += packed;
      total += size;
      packed_sizes.push_back(packed);
      sizes.push_back(size);
    }
    if (total != n)
      fail(s.at,
           what + ": the compression header gives " + std::to_string(total) + " bytes; expected " + expected);

    const std::string packed = take(s, data_pos, packed_total, true, what);
    // The output grows as blocks inflate, not to the header's total up front: a header may claim up to
    // 1032 bytes per compressed byte, and only the inflated data shows whether that is true.
    std::string out;
    std::size_t in_pos = 0;
    for (std::size_t b = 0; b < sizes.size(); ++b) {
      const std::string_view block(packed.data() + in_pos, static_cast<std::size_t>(packed_sizes[b]));
      const std::string problem = inflate_block(block, sizes[b], out);
      if (!problem.empty())
        fail(file_offset(s, data_pos, in_pos),
             what + ": compressed block " + std::to_string(b) + " " + problem);
      in_pos += block.size();
    }
    return {std::move(out), data_pos + span(s, packed_total)};
  }

  std::string_view bytes_;
  const std::string& source_;
  const ReadOptions& options_;
  bool big_endian_ = false;
  std::size_t header_size_ = 4;
  bool compressed_ = false;
  bool has_appended_ = false;
  std::string_view appended_;  ///< between the '_' and </AppendedData> (or the end of the file)
  std::size_t appended_at_ = 0;
  bool appended_base64_ = false;
  std::optional<bool> radius_per_point_;  ///< set by the first piece; the others must agree
  std::vector<std::size_t> newlines_;     ///< offsets of the XML part's line breaks, for line numbers
};

}  // namespace

CenterlineData parse_vtp(std::string_view bytes, const std::string& source, const ReadOptions& options) {
  return VtpReader(bytes, source, options).read();
}

}  // namespace vesselmesh
