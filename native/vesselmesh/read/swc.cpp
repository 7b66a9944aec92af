#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "vesselmesh/error.hpp"
#include "vesselmesh/read/read.hpp"
#include "vesselmesh/read/text.hpp"

namespace vesselmesh {

namespace {

constexpr int32_t kNoParent = -1;

/// One SWC record as read, before parent ids are resolved to point indices.
struct Node {
  int64_t id;
  int64_t parent_id;
  std::size_t line;
};

/// Point indices of each node's parent (kNoParent for roots), checked against the ids in the file.
std::vector<int32_t> resolve_parents(const std::vector<Node>& nodes,
                                     const std::unordered_map<int64_t, int32_t>& index_of,
                                     const std::string& source) {
  std::vector<int32_t> parent(nodes.size(), kNoParent);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Node& node = nodes[i];
    if (node.parent_id < 0) continue;
    if (node.parent_id == node.id)
      throw InputError(source, at_line(node.line), "node " + std::to_string(node.id) + " is its own parent");
    auto found = index_of.find(node.parent_id);
    if (found == index_of.end())
      throw InputError(source, at_line(node.line),
                       "parent id " + std::to_string(node.parent_id) + " of node " + std::to_string(node.id) +
                           " does not exist");
    parent[i] = found->second;
  }
  return parent;
}

/// Throws when some parent chain never reaches a root. Each node is walked once: a walk stops at a
/// root or at a node already known to reach one, so the whole check is O(N).
void reject_cycles(const std::vector<Node>& nodes, const std::vector<int32_t>& parent,
                   const std::string& source) {
  enum State : uint8_t { kUnseen, kOnWalk, kReachesRoot };
  std::vector<State> state(nodes.size(), kUnseen);
  std::vector<int32_t> walk;
  for (std::size_t start = 0; start < nodes.size(); ++start) {
    int32_t v = static_cast<int32_t>(start);
    while (v != kNoParent && state[v] == kUnseen) {
      state[v] = kOnWalk;
      walk.push_back(v);
      v = parent[v];
    }
    if (v != kNoParent && state[v] == kOnWalk) {
      // v lies on the cycle: name the cycle's earliest line and the first few ids of the chain from it.
      int32_t first = v;
      for (int32_t u = parent[v]; u != v; u = parent[u]) first = std::min(first, u);
      constexpr int kShownIds = 8;
      std::string ids = std::to_string(nodes[first].id);
      int32_t u = parent[first];
      for (int shown = 1; u != first && shown < kShownIds; u = parent[u], ++shown)
        ids += " -> " + std::to_string(nodes[u].id);
      ids += " -> " + (u == first ? std::to_string(nodes[first].id) : std::string("..."));
      throw InputError(source, at_line(nodes[first].line),
                       "parent cycle: the parent chain " + ids + " never reaches a root");
    }
    for (int32_t u : walk) state[u] = kReachesRoot;
    walk.clear();
  }
}

}  // namespace

CenterlineData parse_swc(std::string_view text, const std::string& source) {
  CenterlineData data;
  std::vector<Node> nodes;
  std::unordered_map<int64_t, int32_t> index_of;

  LineCursor cursor(text);
  std::string_view line;
  while (cursor.next(line)) {
    const std::string_view content = trim(line);
    if (content.empty() || content.front() == '#') continue;
    const std::size_t n = cursor.number();
    const auto columns = split(content, " \t", true);
    if (columns.size() < 7)
      throw InputError(
          source, at_line(n),
          "expected 7 columns: id type x y z radius parent, found " + std::to_string(columns.size()));
    // Columns after the 7th are ignored: some tools append their own.
    const int64_t id = parse_int(columns[0], source, n, "the id");
    parse_int(columns[1], source, n, "the type");  // unused, but garbage there means a broken file
    const Vec3 position(parse_double(columns[2], source, n, "x"), parse_double(columns[3], source, n, "y"),
                        parse_double(columns[4], source, n, "z"));
    const double radius = parse_double(columns[5], source, n, "the radius");
    const int64_t parent_id = parse_int(columns[6], source, n, "the parent id");
    if (radius <= 0.0)
      throw InputError(source, at_line(n), "radius must be positive, found " + std::string(trim(columns[5])));

    const auto [it, inserted] = index_of.emplace(id, static_cast<int32_t>(nodes.size()));
    if (!inserted)
      throw InputError(source, at_line(n),
                       "duplicate id " + std::to_string(id) + " (first on line " +
                           std::to_string(nodes[it->second].line) + ")");
    nodes.push_back({id, parent_id, n});
    data.points.push_back(position);
    data.radius.push_back(radius);
  }
  if (nodes.empty()) throw InputError(source, "", "no points (the file holds only comments or blank lines)");

  const std::vector<int32_t> parent = resolve_parents(nodes, index_of, source);
  reject_cycles(nodes, parent, source);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int32_t child = static_cast<int32_t>(i);
    if (parent[i] == kNoParent)
      data.roots.push_back(child);
    else
      data.edges.push_back({parent[i], child});
  }
  return data;
}

}  // namespace vesselmesh
