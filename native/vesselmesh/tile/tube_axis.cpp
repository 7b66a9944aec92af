// The tube axes (TubeAxis) as vertex properties, which carry them through subdivision to the round stage
// and the tube curvature.

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "vesselmesh/tile/base_mesh.hpp"

namespace vesselmesh {

std::vector<VertexProperty> tube_axis_properties(const std::vector<TubeAxis>& axes) {
  std::vector<VertexProperty> out;
  for (const std::string& name : kTubeAxisNames) out.push_back({name, std::vector<float>(axes.size())});
  for (std::size_t v = 0; v < axes.size(); ++v) {
    const TubeAxis& a = axes[v];
    for (int k = 0; k < 3; ++k) {
      out[k].values[v] = static_cast<float>(a.offset[k]);
      out[5 + k].values[v] = static_cast<float>(a.tangent[k]);
      out[8 + k].values[v] = static_cast<float>(a.bend[k]);
    }
    out[3].values[v] = static_cast<float>(a.radius);
    out[4].values[v] = static_cast<float>(a.weight);
    out[11].values[v] = static_cast<float>(a.slope);
  }
  return out;
}

std::array<const std::vector<float>*, kTubeAxisNames.size()> find_tube_axis_properties(const TriMesh& mesh,
                                                                                       std::size_t count) {
  std::array<const std::vector<float>*, kTubeAxisNames.size()> p{};
  count = std::min(count, p.size());
  for (std::size_t k = 0; k < count; ++k)
    for (const VertexProperty& q : mesh.vertex_properties)
      if (q.name == kTubeAxisNames[k]) p[k] = &q.values;
  if (std::any_of(p.begin(), p.begin() + count, [](const auto* q) { return q == nullptr; })) p.fill(nullptr);
  return p;
}

void drop_tube_axis_properties(TriMesh& mesh, std::size_t from) {
  const auto first = kTubeAxisNames.begin() + static_cast<std::ptrdiff_t>(std::min(from, kTubeAxisNames.size()));
  auto& p = mesh.vertex_properties;
  p.erase(std::remove_if(p.begin(), p.end(),
                         [&](const VertexProperty& q) {
                           return std::find(first, kTubeAxisNames.end(), q.name) != kTubeAxisNames.end();
                         }),
          p.end());
}

}  // namespace vesselmesh
