#include "vesselmesh/geometry/guarded_moves.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <mutex>

#include "vesselmesh/geometry/bvh.hpp"
#include "vesselmesh/geometry/predicates.hpp"
#include "vesselmesh/parallel.hpp"

namespace vesselmesh {

namespace {

/// A triangle whose normal turns further than this (cosine: a right angle) has folded over. The sides of a
/// crotch's crease turn by up to about 60° from the web they come from.
constexpr double kTurnCosine = 0.0;
/// A move can carry a triangle through another part of the surface once it is longer than this share of
/// the vertex's shortest edge (a triangle near by), or than this share of the local radius (another
/// vessel passing close); shorter moves only bend the triangles round it, which the fold test watches.
constexpr double kLongAgainstEdge = 0.5;
constexpr double kLongAgainstRadius = 0.2;
/// A move that folds or crosses is halved, and dropped once it has been cut this many times.
constexpr int kHalvings = 6;
bool share_corner(const Tri& a, const Tri& b) {
  for (int32_t v : a)
    if (v == b[0] || v == b[1] || v == b[2]) return true;
  return false;
}

bool touches(const Tri& t, const std::vector<char>& dirty) {
  return dirty[t[0]] || dirty[t[1]] || dirty[t[2]];
}

/// Corners of the moved triangles with a dirty corner whose normal turned over.
std::vector<int32_t> folded(const TriMesh& mesh, const std::vector<Vec3>& moved,
                            const std::vector<char>& dirty, const std::vector<int32_t>& faces,
                            const std::vector<Vec3>& before) {
  std::vector<int32_t> out;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const Tri& t = mesh.faces[faces[i]];
    if (!touches(t, dirty)) continue;
    const Vec3 now = face_normal(moved, t);
    if (now.dot(before[i]) < kTurnCosine * now.norm() * before[i].norm())
      out.insert(out.end(), t.begin(), t.end());
  }
  return out;
}

/// The cells of a grid over some boxes that any of them covers. Most triangles lie far from every long move:
/// a look at the few cells a triangle's box covers settles that sooner than a walk down a hierarchy.
class Occupancy {
 public:
  explicit Occupancy(const std::vector<Box>& boxes) {
    for (const Box& b : boxes) all_.extend(b);
    if (boxes.empty()) return;
    // Cells as large as the median box (each box then covers a few), fewer than kMaxCells in all.
    std::vector<double> sizes;
    sizes.reserve(boxes.size());
    for (const Box& b : boxes) sizes.push_back((b.hi - b.lo).maxCoeff());
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    const Vec3 extent = all_.hi - all_.lo;
    cell_ = std::max(sizes[sizes.size() / 2], extent.maxCoeff() * 1e-6);
    if (!(cell_ > 0)) cell_ = 1;  // every box a point at one place
    for (;;) {
      for (int a = 0; a < 3; ++a) count_[a] = static_cast<int64_t>(extent[a] / cell_) + 1;
      if (count_[0] * count_[1] * count_[2] <= kMaxCells) break;
      cell_ *= 1.5;
    }
    occupied_.assign(count_[0] * count_[1] * count_[2], 0);
    for (const Box& b : boxes)
      visit(b, [&](int64_t c) {
        occupied_[c] = 1;
        return false;
      });
  }

  /// False when `box` meets no box of the set (true may still mean none, and does for a box over more
  /// than kMostLooked cells, which the hierarchy answers sooner).
  bool may_meet(const Box& box) const {
    if (occupied_.empty() || !box.overlaps(all_)) return false;
    int64_t cells = 1;
    for (int a = 0; a < 3; ++a) cells *= index(box.hi[a], a) - index(box.lo[a], a) + 1;
    if (cells > kMostLooked) return true;
    return visit(box, [&](int64_t c) { return occupied_[c] != 0; });
  }

 private:
  static constexpr int64_t kMaxCells = int64_t{1} << 22;
  static constexpr int64_t kMostLooked = 64;
  /// Calls f(cell) on the cells `box` covers (within the grid) until f returns true; returns whether it did.
  template <class F>
  bool visit(const Box& box, F&& f) const {
    std::array<int64_t, 3> lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = index(box.lo[a], a);
      hi[a] = index(box.hi[a], a);
    }
    for (int64_t x = lo[0]; x <= hi[0]; ++x)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t z = lo[2]; z <= hi[2]; ++z)
          if (f((x * count_[1] + y) * count_[2] + z)) return true;
    return false;
  }
  /// The cell along axis `a` that holds coordinate v (clamped to the grid): monotone in v, so that boxes
  /// that meet share a cell.
  int64_t index(double v, int a) const {
    const double i = std::floor((v - all_.lo[a]) / cell_);
    if (!(i > 0)) return 0;
    return i < static_cast<double>(count_[a] - 1) ? static_cast<int64_t>(i) : count_[a] - 1;
  }

  Box all_;
  double cell_ = 1;
  std::array<int64_t, 3> count_ = {0, 0, 0};
  std::vector<uint8_t> occupied_;
};

/// Pairs of a triangle with a long move and another triangle that the move may carry it into: their boxes,
/// each swept from the triangle's place before the fit to after it (every halved move lies in between),
/// overlap, and they did not cross before the fit (input tubes that overlap cross anyway). Each pair once,
/// in no particular order.
std::vector<std::array<int32_t, 2>> crossing_candidates(const TriMesh& mesh, const std::vector<Vec3>& moved,
                                                        const std::vector<int32_t>& long_faces) {
  std::vector<std::array<int32_t, 2>> out;
  if (long_faces.empty()) return out;
  auto swept = [&](const Tri& t) {
    Box box;
    for (int32_t v : t) box.extend(mesh.vertices[v]), box.extend(moved[v]);
    return box;
  };
  std::vector<char> is_long(mesh.faces.size(), 0);
  for (int32_t f : long_faces) is_long[f] = 1;
  std::vector<Box> boxes(long_faces.size());
  for (std::size_t i = 0; i < long_faces.size(); ++i) boxes[i] = swept(mesh.faces[long_faces[i]]);
  const Occupancy near_long(boxes);
  const Bvh bvh(boxes);
  std::mutex lock;
  parallel_for(mesh.faces.size(), [&](std::size_t begin, std::size_t end) {
    std::vector<std::array<int32_t, 2>> found;
    for (std::size_t g = begin; g < end; ++g) {
      const Tri& tg = mesh.faces[g];
      const Box box = swept(tg);
      if (!near_long.may_meet(box)) continue;
      bvh.search([&](const Box& b) { return b.overlaps(box) ? 0.0 : 1.0; }, 0.0,
                 [&](int32_t i) {
                   const int32_t f = long_faces[i];
                   if (f == static_cast<int32_t>(g) || (is_long[g] && static_cast<int32_t>(g) < f)) return;
                   // Neighbours (sharing a corner) do not cross in the surface as subdivided; others may,
                   // where input tubes overlap.
                   const Tri& tf = mesh.faces[f];
                   if (share_corner(tf, tg) ||
                       !triangle_interiors_meet(corners(mesh.vertices, tf), corners(mesh.vertices, tg)))
                     found.push_back({f, static_cast<int32_t>(g)});
                 });
    }
    const std::lock_guard<std::mutex> guard(lock);
    out.insert(out.end(), found.begin(), found.end());
  });
  return out;
}

/// Corners of the candidate pairs with a dirty corner that cross.
std::vector<int32_t> crossing(const TriMesh& mesh, const std::vector<Vec3>& moved,
                              const std::vector<char>& dirty,
                              const std::vector<std::array<int32_t, 2>>& candidates) {
  std::vector<int32_t> out;
  auto box = [&](const Tri& t) {
    Box b;
    for (int32_t v : t) b.extend(moved[v]);
    return b;
  };
  for (const auto& [f, g] : candidates)
    if ((touches(mesh.faces[f], dirty) || touches(mesh.faces[g], dirty)) &&
        box(mesh.faces[f]).overlaps(box(mesh.faces[g])) &&
        triangle_interiors_meet(corners(moved, mesh.faces[f]), corners(moved, mesh.faces[g]))) {
      out.insert(out.end(), mesh.faces[f].begin(), mesh.faces[f].end());
      out.insert(out.end(), mesh.faces[g].begin(), mesh.faces[g].end());
    }
  return out;
}

}  // namespace

Vec3 face_normal(const std::vector<Vec3>& v, const Tri& t) {
  return (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
}

GuardedMoves move_without_folding(TriMesh& mesh, std::vector<Vec3> move, const std::vector<double>& radius) {
  GuardedMoves stats;
  const std::size_t n = mesh.vertices.size();
  // Only triangles with a moved corner can fold; only those with a long move can cross others.
  std::vector<double> reach(n);  // how far a vertex moves before its move is long
  for (std::size_t v = 0; v < n; ++v) reach[v] = kLongAgainstRadius * radius[v];
  for (const Tri& t : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const double edge = kLongAgainstEdge * (mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).norm();
      reach[t[k]] = std::min(reach[t[k]], edge);
      reach[t[(k + 1) % 3]] = std::min(reach[t[(k + 1) % 3]], edge);
    }
  std::vector<int32_t> faces, long_faces;
  std::vector<Vec3> before;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Tri& t = mesh.faces[f];
    if (std::all_of(t.begin(), t.end(), [&](int32_t v) { return move[v] == Vec3::Zero(); })) continue;
    faces.push_back(static_cast<int32_t>(f));
    before.push_back(face_normal(mesh.vertices, t));
    if (std::any_of(t.begin(), t.end(), [&](int32_t v) { return move[v].norm() > reach[v]; }))
      long_faces.push_back(static_cast<int32_t>(f));
  }

  // The tests judge the surface as it is written, in floats: rounding can turn a triangle over that a move
  // left almost flat.
  std::vector<Vec3> moved(n);
  for (std::size_t v = 0; v < n; ++v) moved[v] = rounded_to_float(mesh.vertices[v] + move[v]);
  const std::vector<std::array<int32_t, 2>> candidates = crossing_candidates(mesh, moved, long_faces);
  // Each round halves the moves of the corners of every folded or crossing triangle (once per round);
  // on the kHalvings-th cut a vertex stays where it was. Only triangles with a corner that the last round
  // changed (dirty) are looked at again, and every round changes something or ends the loop.
  std::vector<int> halved(n, 0);
  std::vector<char> dirty(n, 1);
  for (;;) {
    std::vector<int32_t> bad = folded(mesh, moved, dirty, faces, before);
    const std::vector<int32_t> crossed = crossing(mesh, moved, dirty, candidates);
    bad.insert(bad.end(), crossed.begin(), crossed.end());
    std::sort(bad.begin(), bad.end());
    bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
    std::fill(dirty.begin(), dirty.end(), 0);
    bool changed = false;
    for (int32_t v : bad) {
      if (move[v] == Vec3::Zero()) continue;
      move[v] = ++halved[v] < kHalvings ? Vec3(0.5 * move[v]) : Vec3::Zero();
      moved[v] = rounded_to_float(mesh.vertices[v] + move[v]);
      dirty[v] = 1;
      changed = true;
    }
    if (!changed) break;
  }
  for (std::size_t v = 0; v < n; ++v) {
    stats.moved += move[v] != Vec3::Zero();
    stats.held_back += halved[v] != 0;
  }
  mesh.vertices = std::move(moved);
  return stats;
}

}  // namespace vesselmesh
