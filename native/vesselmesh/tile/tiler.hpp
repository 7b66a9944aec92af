#pragma once
// The tiler behind tile_base_mesh (base_mesh.hpp), for the files that hold its mechanisms: base_mesh.cpp
// (the run, and each branch's kind), squares.cpp (pushing a patch's squares clear), patches.cpp (closing
// each patch's hull), tunnels.cpp (loops closed through a patch) and tubes.cpp (the tubes and their caps).

#include <array>
#include <cstdint>
#include <vector>

#include "vesselmesh/frames/frames.hpp"
#include "vesselmesh/graph/union_find.hpp"
#include "vesselmesh/sample/branch_curve.hpp"
#include "vesselmesh/tile/base_mesh.hpp"

namespace vesselmesh::tile_detail {

/// Ways a tunnel is turned (each from where the patch's squares then stand) before its loop is given up.
constexpr int kTurns = 3;

/// A shared square is tried at this many points along its branch, tilted from the tangent by up to this
/// many steps of 15° (see best_shared_square), and placed again up to this many times, each from where
/// the squares pushed out round it then stand, before its two joints merge.
constexpr int kSharedPositions = 15;
constexpr int kSharedTilts = 3;
constexpr int kSharedTries = 4;

/// A free square pushed further from its joint than this many corner radii of the patch's widest branch
/// may tilt to clear the other squares (see tilt_square); the square of a branch under half as wide, this
/// many of its own. Counted in the widest branch's radii, a thin branch that leaves a fat vessel at a small
/// angle had its square pushed on along it, out of the fat tube, until the fat vessel's square stood past
/// it, and the hull of the two was a web (fixture thin_branch_wavering_out_of_a_fat_vessel: 1.3 to 1.5
/// radii off the tubes; 0.6 to 0.9 so). Counted in their own radii, squares about as wide as the widest
/// tilted close to the joint and folded the tube beside them (vesselgraph-demo crossed itself).
constexpr double kTiltFrom = 2;

/// Small squares have their corners at this share of the tubes' corner reach; the fit brings the patch out
/// onto the tubes. They clear each other nearer their joints, so that the patch's convex hull hugs its
/// branches rather than spanning a vessel's bend and its side branches' roots (neuron-hemibrain-da1's blobs,
/// fixture fat_trunk_with_a_side_branch_at_every_point: 60 % of its area off the tubes, 8 % so). A patch
/// along a vessel (three joints or more) has them always; every patch has them where the surface is checked
/// for crossings (TileOptions::small_squares): with small squares a tube starts nearer its joint and can cross
/// a vessel passing close by, and the patches near such a crossing are tried again with full squares.
/// At 0.55 more random trees crossed (docs/pipeline.md, decisions log).
constexpr double kSmallSquare = 0.7;

/// A joint this many times as wide as the widest of its patch's openings bulges out of their hull (a soma,
/// a bulb), and its sphere gets hull points (Tiler::uncovered_sphere_points). At 1.25, brava-bg0003's
/// noisy radii (a joint of radius 0.93 whose branches leave at 0.62) gave a face 1.02 radii off the tubes.
constexpr double kFatterThanItsOpenings = 2;

/// A patch keeps full squares when one of its joints, or a point of one of its branches, lies within this
/// many of its radii of a place where the surface crossed itself with small squares
/// (TileOptions::full_squares_near).
constexpr double kNearCrossing = 4;

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
  double reach = 1;           ///< share of the tubes' corner reach its corners stand at (kSmallSquare)
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

/// A terminal branch longer than this many diameters (of its two ends) that has no room for a tube after
/// its joint's square curls back on itself (Tiler::curled).
constexpr double kCurlDiameters = 4;

/// Tiles one graph: run() builds its base mesh (tile_base_mesh).
class Tiler {
 public:
  /// `corners`: points to tile as corners besides the sharp ones (cut_at_corners).
  Tiler(const CenterlineGraph& g, const TileOptions& o, const std::vector<int32_t>& corners = {});
  BaseMesh run();
  /// Points to tile as corners, found by run(), which then stops short: a long terminal branch with no room
  /// for a tube after its joint's square (room_for_tube) curls back to the joint; made a stub, its terminal
  /// square a face of the patch's hull, it was a spike where a vessel 34 radii long had been (fixture
  /// terminal_curling_back_to_its_joint, from brava-records BH0038). Cut at its point furthest from the
  /// joint, each half has room.
  const std::vector<int32_t>& curled() const { return curled_; }

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
  std::vector<int32_t> patch_of_end_;  // per end: its patch, an index into patches_
  std::vector<int32_t> curled_;        // see curled()

  bool is_joint(int32_t v) const { return g_.degree(v) >= 3 || corner_[v]; }
  int32_t first_point(int32_t b) const { return branches_[b].points.front(); }
  int32_t last_point(int32_t b) const { return branches_[b].points.back(); }

  double scale() const { return opt_.radius_scale; }
  Vec3 corner(const End& e, int k) const { return e.square.corner(k, scale() * e.reach); }

  // base_mesh.cpp: each branch's kind, and the vertices no face uses dropped at the end.
  bool tube_folds(int32_t b, bool thorough) const;
  bool room_for_tube(int32_t b) const;
  int32_t curl_apex(int32_t b) const;
  void find_patches();
  bool decide_kinds(bool thorough);
  bool has_room(int32_t b) const;
  void give_up_tube(int32_t b);
  void drop_unused_vertices();

  // squares.cpp: a patch's squares pushed (or tilted) clear of each other, and shared squares.
  Section square_at(const End& e, double t) const;
  double travel(const End& e) const;
  void orient_squares(const Patch& p, int attempt);
  double intrusion(const End& e, const Patch& p) const;
  std::vector<Vec3> others(const End& e, const Patch& p) const;
  double reach_past(const Section& s, const std::vector<Vec3>& points) const;
  void place_squares(const Patch& p, int attempt);
  void push_squares(const Patch& p, int attempt);
  bool tilt_on_the_way(End& e, const Patch& p, double to, double tilt_from);
  bool held_back_beside(const End& e, const Patch& p) const;
  bool tubes_apart(const End& e, const Patch& p) const;
  static double across(const End& e, const End& o);
  bool tilt_square(End& e, const Patch& p);
  double best_shared_square(int32_t b);

  // patches.cpp: the patches, each closed as the hull of its squares.
  void collect_patches();
  void shrink_squares(const Patch& p);
  bool near_crossing(const Patch& p) const;
  void add_body(Patch& p);
  std::vector<Vec3> uncovered_sphere_points(const Patch& p, const std::vector<Vec3>& corners) const;
  void give_up_loop(const Patch& p, int32_t tunnel, const std::string& why);
  std::array<int32_t, 4> square_vertices(const End& e);
  bool build_patch(const Patch& p);
  bool close_patch(const Patch& p);
  bool closes_openings(const std::vector<Tri>& patch, const Patch& p,
                       const std::vector<int>& open_side) const;

  // tunnels.cpp: loops closed inside a patch, through it.
  bool turn_tunnel(int32_t b, const Patch& p, const std::vector<int32_t>& kept);
  bool mouths_meet(int32_t a, int32_t b) const;
  bool hole_crossed(int32_t b) const;
  void find_tunnel_holes();
  void build_tunnel(int32_t b);

  // tubes.cpp: the tubes, their sections and caps.
  int32_t add_section(const Section& s, const Vec3& axis, double weight, const Vec3& bend = Vec3::Zero(),
                      double slope = 0, double reach = 1);
  int32_t add_square(const Section& s, double reach = 1);
  TubePlan plan_tube(int32_t b) const;
  void build_tube(int32_t b, const TubePlan& plan);
};

}  // namespace vesselmesh::tile_detail
