#include "vesselmesh/geometry/self_intersections.hpp"

#include <algorithm>
#include <mutex>

#include "vesselmesh/geometry/bvh.hpp"
#include "vesselmesh/geometry/predicates.hpp"
#include "vesselmesh/parallel.hpp"

namespace vesselmesh {

namespace {

Box box_of(const Triangle& t) {
  Box box;
  for (const Vec3& p : t) box.extend(p);
  return box;
}

/// Faces with an interior: those that repeat no vertex and have a plane.
bool has_interior(const TriMesh& mesh, int32_t f) {
  return !repeats_vertex(mesh.faces[f]) && !is_degenerate(corners(mesh.vertices, mesh.faces[f]));
}

}  // namespace

std::vector<std::array<int32_t, 2>> intersecting_face_pairs(const TriMesh& mesh,
                                                            const std::vector<char>& among) {
  const bool all = among.empty();
  std::vector<int32_t> face_of;
  std::vector<Box> boxes;
  const std::size_t count =
      all ? mesh.faces.size() : static_cast<std::size_t>(std::count(among.begin(), among.end(), 1));
  face_of.reserve(count);
  boxes.reserve(count);
  for (int32_t f = 0; f < static_cast<int32_t>(mesh.faces.size()); ++f)
    if ((all || among[f]) && has_interior(mesh, f))
      face_of.push_back(f), boxes.push_back(box_of(corners(mesh.vertices, mesh.faces[f])));
  std::vector<std::array<int32_t, 2>> hits;
  std::mutex lock;  // hits are rare: the threads rarely wait here
  // Pairs sharing an edge or a vertex need no special case: the predicate knows shared corners lie on
  // the other plane, so such pairs count only when they fold over or cross away from what they share.
  auto test = [&](int32_t f, int32_t g) {
    if (triangle_interiors_meet(corners(mesh.vertices, mesh.faces[f]),
                                corners(mesh.vertices, mesh.faces[g]))) {
      const std::lock_guard<std::mutex> guard(lock);
      hits.push_back({std::min(f, g), std::max(f, g)});
    }
  };
  const Bvh bvh(boxes);
  if (all) {
    bvh.for_each_overlapping_pair([&](int32_t i, int32_t j) { test(face_of[i], face_of[j]); }, true);
  } else {
    // Every face against the hierarchy of the flagged ones, a pair of two flagged faces once, from the
    // first. Most faces lie far from any flagged one: whether they have an interior is asked only of
    // those near one.
    parallel_for(mesh.faces.size(), [&](std::size_t begin, std::size_t end) {
      for (auto f = static_cast<int32_t>(begin); f < static_cast<int32_t>(end); ++f) {
        const Box box = box_of(corners(mesh.vertices, mesh.faces[f]));
        int interior = -1;  // not asked yet
        bvh.search([&](const Box& b) { return box.overlaps(b) ? 0.0 : 1.0; }, 0.0,
                   [&](int32_t i) {
                     const int32_t g = face_of[i];
                     if (g == f || (among[f] && g < f)) return;
                     if (interior < 0) interior = has_interior(mesh, f);
                     if (interior) test(f, g);
                   });
      }
    });
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

}  // namespace vesselmesh
