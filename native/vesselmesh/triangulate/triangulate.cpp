#include "vesselmesh/triangulate/triangulate.hpp"

namespace vesselmesh {

TriMesh triangulate(const BaseMesh& base) {
  TriMesh mesh;
  mesh.vertices = base.vertices;
  mesh.faces.reserve(2 * base.quads.size() + base.triangles.size());
  for (const auto& q : base.quads) {
    mesh.faces.push_back({q[0], q[1], q[2]});
    mesh.faces.push_back({q[0], q[2], q[3]});
  }
  mesh.faces.insert(mesh.faces.end(), base.triangles.begin(), base.triangles.end());
  mesh.vertex_properties = tube_axis_properties(base.axes);
  return mesh;
}

}  // namespace vesselmesh
