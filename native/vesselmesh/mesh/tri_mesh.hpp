#pragma once
// The triangle mesh that flows between the surface stages (triangulate → curvature → subdivide →
// write/check): flat arrays, as they cross into Python and Blender without conversion.

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "vesselmesh/centerline.hpp"

namespace vesselmesh {

using Tri = std::array<int32_t, 3>;

/// A face with a corner twice has no area, whatever the positions.
inline bool repeats_vertex(const Tri& f) { return f[0] == f[1] || f[1] == f[2] || f[2] == f[0]; }

/// One key for the edge between vertices a and b, whichever way round: for hashing a mesh's edges.
inline uint64_t edge_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

/// A named per-vertex scalar (curvature measures and the like), written to PLY as a float property.
struct VertexProperty {
  std::string name;
  std::vector<float> values;  ///< one per vertex
};

/// p with each coordinate rounded to float, as every file and Blender hold it. Through volatile floats: GCC
/// 12 at -O2 and above compiles p.cast<float>().cast<double>(), and the same written per coordinate, to a
/// plain copy of the two coordinates it vectorises together (x and y), rounding z alone.
inline Vec3 rounded_to_float(const Vec3& p) {
  Vec3 out;
  for (int k = 0; k < 3; ++k) {
    const volatile float f = static_cast<float>(p[k]);
    out[k] = f;
  }
  return out;
}

struct TriMesh {
  std::vector<Vec3> vertices;                   ///< V positions
  std::vector<Tri> faces;                       ///< F triangles, counter-clockwise seen from outside
  std::vector<VertexProperty> vertex_properties;  ///< optional, each with V values
};

}  // namespace vesselmesh
