#include "vesselmesh/tile/base_mesh.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

#include "vesselmesh/error.hpp"
#include "vesselmesh/frames/frames.hpp"
#include "vesselmesh/geometry/closest_point.hpp"
#include "vesselmesh/graph/union_find.hpp"
#include "vesselmesh/parallel.hpp"
#include "vesselmesh/sample/branch_curve.hpp"
#include "vesselmesh/tile/convex_hull.hpp"
#include "vesselmesh/tile/corners.hpp"
#include "vesselmesh/tile/tube_sections.hpp"

namespace vesselmesh {

namespace {

using Quad = std::array<int32_t, 4>;

/// Ways a tunnel is turned (each from where the patch's squares then stand) before its loop is given up.
constexpr int kTurns = 3;

/// A shared square is tried at this many points along its branch, tilted from the tangent by up to this
/// many steps of 15° (see best_shared_square), and placed again up to this many times, each from where
/// the squares pushed out round it then stand, before its two joints merge.
constexpr int kSharedPositions = 15;
constexpr int kSharedTilts = 3;
constexpr int kSharedTries = 4;

/// A free square pushed further from its joint than this many corner radii of the patch's widest branch
/// may tilt to clear the other squares (see tilt_square).
constexpr double kTiltFrom = 2;

/// A square held back by the square beside it is tried at this many steps along its push, less one
/// (tilt_on_the_way).
constexpr int kWaySteps = 4;

/// Rounds of pushing a patch's squares out (push_squares) before those that have not cleared the others
/// are taken as stuck. Branches that run side by side from a joint, their tubes overlapping all along
/// (vessels duplicated a little apart), push each other's squares on in turn, a fraction of a radius a
/// round, to their far ends: tens of thousands of rounds on a branch 5e4 radii long.
constexpr int kPushes = 1000;

/// How a branch that meets a joint is built.
enum class Kind {
  tube,       ///< a square at each joint end, a tube between them
  shared,     ///< between two joints, too short for a tube: one square is a face of both patches
  stub,       ///< from a joint to a terminal, too short for a tube: its terminal square joins the patch
  swallowed,  ///< between two joints that could not be parted: inside their merged patch
  tunnel,     ///< would close a loop inside a merged patch: the loop's hole goes through the patch instead
};

/// One end of a branch at a joint, and the square that closes the patch there.
struct End {
  int32_t branch = -1;
  bool at_start = true;       ///< the joint is the branch's first point
  double t = 0;               ///< arc distance of the square from the joint
  bool stuck = false;         ///< pushed to the far end of its branch without clearing the other squares
  bool fixed = false;         ///< stub and shared squares stay where they are
  bool chord = false;         ///< faces along the chord from the joint to its centre, not along the tangent
  bool tilted = false;        ///< tilted from that direction to clear the other squares (tilt_square)
  Section square;             ///< normal points away from the joint, corners counter-clockwise about it
  int32_t first_vertex = -1;  ///< the square's corners are vertices first_vertex .. first_vertex + 3
};

/// The hole of a loop closed inside a merged patch: a straight hole through the patch's hull, between two
/// square mouths on opposite sides of the hull, each pushed out from the loop's centroid until it is a
/// face of the hull. The loop's tubes overlap (that is why its joints merged), so the input has no hole
/// to copy; a small one, well inside the patch, gives the surface the loop's genus.
struct Tunnel {
  Vec3 center = Vec3::Zero();   ///< the loop's centroid, plus `offset`
  Vec3 normal = Vec3::UnitZ();  ///< of the loop's best-fit plane
  /// Directions of the head's and the tail's mouth: either side of the loop's plane, tilted away from
  /// the mean centroid of the patch's loops by the loop's offset from it in loop radii, up to 27°, so
  /// that the mouths of several loops in one patch fan out rather than push each other out without end.
  std::array<Vec3, 2> out;
  double radius = 0;  ///< the loop's mean radius
  /// Whether the mouths face `turned_out` instead: the loop's mouths could not clear the patch on either
  /// side of its plane, and were turned to faces of the patch's hull (Tiler::turn_tunnel).
  bool turned = false;
  std::array<Vec3, 2> turned_out;
  int turns = 0;  ///< how often it has been turned
  /// Added to the loop's centroid once the mouths have met another tunnel's: away from that tunnel's
  /// centre by twice their corners' reach. A hole anywhere through the patch gives it the loop's handle.
  Vec3 offset = Vec3::Zero();
  double hole() const { return 0.25 * radius; }
  /// Mouths pushed further than this cannot clear the patch: the loop is absorbed after all. (Along the
  /// loop's normal, a mouth pushed further stands out of the patch as a spike; on faces of the patch's
  /// hull, a longer hole keeps the outer surface from coming in onto the tubes round its mouths.)
  double reach() const { return 4 * radius; }
};

/// A tube's sections before it joins the mesh (Tiler::plan_tube).
struct TubePlan {
  std::vector<Section> sections;  ///< placed for the limit surface, with their frames
  std::vector<Vec3> axis;         ///< per section: the direction the tube really runs (add_section)
  std::vector<Vec3> bend;         ///< per section: the axis's curvature vector (TubeAxis)
  std::vector<double> slope;      ///< per section: dr/ds
  bool ring = false;              ///< a closed ring of degree-2 points
  int k = 0;                      ///< the quarter turn the frames end with (transport_frames)
};

/// A joint patch: one joint, or several joints too close to part, and the branch ends that meet it.
struct Patch {
  std::vector<int32_t> joints;  ///< joint points
  std::vector<int32_t> ends;    ///< indices into Tiler::ends_
  /// Hull points that close no opening: around each tunnel, its loop's points at the height of the
  /// tubes' corners on either side of the loop's plane, so that the hull covers the loop and surrounds
  /// the hole even where no branch leaves the loop.
  std::vector<Vec3> rim;
  std::vector<int32_t> inside;  ///< its stubs and swallowed branches
};

class Tiler {
 public:
  Tiler(const CenterlineGraph& g, const TileOptions& o)
      : g_(g), opt_(o), joints_(g.points.size()) {
    SamplingOptions sampling = o.sampling;  // the corners are found by sampling each branch as a whole
    sampling.max_sections = o.max_sections;
    CutBranches cut = cut_at_corners(g, sampling, o.radius_scale);
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

  BaseMesh run() {
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

 private:
  const CenterlineGraph& g_;
  const TileOptions& opt_;
  UnionFind joints_;              // joints that share a patch
  std::vector<char> corner_;      // per point: a sharp corner, tiled as a joint of two branches
  std::vector<Branch> branches_;  // the graph's branches, cut at the corners
  std::vector<BranchCurve> curves_;
  std::vector<Kind> kind_;
  std::vector<double> shared_at_;       // shared: arc position of the square from the branch's start
  std::vector<Vec3> shared_up_;         // shared: its up-vector
  std::vector<Vec3> shared_normal_;     // shared: its normal, seen from the branch's start
  std::vector<int> shared_tries_;       // how often a shared square has been placed on the branch
  std::vector<int32_t> shared_vertex_;  // shared: first corner vertex, corners as seen from the start
  std::vector<Tunnel> tunnel_;          // tunnel: its hole
  std::vector<End> ends_;
  std::vector<int32_t> head_, tail_;  // per branch: its end at its first / last point, or -1
  std::vector<Patch> patches_;
  BaseMesh mesh_;

  bool is_joint(int32_t v) const { return g_.degree(v) >= 3 || corner_[v]; }
  int32_t first_point(int32_t b) const { return branches_[b].points.front(); }
  int32_t last_point(int32_t b) const { return branches_[b].points.back(); }

  double scale() const { return opt_.radius_scale; }

  /// The square of `e` at arc distance t from its joint (up-vector still to be chosen). A tunnel's
  /// mouths sit at distance t from the loop's centroid, the head's on one side of the loop's plane, the
  /// tail's on the other.
  Section square_at(const End& e, double t) const {
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
  double travel(const End& e) const {
    return kind_[e.branch] == Kind::tunnel ? tunnel_[e.branch].reach() : curves_[e.branch].length();
  }

  /// Up-vectors for a patch's free squares: the projection of the patch's reference direction (the
  /// normal of the best-fit plane of its branch directions), turned 45° so that a square's edge faces
  /// its neighbours, plus a small per-square offset so that corners of different squares are not
  /// coplanar.
  void orient_squares(const Patch& p, int attempt) {
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
  double intrusion(const End& e, const Patch& p) const { return reach_past(e.square, others(e, p)); }

  /// The corners of `p`'s squares other than e's, and its rim: what e's square must have behind its plane.
  std::vector<Vec3> others(const End& e, const Patch& p) const {
    std::vector<Vec3> out(p.rim.begin(), p.rim.end());
    for (int32_t i : p.ends)
      if (&ends_[i] != &e)
        for (int k = 0; k < 4; ++k) out.push_back(ends_[i].square.corner(k, scale()));
    return out;
  }

  /// How far `points` reach past the plane of square `s`, plus a margin.
  double reach_past(const Section& s, const std::vector<Vec3>& points) const {
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
  void place_squares(const Patch& p, int attempt) {
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

  void push_squares(const Patch& p, int attempt) {
    // Squares pushed this far from the joint (out of the widest tube's reach round it) may tilt.
    double widest = 0;
    for (int32_t i : p.ends) {
      const End& e = ends_[i];
      if (kind_[e.branch] != Kind::tunnel)
        widest = std::max(widest, curves_[e.branch].radius_at(e.at_start ? 0 : curves_[e.branch].length()));
    }
    const double tilt_from = kTiltFrom * scale() * widest;
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
  bool tilt_on_the_way(End& e, const Patch& p, double to, double tilt_from) {
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
  bool held_back_beside(const End& e, const Patch& p) const {
    double furthest = -std::numeric_limits<double>::infinity();
    const End* by = nullptr;
    for (int32_t i : p.ends) {
      const End& o = ends_[i];
      if (&o == &e) continue;
      for (int q = 0; q < 4; ++q) {
        const double reach = e.square.normal.dot(o.square.corner(q, scale()) - e.square.center);
        if (reach > furthest) furthest = reach, by = &o;
      }
    }
    return by && kind_[by->branch] == Kind::tube &&
           across(e, *by) < scale() * (e.square.radius + by->square.radius);
  }

  /// Whether no other tube square of the patch lies closer to e's across the branch than their two radii.
  bool tubes_apart(const End& e, const Patch& p) const {
    for (int32_t i : p.ends) {
      const End& o = ends_[i];
      if (&o != &e && kind_[o.branch] == Kind::tube && across(e, o) < e.square.radius + o.square.radius)
        return false;
    }
    return true;
  }

  /// The distance of o's square's centre from e's, across e's branch (in the plane of e's square).
  static double across(const End& e, const End& o) {
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
  bool tilt_square(End& e, const Patch& p) {
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
  double best_shared_square(int32_t b) {
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
                    std::min(clearance, -side * normal.dot(ends_[i].square.corner(q, scale()) - center));
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

  /// Whether the tube of branch b, between the squares at its two joints, would fold: no chain of its
  /// sections from one square to the other gets there without one reaching across the next one's plane
  /// (fold_free_chains). A short thick branch between two patches that face it from sides a right angle
  /// apart folded so (brava-records BH0005). Unless `thorough`, only tubes shorter than four corner radii
  /// are looked at: longer ones mostly have room to turn, and their bends too tight for sections are
  /// corners already. Not always: squares pushed out up to a bend of their branch (a loop from a patch
  /// back to it, 116° turns between its legs) face across it, the tube keeps only those two squares, and
  /// the straight prism between them runs along the patch's own faces (a non-manifold base mesh).
  bool tube_folds(int32_t b, bool thorough) const {
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
  bool room_for_tube(int32_t b) const {
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
  void find_patches() {
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
          kind_[b] = Kind::swallowed;
          --mesh_.tunnels;
        }
      }
      if (changed || decide_kinds(false) || decide_kinds(true)) continue;
      return;
    }
  }

  /// Decides the kind of each branch from where its squares stand (find_patches); true when one
  /// changed. `thorough`: whether tube_folds looks at every tube between two joints, not only short ones.
  bool decide_kinds(bool thorough) {
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
  bool has_room(int32_t b) const {
    double used = 0.25 * std::min(curves_[b].radius.front(), curves_[b].radius.back());
    for (int32_t i : {head_[b], tail_[b]})
      if (i >= 0) {
        if (ends_[i].stuck) return false;
        used += ends_[i].t;
      }
    return used <= curves_[b].length();
  }

  /// Branch b is no tube (or shared square) at its joints: a stub when it ends at a terminal, else a
  /// shared square, a tunnel, or swallowed by its joints' merged patch.
  void give_up_tube(int32_t b) {
    if (head_[b] < 0 || tail_[b] < 0) {
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

  std::vector<int32_t> patch_of_end_;

  /// A straight hole through a convex patch gives it a genus whichever way it runs. For a tunnel whose
  /// mouths could not clear patch `p` on either side of its loop's plane, or met another tunnel's:
  /// mouths on two faces of the hull of the patch's other squares and rims, facing apart (normals over
  /// 134° apart) and not along a branch, whose planes the tunnel's centre is nearest to and lies in front
  /// of. A mouth on a face of the hull adds no bulge to it, wherever the patch is thick. The hole must
  /// keep clear of the holes of the tunnels `kept` already. Returns false when no pair of faces will do
  /// within the tunnel's reach.
  bool turn_tunnel(int32_t b, const Patch& p, const std::vector<int32_t>& kept) {
    Tunnel& h = tunnel_[b];
    ++h.turns;
    h.turned = false;
    std::vector<Vec3> others = p.rim;
    for (int32_t i : p.ends)
      if (ends_[i].branch != b)
        for (int k = 0; k < 4; ++k) others.push_back(ends_[i].square.corner(k, scale()));
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

  /// Whether a mouth of tunnel a comes within twice the corners' reach of a mouth of tunnel b, so that
  /// the hull would leave no wall between the two holes.
  bool mouths_meet(int32_t a, int32_t b) const {
    for (int32_t i : {head_[a], tail_[a]})
      for (int32_t j : {head_[b], tail_[b]}) {
        const Section &p = ends_[i].square, &q = ends_[j].square;
        if ((p.center - q.center).norm() < 2 * scale() * (p.radius + q.radius)) return true;
      }
    return false;
  }

  void collect_patches() {
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
    for (Patch& p : patches_) add_body(p);
  }

  /// A patch with fewer than two openings (tube, shared or tunnel squares) is all its component has
  /// there: its squares alone may span no solid (one square, or stubs' squares at their terminals far
  /// from the joint) and leave the joints and swallowed branches outside. Such a patch gets round each
  /// joint, and each point inside its stubs and swallowed branches, six rim points at the corners' reach
  /// (an octahedron turned by a different angle at each point, so that no four of them are coplanar by
  /// accident), and its hull covers the branches it took in.
  void add_body(Patch& p) {
    const auto openings = std::count_if(p.ends.begin(), p.ends.end(), [&](int32_t i) {
      return kind_[ends_[i].branch] != Kind::stub;
    });
    if (openings >= 2) return;
    int turn = 0;
    auto octahedron = [&](const Vec3& at, double r) {
      const double angle = 2 * M_PI * std::fmod(0.6180339887 * ++turn, 1.0);
      const Vec3 axis = Vec3(1, 2, 3).normalized();
      for (int k = 0; k < 3; ++k)
        for (double side : {1.0, -1.0})
          p.rim.push_back(at + side * scale() * r * rotate(Vec3::Unit(k), axis, angle));
    };
    for (int32_t j : p.joints) octahedron(g_.points[j], g_.radius[j]);
    for (int32_t b : p.inside)
      for (std::size_t i = 1; i + 1 < curves_[b].points.size(); ++i)
        octahedron(curves_[b].points[i], curves_[b].radius[i]);
  }

  /// Each tunnel's hole from its loop: the tunnel's branch and the path of swallowed branches (a tree
  /// in each patch) between its joints. Centroid and plane are those of the loop's edges, weighted by length.
  void find_tunnel_holes() {
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

  /// Adds the section's four corners. Its plane follows the smoothed tangent, which leans against
  /// `axis`, the direction the tube really runs (the polyline's) on a coarse or jagged centerline: each
  /// corner is pushed out to the radius from the axis line rather than from the centre, or the tube
  /// would be too thin by the cosine of the lean (capped at twice the radius, a 60° lean).
  /// `weight`: 1 for a tube's sections, 0 for a joint patch's squares; `bend` and `slope` the axis's there
  /// (TubeAxis).
  int32_t add_section(const Section& s, const Vec3& axis, double weight, const Vec3& bend = Vec3::Zero(),
                      double slope = 0) {
    const int32_t first = static_cast<int32_t>(mesh_.vertices.size());
    for (int k = 0; k < 4; ++k) {
      const Vec3 offset = s.corner(k, scale()) - s.center;
      const double along = offset.normalized().dot(axis);
      mesh_.vertices.push_back(s.center + offset / std::sqrt(std::max(1.0 - along * along, 0.25)));
      mesh_.axes.push_back({s.center - mesh_.vertices.back(), s.radius, weight, axis, bend, slope});
    }
    mesh_.squares.push_back({first, first + 1, first + 2, first + 3});
    if (++mesh_.sections > opt_.max_sections)
      throw SizeLimitError("more than " + std::to_string(opt_.max_sections) + " sections");
    return first;
  }

  int32_t add_square(const Section& s) { return add_section(s, s.normal, 0.0); }

  /// The patch's vertex ids for the square of end `e`, corners counter-clockwise about its normal.
  /// A shared square's corners are made once; seen from the branch's end they run the other way.
  std::array<int32_t, 4> square_vertices(const End& e) {
    if (kind_[e.branch] != Kind::shared) {
      const int32_t first = add_square(e.square);
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

  /// Closes the patch. Where its hull cannot close, a tunnel's loop is given up (its branch is
  /// swallowed), or failing one, the tube whose square was pushed furthest in its radii (the two legs of
  /// a hairpin that run on side by side, their squares abreast, each just clear of the other's plane);
  /// then false is returned, for the kinds to be decided again without it.
  bool build_patch(const Patch& p) {
    if (close_patch(p)) return true;
    const auto tunnel = std::find_if(p.ends.begin(), p.ends.end(),
                                     [&](int32_t i) { return kind_[ends_[i].branch] == Kind::tunnel; });
    if (tunnel != p.ends.end()) {
      kind_[ends_[*tunnel].branch] = Kind::swallowed;
      --mesh_.tunnels;
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
  bool close_patch(const Patch& p) {
    const int32_t squares = static_cast<int32_t>(p.ends.size());
    for (int attempt = 0; attempt < 8; ++attempt) {
      if (attempt > 0) place_squares(p, attempt);
      std::vector<Vec3> corners;
      for (int32_t i : p.ends)
        for (int k = 0; k < 4; ++k) corners.push_back(ends_[i].square.corner(k, scale()));
      corners.insert(corners.end(), p.rim.begin(), p.rim.end());
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
      for (const Vec3& r : p.rim) {
        id.push_back(static_cast<int32_t>(mesh_.vertices.size()));
        mesh_.vertices.push_back(r);
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
  bool closes_openings(const std::vector<Tri>& patch, const Patch& p,
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

  /// Branch b's tube (kind tube) before it joins the mesh: its sections placed for the limit surface, with
  /// the axis, bend and slope at each, and the quarter turn k its frames end with. Reads only the branch
  /// and the squares at its ends, so that tubes are planned on every core at once.
  TubePlan plan_tube(int32_t b) const {
    const BranchCurve& c = curves_[b];
    const End* head = head_[b] >= 0 ? &ends_[head_[b]] : nullptr;
    const End* tail = tail_[b] >= 0 ? &ends_[tail_[b]] : nullptr;
    const bool ring = first_point(b) == last_point(b) && !head;
    const double from = head ? head->t : 0.0, to = c.length() - (tail ? tail->t : 0.0);
    SamplingOptions sampling = opt_.sampling;  // the sections in all are counted as they are added
    sampling.max_sections = opt_.max_sections;
    std::vector<double> arcs = sample_branch(c, from, to, sampling);
    if (ring && arcs.size() < 4) arcs = {0.0, c.length() / 3, 2 * c.length() / 3, c.length()};

    TubePlan plan;
    plan.ring = ring;
    std::vector<Section>& sections = plan.sections;
    sections.resize(arcs.size());
    for (std::size_t i = 0; i < arcs.size(); ++i) {
      sections[i].center = c.position(arcs[i]);
      sections[i].radius = c.radius_at(arcs[i]);
      sections[i].normal = c.tangent(arcs[i]);
    }
    if (ring) sections.back().center = sections.front().center;
    if (head) sections.front().normal = head->square.normal;
    if (tail) sections.back().normal = -tail->square.normal;
    if (!ring) {
      drop_folds(sections, scale());
      unfold_ends(sections, !head, !tail, scale());
    }
    const std::size_t m = sections.size() - 1;
    // Where the tube really runs at each section: along the polyline through the centres.
    std::vector<Vec3>& axis = plan.axis;
    axis.resize(m + 1);
    for (std::size_t i = 0; i <= m; ++i)
      axis[i] = (sections[std::min(i + 1, m)].center - sections[i > 0 ? i - 1 : 0].center).normalized();
    // The bend of the axis through the centres (the difference of the unit chords either side over half
    // their length, exact for centres on a circle) and the radius's slope along it, before the centres move
    // for the limit surface to pass through them: the round stage puts the surface on circles about that
    // axis, so this is the shape whose curvature the tube has.
    std::vector<Vec3>& bend = plan.bend;
    std::vector<double>& slope = plan.slope;
    bend.assign(m + 1, Vec3::Zero());
    slope.assign(m + 1, 0.0);
    for (std::size_t i = 0; i <= m; ++i) {
      const std::size_t a = i > 0 ? i - 1 : ring ? m - 1 : 0, b = i < m ? i + 1 : ring ? 1 : m;
      const Vec3 in = sections[i].center - sections[a].center, out = sections[b].center - sections[i].center;
      const double l_in = in.norm(), l_out = out.norm();
      if (l_in + l_out > 0) slope[i] = (sections[b].radius - sections[a].radius) / (l_in + l_out);
      if (l_in > 0 && l_out > 0) bend[i] = 2 * (out / l_out - in / l_in) / (l_in + l_out);
    }
    place_for_limit(sections, axis, ring, scale());
    sections.front().up = head ? head->square.up : any_perpendicular(sections.front().normal);
    const Vec3 first_up = sections.front().up;
    const Vec3* target = tail ? &tail->square.up : ring ? &first_up : nullptr;
    plan.k = transport_frames(sections, target);
    return plan;
  }


  /// Adds branch b's tube, as planned (plan_tube), to the mesh: its sections' corners and the quads between
  /// them, and flat caps at its terminals.
  void build_tube(int32_t b, const TubePlan& plan) {
    const End* head = head_[b] >= 0 ? &ends_[head_[b]] : nullptr;
    const End* tail = tail_[b] >= 0 ? &ends_[tail_[b]] : nullptr;
    const bool ring = plan.ring;
    const int k = plan.k;
    const std::vector<Section>& sections = plan.sections;
    const std::size_t m = sections.size() - 1;
    // Vertex ids of each section's corners, counter-clockwise about the direction of travel.
    std::vector<std::array<int32_t, 4>> ids(m + 1);
    for (std::size_t i = 0; i <= m; ++i) {
      if (i == 0 && head) {
        for (int j = 0; j < 4; ++j) ids[i][j] = head->first_vertex + j;
      } else if (i == m && ring) {
        for (int j = 0; j < 4; ++j) ids[i][j] = ids[0][((j - k) % 4 + 4) % 4];
      } else if (i == m && tail) {
        // The tail square runs counter-clockwise about its outward normal, against the travel.
        for (int j = 0; j < 4; ++j) ids[i][j] = tail->first_vertex + ((k - j) % 4 + 4) % 4;
      } else {
        // A terminal's end section, whose corners the flat cap joins, keeps the cap's shape.
        const bool cap = !ring && (i == 0 || i == m);
        const int32_t first = add_section(sections[i], plan.axis[i], cap ? 0.0 : 1.0, plan.bend[i], plan.slope[i]);
        for (int j = 0; j < 4; ++j) ids[i][j] = first + j;
      }
    }
    for (std::size_t i = 0; i < m; ++i)
      for (int j = 0; j < 4; ++j)
        mesh_.quads.push_back({ids[i][j], ids[i][(j + 1) % 4], ids[i + 1][(j + 1) % 4], ids[i + 1][j]});
    if (opt_.caps == Caps::flat && !ring) {
      if (!head) mesh_.quads.push_back({ids[0][3], ids[0][2], ids[0][1], ids[0][0]});
      if (!tail) mesh_.quads.push_back({ids[m][0], ids[m][1], ids[m][2], ids[m][3]});
    }
  }

  /// The tunnel's hole: four quads straight through the patch from its head mouth to its tail mouth,
  /// facing the hole's axis. Seen along the head's normal, the tail's corners run clockwise, so head
  /// corner j pairs with tail corner (k − j) mod 4, for the quarter turn k that pairs them closest.
  void build_tunnel(int32_t b) {
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

  /// Stub squares that ended up inside a patch's hull are not used by any face.
  void drop_unused_vertices() {
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
};

}  // namespace

std::vector<VertexProperty> tube_axis_properties(const std::vector<TubeAxis>& axes) {
  std::vector<VertexProperty> out;
  for (const std::string& name : kTubeAxisNames) out.push_back({name, std::vector<float>(axes.size())});
  for (std::size_t v = 0; v < axes.size(); ++v) {
    const TubeAxis& a = axes[v];
    for (int k = 0; k < 3; ++k) {
      out[k].values[v] = static_cast<float>(a.offset[k]);
      out[5 + k].values[v] = static_cast<float>(a.tangent[k]);
      out[8 + k].values[v] = static_cast<float>(a.bend[k]);
    }
    out[3].values[v] = static_cast<float>(a.radius);
    out[4].values[v] = static_cast<float>(a.weight);
    out[11].values[v] = static_cast<float>(a.slope);
  }
  return out;
}

std::array<const std::vector<float>*, kTubeAxisNames.size()> find_tube_axis_properties(const TriMesh& mesh,
                                                                                       std::size_t count) {
  std::array<const std::vector<float>*, kTubeAxisNames.size()> p{};
  count = std::min(count, p.size());
  for (std::size_t k = 0; k < count; ++k)
    for (const VertexProperty& q : mesh.vertex_properties)
      if (q.name == kTubeAxisNames[k]) p[k] = &q.values;
  if (std::any_of(p.begin(), p.begin() + count, [](const auto* q) { return q == nullptr; })) p.fill(nullptr);
  return p;
}

void drop_tube_axis_properties(TriMesh& mesh, std::size_t from) {
  const auto first = kTubeAxisNames.begin() + static_cast<std::ptrdiff_t>(std::min(from, kTubeAxisNames.size()));
  auto& p = mesh.vertex_properties;
  p.erase(std::remove_if(p.begin(), p.end(),
                         [&](const VertexProperty& q) {
                           return std::find(first, kTubeAxisNames.end(), q.name) != kTubeAxisNames.end();
                         }),
          p.end());
}

BaseMesh tile_base_mesh(const CenterlineGraph& graph, const TileOptions& options) {
  return Tiler(graph, options).run();
}

}  // namespace vesselmesh
