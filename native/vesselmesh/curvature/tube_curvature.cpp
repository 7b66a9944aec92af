#include "vesselmesh/curvature/tube_curvature.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "vesselmesh/parallel.hpp"
#include "vesselmesh/tile/base_mesh.hpp"

namespace vesselmesh {

TubeCurvature tube_curvature(const TriMesh& mesh) {
  const auto p = find_tube_axis_properties(mesh);
  if (p[0] == nullptr) return {};
  const std::size_t n = mesh.vertices.size();
  TubeCurvature t;
  t.around.assign(n, 0.0);
  t.along.assign(n, 0.0);
  t.around_dir.assign(n, Vec3::Zero());
  t.along_dir.assign(n, Vec3::Zero());
  t.weight.assign(n, 0.0);
  auto vec = [&](std::size_t first, std::size_t v) {
    return Vec3((*p[first])[v], (*p[first + 1])[v], (*p[first + 2])[v]);
  };
  parallel_for(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const double r = (*p[3])[v], w = std::clamp(static_cast<double>((*p[4])[v]), 0.0, 1.0);
      Vec3 tangent = vec(5, v);
      if (!(w > 0 && r > 0 && tangent.norm() > 0)) continue;
      tangent.normalize();
      // From the axis to the vertex, square to the axis (subdivision blends the sections' offsets).
      Vec3 u = -vec(0, v);
      u -= u.dot(tangent) * tangent;
      if (!(u.norm() > 0)) continue;
      u.normalize();
      const double slope = (*p[11])[v], cos_phi = 1 / std::sqrt(1 + slope * slope);
      // Past a bend tighter than the radius the inside of the tube folds (such bends are corner joints):
      // the denominator is kept from reaching zero there.
      const double bend_u = vec(8, v).dot(u), rest = std::max(1 - r * bend_u, 0.05);
      t.around[v] = cos_phi / r;
      t.along[v] = -cos_phi * bend_u / rest;
      t.around_dir[v] = tangent.cross(u);
      t.along_dir[v] = (cos_phi * tangent + slope * cos_phi * u).normalized();
      t.weight[v] = w;
    }
  });
  return t;
}

namespace {

/// A tube weight this close to 1 is 1: subdivision's masks sum to 1 only up to rounding (the weights are
/// floats).
bool wholly_on_tube(double weight) { return weight >= 1 - 1e-6; }

}  // namespace

std::vector<char> needs_fit(const TubeCurvature& t) {
  std::vector<char> fit(t.weight.size());
  for (std::size_t v = 0; v < fit.size(); ++v) fit[v] = !wholly_on_tube(t.weight[v]);
  return fit;
}

void blend_tube_curvature(VertexCurvature& c, const TubeCurvature& t) {
  if (t.weight.empty()) return;
  parallel_for(t.weight.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const double w = wholly_on_tube(t.weight[v]) ? 1.0 : t.weight[v];
      if (!(w > 0)) continue;
      const bool around_first = t.around[v] >= t.along[v];
      const double k1 = around_first ? t.around[v] : t.along[v], k2 = around_first ? t.along[v] : t.around[v];
      c.k1[v] = w * k1 + (1 - w) * c.k1[v];
      c.k2[v] = w * k2 + (1 - w) * c.k2[v];
      c.mean[v] = (c.k1[v] + c.k2[v]) / 2;
      c.gaussian[v] = c.k1[v] * c.k2[v];
      c.rms[v] = std::sqrt((c.k1[v] * c.k1[v] + c.k2[v] * c.k2[v]) / 2);
      if (w >= 0.5) {
        c.dir1[v] = around_first ? t.around_dir[v] : t.along_dir[v];
        c.dir2[v] = around_first ? t.along_dir[v] : t.around_dir[v];
      }
    }
  });
}

}  // namespace vesselmesh
