#include "vesselmesh/tile/octagons.hpp"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

namespace vesselmesh {

BaseMesh octagonal_sections(BaseMesh base, double shrink) {
  std::unordered_map<uint64_t, int32_t> split;  // side → its new vertex; −1 until one is placed
  for (const auto& q : base.quads)
    for (int k = 0; k < 4; ++k) split.emplace(edge_key(q[k], q[(k + 1) % 4]), -1);
  std::unordered_set<uint64_t> on_patch;
  for (const Tri& t : base.triangles)
    for (int k = 0; k < 3; ++k) {
      split.emplace(edge_key(t[k], t[(k + 1) % 3]), -1);
      on_patch.insert(edge_key(t[k], t[(k + 1) % 3]));
    }
  for (const auto& s : base.squares) {
    // A joint patch's square keeps straight sides, split at their middles: the patch keeps the shape of
    // the hull it was built as (pushed out to the circle, 16 instead of 12 of 1,000 random trees crossed at
    // level 2).
    bool patch = false;
    for (int k = 0; k < 4; ++k) patch = patch || on_patch.count(edge_key(s[k], s[(k + 1) % 4])) > 0;
    for (int32_t v : s) {  // each vertex is the corner of one square (a shared one's are made once)
      base.vertices[v] += (1 - shrink) * base.axes[v].offset;
      base.axes[v].offset *= shrink;
    }
    for (int k = 0; k < 4; ++k) {
      const int32_t a = s[k], b = s[(k + 1) % 4];
      const auto it = split.find(edge_key(a, b));
      if (it == split.end() || it->second >= 0) continue;
      const Vec3 center = base.vertices[a] + base.axes[a].offset;
      const Vec3 mid = (base.vertices[a] + base.vertices[b]) / 2 - center;
      const double reach = (base.axes[a].offset.norm() + base.axes[b].offset.norm()) / 2;
      const Vec3 at = center + mid * (patch ? 1.0 : reach / mid.norm());
      TubeAxis axis = base.axes[a];
      axis.offset = center - at;
      it->second = static_cast<int32_t>(base.vertices.size());
      base.vertices.push_back(at);
      base.axes.push_back(axis);
    }
  }
  const auto mid = [&](int32_t a, int32_t b) { return split.at(edge_key(a, b)); };

  std::vector<Tri> triangles;
  // A triangle with the new vertices of its split sides: four triangles when all three are split, else a
  // fan.
  const auto split_triangle = [&](const Tri& t) {
    const std::array<int32_t, 3> m = {mid(t[0], t[1]), mid(t[1], t[2]), mid(t[2], t[0])};
    std::vector<int32_t> ring;  // the triangle's boundary with the new vertices in it
    for (int k = 0; k < 3; ++k) {
      ring.push_back(t[k]);
      if (m[k] >= 0) ring.push_back(m[k]);
    }
    if (ring.size() == 3) {
      triangles.push_back(t);
    } else if (ring.size() == 6) {
      triangles.insert(triangles.end(), {Tri{t[0], m[0], m[2]}, Tri{t[1], m[1], m[0]}, Tri{t[2], m[2], m[1]},
                                         Tri{m[0], m[1], m[2]}});
    } else {
      // A fan from a new vertex: no triangle of it has three points on one side.
      const std::size_t from = static_cast<std::size_t>(
          std::find_if(ring.begin(), ring.end(), [&](int32_t v) { return v == m[0] || v == m[1] || v == m[2]; }) -
          ring.begin());
      for (std::size_t i = 1; i + 1 < ring.size(); ++i)
        triangles.push_back({ring[from], ring[(from + i) % ring.size()], ring[(from + i + 1) % ring.size()]});
    }
  };

  std::vector<std::array<int32_t, 4>> quads;
  for (const auto& q : base.quads) {
    const std::array<int32_t, 4> m = {mid(q[0], q[1]), mid(q[1], q[2]), mid(q[2], q[3]), mid(q[3], q[0])};
    const int count = static_cast<int>(std::count_if(m.begin(), m.end(), [](int32_t v) { return v >= 0; }));
    if (count == 0) {
      quads.push_back(q);
    } else if (count == 4) {  // a flat cap
      quads.push_back(m);
      for (int k = 0; k < 4; ++k) triangles.push_back({q[k], m[k], m[(k + 3) % 4]});
    } else if (count == 2 && (m[0] >= 0) == (m[2] >= 0)) {  // a tube quad, split along the tube
      const int k = m[0] >= 0 ? 0 : 1;
      const int32_t a = q[k], b = q[(k + 1) % 4], c = q[(k + 2) % 4], d = q[(k + 3) % 4];
      quads.push_back({a, m[k], m[k + 2], d});
      quads.push_back({m[k], b, c, m[k + 2]});
    } else {  // cut along the diagonal triangulate() would, each half split
      split_triangle({q[0], q[1], q[2]});
      split_triangle({q[0], q[2], q[3]});
    }
  }
  for (const Tri& t : base.triangles) split_triangle(t);
  base.quads = std::move(quads);
  base.triangles = std::move(triangles);
  base.squares.clear();
  return base;
}

}  // namespace vesselmesh
