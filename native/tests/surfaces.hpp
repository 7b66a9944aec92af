#pragma once
// Analytic test surfaces shared by the tests of the surface stages.

#include <cmath>
#include <vector>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh::surfaces {

/// `mesh` with every vertex multiplied by `scale`.
inline TriMesh scaled(TriMesh mesh, double scale) {
  for (Vec3& p : mesh.vertices) p *= scale;
  return mesh;
}

/// A torus about the z axis: `sections` rings of `corners` vertices, vertex i·corners + j at major angle
/// 2πi/sections and minor angle θ = 2πj/corners from the outer equator; major radius R, minor radius r;
/// faces outwards. Quad (i, j), (i+1, j), (i+1, j+1), (i, j+1) is cut along (i, j)–(i+1, j+1), as the
/// pipeline cuts tube quads, so every vertex has valence 6.
inline TriMesh torus(int sections, int corners, double R, double r) {
  TriMesh m;
  for (int i = 0; i < sections; ++i) {
    const double phi = 2 * M_PI * i / sections;
    const Vec3 radial(std::cos(phi), std::sin(phi), 0);
    for (int j = 0; j < corners; ++j) {
      const double theta = 2 * M_PI * j / corners;
      m.vertices.push_back(R * radial + r * (std::cos(theta) * radial + std::sin(theta) * Vec3::UnitZ()));
    }
  }
  const auto id = [&](int i, int j) { return static_cast<int32_t>((i % sections) * corners + j % corners); };
  for (int i = 0; i < sections; ++i)
    for (int j = 0; j < corners; ++j) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

/// Faces of a grid of (nx + 1) × (ny + 1) vertices, vertex (i, j) at index j·(nx + 1) + i, each quad cut
/// along alternating diagonals (valences 4 to 8), counter-clockwise when i runs along x and j along y.
inline std::vector<Tri> grid_faces(int nx, int ny) {
  std::vector<Tri> faces;
  const auto id = [&](int i, int j) { return static_cast<int32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0)
        faces.insert(faces.end(), {Tri{a, b, c}, Tri{a, c, d}});
      else
        faces.insert(faces.end(), {Tri{a, b, d}, Tri{b, c, d}});
    }
  return faces;
}

}  // namespace vesselmesh::surfaces
