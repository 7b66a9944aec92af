// Tunnels: a loop too short to part, closed inside its merged patch as a straight hole through it, from
// the loop's centroid out to two square mouths on the patch's hull.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "vesselmesh/geometry/closest_point.hpp"
#include "vesselmesh/tile/convex_hull.hpp"
#include "vesselmesh/tile/tiler.hpp"

namespace vesselmesh::tile_detail {

/// A straight hole through a convex patch gives it a genus whichever way it runs. For a tunnel whose
/// mouths could not clear patch `p` on either side of its loop's plane, or met another tunnel's:
/// mouths on two faces of the hull of the patch's other squares and rims, facing apart (normals over
/// 134° apart) and not along a branch, whose planes the tunnel's centre is nearest to and lies in front
/// of. A mouth on a face of the hull adds no bulge to it, wherever the patch is thick. The hole must
/// keep clear of the holes of the tunnels `kept` already. Returns false when no pair of faces will do
/// within the tunnel's reach.
bool Tiler::turn_tunnel(int32_t b, const Patch& p, const std::vector<int32_t>& kept) {
  Tunnel& h = tunnel_[b];
  ++h.turns;
  h.turned = false;
  std::vector<Vec3> others = p.rim;
  for (int32_t i : p.ends)
    if (ends_[i].branch != b)
      for (int k = 0; k < 4; ++k) others.push_back(corner(ends_[i], k));
  // Each face the centroid lies in front of: its outward normal and the centroid's depth below it.
  std::vector<std::pair<Vec3, double>> faces;
  for (const Tri& t : convex_hull(others)) {
    const Vec3 &a = others[t[0]], &c = others[t[1]], &d = others[t[2]];
    const Vec3 n = (c - a).cross(d - a).normalized();
    const double depth = n.dot(a - h.center);
    const Vec3 foot = h.center + depth * n;
    auto inside = [&](const Vec3& u, const Vec3& v) { return (v - u).cross(foot - u).dot(n) >= 0; };
    // A mouth facing within 30° of a branch's square would push it along its branch, and be pushed by
    // it, without end (vesselgraph-demo lost a loop so).
    const bool along_a_branch = std::any_of(p.ends.begin(), p.ends.end(), [&](int32_t i) {
      return kind_[ends_[i].branch] != Kind::tunnel && n.dot(ends_[i].square.normal) > std::cos(M_PI / 6);
    });
    if (depth > 0 && !along_a_branch && inside(a, c) && inside(c, d) && inside(d, a))
      faces.push_back({n, depth});
  }
  const double margin = 0.1 * scale() * h.hole();  // in front of a face, as intrusion() asks
  double best = h.reach() - margin;
  for (const auto& [n0, t0] : faces)
    for (const auto& [n1, t1] : faces) {
      if (n0.dot(n1) > -0.7 || std::max(t0, t1) >= best) continue;
      const Vec3 head = h.center + (t0 + margin) * n0, tail = h.center + (t1 + margin) * n1;
      const bool clash = std::any_of(kept.begin(), kept.end(), [&](int32_t other) {
        const Vec3 &a = ends_[head_[other]].square.center, &c = ends_[tail_[other]].square.center;
        const auto [s, t] = closest_parameters(head, tail, a, c);
        return (head + s * (tail - head) - (a + t * (c - a))).norm() <
               2 * scale() * (tunnel_[other].hole() + h.hole());
      });
      if (!clash) best = std::max(t0, t1), h.turned = true, h.turned_out = {n0, n1};
    }
  return h.turned;
}

/// Whether tunnel b's hole, from its head's mouth to its tail's, passes within kNearCrossing of its loop's
/// radii of a place in TileOptions::loops_closed_near.
bool Tiler::hole_crossed(int32_t b) const {
  const Vec3 &head = ends_[head_[b]].square.center, &tail = ends_[tail_[b]].square.center;
  return std::any_of(opt_.loops_closed_near.begin(), opt_.loops_closed_near.end(), [&](const Vec3& at) {
    const double t = closest_parameters(head, tail, at, at).first;
    return (head + t * (tail - head) - at).norm() <= kNearCrossing * tunnel_[b].radius;
  });
}

/// Whether a mouth of tunnel a comes within twice the corners' reach of a mouth of tunnel b, so that
/// the hull would leave no wall between the two holes.
bool Tiler::mouths_meet(int32_t a, int32_t b) const {
  for (int32_t i : {head_[a], tail_[a]})
    for (int32_t j : {head_[b], tail_[b]}) {
      const Section &p = ends_[i].square, &q = ends_[j].square;
      if ((p.center - q.center).norm() < 2 * scale() * (p.radius + q.radius)) return true;
    }
  return false;
}

/// Each tunnel's hole from its loop: the tunnel's branch and the path of swallowed branches (a tree
/// in each patch) between its joints. Centroid and plane are those of the loop's edges, weighted by length.
void Tiler::find_tunnel_holes() {
  std::map<int32_t, std::vector<int32_t>> swallowed_at;  // joint → swallowed branches that meet it
  for (std::size_t b = 0; b < branches_.size(); ++b)
    if (kind_[b] == Kind::swallowed)
      for (int32_t v : {first_point(b), last_point(b)}) swallowed_at[v].push_back(static_cast<int32_t>(b));
  for (std::size_t bi = 0; bi < branches_.size(); ++bi) {
    if (kind_[bi] != Kind::tunnel) continue;
    const int32_t b = static_cast<int32_t>(bi);
    // Breadth-first from the branch's last point through the tree to its first.
    std::map<int32_t, int32_t> reached_by{{last_point(b), -1}};
    std::vector<int32_t> queue{last_point(b)};
    for (std::size_t q = 0; q < queue.size() && !reached_by.count(first_point(b)); ++q)
      for (int32_t s : swallowed_at[queue[q]]) {
        const int32_t next = first_point(s) == queue[q] ? last_point(s) : first_point(s);
        if (reached_by.emplace(next, s).second) queue.push_back(next);
      }
    std::vector<int32_t> loop{b};
    for (int32_t v = first_point(b); reached_by.at(v) >= 0;) {
      const int32_t s = reached_by.at(v);
      loop.push_back(s);
      v = first_point(s) == v ? last_point(s) : first_point(s);
    }
    double length = 0, radius = 0;
    Vec3 center = Vec3::Zero();
    for (int32_t s : loop)
      for (std::size_t i = 0; i + 1 < curves_[s].points.size(); ++i) {
        const double l = curves_[s].arc[i + 1] - curves_[s].arc[i];
        length += l;
        center += l * 0.5 * (curves_[s].points[i] + curves_[s].points[i + 1]);
        radius += l * 0.5 * (curves_[s].radius[i] + curves_[s].radius[i + 1]);
      }
    center /= length;
    Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
    for (int32_t s : loop)
      for (std::size_t i = 0; i + 1 < curves_[s].points.size(); ++i) {
        const double l = curves_[s].arc[i + 1] - curves_[s].arc[i];
        const Vec3 d = 0.5 * (curves_[s].points[i] + curves_[s].points[i + 1]) - center;
        spread += l * d * d.transpose();
      }
    Tunnel& h = tunnel_[b];
    h.center = center + h.offset;
    h.radius = radius / length;
    h.normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(spread).eigenvectors().col(0);
    Patch& p = patches_[patch_of_end_[head_[b]]];
    for (int32_t s : loop)
      for (std::size_t i = 0; i < curves_[s].points.size(); ++i)
        for (double side : {1.0, -1.0}) {
          p.rim.push_back(curves_[s].points[i] + side * scale() * curves_[s].radius[i] * h.normal);
        }
  }
  for (const Patch& p : patches_) {
    std::vector<int32_t> tunnels;
    Vec3 mean = Vec3::Zero();
    for (int32_t i : p.ends)
      if (kind_[ends_[i].branch] == Kind::tunnel && ends_[i].at_start)
        tunnels.push_back(ends_[i].branch), mean += tunnel_[ends_[i].branch].center;
    mean /= std::max<double>(1, static_cast<double>(tunnels.size()));
    for (int32_t b : tunnels) {
      Tunnel& h = tunnel_[b];
      Vec3 tilt = (h.center - mean) / h.radius;
      tilt -= tilt.dot(h.normal) * h.normal;
      if (tilt.norm() > 0.5) tilt *= 0.5 / tilt.norm();
      h.out = {(h.normal + tilt).normalized(), (tilt - h.normal).normalized()};
      if (h.turned) h.out = h.turned_out;
    }
  }
}

/// The tunnel's hole: four quads straight through the patch from its head mouth to its tail mouth,
/// facing the hole's axis. Seen along the head's normal, the tail's corners run clockwise, so head
/// corner j pairs with tail corner (k − j) mod 4, for the quarter turn k that pairs them closest.
void Tiler::build_tunnel(int32_t b) {
  const int32_t head = ends_[head_[b]].first_vertex, tail = ends_[tail_[b]].first_vertex;
  auto paired = [](int k, int j) { return ((k - j) % 4 + 4) % 4; };
  int best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) {
    double distance = 0;
    for (int j = 0; j < 4; ++j)
      distance += (mesh_.vertices[head + j] - mesh_.vertices[tail + paired(k, j)]).squaredNorm();
    if (distance < best_distance) best_distance = distance, best = k;
  }
  for (int j = 0; j < 4; ++j)
    mesh_.quads.push_back(
        {head + j, head + (j + 1) % 4, tail + paired(best, j + 1), tail + paired(best, j)});
}

}  // namespace vesselmesh::tile_detail
