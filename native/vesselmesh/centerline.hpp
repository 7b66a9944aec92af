#pragma once
// A centerline as a file gives it: points with radii, joined by edges. This is what every reader
// returns and what the graph stage takes in. Units are the file's own; nothing assumes a scale.

#include <Eigen/Geometry>  // Vec3 users need cross()
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vesselmesh {

using Vec3 = Eigen::Vector3d;
using Edge = std::array<int32_t, 2>;

struct CenterlineData {
  std::vector<Vec3> points;         ///< N positions
  std::vector<double> radius;       ///< N radii; empty when the radius is given per edge
  std::vector<Edge> edges;          ///< E pairs of point indices
  std::vector<double> edge_radius;  ///< E radii, constant along each edge; empty when given per point
  std::vector<int32_t> roots;       ///< points the file marks as roots (SWC parent -1); may be empty
};

/// Limits on what can be meshed, so that every later stage's arithmetic stays finite and its work stays
/// bounded by the surface it makes rather than by numbers in the file.
/// Coordinates and radii at most this large in magnitude: the surface, within a few radii of its points,
/// stays within what the files' floats hold (3.4e38), and squares and products stay finite.
constexpr double kMaxCoordinate = 1e30;
/// Radii at least this fraction of the data set's size (the largest of its extent, its distance from the
/// origin and its largest radius): a tube thinner than that is lost in the rounding of its own coordinates.
constexpr double kMinRadiusOfSize = 1e-12;
/// Radii at least this many steps of a float at their point's coordinates: the surface is written, and held by
/// Blender, in floats, and a tube thinner than that is lost in their rounding (a radius of 1 at 2e8 from the
/// origin, where floats lie 16 apart, gave a surface of degenerate faces). Millimetre, micrometre and metre
/// data sets lie thousands of steps above it.
constexpr double kMinRadiusInFloatSteps = 32;
/// Radii at least this large: the surface's areas (lengths squared) and the predicates' volumes (cubed)
/// stay normal doubles. A data set of radius 1e-154 gave faces whose areas underflowed to zero.
constexpr double kMinRadius = 1e-100;
/// Edges at most this many times as long as the smaller radius at their ends: sections go about a
/// diameter apart, so longer tubes are beyond any surface that fits in memory.
constexpr double kMaxLengthOverRadius = 1e7;

/// Throws InputError naming `source` and the first offending element unless `data` is a usable
/// centerline: at least one edge of non-zero length, finite coordinates, radii finite and positive,
/// given either per point (N values) or per edge (E values) but not both, edge and root indices in
/// range, and coordinates, radii and edge lengths within the limits above.
void validate(const CenterlineData& data, const std::string& source);

}  // namespace vesselmesh
