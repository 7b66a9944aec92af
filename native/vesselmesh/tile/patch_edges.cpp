#include "vesselmesh/tile/patch_edges.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace vesselmesh {

namespace {

constexpr double kShortest = 2.0;  ///< local radii: shorter edges are left
constexpr double kLongest = 4.0;   ///< local radii: longer edges span merged joints and are left
constexpr double kMostMove = 0.2;  ///< of the edge's length: the furthest a new vertex leaves its middle
constexpr int kRounds = 2;         ///< four: vmtk-aorta-centerline at uniform level 2 worse (decisions log)

/// One round of the bisection.
void split_round(BaseMesh& base, const RoundCones& cones, double scale) {
  const auto length = [&](int32_t a, int32_t b) { return (base.vertices[a] - base.vertices[b]).norm(); };
  // Per edge, its triangles and how many of them it is the longest edge of.
  struct EdgeFaces {
    std::array<int32_t, 2> faces{-1, -1};
    int count = 0, longest = 0;
  };
  std::unordered_map<uint64_t, EdgeFaces> edges;
  for (std::size_t f = 0; f < base.triangles.size(); ++f) {
    const Tri& t = base.triangles[f];
    const std::array<double, 3> l = {length(t[0], t[1]), length(t[1], t[2]), length(t[2], t[0])};
    for (int k = 0; k < 3; ++k) {
      EdgeFaces& e = edges[edge_key(t[k], t[(k + 1) % 3])];
      if (e.count < 2) e.faces[e.count] = static_cast<int32_t>(f);
      ++e.count;
      e.longest += l[k] >= l[(k + 1) % 3] && l[k] >= l[(k + 2) % 3];
    }
  }
  std::vector<char> split_face(base.triangles.size(), 0);  // one split edge per triangle
  std::unordered_map<uint64_t, int32_t> middle;            // split edge → its new vertex
  int32_t hint = -1;
  for (const Tri& t : base.triangles)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      const TubeAxis &A = base.axes[a], &B = base.axes[b];
      const EdgeFaces& e = edges.at(edge_key(a, b));
      if (e.count != 2 || e.longest != 2 || split_face[e.faces[0]] || split_face[e.faces[1]]) continue;
      if (A.weight != 0 || B.weight != 0) continue;  // a tube's or a cap's edge
      const double r = std::min(A.radius, B.radius), l = length(a, b);
      if (!(l > kShortest * r && l < kLongest * r)) continue;
      Vec3 at = (base.vertices[a] + base.vertices[b]) / 2;
      const ConeDistance d = cones.nearest(at, &hint);
      if (std::isfinite(d.distance)) {
        const Vec3 on = at + ((scale - 1) * d.radius - d.distance) * d.direction;
        if ((on - at).norm() <= kMostMove * l) at = on;
      }
      TubeAxis axis;
      axis.radius = (A.radius + B.radius) / 2;
      axis.offset = (base.vertices[a] + A.offset + base.vertices[b] + B.offset) / 2 - at;
      axis.tangent = (A.tangent + B.tangent).normalized();
      axis.bend = (A.bend + B.bend) / 2;
      axis.slope = (A.slope + B.slope) / 2;
      split_face[e.faces[0]] = split_face[e.faces[1]] = 1;
      middle[edge_key(a, b)] = static_cast<int32_t>(base.vertices.size());
      base.vertices.push_back(at);
      base.axes.push_back(axis);
    }
  std::vector<Tri> triangles;
  triangles.reserve(base.triangles.size() + 2 * middle.size());
  for (const Tri& t : base.triangles) {
    int k = 0;
    while (k < 3 && !middle.count(edge_key(t[k], t[(k + 1) % 3]))) ++k;
    if (k == 3) {
      triangles.push_back(t);
      continue;
    }
    const int32_t a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3], m = middle.at(edge_key(a, b));
    triangles.push_back({a, m, c});
    triangles.push_back({m, b, c});
  }
  base.triangles = std::move(triangles);
}

}  // namespace

BaseMesh split_long_patch_edges(BaseMesh base, const RoundCones& cones, double scale) {
  for (int round = 0; round < kRounds; ++round) split_round(base, cones, scale);
  return base;
}

}  // namespace vesselmesh
