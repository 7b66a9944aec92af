#pragma once
// The mesh checker: what a user needs to trust a surface. Topology (boundary and non-manifold edges
// and vertices, orientation, components, Euler characteristic, genus), self-intersecting triangle
// pairs, triangle quality, and radius fidelity against the centerline it was made from.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vesselmesh/graph/centerline_graph.hpp"
#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// Summary of a set of values (all zero when it is empty); the quantiles interpolate linearly between
/// neighbouring values.
struct Distribution {
  double min = 0, median = 0, p95 = 0, p99 = 0, max = 0, mean = 0;
  int64_t count = 0;
};

/// Faces with a repeated vertex are counted (in `faces` and `degenerate_faces`) but take no part in
/// edges, fans, components, χ or volume.
struct TopologyReport {
  int64_t vertices = 0, edges = 0, faces = 0;  ///< vertices: those used by faces
  int64_t boundary_edges = 0;                  ///< edges with one face
  int64_t non_manifold_edges = 0;              ///< edges with three or more faces
  int64_t non_manifold_vertices = 0;           ///< vertices whose faces form more than one fan (faces joined
                                               ///< through shared edges: a pinch, not a non-manifold edge)
  int64_t inconsistent_edges = 0;              ///< edges whose two faces traverse them in the same direction
  int64_t degenerate_faces = 0;      ///< faces with a repeated vertex or zero area (below 1e-14 times
                                     ///< the squared longest edge)
  int64_t components = 0;            ///< connected components (by shared vertices)
  int64_t euler_characteristic = 0;  ///< V − E + F
  int64_t genus = 0;                 ///< (2·components − χ) / 2 when closed_manifold(), else 0
  double signed_volume = 0;          ///< > 0 for outward-facing closed surfaces
  bool closed_manifold() const {
    return boundary_edges == 0 && non_manifold_edges == 0 && non_manifold_vertices == 0 &&
           inconsistent_edges == 0 && degenerate_faces == 0;
  }
};

/// Two triangles intersect when their relative interiors meet: they cross, one passes through the
/// other, or they overlap in a common plane (which includes a pair folded back over a shared edge).
/// Contact only along edges or at vertices (a shared edge or vertex, or touching) does not count.
/// Faces with a repeated vertex or collinear corners have no interior and are left out.
struct IntersectionReport {
  int64_t pairs = 0;                             ///< intersecting triangle pairs
  int64_t pairs_in_overlapping_tubes = 0;        ///< of those, pairs where the input tubes themselves overlap
  std::vector<std::array<int32_t, 2>> examples;  ///< the first 20 pairs (face indices, ascending), for a look
};

struct QualityReport {
  Distribution radius_ratio;  ///< circumradius / inradius per triangle (2 for equilateral)
  Distribution min_angle;     ///< smallest angle per triangle, degrees
  int64_t degenerate = 0;     ///< degenerate faces (radius ratio +inf), left out of both distributions
};

struct FidelityReport {
  Distribution abs_relative_error;  ///< |signed distance to the union of round cones| / local radius
  Distribution relative_error;      ///< signed (negative = inside, too thin)
  int64_t excluded_cap_vertices = 0;
  /// Share of the surface's area (faces at the caps left out) on faces whose centroid lies more than half
  /// the local radius off the tubes, in or out: surface spanning across the tubes rather than following
  /// them (a hull bridging a bend, a triangle from one tube to another), which the vertices' errors miss
  /// when every corner lies on a tube.
  double area_off_tubes = 0;
  /// |distance| of each face's centroid to the tubes / local radius, weighted by the face's area (caps left
  /// out): the error between the vertices, where a flat triangle cuts inside a round tube.
  Distribution centroid_error;
  /// The face centroid furthest off the tubes (in or out; caps left out), in local radii, and where it is:
  /// a fin or a web, of which the vertices say nothing when they lie on the tubes.
  double largest_centroid_offset = 0;
  Vec3 largest_centroid_offset_at = Vec3::Zero();
  /// The longest edge in local radii (the larger of the radii at its two ends, caps left out), and its
  /// midpoint: a long edge reaching across from one vessel to another.
  double longest_edge = 0;
  double longest_edge_length = 0;
  Vec3 longest_edge_at = Vec3::Zero();
  /// The longest edge, in local radii, whose midpoint lies more than half the local radius off the tubes:
  /// one reaching across (a fin, a web), where an edge along a straight tube may be long and lie on it.
  double longest_edge_off_tubes = 0;
  Vec3 longest_edge_off_tubes_at = Vec3::Zero();
  /// The input's axis lying outside the surface by more than its radius (samples every half radius along
  /// each edge, caps left out), in local radii of length, and the first such sample: a vessel, or the end
  /// of one, that the surface lost. The other measures look from the surface to the tubes and say nothing
  /// of a tube with no surface round it. A vessel the separate stage moved lies within its radius of its
  /// axis, since the moves stay below two radii.
  double missing_axis = 0;
  Vec3 missing_axis_at = Vec3::Zero();
  std::vector<float> per_vertex;    ///< signed relative error of each vertex, NaN for cap vertices
};

struct CheckReport {
  TopologyReport topology;
  IntersectionReport intersections;
  QualityReport quality;
  std::optional<FidelityReport> fidelity;  ///< only when a centerline is given
};

// Each function throws std::invalid_argument when a face refers to a vertex the mesh does not have.

TopologyReport check_topology(const TriMesh& mesh);
/// Exact-predicate triangle–triangle tests on the pairs a bounding-volume hierarchy proposes.
/// With a centerline, an intersecting pair is classed as overlapping tubes when the two triangles lie
/// near (centroid within 1.5 local radii of the axis) edges of two different branches whose round
/// cones overlap: the axes' closest points are nearer than the sum of the radii there, leaving out
/// the parts within 3 radii of a joint the two branches share (where they are meant to meet); or near
/// two edges of one branch whose cones overlap at parts more than 3 radii apart along the branch.
/// With `among` (a flag per face), only the pairs with a flagged face (intersecting_face_pairs).
IntersectionReport find_self_intersections(const TriMesh& mesh, const CenterlineGraph* centerline = nullptr,
                                           const std::vector<char>& among = {});
/// The report of the intersecting pairs `hits` of `mesh` (intersecting_face_pairs), classed as
/// find_self_intersections classes them.
IntersectionReport intersection_report(const TriMesh& mesh, const CenterlineGraph* centerline,
                                       const std::vector<std::array<int32_t, 2>>& hits);
QualityReport triangle_quality(const TriMesh& mesh);
/// Signed distance of each vertex to the union of the centerline edges' round cones (two spheres and
/// their tangent cone; the minimum over edges), divided by the local radius (that of the cone where
/// the vertex is closest), leaving out cap vertices: those within 2 radii of a terminal and within
/// one radius of its section along its axis, or beyond it. The same at the face centroids gives the
/// area off the tubes and the centroid furthest off them; each edge's length over the larger local radius
/// at its ends (that of the nearest cone; edges with both ends at a cap left out), the longest edge.
FidelityReport radius_fidelity(const TriMesh& mesh, const CenterlineGraph& centerline);

/// Per point: whether it lies inside the closed surface `mesh` (the parity of the faces a ray from it
/// passes through, along three directions, by majority).
std::vector<bool> inside_surface(const TriMesh& mesh, const std::vector<Vec3>& points);

/// How far one surface strays from another, relative to the vessel's size: the distance from each sample
/// of `from` to the nearest point of `to`, divided by the local radius of the centerline (that of the
/// nearest round cone). Samples: `from`'s vertices and its face centroids (the centroid shows the most a
/// flat triangle can miss). For an adaptive surface against the uniform one of the same level.
struct SurfaceDistanceReport {
  Distribution vertices, centroids;
};
SurfaceDistanceReport surface_distance(const TriMesh& from, const TriMesh& to, const CenterlineGraph& centerline);
/// {"vertices": {...}, "centroids": {...}}, each distribution as in report_json.
std::string report_json(const SurfaceDistanceReport& report, int indent = 2);

CheckReport check_mesh(const TriMesh& mesh, const CenterlineGraph* centerline = nullptr);
/// The report as JSON text (what `vesselmesh check --json` prints).
std::string report_json(const CheckReport& report, int indent = 2);

}  // namespace vesselmesh
