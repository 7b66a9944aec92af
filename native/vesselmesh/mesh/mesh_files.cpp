#include "vesselmesh/mesh/mesh_files.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "vesselmesh/error.hpp"
#include "vesselmesh/read/text.hpp"
#include "vesselmesh/write/buffered_file.hpp"

namespace vesselmesh {

namespace {

/// Hash of three integers (the bit patterns of a point's coordinates), for welding and for finding
/// coincident points.
struct BitsHash {
  template <typename T>
  std::size_t operator()(const std::array<T, 3>& key) const {
    uint64_t h = key[0];
    h = h * 0x9e3779b97f4a7c15ULL ^ key[1];
    h = h * 0x9e3779b97f4a7c15ULL ^ key[2];
    return static_cast<std::size_t>(h ^ h >> 29);
  }
};

std::string extension_of(const std::string& path) {
  return lower(std::filesystem::path(path).extension().string());
}

/// Appends polygon (v0 v1 … vk) as the triangles (v0 v1 v2), (v0 v2 v3), …; it has at least 3 vertices.
void add_fan(const std::vector<int32_t>& polygon, std::vector<Tri>& faces) {
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
}

// ---------------------------------------------------------------------------------------------------
// Writing

/// A float as four little-endian bytes.
void binary_float(BufferedFile& out, float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  out.little_endian(bits, sizeof bits);
}

/// A double as eight little-endian bytes.
void binary_double(BufferedFile& out, double value) {
  uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  out.little_endian(bits, sizeof bits);
}

/// The shortest decimal text that reads back as the same double, then `separator`.
void shortest_decimal(BufferedFile& out, double value, char separator) {
  char digits[40];
  char* end = std::to_chars(digits, digits + sizeof digits - 1, value).ptr;
  *end++ = separator;
  out.text(std::string_view(digits, static_cast<std::size_t>(end - digits)));
}

/// Refuses meshes that would make a file read_mesh rejects, or that the writers cannot index safely.
void check_writable(const TriMesh& mesh, const std::string& path, const WriteOptions& options) {
  for (const VertexProperty& property : mesh.vertex_properties)
    if (property.values.size() != mesh.vertices.size())
      throw std::runtime_error("cannot write '" + path + "': vertex property '" + property.name + "' has " +
                               std::to_string(property.values.size()) + " values for " +
                               std::to_string(mesh.vertices.size()) + " vertices");
  if (!options.colors.empty() && options.colors.size() != mesh.vertices.size())
    throw std::runtime_error("cannot write '" + path + "': " + std::to_string(options.colors.size()) +
                             " colours for " + std::to_string(mesh.vertices.size()) + " vertices");
  const auto vertex_count = static_cast<int64_t>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int32_t v : mesh.faces[f])
      if (v < 0 || v >= vertex_count)
        throw std::runtime_error("cannot write '" + path + "': face " + std::to_string(f) +
                                 " has vertex index " + std::to_string(v) + ", out of range for " +
                                 std::to_string(vertex_count) + " vertices");
}

/// `comments` as lines of a file's header, each after `prefix`, line breaks as spaces.
std::string comment_lines(const std::vector<std::string>& comments, const std::string& prefix) {
  std::string lines;
  for (std::string c : comments) {
    std::replace_if(
        c.begin(), c.end(), [](char x) { return x == '\n' || x == '\r'; }, ' ');
    lines += prefix + c + "\n";
  }
  return lines;
}

void write_ply(const TriMesh& mesh, const std::string& path, const WriteOptions& options) {
  for (const VertexProperty& property : mesh.vertex_properties)
    if (property.name.empty() || property.name.find_first_of(" \t\r\n") != std::string::npos)
      throw std::runtime_error("cannot write '" + path + "': vertex property name '" + property.name +
                               "' is empty or holds whitespace, which PLY headers cannot");
  // Float is what every PLY reader takes; double only where float would change the mesh (Blender's
  // PLY importer, MeshLab and the readers here take either).
  const bool exact = float_rounding(mesh).changes_mesh();
  const std::string coordinate = exact ? "double" : "float";
  const bool colors = !options.colors.empty();
  const int channels = colors ? (options.alpha ? 4 : 3) : 0;
  BufferedFile out(path);
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment VesselMesh\n" +
                       comment_lines(options.comments, "comment ") + "element vertex " +
                       std::to_string(mesh.vertices.size()) + "\n";
  for (const char* axis : {"x", "y", "z"}) header += "property " + coordinate + " " + axis + "\n";
  for (int c = 0; c < channels; ++c)
    header += std::string("property uchar ") + std::array{"red", "green", "blue", "alpha"}[c] + "\n";
  for (const VertexProperty& property : mesh.vertex_properties)
    header += "property float " + property.name + "\n";
  header += "element face " + std::to_string(mesh.faces.size()) +
            "\nproperty list uchar int vertex_indices\nend_header\n";
  out.text(header);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    for (int axis = 0; axis < 3; ++axis) {
      if (exact) {
        binary_double(out, mesh.vertices[v][axis]);
      } else {
        binary_float(out, static_cast<float>(mesh.vertices[v][axis]));
      }
    }
    for (int c = 0; c < channels; ++c) out.little_endian(options.colors[v][c], 1);
    for (const VertexProperty& property : mesh.vertex_properties) binary_float(out, property.values[v]);
  }
  for (const Tri& face : mesh.faces) {
    out.little_endian(3, 1);
    for (int32_t v : face) out.little_endian(static_cast<uint32_t>(v), 4);
  }
  out.close();
}

void write_mtl(const std::string& path, const std::string& material) {
  BufferedFile out(path);
  out.text("# VesselMesh\nnewmtl " + material + "\nKa 0 0 0\nKd 1 1 1\nKs 0.2 0.2 0.2\nNs 50\nd 1\nillum 2\n");
  out.close();
}

void write_obj(const TriMesh& mesh, const std::string& path, const WriteOptions& options) {
  if (options.material.find_first_of(" \t\r\n") != std::string::npos)
    throw std::runtime_error("cannot write '" + path + "': material name '" + options.material +
                             "' holds whitespace, which OBJ cannot");
  BufferedFile out(path);
  out.text("# VesselMesh\n" + comment_lines(options.comments, "# "));
  if (!options.material.empty()) {
    const std::filesystem::path library = std::filesystem::path(path).replace_extension(".mtl");
    write_mtl(library.string(), options.material);
    out.text("mtllib " + library.filename().string() + "\n");
  }
  const bool colors = !options.colors.empty();
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Vec3& p = mesh.vertices[v];
    out.text("v ");
    shortest_decimal(out, p.x(), ' ');
    shortest_decimal(out, p.y(), ' ');
    shortest_decimal(out, p.z(), colors ? ' ' : '\n');
    if (colors)
      for (int c = 0; c < 3; ++c) out.decimal(options.colors[v][c] / 255.0, 4, c < 2 ? ' ' : '\n');
  }
  if (!options.material.empty()) out.text("usemtl " + options.material + "\n");
  for (const Tri& face : mesh.faces) {
    out.text("f ");
    out.decimal(face[0] + int64_t{1}, ' ');
    out.decimal(face[1] + int64_t{1}, ' ');
    out.decimal(face[2] + int64_t{1}, '\n');
  }
  out.close();
}

void write_stl(const TriMesh& mesh, const std::string& path) {
  if (mesh.faces.size() > std::numeric_limits<uint32_t>::max())
    throw std::runtime_error("cannot write '" + path + "': binary STL holds at most 2^32-1 triangles");
  const FloatRounding rounding = float_rounding(mesh);
  if (rounding.changes_mesh())
    throw std::runtime_error(
        "cannot write '" + path + "': STL stores coordinates in single precision, which would make " +
        std::to_string(rounding.degenerate_faces) + " of " + std::to_string(mesh.faces.size()) +
        " triangles degenerate, turned over or tilted" +
        (rounding.merged_vertices > 0 ? " and merge " + std::to_string(rounding.merged_vertices) + " vertices" : "") +
        " (the surface lies far from the origin for its size); write PLY or OBJ instead, which keep the "
        "coordinates exact, or move the surface nearer the origin");
  BufferedFile out(path);
  // The header must not start with "solid", or readers may take the file for ASCII STL.
  std::string header = "VesselMesh binary STL";
  header.resize(80, ' ');
  out.text(header);
  out.little_endian(mesh.faces.size(), 4);
  for (const Tri& face : mesh.faces) {
    const Vec3& a = mesh.vertices[face[0]];
    const Vec3& b = mesh.vertices[face[1]];
    const Vec3& c = mesh.vertices[face[2]];
    const Vec3 cross = (b - a).cross(c - a);
    const double length = cross.norm();
    const Vec3 normal = length > 0 ? Vec3(cross / length) : Vec3(Vec3::Zero());
    for (const Vec3* p : {&normal, &a, &b, &c})
      for (int axis = 0; axis < 3; ++axis) binary_float(out, static_cast<float>((*p)[axis]));
    out.little_endian(0, 2);
  }
  out.close();
}

// ---------------------------------------------------------------------------------------------------
// PLY reading

enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

Type parse_type(std::string_view name, const std::string& path, std::size_t line) {
  struct Named {
    const char* name;
    Type type;
  };
  static const Named kTypes[] = {
      {"char", Type::kInt8},      {"int8", Type::kInt8},       {"uchar", Type::kUint8},
      {"uint8", Type::kUint8},    {"short", Type::kInt16},     {"int16", Type::kInt16},
      {"ushort", Type::kUint16},  {"uint16", Type::kUint16},   {"int", Type::kInt32},
      {"int32", Type::kInt32},    {"uint", Type::kUint32},     {"uint32", Type::kUint32},
      {"float", Type::kFloat32},  {"float32", Type::kFloat32}, {"double", Type::kFloat64},
      {"float64", Type::kFloat64}};
  for (const Named& t : kTypes)
    if (name == t.name) return t.type;
  throw InputError(path, at_line(line), "unknown property type '" + std::string(name) + "'");
}

std::size_t type_size(Type type) {
  switch (type) {
    case Type::kInt8:
    case Type::kUint8:
      return 1;
    case Type::kInt16:
    case Type::kUint16:
      return 2;
    case Type::kInt32:
    case Type::kUint32:
    case Type::kFloat32:
      return 4;
    case Type::kFloat64:
      return 8;
  }
  return 0;
}

bool is_integer(Type type) { return type != Type::kFloat32 && type != Type::kFloat64; }

enum class Encoding { kAscii, kLittleEndian, kBigEndian };

struct Property {
  std::string name;
  Type type = Type::kFloat32;  ///< the value's type; for a list, the items' type
  bool is_list = false;
  Type count_type = Type::kUint8;  ///< lists only
};

struct Element {
  std::string name;
  int64_t count = 0;
  std::size_t line = 0;  ///< of its header declaration, for messages
  std::vector<Property> properties;
};

struct Header {
  Encoding encoding = Encoding::kAscii;
  std::vector<Element> elements;
};

/// Reads the header up to and including end_header; `cursor` is then at the first data line or byte.
Header parse_ply_header(LineCursor& cursor, const std::string& path) {
  std::string_view line;
  if (!cursor.next(line) || trim(line) != "ply")
    throw InputError(path, at_line(1), "expected 'ply' on the first line (not a PLY file)");
  Header header;
  bool has_format = false;
  while (cursor.next(line)) {
    const std::size_t n = cursor.number();
    const std::vector<std::string_view> tokens = split(line, " \t", true);
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    if (tokens[0] == "end_header") {
      if (!has_format) throw InputError(path, at_line(n), "end_header before any 'format' line");
      return header;
    }
    if (tokens[0] == "format") {
      if (tokens.size() != 3) throw InputError(path, at_line(n), "expected 'format <encoding> 1.0'");
      if (tokens[1] == "ascii") {
        header.encoding = Encoding::kAscii;
      } else if (tokens[1] == "binary_little_endian") {
        header.encoding = Encoding::kLittleEndian;
      } else if (tokens[1] == "binary_big_endian") {
        header.encoding = Encoding::kBigEndian;
      } else {
        throw InputError(path, at_line(n),
                         "unknown format '" + std::string(tokens[1]) +
                             "'; expected ascii, binary_little_endian or binary_big_endian");
      }
      has_format = true;
    } else if (tokens[0] == "element") {
      if (tokens.size() != 3) throw InputError(path, at_line(n), "expected 'element <name> <count>'");
      const int64_t count = parse_int(tokens[2], path, n, "the element count");
      if (count < 0) throw InputError(path, at_line(n), "negative element count " + std::to_string(count));
      header.elements.push_back({std::string(tokens[1]), count, n, {}});
    } else if (tokens[0] == "property") {
      if (header.elements.empty()) throw InputError(path, at_line(n), "a property before any element");
      Property property;
      if (tokens.size() == 5 && tokens[1] == "list") {
        property.is_list = true;
        property.count_type = parse_type(tokens[2], path, n);
        property.type = parse_type(tokens[3], path, n);
        property.name = tokens[4];
        if (!is_integer(property.count_type))
          throw InputError(path, at_line(n),
                           "the count type of list '" + property.name + "' is not an integer type");
      } else if (tokens.size() == 3 && tokens[1] != "list") {
        property.type = parse_type(tokens[1], path, n);
        property.name = tokens[2];
      } else {
        throw InputError(
            path, at_line(n),
            "expected 'property <type> <name>' or 'property list <count type> <item type> <name>'");
      }
      header.elements.back().properties.push_back(property);
    } else {
      throw InputError(path, at_line(n), "unknown header keyword '" + std::string(tokens[0]) + "'");
    }
  }
  throw InputError(path, at_line(cursor.number()), "the header ends without 'end_header'");
}

/// What the data means to the mesh: where each vertex property goes and which face list holds indices.
struct Layout {
  const Element* vertex = nullptr;
  const Element* face = nullptr;
  std::vector<int> vertex_slot;  ///< per vertex property: 0-2 x y z, 3+k vertex_properties[k], -1 skipped
  std::size_t face_list = 0;     ///< index of the vertex index list among the face properties
};

Layout plan_layout(const Header& header, TriMesh& mesh, const std::string& path) {
  Layout layout;
  for (const Element& element : header.elements) {
    const Element** role = element.name == "vertex" ? &layout.vertex
                           : element.name == "face" ? &layout.face
                                                    : nullptr;
    if (role == nullptr) continue;
    if (*role != nullptr)
      throw InputError(path, at_line(element.line), "a second '" + element.name + "' element");
    *role = &element;
  }
  if (layout.vertex == nullptr) throw InputError(path, "", "the header declares no 'vertex' element");
  const Element& vertex = *layout.vertex;
  if (vertex.count > std::numeric_limits<int32_t>::max())
    throw InputError(
        path, at_line(vertex.line),
        std::to_string(vertex.count) + " vertices are more than 32-bit face indices can address");
  bool has_axis[3] = {false, false, false};
  for (const Property& property : vertex.properties) {
    const std::size_t axis =
        property.name.size() == 1 ? std::string_view("xyz").find(property.name[0]) : std::string_view::npos;
    int slot = -1;
    if (property.is_list) {
      // Lists on vertices (texture coordinates per corner and the like) have no place in a TriMesh.
    } else if (axis != std::string_view::npos && !has_axis[axis]) {
      has_axis[axis] = true;
      slot = static_cast<int>(axis);
    } else {
      slot = 3 + static_cast<int>(mesh.vertex_properties.size());
      mesh.vertex_properties.push_back({property.name, {}});
    }
    layout.vertex_slot.push_back(slot);
  }
  for (int axis = 0; axis < 3; ++axis)
    if (!has_axis[axis])
      throw InputError(path, at_line(vertex.line),
                       std::string("the vertex element has no scalar '") + "xyz"[axis] + "' property");

  if (layout.face != nullptr) {
    const std::vector<Property>& properties = layout.face->properties;
    layout.face_list = properties.size();
    for (std::size_t p = 0; p < properties.size() && layout.face_list == properties.size(); ++p)
      if (properties[p].is_list &&
          (properties[p].name == "vertex_indices" || properties[p].name == "vertex_index"))
        layout.face_list = p;
    if (layout.face_list == properties.size())
      throw InputError(path, at_line(layout.face->line), "the face element has no vertex_indices list");
    if (!is_integer(properties[layout.face_list].type))
      throw InputError(path, at_line(layout.face->line),
                       "the face vertex indices are not of an integer type");
  }
  return layout;
}

/// Rejects element counts that the bytes after the header cannot hold, before anything is allocated.
/// An entry takes at least its fixed-size values (binary) or one character and a separator per value
/// (ascii), each list counting as its count alone.
void check_counts_fit(const Header& header, std::size_t available, const std::string& path) {
  for (const Element& element : header.elements) {
    std::size_t least = 0;
    for (const Property& property : element.properties)
      least += header.encoding == Encoding::kAscii
                   ? 2
                   : type_size(property.is_list ? property.count_type : property.type);
    if (least == 0) continue;
    if (static_cast<uint64_t>(element.count) > available / least)
      throw InputError(path, at_line(element.line),
                       "element '" + element.name + "' declares " + std::to_string(element.count) +
                           " entries, more than the " + std::to_string(available) +
                           " bytes after the header can hold");
    available -= static_cast<std::size_t>(element.count) * least;
  }
}

std::string entry_name(const Element& element, int64_t index) {
  return element.name + " " + std::to_string(index);
}

/// Values of ascii PLY data: one element entry per line, whitespace-separated.
class AsciiSource {
 public:
  AsciiSource(LineCursor& cursor, const std::string& path) : cursor_(cursor), path_(path) {}

  void begin(const Element& element, int64_t index) {
    element_ = &element;
    index_ = index;
    std::string_view line;
    do {
      if (!cursor_.next(line))
        throw InputError(path_, at_line(cursor_.number() + 1),
                         "expected " + entry_name(element, index) + " of " + std::to_string(element.count) +
                             ", found the end of the file");
      tokens_ = split(line, " \t", true);
    } while (tokens_.empty());
    next_ = 0;
  }

  double real(Type, const Property& property) {
    return parse_double(take(property.name), path_, line(), property.name.c_str());
  }

  int64_t integer(Type, const Property& property) {
    return parse_int(take(property.name), path_, line(), property.name.c_str());
  }

  void skip(Type, const Property& property) { take(property.name); }

  /// Rejects a list count that is negative or longer than the rest of the line.
  void check_list(int64_t count, Type, const Property& property) {
    if (count < 0 || static_cast<uint64_t>(count) > tokens_.size() - next_)
      throw InputError(path_, where(),
                       "list '" + property.name + "' of " + entry_name(*element_, index_) + " has " +
                           std::to_string(count) + " items, but the line holds " +
                           std::to_string(tokens_.size() - next_) + " more values");
  }

  void end() {
    if (next_ < tokens_.size())
      throw InputError(path_, where(),
                       "more values on the line of " + entry_name(*element_, index_) +
                           " than the header declares for '" + element_->name + "'");
  }

  std::string where() const { return at_line(line()); }

 private:
  std::size_t line() const { return cursor_.number(); }

  std::string_view take(const std::string& name) {
    if (next_ == tokens_.size())
      throw InputError(path_, where(),
                       "expected a value for '" + name + "' of " + entry_name(*element_, index_) +
                           ", found the end of the line");
    return tokens_[next_++];
  }

  LineCursor& cursor_;
  const std::string& path_;
  const Element* element_ = nullptr;
  int64_t index_ = 0;
  std::vector<std::string_view> tokens_;
  std::size_t next_ = 0;
};

/// Values of binary PLY data in either byte order, bounds-checked.
class BinarySource {
 public:
  BinarySource(std::string_view bytes, std::size_t offset, bool big_endian, const std::string& path)
      : bytes_(bytes), pos_(offset), last_(offset), big_endian_(big_endian), path_(path) {}

  void begin(const Element& element, int64_t index) {
    element_ = &element;
    index_ = index;
  }

  double real(Type type, const Property& property) {
    const uint64_t bits = load(type, property);
    switch (type) {
      case Type::kInt8:
        return static_cast<int8_t>(bits);
      case Type::kUint8:
        return static_cast<uint8_t>(bits);
      case Type::kInt16:
        return static_cast<int16_t>(bits);
      case Type::kUint16:
        return static_cast<uint16_t>(bits);
      case Type::kInt32:
        return static_cast<int32_t>(bits);
      case Type::kUint32:
        return static_cast<uint32_t>(bits);
      case Type::kFloat32: {
        const auto narrow = static_cast<uint32_t>(bits);
        float value;
        std::memcpy(&value, &narrow, sizeof value);
        return value;
      }
      case Type::kFloat64: {
        double value;
        std::memcpy(&value, &bits, sizeof value);
        return value;
      }
    }
    return 0;
  }

  /// Integer types only (the header checks), which a double holds exactly.
  int64_t integer(Type type, const Property& property) { return static_cast<int64_t>(real(type, property)); }

  void skip(Type type, const Property& property) { load(type, property); }

  void check_list(int64_t count, Type type, const Property& property) {
    const std::size_t left = bytes_.size() - pos_;
    if (count < 0 || static_cast<uint64_t>(count) > left / type_size(type))
      throw InputError(path_, where(),
                       "list '" + property.name + "' of " + entry_name(*element_, index_) + " has " +
                           std::to_string(count) + " items, but only " + std::to_string(left) +
                           " bytes remain");
  }

  void end() {}

  /// The offset of the value read last.
  std::string where() const { return at_byte(last_); }

 private:
  uint64_t load(Type type, const Property& property) {
    const std::size_t size = type_size(type);
    if (bytes_.size() - pos_ < size)
      throw InputError(path_, at_byte(pos_),
                       "the file ends inside " + entry_name(*element_, index_) + " ('" + property.name +
                           "'): truncated data");
    const auto* p = reinterpret_cast<const unsigned char*>(bytes_.data() + pos_);
    uint64_t bits = 0;
    for (std::size_t i = 0; i < size; ++i) bits = bits << 8 | p[big_endian_ ? i : size - 1 - i];
    last_ = pos_;
    pos_ += size;
    return bits;
  }

  std::string_view bytes_;
  std::size_t pos_;
  std::size_t last_;
  bool big_endian_;
  const std::string& path_;
  const Element* element_ = nullptr;
  int64_t index_ = 0;
};

template <class Source>
void skip_property(Source& source, const Property& property) {
  if (!property.is_list) {
    source.skip(property.type, property);
    return;
  }
  const int64_t count = source.integer(property.count_type, property);
  source.check_list(count, property.type, property);
  for (int64_t i = 0; i < count; ++i) source.skip(property.type, property);
}

/// Reads every element entry in header order. A Source (AsciiSource, BinarySource) yields the values:
/// real() for scalars, integer() for list counts and indices, skip() for values the mesh has no place for;
/// check_list() rejects a list count the rest of the data cannot hold; where() names the line or byte of
/// the value read last.
template <class Source>
void read_ply_data(const Header& header, const Layout& layout, Source& source, TriMesh& mesh,
                   const std::string& path) {
  const int64_t vertex_count = layout.vertex->count;
  std::vector<int32_t> polygon;
  for (const Element& element : header.elements) {
    // An element without properties has no data; skipping it also keeps a huge count from spinning.
    if (element.properties.empty()) continue;
    for (int64_t i = 0; i < element.count; ++i) {
      source.begin(element, i);
      if (&element == layout.vertex) {
        for (std::size_t p = 0; p < element.properties.size(); ++p) {
          const Property& property = element.properties[p];
          const int slot = layout.vertex_slot[p];
          if (slot < 0) {
            skip_property(source, property);
            continue;
          }
          const double value = source.real(property.type, property);
          if (slot >= 3) {
            mesh.vertex_properties[slot - 3].values[i] = static_cast<float>(value);
          } else if (!std::isfinite(value)) {
            throw InputError(
                path, source.where(),
                "vertex " + std::to_string(i) + ": " + property.name + " is not a finite number");
          } else {
            mesh.vertices[i][slot] = value;
          }
        }
      } else if (&element == layout.face) {
        for (std::size_t p = 0; p < element.properties.size(); ++p) {
          const Property& property = element.properties[p];
          if (p != layout.face_list) {
            skip_property(source, property);
            continue;
          }
          const int64_t count = source.integer(property.count_type, property);
          if (count < 3)
            throw InputError(path, source.where(),
                             "face " + std::to_string(i) + " has " + std::to_string(count) +
                                 " vertices; a face needs at least 3");
          source.check_list(count, property.type, property);
          polygon.clear();
          for (int64_t k = 0; k < count; ++k) {
            const int64_t v = source.integer(property.type, property);
            if (v < 0 || v >= vertex_count)
              throw InputError(path, source.where(),
                               "face " + std::to_string(i) + ": vertex index " + std::to_string(v) +
                                   " is out of range for " + std::to_string(vertex_count) + " vertices");
            polygon.push_back(static_cast<int32_t>(v));
          }
          add_fan(polygon, mesh.faces);
        }
      } else {
        for (const Property& property : element.properties) skip_property(source, property);
      }
      source.end();
    }
  }
}

TriMesh read_ply(std::string_view bytes, const std::string& path) {
  LineCursor cursor(bytes);
  const Header header = parse_ply_header(cursor, path);
  TriMesh mesh;
  const Layout layout = plan_layout(header, mesh, path);
  const std::size_t data_offset = cursor.offset();
  // The last ascii value needs no separator after it.
  const std::size_t available = bytes.size() - data_offset + (header.encoding == Encoding::kAscii ? 1 : 0);
  check_counts_fit(header, available, path);

  const auto vertex_count = static_cast<std::size_t>(layout.vertex->count);
  mesh.vertices.resize(vertex_count);
  for (VertexProperty& property : mesh.vertex_properties) property.values.resize(vertex_count);
  if (layout.face != nullptr) mesh.faces.reserve(static_cast<std::size_t>(layout.face->count));

  if (header.encoding == Encoding::kAscii) {
    AsciiSource source(cursor, path);
    read_ply_data(header, layout, source, mesh, path);
  } else {
    BinarySource source(bytes, data_offset, header.encoding == Encoding::kBigEndian, path);
    read_ply_data(header, layout, source, mesh, path);
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------------
// OBJ reading

/// The 0-based vertex of an `f` token (`i`, `i/t`, `i//n`, `i/t/n`); negative indices count back from the
/// last vertex defined so far.
int32_t obj_vertex(std::string_view token, std::size_t defined, const std::string& path, std::size_t line) {
  const int64_t index = parse_int(token.substr(0, token.find('/')), path, line, "a vertex index");
  const auto count = static_cast<int64_t>(defined);
  const int64_t resolved = index < 0 ? count + index : index - 1;
  if (index == 0 || resolved < 0 || resolved >= count)
    throw InputError(path, at_line(line),
                     "vertex index " + std::to_string(index) + " is out of range: " + std::to_string(count) +
                         " vertices are defined before this line");
  return static_cast<int32_t>(resolved);
}

TriMesh read_obj(std::string_view text, const std::string& path) {
  TriMesh mesh;
  LineCursor cursor(text);
  std::string_view line;
  std::vector<int32_t> polygon;
  while (cursor.next(line)) {
    const std::size_t n = cursor.number();
    const std::vector<std::string_view> tokens = split(line.substr(0, line.find('#')), " \t", true);
    if (tokens.empty()) continue;
    if (tokens[0] == "v") {
      if (tokens.size() < 4) throw InputError(path, at_line(n), "expected 'v x y z'");
      const double x = parse_double(tokens[1], path, n, "x");
      const double y = parse_double(tokens[2], path, n, "y");
      const double z = parse_double(tokens[3], path, n, "z");
      if (mesh.vertices.size() == static_cast<std::size_t>(std::numeric_limits<int32_t>::max()))
        throw InputError(path, at_line(n), "more vertices than 32-bit face indices can address");
      mesh.vertices.emplace_back(x, y, z);
    } else if (tokens[0] == "f") {
      if (tokens.size() < 4)
        throw InputError(
            path, at_line(n),
            "a face with " + std::to_string(tokens.size() - 1) + " vertices; a face needs at least 3");
      polygon.clear();
      for (std::size_t k = 1; k < tokens.size(); ++k)
        polygon.push_back(obj_vertex(tokens[k], mesh.vertices.size(), path, n));
      add_fan(polygon, mesh.faces);
    }
  }
  if (mesh.vertices.empty()) throw InputError(path, "", "no vertices ('v' lines): not an OBJ mesh");
  return mesh;
}

// ---------------------------------------------------------------------------------------------------
// STL reading

/// Gives bit-identical positions one vertex, so that the triangle soup of an STL file becomes a mesh
/// again (and a closed surface reads back closed).
class Welder {
 public:
  Welder(TriMesh& mesh, std::size_t expected) : mesh_(mesh) { index_.reserve(expected); }

  int32_t add(const Vec3& p) {
    Key key;
    for (int axis = 0; axis < 3; ++axis) {
      const double value = p[axis] + 0.0;  // -0 + 0 is +0: the two zeros are one position
      std::memcpy(&key[axis], &value, sizeof value);
    }
    const auto [it, inserted] = index_.try_emplace(key, static_cast<int32_t>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.push_back(p);
    return it->second;
  }

 private:
  using Key = std::array<uint64_t, 3>;

  TriMesh& mesh_;
  std::unordered_map<Key, int32_t, BitsHash> index_;
};

uint32_t little_endian_u32(std::string_view bytes, std::size_t offset) {
  uint32_t value = 0;
  for (std::size_t i = 4; i-- > 0;) value = value << 8 | static_cast<unsigned char>(bytes[offset + i]);
  return value;
}

float little_endian_float(std::string_view bytes, std::size_t offset) {
  const uint32_t bits = little_endian_u32(bytes, offset);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// The triangle count of a binary STL file, or -1 when the size is not exactly 84 + 50 per triangle.
int64_t binary_stl_count(std::string_view bytes) {
  if (bytes.size() < 84) return -1;
  const uint32_t count = little_endian_u32(bytes, 80);
  return bytes.size() == 84 + 50 * uint64_t{count} ? int64_t{count} : -1;
}

TriMesh read_binary_stl(std::string_view bytes, std::size_t count, const std::string& path) {
  TriMesh mesh;
  mesh.faces.reserve(count);
  Welder welder(mesh, count / 2);
  for (std::size_t t = 0; t < count; ++t) {
    const std::size_t record = 84 + 50 * t;
    Tri face;
    for (int corner = 0; corner < 3; ++corner) {
      Vec3 p;
      for (int axis = 0; axis < 3; ++axis) {
        const std::size_t offset = record + 12 + 12 * corner + 4 * axis;
        p[axis] = little_endian_float(bytes, offset);
        if (!std::isfinite(p[axis]))
          throw InputError(path, at_byte(offset),
                           "triangle " + std::to_string(t) + ": vertex " + std::to_string(corner) +
                               " is not a finite number");
      }
      face[corner] = welder.add(p);
    }
    mesh.faces.push_back(face);
  }
  return mesh;
}

TriMesh read_ascii_stl(std::string_view text, const std::string& path) {
  TriMesh mesh;
  Welder welder(mesh, 0);
  LineCursor cursor(text);
  std::string_view line;
  std::vector<int32_t> polygon;
  std::size_t facet_line = 0;  // the open facet's line; 0 outside facets
  while (cursor.next(line)) {
    const std::size_t n = cursor.number();
    const std::vector<std::string_view> tokens = split(line, " \t", true);
    if (tokens.empty()) continue;
    const std::string keyword = lower(tokens[0]);
    const bool in_facet = facet_line != 0;
    if (keyword == "facet" && !in_facet) {
      facet_line = n;
      polygon.clear();
    } else if (keyword == "vertex" && in_facet) {
      if (tokens.size() != 4) throw InputError(path, at_line(n), "expected 'vertex x y z'");
      const Vec3 p(parse_double(tokens[1], path, n, "x"), parse_double(tokens[2], path, n, "y"),
                   parse_double(tokens[3], path, n, "z"));
      polygon.push_back(welder.add(p));
    } else if (keyword == "endfacet" && in_facet) {
      if (polygon.size() < 3)
        throw InputError(
            path, at_line(n),
            "the facet has " + std::to_string(polygon.size()) + " vertices; a facet needs at least 3");
      add_fan(polygon, mesh.faces);
      facet_line = 0;
    } else if (!((keyword == "outer" || keyword == "endloop") && in_facet) &&
               !((keyword == "solid" || keyword == "endsolid") && !in_facet)) {
      throw InputError(
          path, at_line(n),
          "unexpected '" + std::string(tokens[0]) + "' " + (in_facet ? "inside a facet" : "outside a facet"));
    }
  }
  if (facet_line != 0)
    throw InputError(path, at_line(cursor.number()),
                     "the file ends inside the facet that starts at line " + std::to_string(facet_line));
  return mesh;
}

TriMesh read_stl(std::string_view bytes, const std::string& path) {
  const int64_t count = binary_stl_count(bytes);
  if (count >= 0) return read_binary_stl(bytes, static_cast<std::size_t>(count), path);
  std::string_view first_line;
  for (LineCursor cursor(bytes); first_line.empty() && cursor.next(first_line);)
    first_line = trim(first_line);
  if (lower(first_line.substr(0, 5)) != "solid") {
    const std::string binary_note = bytes.size() < 84 ? "shorter than the 84 bytes of a binary STL header"
                                                      : "not 84 + 50·n bytes for the " +
                                                            std::to_string(little_endian_u32(bytes, 80)) +
                                                            " triangles its header declares";
    throw InputError(path, at_byte(0),
                     "neither binary STL (the file's " + std::to_string(bytes.size()) + " bytes are " +
                         binary_note + ") nor ASCII STL (it does not start with 'solid')");
  }
  return read_ascii_stl(bytes, path);
}

}  // namespace

FloatRounding float_rounding(const TriMesh& mesh) {
  constexpr double kCos30 = 0.8660254037844386;
  using Key = std::array<uint32_t, 3>;
  const std::size_t n = mesh.vertices.size();
  std::vector<Vec3> rounded(n);
  std::vector<Key> keys(n);
  // The first vertex of each rounded position, in an open-addressing table of vertex ids: a node per
  // vertex in a std::unordered_map took 3 s of writing an 18-million-triangle surface.
  std::size_t size = 16;
  while (size < 2 * n) size *= 2;
  std::vector<int64_t> first(size, -1);
  FloatRounding result;
  for (std::size_t v = 0; v < n; ++v) {
    Key& key = keys[v];
    for (int axis = 0; axis < 3; ++axis) {
      const float value = static_cast<float>(mesh.vertices[v][axis]) + 0.0f;  // one zero, not two
      std::memcpy(&key[axis], &value, sizeof value);
      rounded[v][axis] = value;
    }
    std::size_t slot = BitsHash{}(key) & (size - 1);
    while (first[slot] >= 0 && keys[first[slot]] != key) slot = (slot + 1) & (size - 1);
    if (first[slot] < 0)
      first[slot] = static_cast<int64_t>(v);
    else if (mesh.vertices[first[slot]] != mesh.vertices[v])
      ++result.merged_vertices;
  }
  for (const Tri& f : mesh.faces) {
    const Vec3 exact = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    if (exact == Vec3::Zero()) continue;  // degenerate as it is: float takes nothing from it
    const Vec3 single = (rounded[f[1]] - rounded[f[0]]).cross(rounded[f[2]] - rounded[f[0]]);
    // Lost, turned over, or tilted by more than 30° (a face flattened onto a plane of float steps).
    if (single.dot(exact) <= kCos30 * single.norm() * exact.norm()) ++result.degenerate_faces;
  }
  return result;
}

void write_mesh(const TriMesh& mesh, const std::string& path, const WriteOptions& options) {
  const std::string extension = extension_of(path);
  if (extension != ".ply" && extension != ".obj" && extension != ".stl")
    throw std::runtime_error("cannot write '" + path + "': unknown mesh extension '" + extension +
                             "'; expected .ply, .obj or .stl");
  check_writable(mesh, path, options);
  if (extension == ".ply") {
    write_ply(mesh, path, options);
  } else if (extension == ".obj") {
    write_obj(mesh, path, options);
  } else {
    write_stl(mesh, path);
  }
}

std::vector<std::string> read_mesh_comments(const std::string& path) {
  const std::string extension = extension_of(path);
  std::vector<std::string> comments;
  if (extension != ".ply" && extension != ".obj") return comments;
  const std::string prefix = extension == ".ply" ? "comment " : "# ";
  std::ifstream in(path, std::ios::binary);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "end_header" || line.rfind("v ", 0) == 0) break;
    if (line.rfind(prefix, 0) == 0 && line != prefix + "VesselMesh")
      comments.push_back(line.substr(prefix.size()));
  }
  return comments;
}

TriMesh read_mesh(const std::string& path) {
  const std::string extension = extension_of(path);
  if (extension != ".ply" && extension != ".obj" && extension != ".stl")
    throw InputError(path, "", "unknown mesh extension '" + extension + "'; expected .ply, .obj or .stl");
  const std::string bytes = read_file(path);
  if (extension == ".ply") return read_ply(bytes, path);
  if (extension == ".obj") return read_obj(bytes, path);
  return read_stl(bytes, path);
}

}  // namespace vesselmesh
