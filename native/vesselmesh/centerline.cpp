#include "vesselmesh/centerline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vesselmesh/error.hpp"

namespace vesselmesh {

namespace {

std::string element(const char* kind, std::size_t i) { return std::string(kind) + " " + std::to_string(i); }

std::string position(const Vec3& p) {
  return "(" + number_text(p.x()) + ", " + number_text(p.y()) + ", " + number_text(p.z()) + ")";
}

void check_radii(const std::vector<double>& radii, const char* kind, const std::string& source) {
  for (std::size_t i = 0; i < radii.size(); ++i) {
    if (!std::isfinite(radii[i])) throw InputError(source, element(kind, i), "radius is not a finite number");
    if (radii[i] <= 0.0)
      throw InputError(source, element(kind, i), "radius " + number_text(radii[i]) + " is not positive");
    if (radii[i] > kMaxCoordinate)
      throw InputError(source, element(kind, i),
                       "radius " + number_text(radii[i]) + " is beyond " + number_text(kMaxCoordinate));
  }
}

/// The limits of kMaxCoordinate, kMinRadiusOfSize, kMinRadius, kMaxLengthOverRadius and
/// kMinRadiusInFloatSteps, on data whose indices and radii are otherwise valid.
void check_scale(const CenterlineData& data, const std::string& source) {
  const bool per_point = !data.radius.empty();
  Vec3 lo = data.points[0], hi = data.points[0];
  double farthest = 0;
  for (std::size_t i = 0; i < data.points.size(); ++i) {
    const Vec3& p = data.points[i];
    if (p.cwiseAbs().maxCoeff() > kMaxCoordinate)
      throw InputError(source, element("point", i),
                       "coordinate beyond ±" + number_text(kMaxCoordinate) + " at " + position(p));
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    farthest = std::max(farthest, p.norm());
  }
  // The largest radius too: a surface spans at least its widest tube, and radii of 1e100 next to 2 (a fuzz
  // finding) gave a tube 1e99 radii long to sample and the separate stage moves of 1e99.
  double widest = 0;
  for (const double r : data.radius) widest = std::max(widest, r);
  for (const double r : data.edge_radius) widest = std::max(widest, r);
  const double size = std::max({(hi - lo).norm(), farthest, widest});
  auto too_thin = [&](double r) { return r < kMinRadiusOfSize * size; };
  auto thin_message = [&](double r) {
    return "radius " + number_text(r) + " is below " + number_text(kMinRadiusOfSize) +
           " of the data set's size " + number_text(size) +
           " (its extent, its distance from the origin or its largest radius): too thin to mesh at this "
           "scale";
  };
  for (std::size_t i = 0; i < data.radius.size(); ++i)
    if (too_thin(data.radius[i])) throw InputError(source, element("point", i), thin_message(data.radius[i]));
  for (std::size_t e = 0; e < data.edge_radius.size(); ++e)
    if (too_thin(data.edge_radius[e]))
      throw InputError(source, element("edge", e), thin_message(data.edge_radius[e]));
  auto too_small = [&](const std::vector<double>& radii, const char* kind) {
    for (std::size_t i = 0; i < radii.size(); ++i)
      if (radii[i] < kMinRadius)
        throw InputError(source, element(kind, i),
                         "radius " + number_text(radii[i]) + " is below " + number_text(kMinRadius) +
                             ": the surface's areas would underflow double precision (scale the data up)");
  };
  too_small(data.radius, "point");
  too_small(data.edge_radius, "edge");
  bool any_length = false;
  for (std::size_t e = 0; e < data.edges.size(); ++e) {
    const auto [a, b] = data.edges[e];
    const double length = (data.points[b] - data.points[a]).norm();
    const double r = per_point ? std::min(data.radius[a], data.radius[b]) : data.edge_radius[e];
    any_length = any_length || length > 0;
    if (length > kMaxLengthOverRadius * r)
      throw InputError(source, element("edge", e),
                       "from point " + std::to_string(a) + " to point " + std::to_string(b) + ", " +
                           number_text(length) + " long, is " + number_text(length / r) +
                           " times its radius " + number_text(r) + ", beyond the " +
                           number_text(kMaxLengthOverRadius) +
                           " that can be meshed (are the radii in the unit of the coordinates?)");
  }
  if (!any_length)
    throw InputError(source, "", "every edge joins two points at the same place: nothing to mesh");
  // A float's step at a point: the largest of its coordinates' magnitudes times float epsilon.
  auto step = [&](int32_t i) {
    return data.points[i].cwiseAbs().maxCoeff() * std::numeric_limits<float>::epsilon();
  };
  auto coarse = [&](double r, double at, std::size_t i, const char* kind) {
    if (r < kMinRadiusInFloatSteps * at)
      throw InputError(source, element(kind, i),
                       "radius " + number_text(r) + " is under " + number_text(kMinRadiusInFloatSteps) +
                           " steps of the floats the surface is written in, which lie " + number_text(at) +
                           " apart where it is: too thin to write at this distance from the origin (move the "
                           "data nearer the origin)");
  };
  for (std::size_t i = 0; i < data.radius.size(); ++i)
    coarse(data.radius[i], step(static_cast<int32_t>(i)), i, "point");
  for (std::size_t e = 0; e < data.edge_radius.size(); ++e)
    coarse(data.edge_radius[e], std::max(step(data.edges[e][0]), step(data.edges[e][1])), e, "edge");
}

}  // namespace

void validate(const CenterlineData& data, const std::string& source) {
  const std::size_t n = data.points.size();
  if (n == 0) throw InputError(source, "", "no points");
  if (data.edges.empty())
    throw InputError(source, "", "no edges: a centerline needs at least two connected points");
  for (std::size_t i = 0; i < n; ++i)
    if (!data.points[i].allFinite())
      throw InputError(source, element("point", i), "coordinate is not a finite number");

  const bool per_point = !data.radius.empty();
  const bool per_edge = !data.edge_radius.empty();
  if (per_point == per_edge)
    throw InputError(source, "", per_point ? "radius given both per point and per edge" : "no radius");
  if (per_point && data.radius.size() != n)
    throw InputError(
        source, "", std::to_string(data.radius.size()) + " point radii for " + std::to_string(n) + " points");
  if (per_edge && data.edge_radius.size() != data.edges.size())
    throw InputError(source, "",
                     std::to_string(data.edge_radius.size()) + " edge radii for " +
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
      throw InputError(source, "",
                       "root index " + std::to_string(r) + " is outside 0.." + std::to_string(n - 1));
  check_scale(data, source);
}

}  // namespace vesselmesh
