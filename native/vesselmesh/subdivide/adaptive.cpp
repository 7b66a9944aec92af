#include "vesselmesh/subdivide/adaptive.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vesselmesh/error.hpp"
#include "vesselmesh/subdivide/loop.hpp"

namespace vesselmesh {
namespace {

/// The uniform levels 0..N of the base mesh, faces only (level k + 1 numbers its faces and vertices as
/// loop_subdivide documents, so face f of level k has children 4f..4f+3 and keeps its vertex ids), and
/// the limit position (and vertex properties) of every vertex of level N, which includes every vertex of
/// the coarser levels.
struct Hierarchy {
  std::vector<std::vector<Tri>> faces;
  std::vector<Vec3> limit;
  std::vector<VertexProperty> properties;
};

Hierarchy uniform_hierarchy(const TriMesh& base, int levels) {
  Hierarchy h;
  TriMesh m = base;
  h.faces.push_back(m.faces);
  for (int k = 0; k < levels; ++k) {
    m = k + 1 < levels ? loop_subdivide(m) : loop_subdivide_to_limit(m);
    h.faces.push_back(m.faces);
  }
  if (levels == 0) m = loop_limit(m);
  h.limit = std::move(m.vertices);
  h.properties = std::move(m.vertex_properties);
  return h;
}

struct LeafId {
  int32_t level, face;
};

/// The output mesh of a forest, with where each of its faces and vertices comes from.
struct Conforming {
  TriMesh mesh;
  std::vector<LeafId> leaf;          ///< per face: the leaf it lies in
  std::vector<uint8_t> transition;   ///< per face: 1 for a crack-closing piece of a leaf
};

/// Which faces of which level are leaves, and how many leaves use each vertex as a corner: a leaf's edge
/// is split exactly when its midpoint is a corner of some leaf (necessarily one across that edge).
class Forest {
 public:
  explicit Forest(const Hierarchy& h) : h_(h), leaf_(h.faces.size()), uses_(h.limit.size(), 0) {
    for (std::size_t k = 0; k < h.faces.size(); ++k) leaf_[k].assign(h.faces[k].size(), 0);
    for (std::size_t f = 0; f < h.faces[0].size(); ++f) add({0, static_cast<int32_t>(f)});
  }

  int finest() const { return static_cast<int>(h_.faces.size()) - 1; }
  bool is_leaf(LeafId l) const { return leaf_[l.level][l.face]; }

  void split(LeafId l) {
    remove(l);
    for (int32_t c = 0; c < 4; ++c) add({l.level + 1, 4 * l.face + c});
  }

  /// Splits leaves until neighbours differ by at most one level and no leaf has all three edges split.
  void close() {
    for (bool changed = true; changed;) {
      changed = false;
      for (int32_t k = 0; k < finest(); ++k)
        for (int32_t f = 0; f < static_cast<int32_t>(leaf_[k].size()); ++f)
          if (leaf_[k][f] && must_split({k, f})) {
            split({k, f});
            changed = true;
          }
    }
  }

  /// Unsplit leaves as they are; a leaf with one split edge in two, with two split edges in three
  /// (a corner triangle and the rest cut along its shorter diagonal), as paper Fig. 6.
  Conforming conforming() const {
    Conforming out;
    const auto emit = [&](LeafId l, bool transition, int32_t a, int32_t b, int32_t c) {
      out.mesh.faces.push_back({a, b, c});
      out.leaf.push_back(l);
      out.transition.push_back(transition);
    };
    for (int32_t k = 0; k <= finest(); ++k)
      for (int32_t f = 0; f < static_cast<int32_t>(leaf_[k].size()); ++f) {
        if (!leaf_[k][f]) continue;
        const LeafId l{k, f};
        const Tri& t = h_.faces[k][f];
        int split_edges = 0, unsplit = 0, split_one = 0;
        for (int j = 0; j < 3; ++j) {
          if (edge_split(l, j)) {
            ++split_edges;
            split_one = j;
          } else {
            unsplit = j;
          }
        }
        if (split_edges == 0) {
          emit(l, false, t[0], t[1], t[2]);
        } else if (split_edges == 1) {
          const int j = split_one;
          const int32_t a = t[j], b = t[(j + 1) % 3], c = t[(j + 2) % 3], m = midpoint(l, j);
          emit(l, true, a, m, c);
          emit(l, true, m, b, c);
        } else {
          const int j = unsplit;
          const int32_t a = t[j], b = t[(j + 1) % 3], c = t[(j + 2) % 3];
          const int32_t m1 = midpoint(l, (j + 1) % 3), m2 = midpoint(l, (j + 2) % 3);  // on bc, on ca
          emit(l, true, m1, c, m2);
          const auto& p = h_.limit;
          if ((p[a] - p[m1]).squaredNorm() <= (p[b] - p[m2]).squaredNorm()) {
            emit(l, true, a, b, m1);
            emit(l, true, a, m1, m2);
          } else {
            emit(l, true, a, b, m2);
            emit(l, true, b, m1, m2);
          }
        }
      }
    // Keep the used vertices in their hierarchy order: a uniform result is numbered as loop_subdivide's.
    std::vector<uint8_t> used(h_.limit.size(), 0);
    for (const Tri& t : out.mesh.faces)
      for (int32_t v : t) used[v] = 1;
    std::vector<int32_t> local(h_.limit.size(), -1);
    for (const VertexProperty& p : h_.properties) out.mesh.vertex_properties.push_back({p.name, {}});
    for (std::size_t v = 0; v < local.size(); ++v)
      if (used[v]) {
        local[v] = static_cast<int32_t>(out.mesh.vertices.size());
        out.mesh.vertices.push_back(h_.limit[v]);
        for (std::size_t k = 0; k < h_.properties.size(); ++k)
          out.mesh.vertex_properties[k].values.push_back(h_.properties[k].values[v]);
      }
    for (Tri& t : out.mesh.faces)
      for (int32_t& v : t) v = local[v];
    return out;
  }

  /// Splits every leaf (a uniform level).
  void split_all() {
    for (int32_t k = finest() - 1; k >= 0; --k)
      for (int32_t f = 0; f < static_cast<int32_t>(leaf_[k].size()); ++f)
        if (leaf_[k][f]) split({k, f});
  }

 private:
  void add(LeafId l) {
    leaf_[l.level][l.face] = 1;
    for (int32_t v : h_.faces[l.level][l.face]) ++uses_[v];
  }
  void remove(LeafId l) {
    leaf_[l.level][l.face] = 0;
    for (int32_t v : h_.faces[l.level][l.face]) --uses_[v];
  }
  /// The vertex the next level puts on edge j (corner j to corner j + 1) of a face.
  int32_t midpoint(LeafId l, int j) const { return h_.faces[l.level + 1][4 * l.face + 3][j]; }
  bool edge_split(LeafId l, int j) const { return l.level < finest() && uses_[midpoint(l, j)] > 0; }

  bool must_split(LeafId l) const {
    int split_edges = 0;
    for (int j = 0; j < 3; ++j) {
      if (!edge_split(l, j)) continue;
      ++split_edges;
      // The halves of edge j are edge j of children j and j + 1: split there means the leaf across is two
      // levels finer.
      if (l.level + 2 <= finest())
        for (int32_t child : {4 * l.face + j, 4 * l.face + (j + 1) % 3})
          if (edge_split({l.level + 1, child}, j)) return true;
    }
    return split_edges == 3;
  }

  const Hierarchy& h_;
  std::vector<std::vector<uint8_t>> leaf_;  ///< per level, per face
  std::vector<int32_t> uses_;               ///< per vertex of the finest level
};

/// Per face: a vertex's scaled and equalised curvature measure reaches the threshold.
std::vector<uint8_t> curvature_tags(const TriMesh& mesh, CurvatureMeasure measure, double threshold) {
  const std::vector<double> e =
      equalize_histogram(scale_to_unit(measure_values(estimate_curvature(mesh), measure)));
  std::vector<uint8_t> tags(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Tri& t = mesh.faces[f];
    tags[f] = e[t[0]] >= threshold || e[t[1]] >= threshold || e[t[2]] >= threshold;
  }
  return tags;
}

/// Per face: the interior dihedral angle to a neighbour across an edge (π minus the angle between their
/// normals; π when coplanar) is below `angle` radians.
std::vector<uint8_t> dihedral_tags(const TriMesh& mesh, double angle) {
  const std::size_t nf = mesh.faces.size();
  std::vector<Vec3> normal(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const Tri& t = mesh.faces[f];
    const Vec3 n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const double length = n.norm();
    normal[f] = length > 0 ? Vec3(n / length) : Vec3::Zero();
  }
  // Half-edges sorted by their undirected edge pair up the two faces of every interior edge.
  std::vector<std::pair<uint64_t, int32_t>> half_edges;
  half_edges.reserve(3 * nf);
  for (std::size_t f = 0; f < nf; ++f)
    for (int j = 0; j < 3; ++j) {
      const uint32_t a = mesh.faces[f][j], b = mesh.faces[f][(j + 1) % 3];
      half_edges.push_back({(uint64_t(std::min(a, b)) << 32) | std::max(a, b), static_cast<int32_t>(f)});
    }
  std::sort(half_edges.begin(), half_edges.end());
  // The normals meet at more than π − angle exactly when the interior angle is below `angle`.
  const double cos_limit = std::cos(M_PI - angle);
  std::vector<uint8_t> tags(nf, 0);
  for (std::size_t i = 0; i + 1 < half_edges.size(); ++i) {
    if (half_edges[i].first != half_edges[i + 1].first) continue;
    const int32_t f = half_edges[i].second, g = half_edges[i + 1].second;
    if (normal[f].dot(normal[g]) < cos_limit) tags[f] = tags[g] = 1;
    ++i;
  }
  return tags;
}

}  // namespace

void validate(const SubdivisionOptions& options) {
  if (options.levels < 0 || options.levels > 4)
    throw std::invalid_argument("levels must be 0 to 4, got " + std::to_string(options.levels));
  if (options.uniform_levels < 0)
    throw std::invalid_argument("uniform levels must be ≥ 0, got " + std::to_string(options.uniform_levels));
  if (!(options.threshold >= 0 && options.threshold <= 1))
    throw std::invalid_argument("threshold must be in [0, 1], got " + number_text(options.threshold));
  if (!(options.angle_degrees >= 0 && options.angle_degrees <= 180))
    throw std::invalid_argument("angle must be in [0, 180] degrees, got " +
                                number_text(options.angle_degrees));
}

SubdividedMesh subdivide(const TriMesh& base, const SubdivisionOptions& options) {
  validate(options);
  Hierarchy hierarchy = uniform_hierarchy(base, options.levels);
  SubdividedMesh out;
  if (options.method == Refinement::uniform || options.levels <= options.uniform_levels) {
    // Every level splits every triangle: the finest uniform level is the result, as the forest would give
    // it (same numbering), without building it again face by face (a third of the stage's time at 18
    // million triangles).
    out.mesh.vertices = std::move(hierarchy.limit);
    out.mesh.faces = std::move(hierarchy.faces.back());
    out.mesh.vertex_properties = std::move(hierarchy.properties);
    out.face_level.assign(out.mesh.faces.size(), static_cast<uint8_t>(options.levels));
    out.transition.assign(out.mesh.faces.size(), 0);
    out.tagged.assign(static_cast<std::size_t>(options.levels), 1.0);
    return out;
  }
  Forest forest(hierarchy);
  for (int level = 0; level < options.levels; ++level) {
    if (options.method == Refinement::uniform || level < options.uniform_levels) {
      forest.split_all();
      out.tagged.push_back(1);
      continue;
    }
    const Conforming current = forest.conforming();
    const std::vector<uint8_t> tags = options.method == Refinement::curvature
                                          ? curvature_tags(current.mesh, options.measure, options.threshold)
                                          : dihedral_tags(current.mesh, options.angle_degrees * M_PI / 180);
    int64_t tagged = 0;
    for (std::size_t f = 0; f < tags.size(); ++f) {
      if (!tags[f]) continue;
      ++tagged;
      // A tagged crack-closing piece splits its whole leaf (the leaf's other pieces may already have).
      if (forest.is_leaf(current.leaf[f])) forest.split(current.leaf[f]);
    }
    out.tagged.push_back(tags.empty() ? 0.0 : double(tagged) / double(tags.size()));
    forest.close();
  }
  Conforming result = forest.conforming();
  out.mesh = std::move(result.mesh);
  out.transition = std::move(result.transition);
  out.face_level.reserve(result.leaf.size());
  for (const LeafId& l : result.leaf) out.face_level.push_back(static_cast<uint8_t>(l.level));
  return out;
}

}  // namespace vesselmesh
