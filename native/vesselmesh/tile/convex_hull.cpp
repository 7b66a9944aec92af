#include "vesselmesh/tile/convex_hull.hpp"

#include <map>

#include "vesselmesh/geometry/predicates.hpp"

namespace vesselmesh {

// Incremental hull: each point outside the current hull replaces the faces it sees by a fan from the
// horizon. Faces are visible only when the point is strictly in front (exact test), so points on the
// hull's planes leave it alone and the result is always a closed, consistently oriented surface.
std::vector<Tri> convex_hull(const std::vector<Vec3>& p) {
  const int n = static_cast<int>(p.size());
  if (n < 4) return {};
  // A first tetrahedron: two distinct points, a third off their line, a fourth off their plane.
  int b = 1;
  while (b < n && p[b] == p[0]) ++b;
  int c = b + 1;
  while (c < n && (p[c] - p[0]).cross(p[b] - p[0]).squaredNorm() == 0) ++c;
  int d = c + 1;
  while (d < n && orient3d(p[0], p[b], p[c], p[d]) == 0) ++d;
  if (d >= n) return {};  // all points coplanar: no solid hull
  if (orient3d(p[0], p[b], p[c], p[d]) > 0) std::swap(b, c);  // d behind face (0, b, c)
  std::vector<Tri> faces = {{0, b, c}, {0, d, b}, {b, d, c}, {c, d, 0}};

  for (int v = 0; v < n; ++v) {
    if (v == 0 || v == b || v == c || v == d) continue;
    std::vector<char> visible(faces.size());
    bool any = false;
    for (std::size_t f = 0; f < faces.size(); ++f)
      any |= visible[f] = orient3d(p[faces[f][0]], p[faces[f][1]], p[faces[f][2]], p[v]) > 0;
    if (!any) continue;
    // Directed edges of the hidden faces; a visible face's edge whose reverse is among them is on the horizon.
    std::map<std::pair<int32_t, int32_t>, char> hidden_edges;
    for (std::size_t f = 0; f < faces.size(); ++f)
      if (!visible[f])
        for (int k = 0; k < 3; ++k) hidden_edges[{faces[f][k], faces[f][(k + 1) % 3]}] = 1;
    std::vector<Tri> next;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (!visible[f]) {
        next.push_back(faces[f]);
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        const int32_t a = faces[f][k], e = faces[f][(k + 1) % 3];
        if (hidden_edges.count({e, a})) next.push_back({a, e, v});
      }
    }
    faces = std::move(next);
  }
  return faces;
}

}  // namespace vesselmesh
