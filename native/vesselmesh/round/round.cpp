#include "vesselmesh/round/round.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "vesselmesh/parallel.hpp"

namespace vesselmesh {

GuardedMoves round_tubes(TriMesh& mesh) {
  const auto p = find_tube_axis_properties(mesh, kRoundAxisProperties);
  if (p[0] == nullptr) return {};
  std::vector<Vec3> move(mesh.vertices.size(), Vec3::Zero());
  std::vector<double> radius(mesh.vertices.size());
  parallel_for(mesh.vertices.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      radius[v] = (*p[3])[v];
      const double weight = std::clamp(static_cast<double>((*p[4])[v]), 0.0, 1.0);
      const Vec3 out = -Vec3((*p[0])[v], (*p[1])[v], (*p[2])[v]);  // from the axis point to the vertex
      const double length = out.norm();
      if (weight > 0 && length > 0) move[v] = weight * (radius[v] / length - 1) * out;
    }
  });
  drop_tube_axis_properties(mesh);
  return move_without_folding(mesh, std::move(move), long_move_reach(mesh, radius));
}

std::vector<char> faces_near_joints(const TriMesh& mesh) {
  const std::vector<float>* weight = find_tube_axis_properties(mesh, kRoundAxisProperties)[4];
  if (weight == nullptr) return {};
  std::vector<char> near(mesh.faces.size());
  for (std::size_t f = 0; f < near.size(); ++f)
    near[f] =
        std::any_of(mesh.faces[f].begin(), mesh.faces[f].end(), [&](int32_t v) { return (*weight)[v] < 1; });
  return near;
}

}  // namespace vesselmesh
