// The joint patches: which branch ends and joints each holds, a body for those with too few openings,
// and each patch closed as the convex hull of its squares with its openings cut out.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "vesselmesh/geometry/closest_point.hpp"
#include "vesselmesh/tile/convex_hull.hpp"
#include "vesselmesh/tile/tiler.hpp"

namespace vesselmesh::tile_detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The corners of an octahedron, then of a cube: directions round a point for hull points on its sphere.
const std::array<Vec3, 14> kSphereDirections = [] {
  std::array<Vec3, 14> d;
  for (int k = 0; k < 6; ++k) d[k] = (k % 2 ? -1.0 : 1.0) * Vec3::Unit(k / 2);
  for (int k = 0; k < 8; ++k) d[6 + k] = Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1).normalized();
  return d;
}();

/// `u` turned about a fixed axis by a different angle for each `turn` (the golden ratio's multiples), so
/// that no four points on the spheres of neighbouring points are coplanar by accident.
Vec3 turned(const Vec3& u, int turn) {
  return rotate(u, Vec3(1, 2, 3).normalized(), 2 * M_PI * std::fmod(0.6180339887 * turn, 1.0));
}

}  // namespace

void Tiler::collect_patches() {
  ends_.clear();
  patches_.clear();
  patch_of_end_.clear();
  head_.assign(branches_.size(), -1);
  tail_.assign(branches_.size(), -1);
  std::vector<int32_t> patch_of(g_.points.size(), -1);
  auto patch_for = [&](int32_t v) {
    int32_t& id = patch_of[joints_.find(v)];
    if (id < 0) id = static_cast<int32_t>(patches_.size()), patches_.emplace_back();
    return id;
  };
  for (int32_t v = 0; v < static_cast<int32_t>(g_.points.size()); ++v)
    if (is_joint(v)) patches_[patch_for(v)].joints.push_back(v);
  for (std::size_t bi = 0; bi < branches_.size(); ++bi) {
    const int32_t b = static_cast<int32_t>(bi);
    if (kind_[b] == Kind::swallowed) continue;
    for (bool at_start : {true, false}) {
      const int32_t v = at_start ? first_point(b) : last_point(b);
      if (!is_joint(v)) continue;
      End e;
      e.branch = b;
      e.at_start = at_start;
      (at_start ? head_ : tail_)[b] = static_cast<int32_t>(ends_.size());
      const int32_t patch = patch_for(v);
      patches_[patch].ends.push_back(static_cast<int32_t>(ends_.size()));
      patch_of_end_.push_back(patch);
      ends_.push_back(e);
    }
  }
  find_tunnel_holes();
  for (std::size_t bi = 0; bi < branches_.size(); ++bi) {
    const int32_t b = static_cast<int32_t>(bi);
    if (kind_[b] == Kind::swallowed) patches_[patch_of[joints_.find(first_point(b))]].inside.push_back(b);
    if (kind_[b] == Kind::stub)
      patches_[patch_of_end_[head_[b] >= 0 ? head_[b] : tail_[b]]].inside.push_back(b);
  }
  for (Patch& p : patches_) {
    add_body(p);
    shrink_squares(p);
  }
}

/// Small squares (kSmallSquare) for a patch whose joints include three or more at least half as wide as its
/// widest (a vessel running through it, not a thin branch's corners beside a fat joint), and for every patch
/// where the options ask for them; but full ones near a place where the surface crossed itself with small
/// squares, and for those a patch shares with the next one and where a tunnel or a rim holds a loop's hole.
void Tiler::shrink_squares(const Patch& p) {
  double widest = 0;
  for (int32_t j : p.joints) widest = std::max(widest, g_.radius[j]);
  const auto wide = std::count_if(p.joints.begin(), p.joints.end(),
                                  [&](int32_t j) { return g_.radius[j] >= 0.5 * widest; });
  const bool tunnel = std::any_of(p.ends.begin(), p.ends.end(),
                                  [&](int32_t i) { return kind_[ends_[i].branch] == Kind::tunnel; });
  if ((wide < 3 && !opt_.small_squares) || tunnel || !p.rim.empty() || near_crossing(p)) return;
  for (int32_t i : p.ends)
    if (kind_[ends_[i].branch] != Kind::shared) ends_[i].reach = kSmallSquare;
}

/// Whether a place where the surface crossed itself with small squares (TileOptions::full_squares_near) lies
/// within kNearCrossing radii of one of the patch's joints or of one of its branches: where a square stands
/// changes its branch's sections all along, and a tube folded 12 radii from its joint (secomb-rat-mesentery).
bool Tiler::near_crossing(const Patch& p) const {
  for (const Vec3& at : opt_.full_squares_near) {
    for (int32_t j : p.joints)
      if ((at - g_.points[j]).norm() <= kNearCrossing * g_.radius[j]) return true;
    for (int32_t i : p.ends) {
      const BranchCurve& c = curves_[ends_[i].branch];
      for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
        const double t = closest_parameters(c.points[k], c.points[k + 1], at, at).first;
        const double radius = c.radius[k] + t * (c.radius[k + 1] - c.radius[k]);
        const Vec3 nearest = c.points[k] + t * (c.points[k + 1] - c.points[k]);
        if ((nearest - at).norm() <= kNearCrossing * radius) return true;
      }
    }
  }
  return false;
}

/// A patch with fewer than two openings (tube, shared or tunnel squares) is all its component has
/// there: its squares alone may span no solid (one square, or stubs' squares at their terminals far
/// from the joint) and leave the joints and swallowed branches outside. Such a patch gets round each
/// joint, and each point inside its stubs and swallowed branches, six rim points at the corners' reach
/// (an octahedron turned by a different angle at each point, so that no four of them are coplanar by
/// accident), and its hull covers the branches it took in.
void Tiler::add_body(Patch& p) {
  const auto openings = std::count_if(p.ends.begin(), p.ends.end(), [&](int32_t i) {
    return kind_[ends_[i].branch] != Kind::stub;
  });
  if (openings >= 2) return;
  int turn = 0;
  auto octahedron = [&](const Vec3& at, double r) {
    ++turn;
    for (int k = 0; k < 6; ++k) p.rim.push_back(at + scale() * r * turned(kSphereDirections[k], turn));
  };
  for (int32_t j : p.joints) octahedron(g_.points[j], g_.radius[j]);
  for (int32_t b : p.inside)
    for (std::size_t i = 1; i + 1 < curves_[b].points.size(); ++i)
      octahedron(curves_[b].points[i], curves_[b].radius[i]);
}

/// Points of the spheres round a sharp corner that is its patch's only joint and round the patch's joints at
/// least kFatterThanItsOpenings times as wide as its widest opening and half as wide as its widest joint, at
/// the corners' reach, where the hull of `corners` (its squares and rim) misses them by over a tenth of their
/// radius and where they lie behind every opening's plane (so that each opening stays a face of the hull). A
/// corner's patch is the hull of its two legs' squares, pushed along the legs until they clear each other:
/// where the legs run back side by side, all of the bend beyond the squares lay outside it (brava-records
/// BH0026's thickest vessel lost the bottom of its U; the cohort's trees up to 23 radii of axis). (Corners
/// merged with other joints too: more random trees crossed themselves, docs/pipeline.md's decisions log.) A
/// fat joint is a soma or a bulb whose branches leave it thinner: neuron-hemibrain-da1's soma, radius 375,
/// merged with nine of its trunk's joints, had only the squares of the branches leaving them (radius 71 at
/// most) in its hull, a slim patch through its sphere. (The trunk's joints of radius 100 in that patch, also
/// over twice its widest opening, spread the hull over their thin side branches, where the fit folded it: a
/// groove 5 radii long.)
std::vector<Vec3> Tiler::uncovered_sphere_points(const Patch& p, const std::vector<Vec3>& corners) const {
  if (!p.rim.empty()) return {};  // a body covers its joints already; a tunnel's rim holds its hole
  double widest_opening = 0;
  for (int32_t i : p.ends)
    if (kind_[ends_[i].branch] != Kind::stub)
      widest_opening = std::max(widest_opening, ends_[i].square.radius);
  double widest_joint = 0;
  for (int32_t j : p.joints) widest_joint = std::max(widest_joint, g_.radius[j]);
  std::vector<int32_t> round;
  for (int32_t j : p.joints)
    if ((corner_[j] && p.joints.size() == 1) ||
        g_.radius[j] >= std::max(kFatterThanItsOpenings * widest_opening, 0.5 * widest_joint))
      round.push_back(j);
  if (round.empty()) return {};
  const std::vector<Tri> hull = convex_hull(corners);
  // How far q lies outside the hull (anywhere, where the points are coplanar and there is none).
  auto outside = [&](const Vec3& q) {
    double most = hull.empty() ? kInf : -kInf;
    for (const Tri& t : hull) {
      const Vec3 n = (corners[t[1]] - corners[t[0]]).cross(corners[t[2]] - corners[t[0]]);
      if (n.norm() > 0) most = std::max(most, n.normalized().dot(q - corners[t[0]]));
    }
    return most;
  };
  std::vector<Vec3> points;
  int turn = 0;
  for (int32_t j : round) {
    const double r = g_.radius[j];
    ++turn;
    for (const Vec3& u : kSphereDirections) {
      const Vec3 q = g_.points[j] + scale() * r * turned(u, turn);
      const bool behind = std::all_of(p.ends.begin(), p.ends.end(), [&](int32_t i) {
        const End& e = ends_[i];
        return kind_[e.branch] == Kind::stub || (q - e.square.center).dot(e.square.normal) < -0.1 * r;
      });
      if (behind && outside(q) > 0.1 * r) points.push_back(q);
    }
  }
  return points;
}

/// The patch's vertex ids for the square of end `e`, corners counter-clockwise about its normal.
/// A shared square's corners are made once; seen from the branch's end they run the other way.
std::array<int32_t, 4> Tiler::square_vertices(const End& e) {
  if (kind_[e.branch] != Kind::shared) {
    const int32_t first = add_square(e.square, e.reach);
    return {first, first + 1, first + 2, first + 3};
  }
  int32_t& first = shared_vertex_[e.branch];
  if (first < 0) {
    Section from_start = e.square;
    if (!e.at_start) from_start.normal = -from_start.normal;
    first = add_square(from_start);
  }
  if (e.at_start) return {first, first + 1, first + 2, first + 3};
  return {first, first + 3, first + 2, first + 1};
}

/// Gives up the loop of `tunnel`, a branch of patch `p`: it is swallowed, and the loop closes in the patch.
void Tiler::give_up_loop(const Patch& p, int32_t tunnel, const std::string& why) {
  mesh_.lost_loops.push_back(
      {g_.points[p.joints[0]], {g_.points[first_point(tunnel)], g_.points[last_point(tunnel)]}, why});
  kind_[tunnel] = Kind::swallowed;
  --mesh_.tunnels;
}

/// Closes the patch. Where its hull cannot close, a tunnel's loop is given up (its branch is
/// swallowed), or failing one, the tube whose square was pushed furthest in its radii (the two legs of
/// a hairpin that run on side by side, their squares abreast, each just clear of the other's plane);
/// then false is returned, for the kinds to be decided again without it.
bool Tiler::build_patch(const Patch& p) {
  if (close_patch(p)) return true;
  const auto tunnel = std::find_if(p.ends.begin(), p.ends.end(),
                                   [&](int32_t i) { return kind_[ends_[i].branch] == Kind::tunnel; });
  if (tunnel != p.ends.end()) {
    give_up_loop(p, ends_[*tunnel].branch, "the joint patch's hull does not close round its hole");
    return false;
  }
  int32_t furthest = -1;
  double most = -1;
  for (int32_t i : p.ends)
    if (kind_[ends_[i].branch] == Kind::tube && ends_[i].t / ends_[i].square.radius > most)
      most = ends_[i].t / ends_[i].square.radius, furthest = ends_[i].branch;
  if (furthest < 0) {
    const Vec3& at = g_.points[p.joints[0]];
    throw std::runtime_error("could not close the surface around the joint at (" + std::to_string(at.x()) +
                             ", " + std::to_string(at.y()) + ", " + std::to_string(at.z()) + ")");
  }
  give_up_tube(furthest);
  return false;
}

/// The convex hull of the patch's squares with the tubes' and shared squares cut out. When exact
/// coplanarity spoils the hull (the check below is exact), retried with other square turns and the
/// free squares pushed further out. False when no attempt closes it.
bool Tiler::close_patch(const Patch& p) {
  const int32_t squares = static_cast<int32_t>(p.ends.size());
  for (int attempt = 0; attempt < 8; ++attempt) {
    if (attempt > 0) place_squares(p, attempt);
    std::vector<Vec3> corners;
    for (int32_t i : p.ends)
      for (int k = 0; k < 4; ++k) corners.push_back(corner(ends_[i], k));
    corners.insert(corners.end(), p.rim.begin(), p.rim.end());
    const std::vector<Vec3> spheres = uncovered_sphere_points(p, corners);
    corners.insert(corners.end(), spheres.begin(), spheres.end());
    // Hull triangles inside one square are dropped: a tube's or shared square is an opening, and a
    // stub's square, when it is a face of the hull, gets two triangles of its own (an exactly planar
    // square would otherwise come back with both diagonals).
    std::vector<Tri> patch;
    std::vector<int> stub_side(p.ends.size(), 0);  // +1: the stub square faces outwards, −1: inwards
    for (const Tri& t : convex_hull(corners)) {
      const int32_t square = t[0] / 4;
      if (square >= squares || t[1] / 4 != square || t[2] / 4 != square) {
        patch.push_back(t);
        continue;
      }
      const Vec3 normal = (corners[t[1]] - corners[t[0]]).cross(corners[t[2]] - corners[t[0]]);
      stub_side[square] = normal.dot(ends_[p.ends[square]].square.normal) > 0 ? 1 : -1;
    }
    for (std::size_t s = 0; s < p.ends.size(); ++s) {
      // With open caps a stub's terminal square on the hull stays open, like any other terminal.
      if (kind_[ends_[p.ends[s]].branch] != Kind::stub || stub_side[s] == 0 || opt_.caps == Caps::open)
        continue;
      const int32_t q = static_cast<int32_t>(4 * s);
      if (stub_side[s] > 0)
        patch.insert(patch.end(), {Tri{q, q + 1, q + 2}, Tri{q, q + 2, q + 3}});
      else
        patch.insert(patch.end(), {Tri{q, q + 2, q + 1}, Tri{q, q + 3, q + 2}});
    }
    // With open caps, a stub's square that is a face of the hull is an opening too.
    std::vector<int> open_side(p.ends.size(), 0);
    if (opt_.caps == Caps::open) open_side = stub_side;
    if (!closes_openings(patch, p, open_side)) continue;
    std::vector<int32_t> id;
    for (int32_t i : p.ends) {
      const auto v = square_vertices(ends_[i]);
      ends_[i].first_vertex = v[0];
      id.insert(id.end(), v.begin(), v.end());
    }
    for (std::size_t k = 4 * p.ends.size(); k < corners.size(); ++k) {
      id.push_back(static_cast<int32_t>(mesh_.vertices.size()));
      mesh_.vertices.push_back(corners[k]);
      mesh_.axes.emplace_back();
    }
    for (const Tri& t : patch) mesh_.triangles.push_back({id[t[0]], id[t[1]], id[t[2]]});
    ++mesh_.joints;
    return true;
  }
  return false;
}

/// The patch must use each opening's edges once, against the square's direction (the tube or the
/// other patch uses them along it), and every other edge twice, once each way. A stub's square is an
/// opening only where `open_side` says so: +1 facing out of the patch, −1 facing into it (its edges
/// then run the other way round the hole).
bool Tiler::closes_openings(const std::vector<Tri>& patch, const Patch& p,
                            const std::vector<int>& open_side) const {
  std::map<std::pair<int32_t, int32_t>, int> directed;
  for (const Tri& t : patch)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (std::size_t s = 0; s < p.ends.size(); ++s) {
    const bool stub = kind_[ends_[p.ends[s]].branch] == Kind::stub;
    if (stub && open_side[s] == 0) continue;
    for (int k = 0; k < 4; ++k) {
      int32_t a = static_cast<int32_t>(4 * s) + k, b = static_cast<int32_t>(4 * s) + (k + 1) % 4;
      if (stub && open_side[s] < 0) std::swap(a, b);
      if (directed[{b, a}] != 1 || directed[{a, b}] != 0) return false;
      directed.erase({b, a});
      directed.erase({a, b});
    }
  }
  for (const auto& [edge, count] : directed) {
    if (count == 0) continue;
    const auto it = directed.find({edge.second, edge.first});
    if (count != 1 || it == directed.end() || it->second != 1) return false;
    // An edge from one mouth of a tunnel to the other would leave the hole no wall on that side (and
    // the tunnel's own quads may use it).
    const std::size_t s = edge.first / 4, t = edge.second / 4;
    if (s != t && s < p.ends.size() && t < p.ends.size() &&
        ends_[p.ends[s]].branch == ends_[p.ends[t]].branch &&
        kind_[ends_[p.ends[s]].branch] == Kind::tunnel)
      return false;
  }
  return true;
}

}  // namespace vesselmesh::tile_detail
