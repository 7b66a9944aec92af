#include "vesselmesh/subdivide/loop.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace vesselmesh {
namespace {

/// What one level needs to know about the mesh, built once and shared by positions and properties.
struct Connectivity {
  /// Unique edges in (lo, hi) order: lo < hi, then the vertices opposite the edge in its first and second
  /// face (-1 when it has only one face, i.e. lies on the boundary).
  std::vector<std::array<int32_t, 4>> edges;
  /// Per face corner k, the edge from corner k to corner k + 1.
  std::vector<int32_t> face_edges;
  /// Per vertex, the neighbours its mask averages (CSR): every neighbour for an interior vertex, the two
  /// along the boundary for a boundary vertex, none for a vertex that stays fixed (isolated, or with more
  /// than two boundary edges).
  std::vector<int32_t> ring_start, ring;
  std::vector<uint8_t> boundary;  ///< 1 for a vertex with exactly two boundary edges
};

std::string edge_name(int32_t a, int32_t b) {
  return "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

Connectivity connect(const TriMesh& mesh) {
  const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
  const int64_t nf = static_cast<int64_t>(mesh.faces.size());
  // The next level numbers V + E ≤ V + 3F vertices in int32.
  if (nv + 3 * nf > std::numeric_limits<int32_t>::max())
    throw std::length_error("Loop subdivision: mesh too large for 32-bit vertex indices after one level");
  for (const auto& p : mesh.vertex_properties)
    if (static_cast<int64_t>(p.values.size()) != nv)
      throw std::invalid_argument("Loop subdivision: vertex property '" + p.name + "' has " +
                                  std::to_string(p.values.size()) + " values for " + std::to_string(nv) +
                                  " vertices");

  // Bucket the 3F half-edges by their lower endpoint (a counting sort), then sort each small bucket by the
  // higher one: unique edges come out in (lo, hi) order without a global sort.
  std::vector<int32_t> bucket_start(nv + 1, 0);
  for (int64_t f = 0; f < nf; ++f) {
    const Tri& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= nv)
        throw std::invalid_argument("Loop subdivision: face " + std::to_string(f) + " refers to vertex " +
                                    std::to_string(t[k]) + " of " + std::to_string(nv));
      if (t[k] == t[(k + 1) % 3])
        throw std::invalid_argument("Loop subdivision: face " + std::to_string(f) + " repeats vertex " +
                                    std::to_string(t[k]));
    }
    for (int k = 0; k < 3; ++k) ++bucket_start[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  for (int64_t v = 0; v < nv; ++v) bucket_start[v + 1] += bucket_start[v];

  // Key: higher endpoint in the top half, so that a bucket sorts by it; half-edge id 3f + k below.
  std::vector<uint64_t> keys(3 * nf);
  {
    std::vector<int32_t> next(bucket_start.begin(), bucket_start.end() - 1);
    for (int64_t f = 0; f < nf; ++f) {
      const Tri& t = mesh.faces[f];
      for (int k = 0; k < 3; ++k) {
        const int32_t a = t[k], b = t[(k + 1) % 3];
        keys[next[std::min(a, b)]++] = (uint64_t(std::max(a, b)) << 32) | uint64_t(3 * f + k);
      }
    }
  }

  Connectivity c;
  c.edges.reserve(3 * nf / 2 + 1);
  c.face_edges.resize(3 * nf);
  const auto corner = [&](uint32_t h, int offset) { return mesh.faces[h / 3][(h % 3 + offset) % 3]; };
  for (int32_t lo = 0; lo < nv; ++lo) {
    const auto begin = keys.begin() + bucket_start[lo], end = keys.begin() + bucket_start[lo + 1];
    std::sort(begin, end);
    for (auto it = begin; it != end;) {
      const int32_t hi = static_cast<int32_t>(*it >> 32);
      const auto group_end =
          std::find_if(it, end, [hi](uint64_t key) { return (key >> 32) != uint64_t(hi); });
      const uint32_t h0 = static_cast<uint32_t>(*it);
      if (group_end - it > 2)
        throw std::invalid_argument("Loop subdivision: edge " + edge_name(lo, hi) + " is shared by " +
                                    std::to_string(group_end - it) + " faces (non-manifold)");
      const int32_t e = static_cast<int32_t>(c.edges.size());
      c.face_edges[h0] = e;
      int32_t opposite1 = -1;
      if (group_end - it == 2) {
        const uint32_t h1 = static_cast<uint32_t>(it[1]);
        if (corner(h0, 0) == corner(h1, 0))
          throw std::invalid_argument("Loop subdivision: edge " + edge_name(lo, hi) +
                                      " runs the same way in faces " + std::to_string(h0 / 3) + " and " +
                                      std::to_string(h1 / 3) + " (inconsistent orientation)");
        c.face_edges[h1] = e;
        opposite1 = corner(h1, 2);
      }
      c.edges.push_back({lo, hi, corner(h0, 2), opposite1});
      it = group_end;
    }
  }

  std::vector<int32_t> degree(nv, 0), boundary_degree(nv, 0);
  for (const auto& [a, b, o0, o1] : c.edges) {
    ++degree[a];
    ++degree[b];
    if (o1 < 0) {
      ++boundary_degree[a];
      ++boundary_degree[b];
    }
  }
  // Consistent orientation makes boundary degrees even; above two, boundary loops touch at the vertex, and it
  // stays fixed.
  const auto in_ring = [&](int32_t v, bool boundary_edge) {
    return boundary_degree[v] == 0 || (boundary_degree[v] == 2 && boundary_edge);
  };
  c.ring_start.assign(nv + 1, 0);
  c.boundary.resize(nv);
  for (int64_t v = 0; v < nv; ++v) {
    c.boundary[v] = boundary_degree[v] == 2;
    c.ring_start[v + 1] = c.ring_start[v] + (boundary_degree[v] == 0 ? degree[v] : c.boundary[v] ? 2 : 0);
  }
  c.ring.resize(c.ring_start[nv]);
  std::vector<int32_t> next(c.ring_start.begin(), c.ring_start.end() - 1);
  for (const auto& [a, b, o0, o1] : c.edges) {
    if (in_ring(a, o1 < 0)) c.ring[next[a]++] = b;
    if (in_ring(b, o1 < 0)) c.ring[next[b]++] = a;
  }
  return c;
}

/// A vertex mask: the vertex's own weight and that of each ring neighbour.
struct VertexMask {
  double self, neighbour;
};

/// Loop's β_n: the weight of each of an interior vertex's n neighbours.
double loop_beta(int n) {
  const double t = 3.0 / 8 + std::cos(2 * M_PI / n) / 4;
  return (5.0 / 8 - t * t) / n;
}

/// Per-vertex masks; `interior` gives the mask for n neighbours, evaluated once per valence present.
template <typename Interior>
std::vector<VertexMask> vertex_masks(const Connectivity& c, VertexMask boundary, Interior interior) {
  const int64_t nv = static_cast<int64_t>(c.boundary.size());
  int max_valence = 0;
  for (int64_t v = 0; v < nv; ++v) max_valence = std::max(max_valence, c.ring_start[v + 1] - c.ring_start[v]);
  std::vector<VertexMask> by_valence(max_valence + 1, VertexMask{1, 0});
  for (int n = 1; n <= max_valence; ++n) by_valence[n] = interior(n);
  std::vector<VertexMask> masks(nv);
  for (int64_t v = 0; v < nv; ++v)
    masks[v] = c.boundary[v] ? boundary : by_valence[c.ring_start[v + 1] - c.ring_start[v]];
  return masks;
}

/// Applies the vertex masks to `in` (V values), writing V values to `out`. Float properties are
/// accumulated in double.
template <typename T>
void apply_vertex_masks(const Connectivity& c, const std::vector<VertexMask>& masks, const T* in, T* out) {
  using Acc = std::conditional_t<std::is_floating_point_v<T>, double, T>;
  const int64_t nv = static_cast<int64_t>(masks.size());
  for (int64_t v = 0; v < nv; ++v) {
    Acc sum = masks[v].self * Acc(in[v]);
    for (int32_t i = c.ring_start[v]; i < c.ring_start[v + 1]; ++i)
      sum += masks[v].neighbour * Acc(in[c.ring[i]]);
    out[v] = T(sum);
  }
}

/// One level of values: the V moved old values, then one per edge (3/8–1/8 inside, midpoint on the boundary).
template <typename T>
std::vector<T> subdivide_values(const Connectivity& c, const std::vector<VertexMask>& masks,
                                const std::vector<T>& in) {
  using Acc = std::conditional_t<std::is_floating_point_v<T>, double, T>;
  const size_t nv = in.size();
  std::vector<T> out(nv + c.edges.size());
  apply_vertex_masks(c, masks, in.data(), out.data());
  T* edge_out = out.data() + nv;
  for (const auto& [a, b, o0, o1] : c.edges) {
    const Acc ends = Acc(in[a]) + Acc(in[b]);
    if (o1 < 0)
      *edge_out++ = T(0.5 * ends);
    else
      *edge_out++ = T(3.0 / 8 * ends + 1.0 / 8 * (Acc(in[o0]) + Acc(in[o1])));
  }
  return out;
}

/// The masks of the Loop subdivision step.
std::vector<VertexMask> subdivision_masks(const Connectivity& c) {
  return vertex_masks(c, {3.0 / 4, 1.0 / 8}, [](int n) {
    const double beta = loop_beta(n);
    return VertexMask{1 - n * beta, beta};
  });
}

/// χ_n: the weight of each of an interior vertex's n neighbours in its limit position.
double limit_weight(int n) { return 1 / (3 / (8 * loop_beta(n)) + n); }

/// The masks that take a vertex to its limit position.
std::vector<VertexMask> limit_masks(const Connectivity& c) {
  return vertex_masks(c, {2.0 / 3, 1.0 / 6}, [](int n) {
    return VertexMask{1 - n * limit_weight(n), limit_weight(n)};
  });
}

/// One level: positions and properties, and the faces numbered as loop.hpp documents.
TriMesh subdivided(const TriMesh& mesh, const Connectivity& c) {
  const std::vector<VertexMask> masks = subdivision_masks(c);
  TriMesh out;
  out.vertices = subdivide_values(c, masks, mesh.vertices);
  out.vertex_properties.reserve(mesh.vertex_properties.size());
  for (const VertexProperty& p : mesh.vertex_properties)
    out.vertex_properties.push_back({p.name, subdivide_values(c, masks, p.values)});

  const int32_t nv = static_cast<int32_t>(mesh.vertices.size());
  out.faces.resize(4 * mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const Tri& t = mesh.faces[f];
    const int32_t m01 = nv + c.face_edges[3 * f], m12 = nv + c.face_edges[3 * f + 1],
                  m20 = nv + c.face_edges[3 * f + 2];
    out.faces[4 * f] = {t[0], m01, m20};
    out.faces[4 * f + 1] = {m01, t[1], m12};
    out.faces[4 * f + 2] = {m20, m12, t[2]};
    out.faces[4 * f + 3] = {m01, m12, m20};
  }
  return out;
}

/// Zero of a value type: a number or an Eigen vector.
template <typename T>
T zero() {
  if constexpr (std::is_arithmetic_v<T>)
    return T(0);
  else
    return T::Zero();
}

/// The limit positions of the next level's values `next`, from this level's values `in` and connectivity:
/// an old vertex's limit does not depend on the level, so it comes from its ring here; an edge vertex's from
/// its ring in the next level, made of the edge's two moved ends (its two neighbours along the boundary, for
/// a boundary edge) and, inside, the two other edge vertices of each of the edge's two faces (valence 6).
template <typename T>
std::vector<T> limit_of_next(const Connectivity& c, const std::vector<T>& in, const std::vector<T>& next) {
  using Acc = std::conditional_t<std::is_floating_point_v<T>, double, T>;
  const size_t nv = in.size();
  std::vector<T> out(next.size());
  apply_vertex_masks(c, limit_masks(c), in.data(), out.data());
  std::vector<Acc> around(c.edges.size(), zero<Acc>());
  for (size_t f = 0; f < c.face_edges.size() / 3; ++f)
    for (int k = 0; k < 3; ++k)
      around[c.face_edges[3 * f + k]] += Acc(next[nv + c.face_edges[3 * f + (k + 1) % 3]]) +
                                         Acc(next[nv + c.face_edges[3 * f + (k + 2) % 3]]);
  const double chi = limit_weight(6);
  for (size_t e = 0; e < c.edges.size(); ++e) {
    const auto& [a, b, o0, o1] = c.edges[e];
    const Acc ends = Acc(next[a]) + Acc(next[b]), self = Acc(next[nv + e]);
    out[nv + e] =
        o1 < 0 ? T(2.0 / 3 * self + 1.0 / 6 * ends) : T((1 - 6 * chi) * self + chi * (ends + around[e]));
  }
  return out;
}

}  // namespace

TriMesh loop_subdivide(const TriMesh& mesh) { return subdivided(mesh, connect(mesh)); }

TriMesh loop_subdivide_to_limit(const TriMesh& mesh) {
  const Connectivity c = connect(mesh);
  TriMesh out = subdivided(mesh, c);
  out.vertices = limit_of_next(c, mesh.vertices, out.vertices);
  for (std::size_t k = 0; k < mesh.vertex_properties.size(); ++k)
    out.vertex_properties[k].values =
        limit_of_next(c, mesh.vertex_properties[k].values, out.vertex_properties[k].values);
  return out;
}

TriMesh loop_subdivide(const TriMesh& mesh, int levels) {
  if (levels < 0)
    throw std::invalid_argument("Loop subdivision: levels must be ≥ 0, got " + std::to_string(levels));
  if (levels == 0) return mesh;
  TriMesh result = loop_subdivide(mesh);
  for (int i = 1; i < levels; ++i) result = loop_subdivide(result);
  return result;
}

TriMesh loop_limit(const TriMesh& mesh) {
  const Connectivity c = connect(mesh);
  const std::vector<VertexMask> masks = limit_masks(c);
  TriMesh limit = mesh;
  apply_vertex_masks(c, masks, mesh.vertices.data(), limit.vertices.data());
  for (std::size_t k = 0; k < mesh.vertex_properties.size(); ++k)
    apply_vertex_masks(c, masks, mesh.vertex_properties[k].values.data(), limit.vertex_properties[k].values.data());
  return limit;
}

}  // namespace vesselmesh
