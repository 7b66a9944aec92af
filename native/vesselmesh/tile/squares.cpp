// A joint patch's squares, pushed out along their branches (or tilted where they stand) until each is a
// face of the patch's hull, clear of the others; and where one square can close two patches at once.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "vesselmesh/tile/tiler.hpp"
#include "vesselmesh/tile/tube_sections.hpp"

namespace vesselmesh::tile_detail {

/// The square of `e` at arc distance t from its joint (up-vector still to be chosen). A tunnel's
/// mouths sit at distance t from the loop's centroid, the head's on one side of the loop's plane, the
/// tail's on the other.
Section Tiler::square_at(const End& e, double t) const {
  Section q;
  if (kind_[e.branch] == Kind::tunnel) {
    const Tunnel& h = tunnel_[e.branch];
    q.normal = h.out[e.at_start ? 0 : 1];
    q.center = h.center + t * q.normal;
    q.radius = h.hole();
    return q;
  }
  const BranchCurve& c = curves_[e.branch];
  const double s = e.at_start ? t : c.length() - t;
  q.center = c.position(s);
  q.radius = c.radius_at(s);
  const Vec3 chord = q.center - (e.at_start ? c.points.front() : c.points.back());
  if (e.chord && chord.norm() > 0.1 * q.radius) {
    q.normal = chord.normalized();
  } else {
    const Vec3 tangent = c.tangent(s);
    q.normal = e.at_start ? tangent : -tangent;
  }
  return q;
}

/// How far the square of `e` may move: to the far end of its branch; a tunnel's mouth, up to the
/// tunnel's reach from the loop's centroid.
double Tiler::travel(const End& e) const {
  return kind_[e.branch] == Kind::tunnel ? tunnel_[e.branch].reach() : curves_[e.branch].length();
}

/// Up-vectors for a patch's free squares: the projection of the patch's reference direction (the
/// normal of the best-fit plane of its branch directions), turned 45° so that a square's edge faces
/// its neighbours, plus a small per-square offset so that corners of different squares are not
/// coplanar.
void Tiler::orient_squares(const Patch& p, int attempt) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  // Tunnel mouths are left out: they face along their loop's normal, not along a branch.
  for (int32_t i : p.ends)
    if (kind_[ends_[i].branch] != Kind::tunnel)
      m += ends_[i].square.normal * ends_[i].square.normal.transpose();
  const Vec3 ref = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvectors().col(0);
  for (std::size_t i = 0; i < p.ends.size(); ++i) {
    End& e = ends_[p.ends[i]];
    if (kind_[e.branch] == Kind::shared) continue;
    Vec3 u = ref - ref.dot(e.square.normal) * e.square.normal;
    u = u.norm() > 0.2 ? u.normalized() : any_perpendicular(e.square.normal);
    const double offset = std::fmod(0.6180339887 * static_cast<double>(i + 7 * attempt), 1.0) - 0.5;
    e.square.up = rotate(u, e.square.normal, M_PI / 4 + offset * (0.1 + 0.3 * attempt));
  }
}

/// How far the corners of `p`'s squares other than e's reach past the plane of e's square, plus a
/// margin: ≤ 0 when they all lie behind it, and e's square is a face of the patch's hull.
double Tiler::intrusion(const End& e, const Patch& p) const { return reach_past(e.square, others(e, p)); }

/// The corners of `p`'s squares other than e's, and its rim: what e's square must have behind its plane.
std::vector<Vec3> Tiler::others(const End& e, const Patch& p) const {
  std::vector<Vec3> out(p.rim.begin(), p.rim.end());
  for (int32_t i : p.ends)
    if (&ends_[i] != &e)
      for (int k = 0; k < 4; ++k) out.push_back(corner(ends_[i], k));
  return out;
}

/// How far `points` reach past the plane of square `s`, plus a margin.
double Tiler::reach_past(const Section& s, const std::vector<Vec3>& points) const {
  double reach = -std::numeric_limits<double>::infinity();
  for (const Vec3& q : points) reach = std::max(reach, s.normal.dot(q - s.center));
  return reach + 0.1 * scale() * s.radius;
}

/// Pushes each free square along its branch until it is a face of the patch's hull; out of the reach of
/// the patch's widest tube, a square that has not cleared the others tilts where it stands if that
/// clears them (tilt_square). Stub and shared squares stay put; a square that reaches the far end of its
/// branch is marked stuck. A square that the turn of its branch's tangent pushes to the far end is tried
/// again facing along its chord: on a short or sharply bent branch the tangent there can point back
/// across the patch, so that the squares keep pushing each other along, where the chord points away
/// from the joint.
void Tiler::place_squares(const Patch& p, int attempt) {
  for (int32_t i : p.ends) ends_[i].chord = false;
  for (;;) {
    push_squares(p, attempt);
    bool again = false;
    for (int32_t i : p.ends) {
      End& e = ends_[i];
      if (e.stuck && !e.chord && kind_[e.branch] != Kind::tunnel) e.chord = again = true;
    }
    if (!again) return;
  }
}

void Tiler::push_squares(const Patch& p, int attempt) {
  double widest = 0;  // the patch's widest branch at the joint
  for (int32_t i : p.ends) {
    const End& e = ends_[i];
    if (kind_[e.branch] != Kind::tunnel)
      widest = std::max(widest, curves_[e.branch].radius_at(e.at_start ? 0 : curves_[e.branch].length()));
  }
  for (int32_t i : p.ends) {
    End& e = ends_[i];
    const BranchCurve& c = curves_[e.branch];
    e.stuck = false;
    e.tilted = false;
    e.fixed = kind_[e.branch] == Kind::stub || kind_[e.branch] == Kind::shared;
    if (kind_[e.branch] == Kind::stub) {
      e.t = c.length();
    } else if (kind_[e.branch] == Kind::shared) {
      e.t = e.at_start ? shared_at_[e.branch] : c.length() - shared_at_[e.branch];
    } else {
      const double r = kind_[e.branch] == Kind::tunnel ? tunnel_[e.branch].hole()
                                                       : c.radius_at(e.at_start ? 0 : c.length());
      e.t = std::min(travel(e), 0.25 * r * (1 + attempt));
    }
    e.square = square_at(e, e.t);
    if (kind_[e.branch] == Kind::shared) {
      e.square.normal = e.at_start ? shared_normal_[e.branch] : -shared_normal_[e.branch];
      e.square.up = shared_up_[e.branch];
    }
  }
  for (int iteration = 0; iteration < kPushes; ++iteration) {
    orient_squares(p, attempt);
    bool moved = false;
    for (int32_t i : p.ends) {
      End& e = ends_[i];
      if (e.fixed || e.stuck) continue;
      double overlap = intrusion(e, p);
      if (overlap <= 0) continue;
      moved = true;
      // A tilted square that no longer clears the others stands upright again, or tilts another way,
      // where it is; only then does it move on.
      if (e.tilted) {
        e.square = square_at(e, e.t);
        e.tilted = false;
        if ((overlap = intrusion(e, p)) <= 0) continue;
      }
      // Squares pushed this far from the joint may tilt: out of the widest tube's reach round it, or, for a
      // branch under half as wide, out of its own (kTiltFrom).
      const double tilt_from =
          kTiltFrom * scale() * (e.square.radius < 0.5 * widest ? e.square.radius : widest);
      if (kind_[e.branch] == Kind::tube && e.t >= tilt_from && tilt_square(e, p)) continue;
      // On a straight branch, moving the square by the intrusion clears it; bends take more steps.
      const double length = travel(e);
      const double to = std::min(length, e.t + std::max(overlap, 0.05 * e.square.radius));
      if (kind_[e.branch] == Kind::tube && tilt_on_the_way(e, p, to, tilt_from)) continue;
      e.t = to;
      e.stuck = e.t >= length;
      e.square = square_at(e, e.t);
    }
    if (!moved) return;
  }
  // Squares that still have not cleared the others are stuck where they are, as if at the far end.
  for (int32_t i : p.ends) {
    End& e = ends_[i];
    if (!e.fixed && intrusion(e, p) > 0) e.stuck = true;
  }
}

/// Tries the square of `e`, standing or tilted (tilt_square), at kWaySteps − 1 points on its way to arc
/// distance `to` where no tube lies beside it; true, the square placed there, when one clears the others.
/// Only for a square held back by the square beside it (held_back_beside). Two branches that run on side
/// by side from a joint push each other's squares on by turns, each whole step taking one past the other,
/// from where it cannot tilt clear of the other's corners (where the tracing wavers, their squares face
/// 25° to 55° apart); abreast, they can. Taking every step whole, the squares of brava-records BH0004's
/// child traced back along its parent went on for 14 mm, the joint's patch along them (docs/pipeline.md).
bool Tiler::tilt_on_the_way(End& e, const Patch& p, double to, double tilt_from) {
  if (!held_back_beside(e, p)) return false;
  const double from = e.t;
  for (int k = 1; k < kWaySteps; ++k) {
    e.t = from + (to - from) * k / kWaySteps;
    if (e.t < tilt_from) continue;
    e.square = square_at(e, e.t);
    if (tubes_apart(e, p) && (intrusion(e, p) <= 0 || tilt_square(e, p))) return true;
  }
  e.t = from;
  e.square = square_at(e, e.t);
  return false;
}

/// Whether the square whose corners reach furthest past the plane of e's is a tube's, within their two
/// corner radii of e's across the branch.
bool Tiler::held_back_beside(const End& e, const Patch& p) const {
  double furthest = -std::numeric_limits<double>::infinity();
  const End* by = nullptr;
  for (int32_t i : p.ends) {
    const End& o = ends_[i];
    if (&o == &e) continue;
    for (int q = 0; q < 4; ++q) {
      const double reach = e.square.normal.dot(corner(o, q) - e.square.center);
      if (reach > furthest) furthest = reach, by = &o;
    }
  }
  return by && kind_[by->branch] == Kind::tube &&
         across(e, *by) < scale() * (e.square.radius + by->square.radius);
}

/// Whether no other tube square of the patch lies closer to e's across the branch than their two radii.
bool Tiler::tubes_apart(const End& e, const Patch& p) const {
  for (int32_t i : p.ends) {
    const End& o = ends_[i];
    if (&o != &e && kind_[o.branch] == Kind::tube && across(e, o) < e.square.radius + o.square.radius)
      return false;
  }
  return true;
}

/// The distance of o's square's centre from e's, across e's branch (in the plane of e's square).
double Tiler::across(const End& e, const End& o) {
  const Vec3 d = o.square.center - e.square.center;
  return (d - d.dot(e.square.normal) * e.square.normal).norm();
}

/// Tilts the square of `e`, where it stands, from its branch's direction by the fewest steps of 15° (up to
/// kSharedTilts) towards one of 8 directions round it, so that the patch's other squares lie behind its
/// plane: of that tilt, the direction that clears them most. Facing along their branches, the squares of
/// two branches that run on side by side from a joint (siblings from one point in brava-records, the
/// legs of a U-bend at a corner joint) each have the other beside them in their plane, wherever they
/// stand: pushed by turns, they went on for tens of radii, and the patch's hull with them, a flat fin
/// between the two (fixture siblings_side_by_side). Tilted away from each other they clear. A tilt must
/// leave the branch's own way on, one and two corner radii further, in front of the square (tilted
/// across a turning branch, a square had the next 16 radii of it behind its plane, and the tube went
/// straight across them). Returns false, the square upright, when no tilt will do.
bool Tiler::tilt_square(End& e, const Patch& p) {
  const Section upright = square_at(e, e.t);
  const Vec3 across = any_perpendicular(upright.normal);
  // The branch's own sections one and two corner radii further on, facing along it, which a tilted
  // square must not reach across: its tube would fold there, or drop its sections for many radii.
  const BranchCurve& c = curves_[e.branch];
  const double reach = scale() * upright.radius;
  if (e.t + 2 * reach > c.length()) return false;
  std::array<Section, 2> ahead;
  for (int k = 0; k < 2; ++k) {
    const double s = e.at_start ? e.t + (k + 1) * reach : c.length() - e.t - (k + 1) * reach;
    ahead[k].center = c.position(s);
    ahead[k].radius = c.radius_at(s);
    ahead[k].normal = e.at_start ? c.tangent(s) : Vec3(-c.tangent(s));
  }
  const std::vector<Vec3> in_front = others(e, p);  // the same for every tilt tried
  const Vec3& n = upright.normal;
  // The tilted normals: n turned about axes an eighth of a turn apart round it, from `across` (Rodrigues'
  // formula for vectors at right angles: few trigonometric calls, in a search that runs for every square
  // that intrudes in every push).
  std::array<Vec3, 8> turned;  // axis × n for each axis
  for (int towards = 0; towards < 8; ++towards)
    turned[towards] = std::cos(M_PI / 4 * towards) * across.cross(n) + std::sin(M_PI / 4 * towards) * across;
  for (int tilt = 1; tilt <= kSharedTilts; ++tilt) {
    double best = 0;
    Vec3 best_normal = n;
    const double c = std::cos(M_PI / 12 * tilt), sn = std::sin(M_PI / 12 * tilt);
    for (int towards = 0; towards < 8; ++towards) {
      e.square.normal = c * n + sn * turned[towards];
      if (sections_cross(e.square, ahead[0], scale()) || sections_cross(e.square, ahead[1], scale()))
        continue;
      const double overlap = reach_past(e.square, in_front);
      if (overlap < best) best = overlap, best_normal = e.square.normal;
    }
    if (best < 0) {
      e.square = upright;
      e.square.normal = best_normal;
      e.tilted = true;
      return true;
    }
  }
  e.square = upright;
  return false;
}

/// Where one square on branch b can close both of its joints' patches: its plane must have the
/// other squares of the start's patch behind it and those of the end's patch in front. Tried at
/// kSharedPositions points along the branch, facing along its tangent or tilted from it by up to
/// kSharedTilts steps of 15° towards 8 directions round it: where a side branch leaves one joint
/// towards the other, only a tilted plane passes between the two patches. Returns the best
/// position's clearance (> 0 when it works) and sets shared_at_[b] and shared_normal_[b].
double Tiler::best_shared_square(int32_t b) {
  const BranchCurve& c = curves_[b];
  const Patch& head_patch = patches_[patch_of_end_[head_[b]]];
  const Patch& tail_patch = patches_[patch_of_end_[tail_[b]]];
  double best = -std::numeric_limits<double>::infinity();
  for (int k = 1; k <= kSharedPositions; ++k) {
    const double s = c.length() * k / (kSharedPositions + 1);
    const Vec3 center = c.position(s);
    const double r = c.radius_at(s);
    const Vec3 tangent = c.tangent(s), across = any_perpendicular(tangent);
    for (int tilt = 0; tilt <= kSharedTilts; ++tilt)
      for (int towards = 0; towards < (tilt > 0 ? 8 : 1); ++towards) {
        const Vec3 axis = rotate(across, tangent, M_PI / 4 * towards);
        const Vec3 normal = rotate(tangent, axis, M_PI / 12 * tilt);
        double clearance = std::numeric_limits<double>::infinity();
        auto consider = [&](const Patch& p, double side) {
          for (int32_t i : p.ends) {
            if (ends_[i].branch == b) continue;
            for (int q = 0; q < 4; ++q)
              clearance =
                  std::min(clearance, -side * normal.dot(corner(ends_[i], q) - center));
          }
        };
        consider(head_patch, 1.0);
        consider(tail_patch, -1.0);
        // Clear of both patches by a margin.
        clearance -= 0.1 * scale() * r;
        if (clearance > best) best = clearance, shared_at_[b] = s, shared_normal_[b] = normal;
      }
  }
  return best;
}

}  // namespace vesselmesh::tile_detail
