#include "vesselmesh/centerline.hpp"

#include <cmath>

#include "vesselmesh/error.hpp"

namespace vesselmesh {

namespace {

std::string element(const char* kind, std::size_t i) { return std::string(kind) + " " + std::to_string(i); }

void check_radii(const std::vector<double>& radii, const char* kind, const std::string& source) {
  for (std::size_t i = 0; i < radii.size(); ++i) {
    if (!std::isfinite(radii[i])) throw InputError(source, element(kind, i), "radius is not a finite number");
    if (radii[i] <= 0.0)
      throw InputError(source, element(kind, i),
                       "radius " + std::to_string(radii[i]) + " is not positive");
  }
}

}  // namespace

void validate(const CenterlineData& data, const std::string& source) {
  const std::size_t n = data.points.size();
  if (n == 0) throw InputError(source, "", "no points");
  if (data.edges.empty()) throw InputError(source, "", "no edges: a centerline needs at least two connected points");
  for (std::size_t i = 0; i < n; ++i)
    if (!data.points[i].allFinite()) throw InputError(source, element("point", i), "coordinate is not a finite number");

  const bool per_point = !data.radius.empty();
  const bool per_edge = !data.edge_radius.empty();
  if (per_point == per_edge)
    throw InputError(source, "", per_point ? "radius given both per point and per edge" : "no radius");
  if (per_point && data.radius.size() != n)
    throw InputError(source, "", std::to_string(data.radius.size()) + " point radii for " + std::to_string(n) +
                                     " points");
  if (per_edge && data.edge_radius.size() != data.edges.size())
    throw InputError(source, "", std::to_string(data.edge_radius.size()) + " edge radii for " +
                                     std::to_string(data.edges.size()) + " edges");
  check_radii(data.radius, "point", source);
  check_radii(data.edge_radius, "edge", source);

  for (std::size_t e = 0; e < data.edges.size(); ++e)
    for (int32_t v : data.edges[e])
      if (v < 0 || static_cast<std::size_t>(v) >= n)
        throw InputError(source, element("edge", e),
                         "point index " + std::to_string(v) + " is outside 0.." + std::to_string(n - 1));
  for (int32_t r : data.roots)
    if (r < 0 || static_cast<std::size_t>(r) >= n)
      throw InputError(source, "", "root index " + std::to_string(r) + " is outside 0.." + std::to_string(n - 1));
}

}  // namespace vesselmesh
