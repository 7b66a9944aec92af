#include "vesselmesh/mesh/adjacency.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace vesselmesh {

Csr vertex_faces(const TriMesh& mesh) {
  const size_t nv = mesh.vertices.size();
  Csr csr;
  csr.offsets.assign(nv + 1, 0);
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int32_t v : mesh.faces[f]) {
      if (v < 0 || static_cast<size_t>(v) >= nv)
        throw std::invalid_argument("face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                    " of " + std::to_string(nv));
      ++csr.offsets[v + 1];
    }
  for (size_t v = 0; v < nv; ++v) csr.offsets[v + 1] += csr.offsets[v];
  csr.items.resize(csr.offsets[nv]);
  std::vector<size_t> next(csr.offsets.begin(), csr.offsets.end() - 1);
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int32_t v : mesh.faces[f]) csr.items[next[v]++] = static_cast<int32_t>(f);
  return csr;
}

Csr vertex_neighbours(const TriMesh& mesh, const Csr& faces) {
  const size_t nv = mesh.vertices.size();
  Csr csr;
  csr.offsets.reserve(nv + 1);
  csr.offsets.push_back(0);
  csr.items.reserve(faces.items.size() + nv);
  for (size_t v = 0; v < nv; ++v) {
    const size_t start = csr.items.size();
    for (const int32_t* f = faces.begin(static_cast<int32_t>(v)); f != faces.end(static_cast<int32_t>(v));
         ++f)
      for (int32_t w : mesh.faces[*f])
        if (static_cast<size_t>(w) != v) csr.items.push_back(w);
    std::sort(csr.items.begin() + start, csr.items.end());
    csr.items.erase(std::unique(csr.items.begin() + start, csr.items.end()), csr.items.end());
    csr.offsets.push_back(csr.items.size());
  }
  return csr;
}

}  // namespace vesselmesh
