#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "vesselmesh/error.hpp"
#include "vesselmesh/read/radius_array.hpp"
#include "vesselmesh/read/read.hpp"
#include "vesselmesh/read/text.hpp"

namespace vesselmesh {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

/// One table: its header row, then its data rows one at a time, each checked against the header.
class Table {
 public:
  Table(std::string_view text, const std::string& source, const char* kind) : cursor_(text), source_(source) {
    std::string_view header;
    do {
      if (!cursor_.next(header))
        throw InputError(source, "", std::string("empty ") + kind + " table: no header row");
    } while (trim(header).empty());
    header_line_ = cursor_.number();
    // The header decides the separator: ';' (VesselGraph, European locales) wins over ','.
    separator_ = header.find(';') != std::string_view::npos ? ";" : ",";
    for (std::string_view name : split(header, separator_, false)) {
      name = trim(name);
      if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
        name = name.substr(1, name.size() - 2);
      names_.emplace_back(name);
    }
  }

  const std::string& source() const { return source_; }
  const std::vector<std::string>& names() const { return names_; }
  std::size_t line() const { return cursor_.number(); }

  /// Index of the column named `wanted` (lower case), matched case-insensitively.
  std::optional<std::size_t> column(const char* wanted) const {
    for (std::size_t i = 0; i < names_.size(); ++i)
      if (lower(names_[i]) == wanted) return i;
    return std::nullopt;
  }

  /// The first set of columns that are all present, matched case-insensitively; else an InputError
  /// listing what was expected and what the header has.
  template <std::size_t K>
  std::array<std::size_t, K> columns(std::initializer_list<std::array<const char*, K>> alternatives) const {
    std::string expected;
    for (const auto& names : alternatives) {
      std::array<std::size_t, K> found{};
      bool all = true;
      for (std::size_t k = 0; k < K && all; ++k) {
        auto i = column(names[k]);
        all = i.has_value();
        if (all) found[k] = *i;
      }
      if (all) return found;
      std::string set;
      for (const char* n : names) set += (set.empty() ? "" : ",") + std::string(n);
      expected += (expected.empty() ? "" : " or ") + set;
    }
    throw InputError(source_, at_line(header_line_),
                     "expected columns " + expected + "; found: " + joined(names_));
  }

  /// The next non-blank row split into exactly as many fields as the header has; false at the end.
  bool next(std::vector<std::string_view>& fields) {
    std::string_view row;
    do {
      if (!cursor_.next(row)) return false;
    } while (trim(row).empty());
    fields = split(row, separator_, false);
    if (fields.size() != names_.size())
      throw InputError(source_, at_line(line()),
                       "expected " + std::to_string(names_.size()) + " fields as in the header, found " +
                           std::to_string(fields.size()));
    return true;
  }

 private:
  LineCursor cursor_;
  const std::string& source_;
  std::size_t header_line_ = 0;
  std::string_view separator_;
  std::vector<std::string> names_;
};

double radius_at(const std::vector<std::string_view>& fields, const RadiusArray& column, const Table& table) {
  const double r =
      parse_double(fields[column.index], table.source(), table.line(), "the radius") * column.scale;
  if (r <= 0.0)
    throw InputError(table.source(), at_line(table.line()),
                     "radius must be positive, found " + std::string(trim(fields[column.index])));
  return r;
}

}  // namespace

CenterlineData parse_csv_graph(std::string_view vertices, const std::string& vertices_source,
                               std::string_view edges, const std::string& edges_source,
                               const ReadOptions& options) {
  Table vertex_table(vertices, vertices_source, "vertices");
  Table edge_table(edges, edges_source, "edges");
  const auto position = vertex_table.columns<3>({{"pos_x", "pos_y", "pos_z"}, {"x", "y", "z"}});
  const auto endpoints = edge_table.columns<2>(
      {{"node1id", "node2id"}, {"source", "target"}, {"node1", "node2"}, {"from", "to"}, {"u", "v"}});
  const std::optional<std::size_t> id_column = vertex_table.column("id");

  // A radius per edge is preferred (VesselGraph has only that); else one per vertex.
  const std::optional<RadiusArray> edge_radius = find_radius_array(edge_table.names(), options.radius_array);
  std::optional<RadiusArray> vertex_radius;
  if (!edge_radius) vertex_radius = find_radius_array(vertex_table.names(), options.radius_array);
  if (!edge_radius && !vertex_radius)
    throw InputError(edges_source, "",
                     missing_radius_message(edge_table.names(), options.radius_array) +
                         "; the vertices table " + vertices_source +
                         " has none either (found: " + joined(vertex_table.names()) + ")");

  CenterlineData data;
  std::unordered_map<int64_t, std::pair<int32_t, std::size_t>> vertex_of;  // id -> (point index, line)
  std::vector<std::string_view> fields;
  while (vertex_table.next(fields)) {
    const std::size_t n = vertex_table.line();
    const auto index = static_cast<int32_t>(data.points.size());
    const int64_t id = id_column ? parse_int(fields[*id_column], vertices_source, n, "the id") : index;
    const auto [it, inserted] = vertex_of.emplace(id, std::make_pair(index, n));
    if (!inserted)
      throw InputError(vertices_source, at_line(n),
                       "duplicate vertex id " + std::to_string(id) + " (first on line " +
                           std::to_string(it->second.second) + ")");
    data.points.emplace_back(parse_double(fields[position[0]], vertices_source, n, "x"),
                             parse_double(fields[position[1]], vertices_source, n, "y"),
                             parse_double(fields[position[2]], vertices_source, n, "z"));
    if (vertex_radius) data.radius.push_back(radius_at(fields, *vertex_radius, vertex_table));
  }
  if (data.points.empty()) throw InputError(vertices_source, "", "no vertices: the table has only a header");

  while (edge_table.next(fields)) {
    const std::size_t n = edge_table.line();
    Edge edge{};
    for (std::size_t k = 0; k < 2; ++k) {
      const std::string& name = edge_table.names()[endpoints[k]];
      const int64_t id = parse_int(fields[endpoints[k]], edges_source, n, name.c_str());
      auto found = vertex_of.find(id);
      if (found == vertex_of.end())
        throw InputError(
            edges_source, at_line(n),
            name + " " + std::to_string(id) + " is not an id in the vertices table " + vertices_source);
      edge[k] = found->second.first;
    }
    data.edges.push_back(edge);
    if (edge_radius) data.edge_radius.push_back(radius_at(fields, *edge_radius, edge_table));
  }
  if (data.edges.empty()) throw InputError(edges_source, "", "no edges: the table has only a header");
  return data;
}

}  // namespace vesselmesh
