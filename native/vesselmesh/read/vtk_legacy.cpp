// Legacy VTK (.vtk) centerline reader: versions 3.0 to 5.1, ASCII or BINARY (big-endian), POLYDATA with
// LINES or UNSTRUCTURED_GRID with line and poly-line cells. Every count is checked against the bytes that
// are left before anything is allocated, so a damaged file fails with a location instead of a crash.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vesselmesh/error.hpp"
#include "vesselmesh/read/radius_array.hpp"
#include "vesselmesh/read/read.hpp"
#include "vesselmesh/read/text.hpp"

namespace vesselmesh {

namespace {

/// A token for a message: short, and with non-printable bytes shown as '?', since after a wrong count in
/// a BINARY file the "keyword" is raw data.
std::string printable(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string out;
  for (char c : token.substr(0, kMax)) out += c >= 0x20 && c < 0x7f ? c : '?';
  if (token.size() > kMax) out += "...";
  return out;
}

/// `a * b`, or SIZE_MAX when that overflows (such a count fails the size check anyway).
std::size_t product(std::size_t a, std::size_t b) {
  return b != 0 && a > std::numeric_limits<std::size_t>::max() / b ? std::numeric_limits<std::size_t>::max()
                                                                   : a * b;
}

enum class NumberKind { kSigned, kUnsigned, kReal };

struct DataType {
  const char* name;
  std::size_t size;  ///< bytes per value in BINARY files
  NumberKind kind;
};

constexpr DataType kUnsignedChar{"unsigned_char", 1, NumberKind::kUnsigned};
constexpr DataType kInt{"int", 4, NumberKind::kSigned};
constexpr DataType kFloat{"float", 4, NumberKind::kReal};

// "long" is taken as 8 bytes, as written on LP64 systems; VTK writes vtkIdType arrays as 32-bit ints.
constexpr DataType kDataTypes[] = {
    kUnsignedChar,
    {"char", 1, NumberKind::kSigned},
    {"signed_char", 1, NumberKind::kSigned},
    {"unsigned_short", 2, NumberKind::kUnsigned},
    {"short", 2, NumberKind::kSigned},
    {"unsigned_int", 4, NumberKind::kUnsigned},
    kInt,
    {"unsigned_long", 8, NumberKind::kUnsigned},
    {"long", 8, NumberKind::kSigned},
    kFloat,
    {"double", 8, NumberKind::kReal},
    {"vtkidtype", 4, NumberKind::kSigned},
    {"vtktypeint8", 1, NumberKind::kSigned},
    {"vtktypeuint8", 1, NumberKind::kUnsigned},
    {"vtktypeint16", 2, NumberKind::kSigned},
    {"vtktypeuint16", 2, NumberKind::kUnsigned},
    {"vtktypeint32", 4, NumberKind::kSigned},
    {"vtktypeuint32", 4, NumberKind::kUnsigned},
    {"vtktypeint64", 8, NumberKind::kSigned},
    {"vtktypeuint64", 8, NumberKind::kUnsigned},
    {"vtktypefloat32", 4, NumberKind::kReal},
    {"vtktypefloat64", 8, NumberKind::kReal},
};

/// Walks the file as whitespace-separated tokens, line by line, and hands out the raw byte blocks of BINARY
/// data. A position ("pos") is a line number in an ASCII file and a byte offset in a BINARY one. Copies are
/// cheap, so an array's data can be revisited once it is known to be the one wanted.
class Tokenizer {
 public:
  Tokenizer(std::string_view bytes, const std::string& source)
      : bytes_(bytes), source_(&source), lines_(bytes), last_(bytes.substr(0, 0)) {}

  const std::string& source() const { return *source_; }
  bool binary() const { return binary_; }
  void set_binary() { binary_ = true; }

  /// The next whole line (the header lines), or InputError naming `what` at the end of the file.
  std::string_view header_line(const char* what) {
    std::string_view text;
    if (!lines_.next(text))
      throw InputError(source(), at_line(line_ + 1),
                       std::string("expected ") + what + ", found the end of the file");
    line_ = lines_before_ + lines_.number();
    last_ = text;
    return text;
  }

  /// The next token; false at the end of the file.
  bool next(std::string_view& token) {
    while (next_ == tokens_.size()) {
      std::string_view text;
      if (!lines_.next(text)) return false;
      tokens_ = split(text, " \t\r", true);
      next_ = 0;
      line_ = lines_before_ + lines_.number();
    }
    token = last_ = tokens_[next_++];
    return true;
  }

  /// The next token, or InputError "expected <what>" at the end of the file.
  std::string_view take(const std::string& what) {
    std::string_view token;
    if (!next(token)) fail_at_end("expected " + what + ", found the end of the file");
    return token;
  }

  /// `token` (the last one taken) as a count: an integer, not negative.
  std::size_t count(std::string_view token, const char* what) const {
    const int64_t n = parse_int(token, source(), line_, what);
    if (n < 0) fail(std::string(what) + " " + std::to_string(n) + " is negative");
    return static_cast<std::size_t>(n);
  }
  std::size_t count(const char* what) { return count(take(what), what); }

  /// Bytes after the last token: an upper bound on what ASCII data that follows it can hold.
  std::size_t bytes_after_token() const { return bytes_.size() - offset_of(last_) - last_.size(); }

  /// BINARY data: drops the rest of the current line and returns the `count` values of `size` bytes that
  /// start after it, moving past them. InputError at the block's first byte when the file is too short.
  std::string_view raw(std::size_t count, std::size_t size, const std::string& what) {
    const std::size_t start = base_ + lines_.offset();
    const std::size_t left = bytes_.size() - start;
    if (count > left / size)
      throw InputError(source(), at_byte(start),
                       "truncated " + what + ": " + std::to_string(count) + " values of " +
                           std::to_string(size) + " bytes need more than the " + std::to_string(left) +
                           " bytes left in the file");
    const std::string_view block = bytes_.substr(start, count * size);
    // Count the newlines inside the block so that line numbers stay true after it.
    lines_before_ = line_ + static_cast<std::size_t>(std::count(block.begin(), block.end(), '\n'));
    base_ = start + block.size();
    lines_ = LineCursor(bytes_.substr(base_));
    tokens_.clear();
    next_ = 0;
    last_ = bytes_.substr(base_, 0);
    return block;
  }

  /// Skips the rest of the current line and every line up to and including the next empty one
  /// (METADATA and INFORMATION blocks end that way).
  void skip_block() {
    tokens_.clear();
    next_ = 0;
    std::string_view text;
    while (lines_.next(text) && !trim(text).empty()) {
    }
    line_ = lines_before_ + lines_.number();
  }

  /// Line (ASCII) or byte offset (BINARY) of the last token.
  std::size_t pos() const { return binary_ ? offset_of(last_) : line_; }
  std::size_t line() const { return line_; }
  /// Byte offset of a piece of the file.
  std::size_t offset_of(std::string_view piece) const {
    return static_cast<std::size_t>(piece.data() - bytes_.data());
  }
  std::string where(std::size_t pos) const { return binary_ ? at_byte(pos) : at_line(pos); }
  std::string where() const { return where(pos()); }

  [[noreturn]] void fail(const std::string& what) const { throw InputError(source(), where(), what); }
  [[noreturn]] void fail_at(std::size_t pos, const std::string& what) const {
    throw InputError(source(), where(pos), what);
  }
  [[noreturn]] void fail_at_end(const std::string& what) const {
    throw InputError(source(), binary_ ? at_byte(bytes_.size()) : at_line(line_), what);
  }

 private:
  std::string_view bytes_;
  const std::string* source_;
  LineCursor lines_;                      ///< over bytes_ from base_ on
  std::size_t base_ = 0;                  ///< byte offset where lines_ starts
  std::size_t lines_before_ = 0;          ///< lines of the file before base_
  std::size_t line_ = 0;                  ///< line of the current line
  std::vector<std::string_view> tokens_;  ///< tokens of the current line
  std::size_t next_ = 0;                  ///< next of tokens_ to hand out
  std::string_view last_;                 ///< last token (or header line) handed out
  bool binary_ = false;
};

/// The data type named by the next token.
DataType read_data_type(Tokenizer& in) {
  const std::string_view token = in.take("a data type");
  const std::string name = lower(token);
  if (name == "bit") in.fail("bit arrays are not supported");
  for (const DataType& type : kDataTypes)
    if (name == type.name) return type;
  in.fail("unknown data type '" + printable(token) +
          "'; expected one such as float, double, int, unsigned_char or vtktypeint64");
}

/// `tuples` x `components` numbers of one type: ASCII tokens, or a big-endian BINARY block that is checked
/// against the bytes left before anything is read. Knows where each value came from.
class Values {
 public:
  Values(Tokenizer& in, DataType type, std::size_t tuples, std::size_t components, std::string what)
      : in_(in), type_(type), count_(product(tuples, components)), what_(std::move(what)) {
    if (in.binary()) {
      block_ = in.raw(count_, type.size, what_);
    } else if (count_ > in.bytes_after_token() / 2) {  // an ASCII value takes a separator and a digit
      in.fail(what_ + ": " + std::to_string(tuples) + " x " + std::to_string(components) +
              " values cannot fit in the " + std::to_string(in.bytes_after_token()) +
              " bytes left in the file");
    }
  }

  std::size_t done() const { return done_; }
  /// Line or byte offset of the value last read.
  std::size_t pos() const { return pos_; }

  /// The next value as a finite double.
  double real() {
    if (!in_.binary()) {
      const std::string_view token = next_token();
      if (type_.kind == NumberKind::kReal) return parse_double(token, in_.source(), pos_, what_.c_str());
      return static_cast<double>(parse_int(token, in_.source(), pos_, what_.c_str()));
    }
    const uint64_t bits = next_bits();
    if (type_.kind == NumberKind::kSigned) return static_cast<double>(signed_value(bits));
    if (type_.kind == NumberKind::kUnsigned) return static_cast<double>(bits);
    double value;
    if (type_.size == 4) {
      const auto narrow = static_cast<uint32_t>(bits);
      float f;
      std::memcpy(&f, &narrow, sizeof f);
      value = f;
    } else {
      std::memcpy(&value, &bits, sizeof value);
    }
    if (!std::isfinite(value)) in_.fail_at(pos_, what_ + " is not a finite number");
    return value;
  }

  /// The next value, of an integer type.
  int64_t integer() {
    if (!in_.binary()) return parse_int(next_token(), in_.source(), pos_, what_.c_str());
    const uint64_t bits = next_bits();
    if (type_.kind == NumberKind::kSigned) return signed_value(bits);
    if (bits > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()))
      in_.fail_at(pos_, what_ + ": value " + std::to_string(bits) + " is out of range");
    return static_cast<int64_t>(bits);
  }

  /// Moves past the values not read (a BINARY block is passed over whole on construction).
  void skip() {
    if (!in_.binary())
      while (done_ < count_) next_token();
  }

 private:
  std::string_view next_token() {
    std::string_view token;
    if (!in_.next(token))
      in_.fail_at_end(what_ + ": the file ends after " + std::to_string(done_) + " of " +
                      std::to_string(count_) + " values");
    ++done_;
    pos_ = in_.line();
    return token;
  }

  uint64_t next_bits() {
    const std::size_t at = done_ * type_.size;
    pos_ = in_.offset_of(block_) + at;
    ++done_;
    uint64_t bits = 0;
    for (std::size_t i = 0; i < type_.size; ++i)
      bits = bits << 8 | static_cast<unsigned char>(block_[at + i]);
    return bits;
  }

  int64_t signed_value(uint64_t bits) const {
    const unsigned shift = 64 - 8 * static_cast<unsigned>(type_.size);
    return static_cast<int64_t>(bits << shift) >> shift;
  }

  Tokenizer& in_;
  DataType type_;
  std::size_t count_;
  std::string what_;
  std::string_view block_;
  std::size_t done_ = 0;
  std::size_t pos_ = 0;
};

enum class Association { kNone, kPoints, kCells };

/// A POINT_DATA or CELL_DATA section: how many values each of its arrays has.
struct Attributes {
  std::size_t count;
  std::string where;
};

/// A point or cell data array met on the way; its values are read only if it is chosen as the radius.
struct ArrayInfo {
  std::string name;
  Association association;
  DataType type;
  std::size_t tuples;
  std::size_t components;
  std::string where;  ///< where it is declared
  Tokenizer data;     ///< positioned just before its values
};

/// Cells as offsets into one list of point ids, with the position each id was read from (so that an id
/// out of range can be reported once the number of points is known, whatever the order of sections).
struct CellList {
  std::string name;                 ///< LINES, VERTICES or CELLS
  std::vector<int64_t> offsets{0};  ///< cell c is ids[offsets[c]] .. ids[offsets[c + 1] - 1]
  std::vector<int64_t> ids;
  std::vector<std::size_t> id_pos;
  std::size_t size() const { return offsets.size() - 1; }
};

class Parser {
 public:
  Parser(std::string_view bytes, const std::string& source) : in_(bytes, source) {}

  CenterlineData parse(const ReadOptions& options) {
    read_header();
    std::string_view keyword;
    while (in_.next(keyword)) read_section(keyword);
    return assemble(options);
  }

 private:
  void read_header();
  void read_section(std::string_view keyword);
  void read_points();
  CellList read_cells(const char* name);
  CellList read_legacy_cells(const char* name);
  CellList read_offsets_connectivity(const char* name);
  DataType read_index_type(const std::string& what);
  void read_cell_types();
  void read_attributes(std::optional<Attributes>& section, const char* keyword, Association association);
  void read_scalars();
  void read_field();
  void skip_attribute(std::string_view keyword);
  void skip_lookup_table();
  void add_array(std::string name, DataType type, std::size_t tuples, std::size_t components,
                 std::string where);
  const Attributes& current(std::string_view keyword) const;
  const char* current_name() const {
    return association_ == Association::kPoints ? "POINT_DATA" : "CELL_DATA";
  }
  void expect(const char* keyword);
  CenterlineData assemble(const ReadOptions& options);

  /// Fails when a section appears a second time, rather than letting it replace the first.
  template <class T>
  void once(const std::optional<T>& section, const char* keyword) const {
    if (section) in_.fail(std::string("a second ") + keyword + " section");
  }

  Tokenizer in_;
  int version_major_ = 0;
  bool polydata_ = true;
  std::optional<std::vector<Vec3>> points_;
  std::optional<CellList> cells_;  ///< LINES of a POLYDATA, CELLS of an UNSTRUCTURED_GRID
  std::optional<std::size_t> vertex_cells_;
  std::optional<std::vector<uint8_t>> cell_types_;
  std::string cell_types_where_;
  std::optional<Attributes> point_data_;
  std::optional<Attributes> cell_data_;
  Association association_ = Association::kNone;
  std::vector<ArrayInfo> arrays_;
};

void Parser::read_header() {
  const std::string_view first = trim(in_.header_line("the header '# vtk DataFile Version X.Y'"));
  constexpr std::string_view kMagic = "# vtk datafile version";
  if (lower(first.substr(0, kMagic.size())) != kMagic)
    in_.fail("not a legacy VTK file: expected '# vtk DataFile Version X.Y', found '" + printable(first) +
             "'");
  const std::string_view version = trim(first.substr(kMagic.size()));
  const double number = parse_double(version, in_.source(), in_.line(), "the version");
  if (number < 3.0 || number > 5.1)
    in_.fail("unsupported version " + printable(version) + "; expected 3.0 to 5.1");
  version_major_ = static_cast<int>(number);

  in_.header_line("a title line");
  const std::string_view format = trim(in_.header_line("ASCII or BINARY"));
  if (lower(format) == "binary")
    in_.set_binary();
  else if (lower(format) != "ascii")
    in_.fail("expected ASCII or BINARY, found '" + printable(format) + "'");

  expect("DATASET");
  const std::string_view type = in_.take("a dataset type");
  if (lower(type) != "polydata" && lower(type) != "unstructured_grid")
    in_.fail("unknown dataset type '" + printable(type) + "'; expected POLYDATA or UNSTRUCTURED_GRID");
  polydata_ = lower(type) == "polydata";
}

void Parser::read_section(std::string_view keyword) {
  const std::string key = lower(keyword);
  if (key == "points") return read_points();
  if (polydata_ && key == "lines") {
    once(cells_, "LINES");
    cells_ = read_cells("LINES");
    return;
  }
  if (polydata_ && key == "vertices") {
    once(vertex_cells_, "VERTICES");
    vertex_cells_ = read_cells("VERTICES").size();
    return;
  }
  if (polydata_ && (key == "polygons" || key == "triangle_strips"))
    in_.fail(printable(keyword) + " describe a surface, not a centerline; expected LINES");
  if (!polydata_ && key == "cells") {
    once(cells_, "CELLS");
    cells_ = read_cells("CELLS");
    return;
  }
  if (!polydata_ && key == "cell_types") return read_cell_types();
  if (key == "point_data") return read_attributes(point_data_, "POINT_DATA", Association::kPoints);
  if (key == "cell_data") return read_attributes(cell_data_, "CELL_DATA", Association::kCells);
  if (key == "scalars") return read_scalars();
  if (key == "field") return read_field();
  if (key == "vectors" || key == "normals" || key == "tensors" || key == "texture_coordinates" ||
      key == "color_scalars")
    return skip_attribute(keyword);
  if (key == "lookup_table") return skip_lookup_table();
  if (key == "metadata" || key == "information") return in_.skip_block();
  in_.fail("unknown keyword '" + printable(keyword) + "' in " +
           (polydata_ ? "POLYDATA" : "UNSTRUCTURED_GRID"));
}

void Parser::expect(const char* keyword) {
  const std::string_view token = in_.take(keyword);
  if (lower(token) != lower(keyword))
    in_.fail(std::string("expected ") + keyword + ", found '" + printable(token) + "'");
}

void Parser::read_points() {
  once(points_, "POINTS");
  const std::size_t n = in_.count("the number of points");
  if (n > static_cast<std::size_t>(std::numeric_limits<int32_t>::max()))
    in_.fail(std::to_string(n) + " points are more than a centerline can index");
  Values values(in_, read_data_type(in_), n, 3, "point coordinate");
  std::vector<Vec3> points(n);
  for (Vec3& p : points)
    for (int k = 0; k < 3; ++k) p[k] = values.real();
  points_ = std::move(points);
}

CellList Parser::read_cells(const char* name) {
  // Version 5 files list cells as OFFSETS and CONNECTIVITY blocks; older ones as "k i0 .. ik-1" records.
  CellList cells = version_major_ >= 5 ? read_offsets_connectivity(name) : read_legacy_cells(name);
  cells.name = name;
  return cells;
}

CellList Parser::read_legacy_cells(const char* name) {
  const std::string where = in_.where();
  const std::size_t n = in_.count("the number of cells");
  const std::size_t size = in_.count("the size of the cell list");
  Values values(in_, kInt, size, 1, std::string(name) + " cell list");
  if (n > size)
    throw InputError(in_.source(), where,
                     std::string(name) + ": " + std::to_string(n) + " cells cannot fit in a list of " +
                         std::to_string(size) + " values");
  CellList cells;
  cells.offsets.reserve(n + 1);
  cells.ids.reserve(size - n);
  cells.id_pos.reserve(size - n);
  for (std::size_t c = 0; c < n; ++c) {
    if (values.done() == size)
      throw InputError(in_.source(), where,
                       std::string(name) + ": the list of " + std::to_string(size) +
                           " values ends inside cell " + std::to_string(c) + " of " + std::to_string(n));
    const int64_t k = values.integer();
    const std::size_t left = size - values.done();
    if (k < 0 || static_cast<uint64_t>(k) > left)
      in_.fail_at(values.pos(), std::string(name) + " cell " + std::to_string(c) + " has " +
                                    std::to_string(k) + " points, but the list has " + std::to_string(left) +
                                    " values left");
    for (int64_t j = 0; j < k; ++j) {
      cells.ids.push_back(values.integer());
      cells.id_pos.push_back(values.pos());
    }
    cells.offsets.push_back(static_cast<int64_t>(cells.ids.size()));
  }
  if (values.done() != size)
    throw InputError(in_.source(), where,
                     std::string(name) + " says its list has " + std::to_string(size) + " values, but its " +
                         std::to_string(n) + " cells use " + std::to_string(values.done()));
  return cells;
}

DataType Parser::read_index_type(const std::string& what) {
  const DataType type = read_data_type(in_);
  if (type.kind == NumberKind::kReal)
    in_.fail(what + " must have an integer type, found '" + type.name + "'");
  return type;
}

CellList Parser::read_offsets_connectivity(const char* name) {
  const std::size_t n_offsets = in_.count("the number of offsets");
  const std::size_t n_ids = in_.count("the connectivity size");
  const std::string what = std::string(name) + " OFFSETS";
  expect("OFFSETS");
  const std::string where = in_.where();
  Values offsets(in_, read_index_type(what), n_offsets, 1, what);
  CellList cells;
  cells.offsets.reserve(std::max<std::size_t>(n_offsets, 1));
  for (std::size_t i = 0; i < n_offsets; ++i) {
    const int64_t offset = offsets.integer();
    if (i == 0) {
      if (offset != 0) in_.fail_at(offsets.pos(), what + " must start at 0, found " + std::to_string(offset));
      continue;
    }
    if (offset < cells.offsets.back())
      in_.fail_at(offsets.pos(), what + " must not decrease: " + std::to_string(offset) + " follows " +
                                     std::to_string(cells.offsets.back()));
    if (static_cast<uint64_t>(offset) > n_ids)
      in_.fail_at(offsets.pos(), what + ": offset " + std::to_string(offset) +
                                     " is past the end of CONNECTIVITY (" + std::to_string(n_ids) +
                                     " values)");
    cells.offsets.push_back(offset);
  }
  if (static_cast<uint64_t>(cells.offsets.back()) != n_ids)
    throw InputError(in_.source(), where,
                     what + " end at " + std::to_string(cells.offsets.back()) + ", but CONNECTIVITY has " +
                         std::to_string(n_ids) + " values");

  const std::string ids_what = std::string(name) + " CONNECTIVITY";
  expect("CONNECTIVITY");
  Values ids(in_, read_index_type(ids_what), n_ids, 1, ids_what);
  cells.ids.reserve(n_ids);
  cells.id_pos.reserve(n_ids);
  for (std::size_t j = 0; j < n_ids; ++j) {
    cells.ids.push_back(ids.integer());
    cells.id_pos.push_back(ids.pos());
  }
  return cells;
}

void Parser::read_cell_types() {
  once(cell_types_, "CELL_TYPES");
  cell_types_where_ = in_.where();
  const std::size_t n = in_.count("the number of cell types");
  Values values(in_, kInt, n, 1, "CELL_TYPES");
  std::vector<uint8_t> types(n);
  for (std::size_t c = 0; c < n; ++c) {
    const int64_t type = values.integer();
    if (type < 1 || type > 4)
      in_.fail_at(values.pos(),
                  "cell " + std::to_string(c) + " has type " + std::to_string(type) +
                      "; a centerline takes only lines (3), poly-lines (4) and vertices (1, 2)");
    types[c] = static_cast<uint8_t>(type);
  }
  cell_types_ = std::move(types);
}

void Parser::read_attributes(std::optional<Attributes>& section, const char* keyword,
                             Association association) {
  once(section, keyword);
  const std::string where = in_.where();
  section = Attributes{in_.count((std::string("the ") + keyword + " count").c_str()), where};
  association_ = association;
}

const Attributes& Parser::current(std::string_view keyword) const {
  if (association_ == Association::kNone) in_.fail(printable(keyword) + " outside POINT_DATA or CELL_DATA");
  return association_ == Association::kPoints ? *point_data_ : *cell_data_;
}

void Parser::read_scalars() {
  const Attributes& section = current("SCALARS");
  const std::string name(in_.take("an array name"));
  const std::string where = in_.where();
  const DataType type = read_data_type(in_);
  std::size_t components = 1;
  std::string_view token = in_.take("LOOKUP_TABLE");
  if (lower(token) != "lookup_table") {  // an optional number of components comes first
    components = in_.count(token, "the number of components");
    token = in_.take("LOOKUP_TABLE");
  }
  if (lower(token) != "lookup_table") in_.fail("expected LOOKUP_TABLE, found '" + printable(token) + "'");
  in_.take("a lookup table name");
  add_array(name, type, section.count, components, where);
}

void Parser::read_field() {
  in_.take("a field name");
  const std::size_t n = in_.count("the number of FIELD arrays");
  for (std::size_t i = 0; i < n; ++i) {
    std::string_view name = in_.take("a FIELD array name");
    while (lower(name) == "metadata") {  // metadata of the previous array
      in_.skip_block();
      name = in_.take("a FIELD array name");
    }
    if (name == "NULL_ARRAY") continue;
    const std::string where = in_.where();
    const std::size_t components = in_.count("the number of components");
    const std::size_t tuples = in_.count("the number of tuples");
    const DataType type = read_data_type(in_);
    if (association_ == Association::kNone) {  // field data of the whole dataset, not per point or cell
      Values(in_, type, tuples, components, "FIELD array '" + std::string(name) + "'").skip();
      continue;
    }
    if (tuples != current("FIELD").count)
      throw InputError(in_.source(), where,
                       "FIELD array '" + std::string(name) + "' has " + std::to_string(tuples) +
                           " tuples, but " + current_name() + " has " +
                           std::to_string(current("FIELD").count));
    add_array(std::string(name), type, tuples, components, where);
  }
}

void Parser::skip_attribute(std::string_view keyword) {
  const std::string key = lower(keyword);
  const Attributes& section = current(keyword);
  in_.take("an array name");
  std::size_t components = key == "tensors" ? 9 : 3;
  DataType type = kFloat;
  if (key == "texture_coordinates") components = in_.count("the texture dimension");
  if (key == "color_scalars") {
    components = in_.count("the number of color components");
    if (in_.binary()) type = kUnsignedChar;  // colors are bytes in BINARY files, floats in ASCII ones
  } else {
    type = read_data_type(in_);
  }
  Values(in_, type, section.count, components, printable(keyword)).skip();
}

void Parser::skip_lookup_table() {
  in_.take("a lookup table name");
  const std::size_t size = in_.count("the lookup table size");
  // RGBA entries: bytes in BINARY files, floats in ASCII ones.
  Values(in_, in_.binary() ? kUnsignedChar : kFloat, size, 4, "LOOKUP_TABLE").skip();
}

void Parser::add_array(std::string name, DataType type, std::size_t tuples, std::size_t components,
                       std::string where) {
  if (components == 0) throw InputError(in_.source(), where, "array '" + name + "' has 0 components");
  ArrayInfo array{std::move(name), association_, type, tuples, components, std::move(where), in_};
  Values(in_, type, tuples, components, "array '" + array.name + "'").skip();
  arrays_.push_back(std::move(array));
}

CenterlineData Parser::assemble(const ReadOptions& options) {
  const std::string& source = in_.source();
  if (!points_) throw InputError(source, "", "no POINTS section");
  if (!cells_)
    throw InputError(source, "",
                     polydata_ ? "no LINES section: a centerline is made of line cells"
                               : "no CELLS section: a centerline is made of line cells");
  const CellList& cells = *cells_;
  const std::size_t n = points_->size();

  // CELL_DATA numbers the cells of a POLYDATA vertices first, then lines.
  const std::size_t first_cell = vertex_cells_.value_or(0);
  const std::size_t total_cells = first_cell + cells.size();
  if (!polydata_) {
    if (!cell_types_) throw InputError(source, "", "CELLS without CELL_TYPES");
    if (cell_types_->size() != cells.size())
      throw InputError(source, cell_types_where_,
                       "CELL_TYPES has " + std::to_string(cell_types_->size()) + " entries for " +
                           std::to_string(cells.size()) + " CELLS");
  }
  if (point_data_ && point_data_->count != n)
    throw InputError(source, point_data_->where,
                     "POINT_DATA has " + std::to_string(point_data_->count) + " values for " +
                         std::to_string(n) + " points");
  if (cell_data_ && cell_data_->count != total_cells)
    throw InputError(source, cell_data_->where,
                     "CELL_DATA has " + std::to_string(cell_data_->count) + " values for " +
                         std::to_string(total_cells) + " cells");
  for (std::size_t j = 0; j < cells.ids.size(); ++j)
    if (cells.ids[j] < 0 || static_cast<uint64_t>(cells.ids[j]) >= n)
      throw InputError(source, in_.where(cells.id_pos[j]),
                       cells.name + " refers to point " + std::to_string(cells.ids[j]) + ", but there are " +
                           std::to_string(n) + " points");

  CenterlineData data;
  data.points = std::move(*points_);
  std::vector<std::size_t> edge_cell;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (!polydata_ && (*cell_types_)[c] <= 2) continue;  // vertex cells carry no edges
    // A line or poly-line of k points joins consecutive points: k - 1 edges.
    for (int64_t j = cells.offsets[c]; j + 1 < cells.offsets[c + 1]; ++j) {
      data.edges.push_back({static_cast<int32_t>(cells.ids[j]), static_cast<int32_t>(cells.ids[j + 1])});
      edge_cell.push_back(first_cell + c);
    }
  }

  std::vector<std::string> names;
  for (const ArrayInfo& array : arrays_) names.push_back(array.name);
  const std::optional<RadiusArray> chosen = find_radius_array(names, options.radius_array);
  if (!chosen) throw InputError(source, "", missing_radius_message(names, options.radius_array));
  ArrayInfo& array = arrays_[chosen->index];
  if (array.components != 1)
    throw InputError(
        source, array.where,
        "array '" + array.name + "' has " + std::to_string(array.components) + " components; a radius has 1");
  Values values(array.data, array.type, array.tuples, 1, "array '" + array.name + "'");
  std::vector<double> radius(array.tuples);
  for (double& r : radius) r = values.real() * chosen->scale;
  if (array.association == Association::kPoints) {
    data.radius = std::move(radius);
  } else {
    data.edge_radius.reserve(edge_cell.size());
    for (std::size_t c : edge_cell) data.edge_radius.push_back(radius[c]);
  }
  return data;
}

}  // namespace

CenterlineData parse_vtk(std::string_view bytes, const std::string& source, const ReadOptions& options) {
  if (bytes.empty()) throw InputError(source, at_line(1), "the file is empty");
  return Parser(bytes, source).parse(options);
}

}  // namespace vesselmesh
