#include "vesselmesh/geometry/self_intersections.hpp"

#include <algorithm>
#include <mutex>

#include "vesselmesh/geometry/bvh.hpp"
#include "vesselmesh/geometry/predicates.hpp"

namespace vesselmesh {

std::vector<std::array<int32_t, 2>> intersecting_face_pairs(const TriMesh& mesh) {
  std::vector<int32_t> face_of;
  std::vector<Box> boxes;
  for (int32_t f = 0; f < static_cast<int32_t>(mesh.faces.size()); ++f) {
    if (repeats_vertex(mesh.faces[f])) continue;
    const Triangle t = corners(mesh.vertices, mesh.faces[f]);
    if (is_degenerate(t)) continue;
    Box box;
    for (const Vec3& p : t) box.extend(p);
    face_of.push_back(f);
    boxes.push_back(box);
  }
  // Pairs sharing an edge or a vertex need no special case: the predicate knows shared corners lie on
  // the other plane, so such pairs count only when they fold over or cross away from what they share.
  std::vector<std::array<int32_t, 2>> hits;
  std::mutex lock;  // hits are rare: the threads rarely wait here
  Bvh(boxes).for_each_overlapping_pair(
      [&](int32_t i, int32_t j) {
        const int32_t f = face_of[i], g = face_of[j];
        if (triangle_interiors_meet(corners(mesh.vertices, mesh.faces[f]), corners(mesh.vertices, mesh.faces[g]))) {
          const std::lock_guard<std::mutex> guard(lock);
          hits.push_back({std::min(f, g), std::max(f, g)});
        }
      },
      true);
  std::sort(hits.begin(), hits.end());
  return hits;
}

}  // namespace vesselmesh
