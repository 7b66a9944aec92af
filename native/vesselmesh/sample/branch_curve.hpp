#pragma once
// A branch of the centerline graph as a continuous curve, parameterised by its length along the vessel
// (vessel_arc): position, radius and centerline curvature at any arc position, by linear interpolation
// between its points.

#include <utility>
#include <vector>

#include "vesselmesh/graph/centerline_graph.hpp"

namespace vesselmesh {

struct BranchCurve {
  std::vector<Vec3> points;     ///< k+1 points in the branch's order; a jittered stretch's on its axis
  std::vector<double> radius;   ///< k+1 radii: the branch's own edge radius at its ends; inside, the mean
                                ///< of the two edges meeting there
  std::vector<double> arc;      ///< k+1 arc lengths along the vessel (vessel_arc), arc[0] = 0
  std::vector<double> kappa;    ///< k+1 curvatures of the Gaussian-smoothed curve (1/length)
  std::vector<Vec3> tangents;   ///< k+1 unit tangents of the Gaussian-smoothed curve
  double median_radius = 0;

  double length() const { return arc.back(); }
  Vec3 position(double s) const;
  double radius_at(double s) const;
  double kappa_at(double s) const;
  /// Unit tangent of the smoothed curve at `s`: section planes follow it, so that the corners of a
  /// coarse or noisy polyline do not fold the tube.
  Vec3 tangent(double s) const;
  /// Index i of the segment [arc[i], arc[i+1]] that holds `s` (clamped to the curve).
  std::size_t segment(double s) const;
  /// The segment holding `s` and the fraction of the way along it.
  std::pair<std::size_t, double> locate(double s) const;
};

/// The branch's curve with its curvature and tangents: scale-space curvature of the curve smoothed by a
/// Gaussian of width max(median radius, mean edge length), so neither staircase noise of voxel centerlines nor
/// the corners of sparsely sampled polylines read as bends. Ends are extended by point reflection (curvature
/// → 0 at a free end). Linear in the branch's points, whatever its length in radii.
BranchCurve branch_curve(const CenterlineGraph& graph, const Branch& branch);

}  // namespace vesselmesh
