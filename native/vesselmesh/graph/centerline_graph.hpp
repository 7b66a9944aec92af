#pragma once
// The centerline graph: the readers' CenterlineData normalised (coincident points merged, zero-length
// edges dropped, parallel duplicate edges merged, points on no edge dropped, coordinates next to zero
// set to zero) with its derived topology
// (degrees, components, branches, joints, terminals, roots, loops). Every later stage works on this.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "vesselmesh/centerline.hpp"

namespace vesselmesh {

/// What normalisation changed, so that a user can see it (vesselmesh info).
struct NormalisationReport {
  int64_t input_points = 0;
  int64_t input_edges = 0;
  int64_t merged_points = 0;      ///< points merged into a coincident point
  int64_t zero_length_edges = 0;  ///< edges dropped because their two ends coincide
  int64_t duplicate_edges = 0;    ///< edges merged into another that joins the same two points
  int64_t isolated_points = 0;    ///< points on no edge, dropped
  int64_t snapped_coordinates = 0;  ///< coordinates within a millionth of the smallest radius of 0, set to 0
};

/// A chain of edges between two points of degree other than 2 (or a closed ring of degree-2 points).
struct Branch {
  std::vector<int32_t> points;  ///< k+1 points in walking order; a ring repeats its first point at the end
  std::vector<int32_t> edges;   ///< k edges, edges[i] joins points[i] and points[i+1]
};

struct CenterlineGraph {
  std::vector<Vec3> points;                       ///< N positions, no two within the merge tolerance
  std::vector<Edge> edges;                        ///< E edges, no self-loops, no parallel duplicates
  std::vector<std::array<double, 2>> end_radius;  ///< E×2: radius at edges[e][0] and at edges[e][1]
  std::vector<double> radius;                     ///< N: largest radius of the point's edge ends
  bool radius_per_edge = false;                   ///< the input gave one radius per edge

  // Adjacency in compressed rows: the edges at point v are incident[offsets[v] .. offsets[v+1]).
  std::vector<int32_t> offsets;   ///< N+1
  std::vector<int32_t> incident;  ///< 2E edge ids

  // Topology.
  std::vector<int32_t> component;  ///< N: component id of each point, 0..components-1
  int32_t components = 0;
  std::vector<int32_t> roots;      ///< one per component: the file's root, else its widest terminal
  std::vector<Branch> branches;
  int64_t loops = 0;               ///< independent loops (cycle rank): E − N + components

  NormalisationReport report;

  int32_t degree(int32_t v) const { return offsets[v + 1] - offsets[v]; }
  /// The point at the other end of edge `e` from point `v`.
  int32_t other(int32_t e, int32_t v) const { return edges[e][0] == v ? edges[e][1] : edges[e][0]; }
  int64_t joints() const;     ///< points of degree ≥ 3
  int64_t terminals() const;  ///< points of degree 1
  int32_t max_degree() const;
};

/// Two points coincide when they are closer than this fraction of the smaller of their radii.
constexpr double kCoincidentFraction = 1e-6;

/// Normalises `data` (which must have passed validate()) and derives the topology. Linear in the
/// input apart from one sort of the points. Throws InputError naming `source` when no edge is left once
/// coincident points have merged (points each within a millionth of a radius of the next, all along).
CenterlineGraph build_graph(const CenterlineData& data, const std::string& source = "centerline");

/// The arc length along the vessel at each of branch `b`'s points (k+1, from 0): the polyline's own, but
/// where, between two points a radius apart and over four edges or more, it runs more than a quarter longer
/// than the straight way, that straight way, the points in between shared out as the polyline's arc is.
/// Points are counted from the first, each next a radius or more from the last one counted (the smaller of
/// their two radii), and the last point, no more than a radius of its way counted where it lies closer.
/// Points closer together than their radius and jittered by a fraction of it (a dense tracing of a thick
/// vessel) turn by any angle from one edge to the next, and their own lengths add up to several times the
/// vessel's; a smooth curve runs that much longer than its chord only where it bends tighter than its
/// radius.
std::vector<double> vessel_arc(const CenterlineGraph& g, const Branch& b);

/// Per edge (E), its length along the vessel (vessel_arc).
std::vector<double> vessel_lengths(const CenterlineGraph& g);

/// `g` as a file gives a centerline, for writing (write/centerline_vtk.hpp): its edges, the radius per edge
/// where the input gave it so, else per point, a point given once for each radius the ends of its edges
/// have (coincident copies where a branch starts thinner from a joint, which build_graph merges back with
/// the same radii at the same ends), and its roots. Only the edges `keep` flags (E flags), when not
/// empty, with the points they join; a root none of them joins is left out.
CenterlineData centerline_data(const CenterlineGraph& g, const std::vector<char>& keep = {});

}  // namespace vesselmesh
