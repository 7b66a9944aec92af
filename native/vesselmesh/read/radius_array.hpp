#pragma once
// Which named array (VTK/VTP data array, CSV column) holds the radius. Shared by the readers so that
// every format picks the same way.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace vesselmesh {

struct RadiusArray {
  std::size_t index;  ///< position in the list of names
  double scale;       ///< 1 for a radius, 0.5 for a diameter
};

/// With `requested` non-empty: that name (exact, else case-insensitive), or nothing.
/// Otherwise the first match, case-insensitive, of: radius, radii, MaximumInscribedSphereRadius, r,
/// avgRadiusAvg, meanRadius, avgRadius; then a diameter (diameter, diam, d) halved; then the first
/// name containing "radius". A requested name containing "diam" is taken as a diameter.
std::optional<RadiusArray> find_radius_array(const std::vector<std::string>& names, const std::string& requested);

/// "no array named 'x'; found: a, b, c" or "no radius array; found: ...; name one with --radius-array".
std::string missing_radius_message(const std::vector<std::string>& names, const std::string& requested);

}  // namespace vesselmesh
