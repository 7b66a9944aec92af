#include "vesselmesh/fit/fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "vesselmesh/geometry/guarded_moves.hpp"
#include "vesselmesh/geometry/round_cones.hpp"
#include "vesselmesh/geometry/self_intersections.hpp"
#include "vesselmesh/parallel.hpp"

namespace vesselmesh {

namespace {

/// τ: how far from the tubes' surface, in local radii, a vertex far from it is left (see fit_to_tubes).
constexpr double kKeep = 0.01;
/// Vertices closer to the tubes' surface than this, in local radii, stay: their move, (d − τr·tanh(d/τr)),
/// would be below 0.1 % of the radius.
constexpr double kLeast = 0.007;
/// How far off the tubes, in local radii, the straddle may take a vertex (straddle_lifts): a face of a ring
/// of 16 sides has its centroid 1.7 % inside the circle through its corners, one of 8 sides 6.9 %.
constexpr double kMostOff = 0.03;
/// Faces straddle the tubes already where their centroids lie less than this deep, in local radii (a ring
/// of 64 sides: 0.1 %); a finer step would read as a ripple to the curvature fit on fine rings.
constexpr double kFinest = 0.002;
/// Where two tubes overlap, each surface keeps this share of the smaller radius from the plane between them.
constexpr double kGap = 0.02;
/// A vertex with the tubes of one vessel only within this many local radii is that vessel's.
constexpr double kClear = 0.25;
/// A vertex whose move the guard cut and that it left further than this many local radii inside the tubes
/// of two branches (a narrow fork), away from other vessels' tubes, moves again (fit_round).
constexpr double kAgain = 0.05;

/// True when `p` lies inside the tubes of two different branches.
bool inside_two_branches(const RoundCones& cones, const Vec3& p) {
  const std::vector<ConeDistance> in = cones.within(p, 0.0);
  return std::any_of(in.begin(), in.end(), [&](const ConeDistance& c) { return c.branch != in[0].branch; });
}

/// Each vertex's way towards the union of the cones (zero for those `fit` leaves), the local radius, the
/// cone nearest to it (outside; inside, the first found that holds it), how far outside the union it
/// lies (0 inside), and how far off the tubes (signed) its move leaves it (NaN where the fit leaves the
/// vertex alone: near a cap, inside another branch's tube). With `again` (a flag per vertex), the others
/// are left alone, and so are those within kAgain of the tubes, outside two branches' tubes or next to
/// another vessel's tube.
void closest_moves(const std::vector<Vec3>& vertices, const RoundCones& cones, Fit fit,
                   std::vector<Vec3>& move, std::vector<double>& radius, std::vector<int32_t>& nearest_cone,
                   std::vector<double>& outside, std::vector<double>& left,
                   const std::vector<char>& again = {}) {
  parallel_for(vertices.size(), [&](std::size_t begin, std::size_t end) {
    int32_t hint = -1;  // consecutive vertices are mostly near each other
    for (std::size_t v = begin; v < end; ++v) {
      if (!again.empty() && !again[v]) continue;
      const Vec3& p = vertices[v];
      ConeDistance d = cones.nearest(p, &hint, false);  // inside: only the sign
      if (!again.empty() && cones.crowded(hint)) continue;
      nearest_cone[v] = hint;
      radius[v] = d.radius;
      outside[v] = std::max(d.distance, 0.0);
      if (d.distance < 0) {
        if (fit != Fit::onto) continue;
        // Inside, the cone that holds the vertex deepest is the one it goes out of (none holds it deeper
        // than kLeast: it stays, and may yet be lifted).
        const ConeDistance deep = cones.deepest(p, kLeast * d.radius);
        const bool shallow = !std::isfinite(deep.distance);
        if (!shallow) d = deep, radius[v] = d.radius;
        // Inside another branch's tube too, a vertex would go out through it; not so inside a joint's
        // sphere, which all its branches share (a soma's, with dendrites from its centre). Just inside a
        // cone that is not crowded, no other branch's tube can hold it.
        if ((!shallow || cones.crowded(hint)) && cones.inside_other_branch(p, d.branch)) continue;
      }
      if (!std::isfinite(d.distance) || cones.near_cap(p)) continue;  // a capped end is not round
      if (!again.empty() && (std::abs(d.distance) < kAgain * d.radius || !inside_two_branches(cones, p)))
        continue;
      left[v] = d.distance;  // inside by less than kLeast: the first cone's depth, as close as the lift needs
      if (std::abs(d.distance) <= kLeast * d.radius) continue;
      const double reach = kKeep * d.radius;
      const double keep = reach * std::tanh(d.distance / reach);  // where the vertex is left
      Vec3 step = -(d.distance - keep) * d.direction;
      if (d.distance > 0 && cones.nearest(p + step, &hint, false).distance < -1e-6 * d.radius) {
        // The closest point on one cone can lie inside another (at a crotch both are near): stop where
        // the way there enters the union.
        double outside = 0, inside = 1;
        for (int i = 0; i < 20; ++i) {
          const double mid = 0.5 * (outside + inside);
          (cones.nearest(p + mid * step, &hint, false).distance < 0 ? inside : outside) = mid;
        }
        step *= outside;
        left[v] = d.distance - outside * (d.distance - keep);
      } else {
        left[v] = keep;
      }
      move[v] = step;
    }
  });
}

/// Adds to each fitted vertex's move a lift along its normal so that its faces straddle the tubes instead
/// of cutting inside them: flat between corners on a round tube, a face's centroid lies inside it (1.7 % of
/// the radius on a ring of 16 sides). On a regular triangulation of a curved surface the centroids of a
/// vertex's faces lie a third of its umbrella's depth (its 1-ring's mean, along the normal) below it, so the
/// vertex goes out by that (in where the surface is concave), as far as it stays within kMostOff of the
/// tubes. Judged on the surface as `move` takes it, where `left` says how far off the tubes each vertex then
/// lies (NaN: not fitted). Not next to another vessel's tube (a crowded cone), where it would press the two
/// surfaces into each other; and no further than keeps a short move short (within `reach`,
/// long_move_reach: between short edges), which would cost the guard a search for crossings there.
void add_straddle_lifts(const TriMesh& mesh, const RoundCones& cones, const std::vector<double>& left,
                        const std::vector<int32_t>& nearest_cone, const std::vector<double>& radius,
                        const std::vector<double>& reach, std::vector<Vec3>& move) {
  const std::size_t n = mesh.vertices.size();
  auto to = [&](int32_t v) { return Vec3(mesh.vertices[v] + move[v]); };
  // Per vertex, its faces' normals and its 1-ring's offsets from it, each summed: short sums of short
  // vectors, which floats hold.
  std::vector<Eigen::Vector3f> normal(n, Eigen::Vector3f::Zero()), around(n, Eigen::Vector3f::Zero());
  std::vector<int32_t> count(n, 0);
  for (const Tri& t : mesh.faces) {
    const std::array<Vec3, 3> c = {to(t[0]), to(t[1]), to(t[2])};
    const Eigen::Vector3f face = (c[1] - c[0]).cross(c[2] - c[0]).cast<float>();  // area-weighted
    for (int k = 0; k < 3; ++k) {
      normal[t[k]] += face;
      around[t[k]] += (c[(k + 1) % 3] + c[(k + 2) % 3] - 2 * c[k]).cast<float>();
      count[t[k]] += 2;
    }
  }
  parallel_for(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      if (!std::isfinite(left[v]) || count[v] == 0 || normal[v].squaredNorm() == 0) continue;
      if (nearest_cone[v] >= 0 && cones.crowded(nearest_cone[v])) continue;
      const double most = kMostOff * radius[v];
      if (std::abs(left[v]) >= most) continue;  // stopped further off (at a crotch)
      const Vec3 up = normal[v].normalized().cast<double>();
      const double depth = -up.dot(around[v].cast<double>()) / (3 * count[v]);  // of its faces' centroids
      if (std::abs(depth) < kFinest * radius[v]) continue;
      double lift = std::clamp(depth, -most - left[v], most - left[v]);
      if (move[v].norm() <= reach[v]) {  // a short move stays short: |move + lift·up| < reach
        const double b = move[v].dot(up), most_long = 0.99 * reach[v];
        const double room = std::sqrt(std::max(0.0, b * b + most_long * most_long - move[v].squaredNorm()));
        lift = std::clamp(lift, -b - room, -b + room);
      }
      move[v] += lift * up;
    }
  });
}

/// Moves `p`, a point of the surface round the tube of sphere (ca, ra), off the tube of sphere (cb, rb)
/// where the two overlap: onto its own side of their radical plane (which holds the circle where the
/// spheres meet), `gap` away from it. It moves along the ray from a point inside its own part of the
/// tube, so that the surface of that part, which is convex, maps onto the part without folding. Returns
/// `p` itself when it is on its own side already, or when its sphere's centre lies past the plane (its
/// tube lies mostly inside the other, and squeezing it into the sliver on its side would fold it).
Vec3 parted(const Vec3& p, const Vec3& ca, double ra, const Vec3& cb, double rb, double gap) {
  const double length = (ca - cb).norm();
  if (length < 1e-9 * ra) return p;
  const Vec3 u = (ca - cb) / length;  // towards its own side
  // f: own power minus the other's, linear in x, negative on its own side of the radical plane.
  auto f = [&](const Vec3& x) { return (x - ca).squaredNorm() - ra * ra - (x - cb).squaredNorm() + rb * rb; };
  const double margin = 2 * length * gap;  // f at `gap` from the plane
  if (f(p) <= -margin) return p;
  const double plane = (f(ca) + margin) / (2 * length);  // along u from ca to where f = -margin
  if (plane >= 0) return p;
  const Vec3 inner = ca + 0.5 * (plane + ra) * u;
  return inner + (-margin - f(inner)) / (f(p) - f(inner)) * (p - inner);
}

/// Each vertex's vessel: the branch of the tubes round it when no other branch's tubes lie within a
/// quarter radius of as near and the surface faces out of them there (`clear`); elsewhere, where tubes
/// meet or overlap, that of the nearest clear vertex along the surface (breadth first), so that a vertex
/// near where two surfaces cross is given to the side it is on. A joint's patch that bulges out of its own
/// tubes onto those of a vessel passing close by lies on that vessel's tube but faces into it: it is not
/// that vessel's. -1 for a component with no clear vertex. `nearest_cone`, `radius` and `outside` are
/// closest_moves'.
std::vector<int32_t> owners(const TriMesh& mesh, const RoundCones& cones,
                            const std::vector<int32_t>& nearest_cone, const std::vector<double>& radius,
                            const std::vector<double>& outside, std::vector<char>& clear) {
  const std::size_t n = mesh.vertices.size();
  std::vector<int32_t> owner(n, -1);
  clear.assign(n, 0);
  std::vector<Vec3> normal(n, Vec3::Zero());  // area-weighted, outward
  for (const Tri& t : mesh.faces) {
    const Vec3 area = face_normal(mesh.vertices, t);
    for (int32_t v : t) normal[v] += area;
  }
  parallel_for(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const int32_t e = nearest_cone[v];
      if (e < 0) continue;
      const int32_t branch = cones.cone(e).branch;
      // Only near a crowded cone can another branch's tube be near.
      if (cones.crowded(e)) {
        const std::vector<ConeDistance> near =
            cones.within(mesh.vertices[v], kClear * radius[v] + outside[v]);
        if (std::any_of(near.begin(), near.end(), [&](const ConeDistance& c) {
              return c.branch != branch || normal[v].dot(c.direction) <= 0;
            }))
          continue;
      }
      owner[v] = branch, clear[v] = 1;
    }
  });
  // The breadth-first search runs over the vertices that are not clear, and their neighbours.
  std::vector<int32_t> slot(n, -1), unclear;
  for (std::size_t v = 0; v < n; ++v)
    if (!clear[v]) slot[v] = static_cast<int32_t>(unclear.size()), unclear.push_back(static_cast<int32_t>(v));
  std::vector<int32_t> offsets(unclear.size() + 1, 0);
  for (const Tri& t : mesh.faces)
    for (int32_t v : t)
      if (slot[v] >= 0) offsets[slot[v] + 1] += 2;
  for (std::size_t i = 0; i < unclear.size(); ++i) offsets[i + 1] += offsets[i];
  std::vector<int32_t> neighbours(offsets.back()), fill(offsets.begin(), offsets.end() - 1);
  for (const Tri& t : mesh.faces)
    for (int k = 0; k < 3; ++k)
      if (slot[t[k]] >= 0) {
        neighbours[fill[slot[t[k]]]++] = t[(k + 1) % 3];
        neighbours[fill[slot[t[k]]]++] = t[(k + 2) % 3];
      }
  auto around = [&](int32_t v) {
    return std::make_pair(neighbours.begin() + offsets[slot[v]], neighbours.begin() + offsets[slot[v] + 1]);
  };
  std::vector<int32_t> queue;
  for (int32_t v : unclear) {
    const auto [first, last] = around(v);
    const auto labelled = std::find_if(first, last, [&](int32_t w) { return clear[w] != 0; });
    if (labelled != last) owner[v] = owner[*labelled], queue.push_back(v);
  }
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const auto [first, last] = around(queue[i]);
    for (auto w = first; w != last; ++w)
      if (owner[*w] < 0) owner[*w] = owner[queue[i]], queue.push_back(*w);
  }
  return owner;
}

/// Where the input's tubes overlap away from the joints their vessels share, each vessel's surface runs
/// through the other's tube and the two cross. Each vertex in (or next to) another vessel's tube, or whose
/// move would land it there, gets the move onto its own side of the plane between the two tubes, in place
/// of its move onto the union: the surfaces meet flat, like vessels pressed together, and the outside of the
/// union, all that shows, stays. Near a joint the two vessels share, their tubes meet by design and nothing
/// is parted. Returns the number of vertices given such a move.
int64_t parting_moves(const TriMesh& mesh, const RoundCones& cones, const std::vector<int32_t>& nearest_cone,
                      const std::vector<double>& radius, const std::vector<double>& outside,
                      std::vector<Vec3>& move) {
  if (!cones.any_crowded()) return 0;
  const std::vector<Vec3>& vertices = mesh.vertices;
  std::vector<char> clear;  // only its own vessel's tubes near: nothing to part from
  const std::vector<int32_t> owner = owners(mesh, cones, nearest_cone, radius, outside, clear);
  std::vector<char> parting(vertices.size(), 0);
  parallel_for(vertices.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      if (clear[v] || owner[v] < 0) continue;
      // `x` on its own side of the plane between its vessel's tube and each other tube it lies in or next to.
      const auto part = [&](const Vec3& x) {
        const std::vector<ConeDistance> near = cones.within(x, kClear * radius[v]);
        const ConeDistance* own = nullptr;  // the closest surface of its own vessel's tubes
        for (const ConeDistance& c : near)
          if (c.branch == owner[v] && (own == nullptr || std::abs(c.distance) < std::abs(own->distance)))
            own = &c;
        if (own == nullptr) return x;
        const Vec3 ca = x - (own->distance + own->radius) * own->direction;  // centre of its sphere
        Vec3 q = x;
        for (const ConeDistance& c : near) {
          if (c.branch == owner[v] || c.distance >= kGap * c.radius || cones.meet_near(owner[v], c.branch, x))
            continue;
          const Vec3 cb = x - (c.distance + c.radius) * c.direction;
          q = parted(q, ca, own->radius, cb, c.radius, kGap * std::min(own->radius, c.radius));
        }
        return q;
      };
      const Vec3& p = vertices[v];
      Vec3 q = part(p);
      // Outside the other tube, its move onto its own tube can still carry it in where the two overlap (the
      // crotch of a narrow fork, beyond the joint's reach: BH0036 crossed itself there at level 2).
      if (q == p && move[v] != Vec3::Zero()) {
        const Vec3 target = p + move[v];
        if (const Vec3 landed = part(target); landed != target) q = landed;
      }
      if (q != p) move[v] = q - p, parting[v] = 1;
    }
  });
  return std::count(parting.begin(), parting.end(), 1);
}

/// One round of the fit: every vertex's move (with `again` empty), or again the moves of the vertices
/// `again` flags, that the first round's guard cut, where they stay over kAgain local radii inside the
/// tubes of two branches, away from other vessels' tubes. These few moves are each tested against the
/// triangles they pass (a reach of zero): made as short moves, they folded patches into each other near
/// joints (brava-bg0003: 15 vertices taken back by the check). `parted` (first round only) counts the
/// vertices given a parting move.
GuardedMoves fit_round(TriMesh& mesh, const RoundCones& cones, Fit fit, const std::vector<char>& again,
                       int64_t* parted) {
  const std::size_t n = mesh.vertices.size();
  std::vector<Vec3> move(n, Vec3::Zero());
  std::vector<double> radius(n, 0.0);
  std::vector<int32_t> nearest_cone(n, -1);
  std::vector<double> outside(n, 0.0);
  std::vector<double> left(n, std::numeric_limits<double>::quiet_NaN());
  closest_moves(mesh.vertices, cones, fit, move, radius, nearest_cone, outside, left, again);
  const auto still = [](const Vec3& m) { return m == Vec3::Zero(); };
  if (!again.empty() && std::all_of(move.begin(), move.end(), still))
    return {};  // none to move again: the lifts and the guard would cost a pass over the whole surface
  // Parted vertices lie next to another vessel's tube (crowded cones), which a second round leaves.
  if (parted != nullptr) *parted = parting_moves(mesh, cones, nearest_cone, radius, outside, move);
  const std::vector<double> reach =
      again.empty() ? long_move_reach(mesh, radius) : std::vector<double>(n, 0.0);
  if (fit == Fit::onto) add_straddle_lifts(mesh, cones, left, nearest_cone, radius, reach, move);
  return move_without_folding(mesh, std::move(move), reach);
}

}  // namespace

FitStats fit_to_tubes(TriMesh& mesh, const CenterlineGraph& graph, Fit fit) {
  return fit_to_tubes(mesh, RoundCones(graph), fit);
}

FitStats fit_to_tubes(TriMesh& mesh, const RoundCones& cones, Fit fit) {
  FitStats stats;
  if (cones.size() == 0 || fit == Fit::none) return stats;
  const GuardedMoves first = fit_round(mesh, cones, fit, {}, &stats.parted);
  stats.moved = first.moved;
  stats.held_back = first.held_back;
  // Cut where its neighbours' moves, made together with its own, would have folded or crossed: from where
  // they now stand, its move is made again (a vertex deep inside two children's tubes at a narrow fork;
  // elsewhere, on the thick vessels' beads, moving such vertices out only stretched faces left inside).
  if (first.held_back > 0) fit_round(mesh, cones, fit, first.cut, nullptr);
  return stats;
}

int64_t take_back_crossing_moves(TriMesh& mesh, const std::vector<Vec3>& before,
                                 const std::vector<char>& among, std::vector<std::array<int32_t, 2>>& pairs) {
  int64_t taken_back = 0;
  for (int round = 0; round < kTakeBackRounds && !pairs.empty(); ++round) {
    int64_t now = 0;
    for (const auto& pair : pairs)
      for (int32_t f : pair)
        for (int32_t v : mesh.faces[f]) {
          const Vec3 back = rounded_to_float(before[v]);
          if (mesh.vertices[v] != back) mesh.vertices[v] = back, ++now;
        }
    if (now == 0) break;
    taken_back += now;
    pairs = intersecting_face_pairs(mesh, among);
  }
  return taken_back;
}

}  // namespace vesselmesh
