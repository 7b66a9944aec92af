#include "vesselmesh/mesh/mesh_edges.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace vesselmesh {

MeshEdges mesh_edges(const std::vector<Tri>& faces, int32_t vertex_count) {
  const std::size_t corners = 3 * faces.size();
  if (corners > static_cast<std::size_t>(std::numeric_limits<int32_t>::max()))
    throw std::length_error("a mesh of " + std::to_string(faces.size()) +
                            " faces has too many corners for 32-bit indices");
  // Bucket each corner's edge under its lower vertex; a bucket holds a vertex's few neighbours, so
  // sorting each one is linear in all.
  std::vector<int64_t> first(static_cast<std::size_t>(vertex_count) + 1, 0);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = faces[f][k], b = faces[f][(k + 1) % 3];
      if (a < 0 || a >= vertex_count || b < 0 || b >= vertex_count)
        throw std::invalid_argument("face " + std::to_string(f) + " refers to a vertex outside 0.." +
                                    std::to_string(vertex_count - 1));
      ++first[std::min(a, b) + 1];
    }
  for (int32_t v = 0; v < vertex_count; ++v) first[v + 1] += first[v];

  struct Corner {
    int32_t upper;
    int32_t corner;  ///< 3·face + k
  };
  std::vector<Corner> bucket(corners);
  std::vector<int64_t> fill(first.begin(), first.end() - 1);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = faces[f][k], b = faces[f][(k + 1) % 3];
      bucket[fill[std::min(a, b)]++] = {std::max(a, b), static_cast<int32_t>(3 * f + k)};
    }

  MeshEdges out;
  out.edges.reserve(corners / 2 + 1);  // a closed surface has exactly corners / 2
  out.corner_edges.resize(faces.size());
  for (int32_t v = 0; v < vertex_count; ++v) {
    const auto begin = bucket.begin() + first[v], end = bucket.begin() + first[v + 1];
    std::sort(begin, end, [](const Corner& x, const Corner& y) { return x.upper < y.upper; });
    for (auto c = begin; c != end; ++c) {
      if (c == begin || c->upper != (c - 1)->upper) out.edges.push_back({v, c->upper});
      out.corner_edges[c->corner / 3][c->corner % 3] = static_cast<int32_t>(out.edges.size() - 1);
    }
  }
  return out;
}

}  // namespace vesselmesh
