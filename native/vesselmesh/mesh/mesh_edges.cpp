#include "vesselmesh/mesh/mesh_edges.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "vesselmesh/parallel.hpp"

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
  {
    std::vector<int64_t> fill(first.begin(), first.end() - 1);
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int32_t a = faces[f][k], b = faces[f][(k + 1) % 3];
        bucket[fill[std::min(a, b)]++] = {std::max(a, b), static_cast<int32_t>(3 * f + k)};
      }
  }

  // Each vertex's bucket sorted, and its edges counted, on both cores; then numbered in vertex order.
  std::vector<int64_t> edge_of_vertex(static_cast<std::size_t>(vertex_count) + 1, 0);
  parallel_for(static_cast<std::size_t>(vertex_count), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const auto b = bucket.begin() + first[v], e = bucket.begin() + first[v + 1];
      std::sort(b, e, [](const Corner& x, const Corner& y) { return x.upper < y.upper; });
      for (auto c = b; c != e; ++c) edge_of_vertex[v + 1] += c == b || c->upper != (c - 1)->upper;
    }
  });
  for (int32_t v = 0; v < vertex_count; ++v) edge_of_vertex[v + 1] += edge_of_vertex[v];

  MeshEdges out;
  out.edges.resize(edge_of_vertex.back());
  out.corner_edges.resize(faces.size());
  out.corners.resize(corners);
  out.first.resize(edge_of_vertex.back() + 1);
  out.first.back() = static_cast<int64_t>(corners);
  parallel_for(static_cast<std::size_t>(vertex_count), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      int64_t edge = edge_of_vertex[v] - 1;
      for (int64_t i = first[v]; i < first[v + 1]; ++i) {
        const Corner& c = bucket[i];
        if (i == first[v] || c.upper != bucket[i - 1].upper) {
          out.edges[++edge] = {static_cast<int32_t>(v), c.upper};
          out.first[edge] = i;
        }
        out.corner_edges[c.corner / 3][c.corner % 3] = static_cast<int32_t>(edge);
        out.corners[i] = c.corner;
      }
    }
  });
  return out;
}

}  // namespace vesselmesh
