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
                            const std::vector<Eigen::Vector3f>& before) {
  std::vector<int32_t> out;
  std::mutex lock;
  parallel_for(faces.size(), [&](std::size_t begin, std::size_t end) {
    std::vector<int32_t> found;
    for (std::size_t i = begin; i < end; ++i) {
      const Tri& t = mesh.faces[faces[i]];
      if (!touches(t, dirty)) continue;
      const Vec3 now = face_normal(moved, t);
      const Vec3 was = before[i].cast<double>();
      if (now.dot(was) < kTurnCosine * now.norm() * was.norm())
        found.insert(found.end(), t.begin(), t.end());
    }
    const std::lock_guard<std::mutex> guard(lock);
    out.insert(out.end(), found.begin(), found.end());
  });
  return out;
}

/// Boxes binned in a grid of cells about as large as the median box. Most triangles lie far from every long
/// move: a look at the few cells a triangle's box covers finds the boxes it meets sooner than a walk down a
/// hierarchy, which answers instead for a box over more than kMostLooked cells.
class BoxGrid {
 public:
  explicit BoxGrid(const std::vector<Box>& boxes) : boxes_(boxes), bvh_(boxes) {
    for (const Box& b : boxes) all_.extend(b);
    if (boxes.empty()) return;
    // Cells as large as the median box (each box then covers a few), fewer than kMaxCells in all, and larger
    // where some boxes are much larger than the rest: the boxes cover kMostHeld cells each on average.
    std::vector<double> sizes;
    sizes.reserve(boxes.size());
    for (const Box& b : boxes) sizes.push_back((b.hi - b.lo).maxCoeff());
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    const Vec3 extent = all_.hi - all_.lo;
    cell_ = std::max(sizes[sizes.size() / 2], extent.maxCoeff() * 1e-6);
    if (!(cell_ > 0)) cell_ = 1;  // every box a point at one place
    for (;; cell_ *= 1.5) {
      for (int a = 0; a < 3; ++a) count_[a] = static_cast<int64_t>(extent[a] / cell_) + 1;
      if (count_[0] * count_[1] * count_[2] > kMaxCells) continue;
      int64_t held = 0;
      for (const Box& b : boxes) held += cells(b);
      if (held <= kMostHeld * static_cast<int64_t>(boxes.size())) break;
    }
    // Each cell's boxes: items_[start_[c], start_[c + 1]).
    start_.assign(count_[0] * count_[1] * count_[2] + 1, 0);
    for (const Box& b : boxes) visit(b, [&](int64_t c) { ++start_[c + 1]; });
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.resize(start_.back());
    std::vector<int64_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < boxes.size(); ++i)
      visit(boxes[i], [&](int64_t c) { items_[fill[c]++] = static_cast<int32_t>(i); });
  }

  /// Calls f(i) once for every box i that `box` meets.
  template <class F>
  void for_each_meeting(const Box& box, F&& f) const {
    if (start_.empty() || !box.overlaps(all_)) return;
    if (cells(box) > kMostLooked) {
      bvh_.search([&](const Box& b) { return b.overlaps(box) ? 0.0 : 1.0; }, 0.0, f);
      return;
    }
    const std::array<int64_t, 3> lo = cell_of(box.lo), hi = cell_of(box.hi);
    for (int64_t x = lo[0]; x <= hi[0]; ++x)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t z = lo[2]; z <= hi[2]; ++z) {
          const int64_t c = (x * count_[1] + y) * count_[2] + z;
          for (int64_t k = start_[c]; k < start_[c + 1]; ++k) {
            const Box& b = boxes_[items_[k]];
            if (!b.overlaps(box)) continue;
            // Two boxes that meet share a block of cells: the pair is reported in its first cell only.
            const std::array<int64_t, 3> first = cell_of(b.lo);
            if (x == std::max(lo[0], first[0]) && y == std::max(lo[1], first[1]) &&
                z == std::max(lo[2], first[2]))
              f(items_[k]);
          }
        }
  }

 private:
  static constexpr int64_t kMaxCells = int64_t{1} << 22;
  static constexpr int64_t kMostLooked = 64;
  static constexpr int64_t kMostHeld = 8;
  /// How many cells `box` covers.
  int64_t cells(const Box& box) const {
    const std::array<int64_t, 3> lo = cell_of(box.lo), hi = cell_of(box.hi);
    return (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
  }
  /// Calls f(cell) on the cells `box` covers (within the grid).
  template <class F>
  void visit(const Box& box, F&& f) const {
    const std::array<int64_t, 3> lo = cell_of(box.lo), hi = cell_of(box.hi);
    for (int64_t x = lo[0]; x <= hi[0]; ++x)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t z = lo[2]; z <= hi[2]; ++z) f((x * count_[1] + y) * count_[2] + z);
  }
  /// The cell that holds point p (clamped to the grid): monotone in each coordinate, so that boxes that
  /// meet share a cell.
  std::array<int64_t, 3> cell_of(const Vec3& p) const {
    std::array<int64_t, 3> cell;
    for (int a = 0; a < 3; ++a) {
      const double i = std::floor((p[a] - all_.lo[a]) / cell_);
      const double last = static_cast<double>(count_[a] - 1);
      cell[a] = !(i > 0) ? 0 : i < last ? static_cast<int64_t>(i) : count_[a] - 1;
    }
    return cell;
  }

  const std::vector<Box>& boxes_;
  Bvh bvh_;
  Box all_;
  double cell_ = 1;
  std::array<int64_t, 3> count_ = {0, 0, 0};
  std::vector<int64_t> start_;
  std::vector<int32_t> items_;
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
  const BoxGrid near_long(boxes);
  std::mutex lock;
  parallel_for(mesh.faces.size(), [&](std::size_t begin, std::size_t end) {
    std::vector<std::array<int32_t, 2>> found;
    for (std::size_t g = begin; g < end; ++g) {
      const Tri& tg = mesh.faces[g];
      near_long.for_each_meeting(swept(tg), [&](int32_t i) {
        const int32_t f = long_faces[i];
        if (f == static_cast<int32_t>(g) || (is_long[g] && static_cast<int32_t>(g) < f)) return;
        // Neighbours (sharing a corner) do not cross in the surface as subdivided; others may, where input
        // tubes overlap.
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

std::vector<double> long_move_reach(const TriMesh& mesh, const std::vector<double>& radius) {
  std::vector<double> reach(mesh.vertices.size());
  for (std::size_t v = 0; v < reach.size(); ++v) reach[v] = kLongAgainstRadius * radius[v];
  for (const Tri& t : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const double edge = kLongAgainstEdge * (mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).norm();
      reach[t[k]] = std::min(reach[t[k]], edge);
      reach[t[(k + 1) % 3]] = std::min(reach[t[(k + 1) % 3]], edge);
    }
  return reach;
}

GuardedMoves move_without_folding(TriMesh& mesh, std::vector<Vec3> move, const std::vector<double>& reach) {
  GuardedMoves stats;
  const std::size_t n = mesh.vertices.size();
  // Only triangles with a moved corner can fold; only those with a long move can cross others.
  std::vector<char> kind(mesh.faces.size());  // 0 still, 1 moved, 2 with a long move
  parallel_for(mesh.faces.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) {
      const Tri& t = mesh.faces[f];
      auto is_long = [&](int32_t v) { return move[v].norm() > reach[v]; };
      auto moves = [&](int32_t v) { return move[v] != Vec3::Zero(); };
      kind[f] = std::any_of(t.begin(), t.end(), is_long) ? 2 : std::any_of(t.begin(), t.end(), moves) ? 1 : 0;
    }
  });
  std::vector<int32_t> faces, long_faces;
  for (std::size_t f = 0; f < kind.size(); ++f) {
    if (kind[f] != 0) faces.push_back(static_cast<int32_t>(f));
    if (kind[f] == 2) long_faces.push_back(static_cast<int32_t>(f));
  }
  // Unit normals: the fold test reads their direction only, which floats hold well enough.
  std::vector<Eigen::Vector3f> before(faces.size());
  parallel_for(faces.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      before[i] = face_normal(mesh.vertices, mesh.faces[faces[i]]).normalized().cast<float>();
  });

  // The tests judge the surface as it is written, in floats: rounding can turn a triangle over that a move
  // left almost flat.
  std::vector<Vec3> moved(n);
  parallel_for(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) moved[v] = rounded_to_float(mesh.vertices[v] + move[v]);
  });
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
  stats.cut.assign(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    stats.moved += move[v] != Vec3::Zero();
    stats.cut[v] = halved[v] != 0;
    stats.held_back += stats.cut[v];
  }
  mesh.vertices = std::move(moved);
  return stats;
}

}  // namespace vesselmesh
