// tile_base_mesh: the tiler's run, and the kind each branch is built as (tube, shared square, stub,
// swallowed or tunnel), decided again until every patch closes.

#include "vesselmesh/tile/base_mesh.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "vesselmesh/error.hpp"
#include "vesselmesh/parallel.hpp"
#include "vesselmesh/tile/corners.hpp"
#include "vesselmesh/tile/tiler.hpp"
#include "vesselmesh/tile/tube_sections.hpp"

namespace vesselmesh::tile_detail {

using Quad = std::array<int32_t, 4>;

Tiler::Tiler(const CenterlineGraph& g, const TileOptions& o, const std::vector<int32_t>& corners)
    : g_(g), opt_(o), joints_(g.points.size()) {
  SamplingOptions sampling = o.sampling;  // the corners are found by sampling each branch as a whole
  sampling.max_sections = o.max_sections;
  CutBranches cut = cut_at_corners(g, sampling, o.radius_scale, corners);
  branches_ = std::move(cut.branches);
  corner_ = std::move(cut.corner);
  for (const Branch& b : branches_) curves_.push_back(branch_curve(g, b));
  kind_.assign(branches_.size(), Kind::tube);
  shared_at_.assign(branches_.size(), 0.0);
  shared_up_.assign(branches_.size(), Vec3::Zero());
  shared_normal_.assign(branches_.size(), Vec3::Zero());
  shared_tries_.assign(branches_.size(), 0);
  shared_vertex_.assign(branches_.size(), -1);
  tunnel_.resize(branches_.size());
}

BaseMesh Tiler::run() {
  // Refused before the work when far beyond the limit (twice: the estimate follows the arcs, the
  // sampler the chords); nearer to it, the sections placed are counted.
  double estimate = 0;
  for (const BranchCurve& c : curves_) estimate += estimated_sections(c, opt_.sampling);
  if (estimate > 2.0 * static_cast<double>(opt_.max_sections))
    throw SizeLimitError("about " + std::to_string(static_cast<int64_t>(estimate)) + " sections");
  // A tunnel or tube whose patch cannot close is given up (build_patch), and the kinds decided again
  // without it: the patch may then have too few openings for its squares to span it, take in its
  // body, and push a square that cleared the given-up mouths to the far end of its branch.
  for (bool closed = false; !closed;) {
    find_patches();
    if (!curled_.empty()) return {};
    mesh_.vertices.clear();
    mesh_.axes.clear();
    mesh_.squares.clear();
    mesh_.triangles.clear();
    mesh_.sections = mesh_.joints = 0;
    std::fill(shared_vertex_.begin(), shared_vertex_.end(), -1);
    closed = std::all_of(patches_.begin(), patches_.end(), [&](const Patch& p) { return build_patch(p); });
  }
  // Tubes are planned on every core at once, then added in branch order: the numbering does not depend
  // on the cores.
  std::vector<TubePlan> plans(branches_.size());
  parallel_for(
      branches_.size(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b)
          if (kind_[b] == Kind::tube) plans[b] = plan_tube(static_cast<int32_t>(b));
      },
      kBranchesPerTask);
  for (std::size_t b = 0; b < branches_.size(); ++b) {
    if (kind_[b] == Kind::tube) build_tube(static_cast<int32_t>(b), plans[b]);
    if (kind_[b] == Kind::tunnel) build_tunnel(static_cast<int32_t>(b));
    plans[b] = {};
  }
  drop_unused_vertices();
  return std::move(mesh_);
}

/// Whether the tube of branch b, between the squares at its two joints, would fold: no chain of its
/// sections from one square to the other gets there without one reaching across the next one's plane
/// (fold_free_chains). A short thick branch between two patches that face it from sides a right angle
/// apart folded so (brava-records BH0005). Unless `thorough`, only tubes shorter than four corner radii
/// are looked at: longer ones mostly have room to turn, and their bends too tight for sections are
/// corners already. Not always: squares pushed out up to a bend of their branch (a loop from a patch
/// back to it, 116° turns between its legs) face across it, the tube keeps only those two squares, and
/// the straight prism between them runs along the patch's own faces (a non-manifold base mesh).
bool Tiler::tube_folds(int32_t b, bool thorough) const {
  const End &head = ends_[head_[b]], &tail = ends_[tail_[b]];
  const BranchCurve& c = curves_[b];
  const double from = head.t, to = c.length() - tail.t;
  if (!thorough && to - from > 4 * scale() * std::max(head.square.radius, tail.square.radius)) return false;
  const std::vector<double> arcs = sample_branch(c, from, to, opt_.sampling);
  std::vector<Section> sections(arcs.size());
  for (std::size_t i = 0; i < arcs.size(); ++i) {
    sections[i].center = c.position(arcs[i]);
    sections[i].radius = c.radius_at(arcs[i]);
    sections[i].normal = c.tangent(arcs[i]);
  }
  sections.front() = head.square;
  sections.back() = tail.square;
  sections.back().normal = -tail.square.normal;  // along the branch, as the others
  std::vector<std::size_t> chain;
  return fold_free_chains(sections, scale(), chain).back() == 0;
}

/// Whether a branch from a joint to a terminal has room for a tube after its joint square: its end lies
/// a quarter of its radius or more in front of the square, or two diameters away. One that turns back
/// behind the square within that (a hairpin a few radii long) would fold into the patch.
bool Tiler::room_for_tube(int32_t b) const {
  const End& e = ends_[head_[b] >= 0 ? head_[b] : tail_[b]];
  const BranchCurve& c = curves_[b];
  const double far = e.at_start ? c.length() : 0.0, r = c.radius_at(far);
  const Vec3 to_end = c.position(far) - e.square.center;
  return e.square.normal.dot(to_end) >= 0.25 * r || to_end.norm() >= 2 * (r + e.square.radius);
}

/// Groups joints into patches and decides each branch's kind. A branch between two joints too short
/// for a tube first tries one shared square (best_shared_square), placed again while the squares
/// pushed out round it come to reach across it, up to kSharedTries times; failing that, its joints
/// merge into one patch, or, when they share one already, it becomes a tunnel. A branch from a joint
/// to a terminal too short for a tube, or without room for one after its square (room_for_tube),
/// becomes a stub. Repeated until nothing changes; then the longer tubes are looked at for folds too
/// (tube_folds, thorough), once the squares stand where they will, as that costs a chain per tube.
void Tiler::find_patches() {
  for (int round = 0;; ++round) {
    collect_patches();
    for (const Patch& p : patches_) place_squares(p, 0);
    // A tunnel whose mouths cannot clear the patch is turned to run where the patch is thinner. One
    // whose mouths come close to another tunnel's (two loops of nearly the same centre) first moves
    // its hole away from the other's by twice their corners' reach, then is turned too. One that
    // still cannot open gives its loop up. The patch is placed again before anything else is decided,
    // as the mouths may have pushed the other squares.
    bool changed = false;
    for (const Patch& p : patches_) {
      std::vector<int32_t> kept;
      for (int32_t i : p.ends) {
        const int32_t b = ends_[i].branch;
        if (kind_[b] != Kind::tunnel || !ends_[i].at_start) continue;
        if (hole_crossed(b)) {
          changed = true;
          give_up_loop(p, b, "the surface crossed itself round its hole through the joint patch");
          continue;
        }
        const auto met =  // a kept tunnel whose mouths this one's come close to
            std::find_if(kept.begin(), kept.end(), [&](int32_t other) { return mouths_meet(b, other); });
        if (met == kept.end() && !ends_[head_[b]].stuck && !ends_[tail_[b]].stuck) {
          kept.push_back(b);
          continue;
        }
        changed = true;
        if (met != kept.end() && tunnel_[b].offset.isZero()) {
          Tunnel &h = tunnel_[b], &other = tunnel_[*met];
          Vec3 away = h.center - other.center;
          away = away.norm() > 0 ? away.normalized() : any_perpendicular(other.normal);
          h.offset = 2 * scale() * (h.hole() + other.hole()) * away;
          continue;
        }
        if (tunnel_[b].turns < kTurns && turn_tunnel(b, p, kept)) continue;
        give_up_loop(p, b,
                     met != kept.end()
                         ? "its hole through the joint patch would meet another loop's there"
                         : "its tubes overlap, and no hole through the joint patch opens within "
                           "four of the loop's radii");
      }
    }
    if (changed || decide_kinds(false) || decide_kinds(true)) continue;
    return;
  }
}

/// Decides the kind of each branch from where its squares stand (find_patches); true when one
/// changed. `thorough`: whether tube_folds looks at every tube between two joints, not only short ones.
bool Tiler::decide_kinds(bool thorough) {
  // Whether each tube between two joints folds, looked at on every core at once: deciding one branch's
  // kind moves no other branch's squares.
  std::vector<char> folds(branches_.size(), 0);
  parallel_for(
      branches_.size(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b)
          if (kind_[b] == Kind::tube && head_[b] >= 0 && tail_[b] >= 0 && has_room(static_cast<int32_t>(b)))
            folds[b] = tube_folds(static_cast<int32_t>(b), thorough);
      },
      kBranchesPerTask);
  bool changed = false;
  for (std::size_t bi = 0; bi < branches_.size(); ++bi) {
    const int32_t b = static_cast<int32_t>(bi);
    if (kind_[b] == Kind::swallowed || kind_[b] == Kind::stub || kind_[b] == Kind::tunnel ||
        (head_[b] < 0 && tail_[b] < 0))
      continue;
    const bool both = head_[b] >= 0 && tail_[b] >= 0;
    if (kind_[b] == Kind::shared) {
      const Patch& hp = patches_[patch_of_end_[head_[b]]];
      const Patch& tp = patches_[patch_of_end_[tail_[b]]];
      if (intrusion(ends_[head_[b]], hp) <= 0 && intrusion(ends_[tail_[b]], tp) <= 0) continue;
    } else if (has_room(b) && (both ? !folds[b] : room_for_tube(b))) {
      continue;
    }
    changed = true;
    give_up_tube(b);
  }
  return changed;
}

/// Whether branch b's squares left it room for a tube: neither is stuck, and they stand a quarter radius
/// or more apart along it.
bool Tiler::has_room(int32_t b) const {
  double used = 0.25 * std::min(curves_[b].radius.front(), curves_[b].radius.back());
  for (int32_t i : {head_[b], tail_[b]})
    if (i >= 0) {
      if (ends_[i].stuck) return false;
      used += ends_[i].t;
    }
  return used <= curves_[b].length();
}

/// The point of terminal branch b furthest from its joint where b curls back (curled()), or −1: it is
/// longer than kCurlDiameters and its squares left it room, but it has none for a tube after its square.
int32_t Tiler::curl_apex(int32_t b) const {
  const BranchCurve& c = curves_[b];
  const std::vector<int32_t>& points = branches_[b].points;
  if (!has_room(b) || room_for_tube(b) ||
      c.length() <= kCurlDiameters * 2 * (c.radius.front() + c.radius.back()))
    return -1;
  const Vec3& joint = g_.points[head_[b] >= 0 ? points.front() : points.back()];
  int32_t apex = -1;
  double furthest = 0;
  for (std::size_t i = 1; i + 1 < points.size(); ++i)
    if (const double d = (g_.points[points[i]] - joint).norm(); d > furthest) furthest = d, apex = points[i];
  return apex;
}

/// Branch b is no tube (or shared square) at its joints: a stub when it ends at a terminal (or, where it
/// curls back, a point to tile as a corner: curled()), else a shared square, a tunnel, or swallowed by its
/// joints' merged patch.
void Tiler::give_up_tube(int32_t b) {
  if (head_[b] < 0 || tail_[b] < 0) {
    if (const int32_t apex = curl_apex(b); apex >= 0) curled_.push_back(apex);
    kind_[b] = Kind::stub;
    ++mesh_.absorbed_branches;
  } else if (joints_.find(first_point(b)) == joints_.find(last_point(b))) {
    // Merging its joints would close a loop inside one patch and fill the loop's hole: merges form
    // a forest, and the branch that would close the loop makes the hole a tunnel instead.
    kind_[b] = Kind::tunnel;
    ++mesh_.absorbed_branches;
    ++mesh_.tunnels;
  } else if (shared_tries_[b] < kSharedTries && best_shared_square(b) > 0) {
    ++shared_tries_[b];
    kind_[b] = Kind::shared;
    shared_up_[b] = any_perpendicular(shared_normal_[b]);
  } else {
    kind_[b] = Kind::swallowed;
    joints_.unite(first_point(b), last_point(b));
    ++mesh_.absorbed_branches;
  }
}

/// Stub squares that ended up inside a patch's hull are not used by any face.
void Tiler::drop_unused_vertices() {
  std::vector<int32_t> new_id(mesh_.vertices.size(), -1);
  for (const Quad& q : mesh_.quads)
    for (int32_t v : q) new_id[v] = 0;
  for (const Tri& t : mesh_.triangles)
    for (int32_t v : t) new_id[v] = 0;
  int32_t next = 0;
  for (std::size_t v = 0; v < new_id.size(); ++v) {
    if (new_id[v] < 0) continue;
    new_id[v] = next;
    mesh_.vertices[next] = mesh_.vertices[v];
    mesh_.axes[next] = mesh_.axes[v];
    ++next;
  }
  mesh_.vertices.resize(next);
  mesh_.axes.resize(next);
  for (Quad& q : mesh_.quads)
    for (int32_t& v : q) v = new_id[v];
  for (Tri& t : mesh_.triangles)
    for (int32_t& v : t) v = new_id[v];
  // A stub's square inside the hull is gone with its corners.
  for (Quad& q : mesh_.squares)
    for (int32_t& v : q) v = new_id[v];
  mesh_.squares.erase(std::remove_if(mesh_.squares.begin(), mesh_.squares.end(),
                                     [](const Quad& q) { return std::find(q.begin(), q.end(), -1) != q.end(); }),
                      mesh_.squares.end());
}

}  // namespace vesselmesh::tile_detail

namespace vesselmesh {

BaseMesh tile_base_mesh(const CenterlineGraph& graph, const TileOptions& options) {
  // Tiled again with the apexes of the terminal branches that curl back as corners, until none does: each
  // round cuts branches at new points, so the rounds end.
  std::vector<int32_t> corners;
  for (;;) {
    tile_detail::Tiler tiler(graph, options, corners);
    BaseMesh mesh = tiler.run();
    if (tiler.curled().empty()) return mesh;
    corners.insert(corners.end(), tiler.curled().begin(), tiler.curled().end());
  }
}

}  // namespace vesselmesh
