#include "vesselmesh/check/check_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "vesselmesh/geometry/bvh.hpp"
#include "vesselmesh/geometry/closest_point.hpp"
#include "vesselmesh/geometry/predicates.hpp"
#include "vesselmesh/geometry/round_cones.hpp"
#include "vesselmesh/geometry/self_intersections.hpp"
#include "vesselmesh/graph/union_find.hpp"
#include "vesselmesh/mesh/mesh_edges.hpp"
#include "vesselmesh/parallel.hpp"

namespace vesselmesh {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDegenerateArea = 1e-14;  // area / (longest edge)² below which a face has no area
constexpr std::size_t kMaxExamples = 20;
constexpr double kOffTube = 0.5;  // local radii off the tubes where a face's centroid counts as off them

void require_valid_indices(const TriMesh& mesh) {
  const auto n = static_cast<int64_t>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int32_t v : mesh.faces[f])
      if (v < 0 || v >= n)
        throw std::invalid_argument("face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                    " of a mesh with " + std::to_string(n) + " vertices");
}

// Measured against the longest edge, so that the test does not depend on the mesh's units.
bool has_no_area(const Triangle& t) {
  const double longest =
      std::max({(t[1] - t[0]).squaredNorm(), (t[2] - t[1]).squaredNorm(), (t[0] - t[2]).squaredNorm()});
  const double area = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
  return !(area >= kDegenerateArea * longest) || longest == 0;
}

/// The distribution of `values`, each counting as much as its weight (all alike without weights); the
/// quantiles interpolate linearly between neighbouring values, each placed at the middle of its weight.
Distribution distribution(std::vector<double> values, std::vector<double> weights = {}) {
  Distribution d;
  if (values.empty()) return d;
  const std::size_t n = values.size();
  if (weights.empty()) weights.assign(n, 1.0);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<double> sorted(n), middle(n);  // middle[i]: the cumulative weight at the middle of value i
  double total = 0, sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sorted[i] = values[order[i]];
    middle[i] = total + 0.5 * weights[order[i]];
    total += weights[order[i]];
    sum += weights[order[i]] * sorted[i];
  }
  auto quantile = [&](double q) {
    const double at = q * total;
    const std::size_t i = std::upper_bound(middle.begin(), middle.end(), at) - middle.begin();
    if (i == 0) return sorted.front();
    if (i == n) return sorted.back();
    const double span = middle[i] - middle[i - 1];
    return span > 0 ? sorted[i - 1] + (at - middle[i - 1]) / span * (sorted[i] - sorted[i - 1]) : sorted[i];
  };
  d.min = sorted.front();
  d.max = sorted.back();
  d.median = quantile(0.5);
  d.p95 = quantile(0.95);
  d.p99 = quantile(0.99);
  d.mean = total > 0 ? sum / total : 0.0;
  d.count = static_cast<int64_t>(n);
  return d;
}

nlohmann::ordered_json distribution_json(const Distribution& d) {
  nlohmann::ordered_json j;
  j["min"] = d.min;
  j["median"] = d.median;
  j["p95"] = d.p95;
  j["p99"] = d.p99;
  j["max"] = d.max;
  j["mean"] = d.mean;
  j["count"] = d.count;
  return j;
}

// A hierarchy over the faces' boxes, for distances to the surface and rays through it.
Bvh face_hierarchy(const TriMesh& mesh) {
  std::vector<Box> boxes(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int32_t v : mesh.faces[f]) boxes[f].extend(mesh.vertices[v]);
  return Bvh(boxes);
}

double distance_to_surface(const Bvh& faces, const TriMesh& mesh, const Vec3& p) {
  double best = kInf;
  faces.search([&](const Box& b) { return b.signed_distance(p); }, best, [&](int32_t f) {
    const Triangle t = corners(mesh.vertices, mesh.faces[f]);
    best = std::min(best, (closest_point_on_triangle(p, t[0], t[1], t[2]) - p).norm());
  });
  return best;
}

bool ray_meets_box(const Vec3& p, const Vec3& d, const Box& b) {
  double near = 0, far = kInf;
  for (int k = 0; k < 3; ++k) {
    double t0 = (b.lo[k] - p[k]) / d[k], t1 = (b.hi[k] - p[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0), far = std::min(far, t1);
    if (near > far) return false;
  }
  return true;
}

// Möller–Trumbore: whether the ray from p along d passes through triangle t.
bool ray_meets_triangle(const Vec3& p, const Vec3& d, const Triangle& t) {
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0], h = d.cross(e2);
  const double a = e1.dot(h);
  if (a == 0) return false;  // the ray runs in the triangle's plane
  const Vec3 s = p - t[0], q = s.cross(e1);
  const double u = s.dot(h) / a, v = d.dot(q) / a;
  return u >= 0 && v >= 0 && u + v <= 1 && e2.dot(q) / a > 0;
}

// Whether p lies inside a closed surface: the parity of the faces a ray from p passes through, along three
// directions, by majority (a ray through an edge or a corner may count a face twice or not at all).
bool inside_surface(const Bvh& faces, const TriMesh& mesh, const Vec3& p) {
  static const Vec3 kDirections[3] = {Vec3(0.5773, 0.5774, 0.5776).normalized(),
                                      Vec3(-0.2673, 0.8018, -0.5346).normalized(),
                                      Vec3(0.8729, -0.2183, 0.4364).normalized()};
  int odd = 0;
  for (const Vec3& d : kDirections) {
    int crossings = 0;
    const double hit = 0.5;  // the search visits the faces whose box the ray meets (bound 0)
    faces.search([&](const Box& b) { return ray_meets_box(p, d, b) ? 0.0 : 1.0; }, hit, [&](int32_t f) {
      if (ray_meets_triangle(p, d, corners(mesh.vertices, mesh.faces[f]))) ++crossings;
    });
    odd += crossings % 2;
  }
  return odd >= 2;
}

// The axis of the input lying outside the surface by more than its radius, in local radii of length
// (FidelityReport::missing_axis), and the first such sample.
std::pair<double, Vec3> missing_axis(const TriMesh& mesh, const RoundCones& cones) {
  std::pair<double, Vec3> out{0.0, Vec3::Zero()};
  if (mesh.faces.empty()) return out;
  const Bvh faces = face_hierarchy(mesh);
  constexpr double kMaxSamples = 64;  // per edge: an edge hundreds of radii long says enough with these
  for (std::size_t e = 0; e < cones.size(); ++e) {
    const RoundCone& k = cones.cone(static_cast<int32_t>(e));
    const double length = (k.c1 - k.c0).norm();
    const int n = 1 + static_cast<int>(std::min(std::ceil(length / (0.5 * std::min(k.r0, k.r1))), kMaxSamples));
    for (int i = 0; i < n; ++i) {
      const double u = (i + 0.5) / n, radius = k.radius_at(u);
      const Vec3 p = k.point_at(u);
      if (cones.near_cap(p) || distance_to_surface(faces, mesh, p) <= radius || inside_surface(faces, mesh, p))
        continue;
      if (out.first == 0) out.second = p;
      out.first += length / n / radius;
    }
  }
  return out;
}

}  // namespace

std::vector<bool> inside_surface(const TriMesh& mesh, const std::vector<Vec3>& points) {
  std::vector<bool> inside(points.size(), false);
  if (mesh.faces.empty()) return inside;
  const Bvh faces = face_hierarchy(mesh);
  for (std::size_t i = 0; i < points.size(); ++i) inside[i] = inside_surface(faces, mesh, points[i]);
  return inside;
}

TopologyReport check_topology(const TriMesh& mesh) {
  require_valid_indices(mesh);
  const std::vector<Tri>& faces = mesh.faces;
  TopologyReport r;
  r.faces = static_cast<int64_t>(faces.size());

  // Faces with three distinct vertices; the others count as degenerate and are left out.
  std::vector<Tri> kept;
  const bool all_kept = std::none_of(faces.begin(), faces.end(), repeats_vertex);
  if (!all_kept)
    std::copy_if(faces.begin(), faces.end(), std::back_inserter(kept),
                 [](const Tri& f) { return !repeats_vertex(f); });
  const std::vector<Tri>& valid = all_kept ? faces : kept;
  r.degenerate_faces = static_cast<int64_t>(faces.size() - valid.size());

  // The volume is taken about the middle of the vertices, which keeps the products small; summed in
  // blocks of a fixed size, so that the sum does not depend on the cores.
  Box bounds;
  for (const Vec3& p : mesh.vertices) bounds.extend(p);
  const Vec3 origin = 0.5 * (bounds.lo + bounds.hi);
  constexpr std::size_t kBlock = 1 << 14;
  const std::size_t blocks = (valid.size() + kBlock - 1) / kBlock;
  std::vector<double> volume(blocks, 0.0);
  std::vector<int64_t> flat(blocks, 0);
  parallel_for(blocks, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b)
      for (std::size_t f = b * kBlock; f < std::min(valid.size(), (b + 1) * kBlock); ++f) {
        const Triangle t = corners(mesh.vertices, valid[f]);
        flat[b] += has_no_area(t);
        volume[b] += (t[0] - origin).dot((t[1] - origin).cross(t[2] - origin)) / 6.0;
      }
  }, 1);
  for (std::size_t b = 0; b < blocks; ++b) r.signed_volume += volume[b], r.degenerate_faces += flat[b];

  std::vector<int32_t> incident(mesh.vertices.size(), 0);  // faces round each vertex
  for (const Tri& face : valid)
    for (int32_t v : face) ++incident[v];
  const MeshEdges e = mesh_edges(valid, static_cast<int32_t>(mesh.vertices.size()));
  UnionFind components(mesh.vertices.size());
  for (const auto& [a, b] : e.edges) components.unite(a, b);  // in order of the lower vertex: near in memory
  for (std::size_t v = 0; v < incident.size(); ++v) {
    if (incident[v] == 0) continue;
    ++r.vertices;
    if (components.find(static_cast<int32_t>(v)) == static_cast<int32_t>(v)) ++r.components;
  }

  // Corners at one vertex are joined when their faces share an edge there; each resulting set is one
  // fan of faces round the vertex, so a vertex has as many fans as faces less the joins that merged two.
  auto start = [&](int32_t c) { return valid[c / 3][c % 3]; };
  auto corner_at = [&](int32_t c, int32_t v) { return c - c % 3 + (start(c) == v ? c % 3 : (c % 3 + 1) % 3); };
  UnionFind fans(3 * valid.size());
  std::vector<int32_t> fan_count = std::move(incident);
  r.edges = static_cast<int64_t>(e.edges.size());
  for (std::size_t edge = 0; edge < e.edges.size(); ++edge) {
    const int32_t* c = e.corners.data() + e.first[edge];
    const int64_t count = e.first[edge + 1] - e.first[edge];
    if (count == 1)
      ++r.boundary_edges;
    else if (count > 2)
      ++r.non_manifold_edges;
    else if (start(c[0]) == start(c[1]))
      ++r.inconsistent_edges;
    for (int64_t h = 1; h < count; ++h)
      for (int32_t v : e.edges[edge]) fan_count[v] -= fans.unite(corner_at(c[0], v), corner_at(c[h], v));
  }
  r.non_manifold_vertices =
      std::count_if(fan_count.begin(), fan_count.end(), [](int32_t n) { return n > 1; });

  r.euler_characteristic = r.vertices - r.edges + static_cast<int64_t>(valid.size());
  if (r.closed_manifold()) r.genus = (2 * r.components - r.euler_characteristic) / 2;
  return r;
}

IntersectionReport find_self_intersections(const TriMesh& mesh, const CenterlineGraph* centerline,
                                           const std::vector<char>& among) {
  require_valid_indices(mesh);
  return intersection_report(mesh, centerline, intersecting_face_pairs(mesh, among));
}

IntersectionReport intersection_report(const TriMesh& mesh, const CenterlineGraph* centerline,
                                       const std::vector<std::array<int32_t, 2>>& hits) {
  IntersectionReport r;
  r.pairs = static_cast<int64_t>(hits.size());
  r.examples.assign(hits.begin(),
                    hits.begin() + static_cast<std::ptrdiff_t>(std::min(hits.size(), kMaxExamples)));
  if (centerline != nullptr && !hits.empty()) {
    const RoundCones cones(*centerline);
    auto centroid = [&](int32_t f) {
      const Triangle t = corners(mesh.vertices, mesh.faces[f]);
      return Vec3((t[0] + t[1] + t[2]) / 3.0);
    };
    for (const auto& [f, g] : hits)
      r.pairs_in_overlapping_tubes += cones.in_overlapping_tubes(centroid(f), centroid(g));
  }
  return r;
}

QualityReport triangle_quality(const TriMesh& mesh) {
  require_valid_indices(mesh);
  QualityReport r;
  std::vector<double> ratio, angle;
  ratio.reserve(mesh.faces.size());
  angle.reserve(mesh.faces.size());
  for (const Tri& face : mesh.faces) {
    const Triangle t = corners(mesh.vertices, face);
    if (repeats_vertex(face) || has_no_area(t)) {
      ++r.degenerate;
      continue;
    }
    const Vec3 e0 = t[1] - t[0], e1 = t[2] - t[1], e2 = t[0] - t[2];
    const double a = e0.norm(), b = e1.norm(), c = e2.norm();
    const double twice_area = e0.cross(e1).norm();
    const double s = 0.5 * (a + b + c);
    ratio.push_back(a * b * c * s / (twice_area * twice_area));  // abc·s / (4A²)
    // The smallest angle has the largest cosine; atan2 keeps it accurate when it is tiny.
    const double largest_dot = std::max({-e0.dot(e2), -e0.dot(e1), -e1.dot(e2)});
    angle.push_back(std::atan2(twice_area, largest_dot) * 180.0 / M_PI);
  }
  r.radius_ratio = distribution(std::move(ratio));
  r.min_angle = distribution(std::move(angle));
  return r;
}

FidelityReport radius_fidelity(const TriMesh& mesh, const CenterlineGraph& centerline) {
  require_valid_indices(mesh);
  FidelityReport r;
  if (centerline.edges.empty()) return r;
  const RoundCones cones(centerline);
  std::vector<double> signed_error, abs_error;
  std::vector<double> local_radius(mesh.vertices.size(), 0.0);  // 0 at cap vertices
  r.per_vertex.assign(mesh.vertices.size(), std::numeric_limits<float>::quiet_NaN());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (cones.near_cap(mesh.vertices[v])) {
      ++r.excluded_cap_vertices;
      continue;
    }
    const ConeDistance d = cones.nearest(mesh.vertices[v]);
    local_radius[v] = d.radius;
    signed_error.push_back(d.distance / d.radius);
    abs_error.push_back(std::abs(d.distance / d.radius));
    r.per_vertex[v] = static_cast<float>(signed_error.back());
  }
  r.relative_error = distribution(std::move(signed_error));
  r.abs_relative_error = distribution(std::move(abs_error));
  double area = 0, off = 0;
  std::vector<double> centroid_error, face_area;
  int32_t hint = -1;  // faces come in runs along the surface: the last face's cone is a good first guess
  for (const Tri& f : mesh.faces) {
    const Triangle t = corners(mesh.vertices, f);
    const Vec3 centroid = (t[0] + t[1] + t[2]) / 3;
    if (cones.near_cap(centroid)) continue;
    const double a = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
    const ConeDistance d = cones.nearest(centroid, &hint);
    area += a;
    const double offset = std::abs(d.distance) / d.radius;
    centroid_error.push_back(offset);
    face_area.push_back(a);
    if (offset > kOffTube) off += a;
    if (offset > r.largest_centroid_offset)
      r.largest_centroid_offset = offset, r.largest_centroid_offset_at = centroid;
    for (int k = 0; k < 3; ++k) {
      const int32_t u = f[k], w = f[(k + 1) % 3];
      const double radius = std::max(local_radius[u], local_radius[w]);
      if (!(radius > 0)) continue;  // both ends at a cap
      const double length = (mesh.vertices[w] - mesh.vertices[u]).norm();
      const Vec3 middle = 0.5 * (mesh.vertices[u] + mesh.vertices[w]);
      if (length > r.longest_edge * radius) {
        r.longest_edge = length / radius;
        r.longest_edge_length = length;
        r.longest_edge_at = middle;
      }
      if (length > r.longest_edge_off_tubes * radius && !cones.near_cap(middle)) {
        const ConeDistance m = cones.nearest(middle, &hint);
        if (std::abs(m.distance) > kOffTube * m.radius) {
          r.longest_edge_off_tubes = length / radius;
          r.longest_edge_off_tubes_at = middle;
        }
      }
    }
  }
  r.area_off_tubes = area > 0 ? off / area : 0.0;
  r.centroid_error = distribution(std::move(centroid_error), std::move(face_area));
  std::tie(r.missing_axis, r.missing_axis_at) = missing_axis(mesh, cones);
  return r;
}

SurfaceDistanceReport surface_distance(const TriMesh& from, const TriMesh& to, const CenterlineGraph& centerline) {
  require_valid_indices(from);
  require_valid_indices(to);
  SurfaceDistanceReport r;
  if (centerline.edges.empty() || to.faces.empty()) return r;
  const Bvh faces = face_hierarchy(to);
  const RoundCones cones(centerline);
  const auto relative_distance = [&](const Vec3& p) {
    return distance_to_surface(faces, to, p) / cones.nearest(p).radius;
  };
  std::vector<double> at_vertices, at_centroids;
  for (const Vec3& p : from.vertices) at_vertices.push_back(relative_distance(p));
  for (const Tri& f : from.faces)
    at_centroids.push_back(relative_distance((from.vertices[f[0]] + from.vertices[f[1]] + from.vertices[f[2]]) / 3));
  r.vertices = distribution(std::move(at_vertices));
  r.centroids = distribution(std::move(at_centroids));
  return r;
}

std::string report_json(const SurfaceDistanceReport& report, int indent) {
  nlohmann::ordered_json j;
  j["vertices"] = distribution_json(report.vertices);
  j["centroids"] = distribution_json(report.centroids);
  return j.dump(indent);
}

CheckReport check_mesh(const TriMesh& mesh, const CenterlineGraph* centerline) {
  CheckReport report;
  report.topology = check_topology(mesh);
  report.intersections = find_self_intersections(mesh, centerline);
  report.quality = triangle_quality(mesh);
  if (centerline != nullptr) report.fidelity = radius_fidelity(mesh, *centerline);
  return report;
}

std::string report_json(const CheckReport& report, int indent) {
  using nlohmann::ordered_json;
  const TopologyReport& t = report.topology;
  ordered_json j;
  j["closed_manifold"] = t.closed_manifold();
  ordered_json& topology = j["topology"];
  topology["vertices"] = t.vertices;
  topology["edges"] = t.edges;
  topology["faces"] = t.faces;
  topology["boundary_edges"] = t.boundary_edges;
  topology["non_manifold_edges"] = t.non_manifold_edges;
  topology["non_manifold_vertices"] = t.non_manifold_vertices;
  topology["inconsistent_edges"] = t.inconsistent_edges;
  topology["degenerate_faces"] = t.degenerate_faces;
  topology["components"] = t.components;
  topology["euler_characteristic"] = t.euler_characteristic;
  topology["genus"] = t.genus;
  topology["signed_volume"] = t.signed_volume;
  ordered_json& intersections = j["intersections"];
  intersections["pairs"] = report.intersections.pairs;
  intersections["pairs_in_overlapping_tubes"] = report.intersections.pairs_in_overlapping_tubes;
  intersections["examples"] = report.intersections.examples;
  ordered_json& quality = j["quality"];
  quality["radius_ratio"] = distribution_json(report.quality.radius_ratio);
  quality["min_angle"] = distribution_json(report.quality.min_angle);
  quality["degenerate"] = report.quality.degenerate;
  if (report.fidelity) {
    ordered_json& fidelity = j["fidelity"];
    fidelity["abs_relative_error"] = distribution_json(report.fidelity->abs_relative_error);
    fidelity["relative_error"] = distribution_json(report.fidelity->relative_error);
    fidelity["excluded_cap_vertices"] = report.fidelity->excluded_cap_vertices;
    fidelity["area_off_tubes"] = report.fidelity->area_off_tubes;
    fidelity["centroid_error"] = distribution_json(report.fidelity->centroid_error);
    const auto point = [](const Vec3& p) { return std::array<double, 3>{p.x(), p.y(), p.z()}; };
    fidelity["largest_centroid_offset"] = {{"relative", report.fidelity->largest_centroid_offset},
                                           {"at", point(report.fidelity->largest_centroid_offset_at)}};
    fidelity["longest_edge"] = {{"relative", report.fidelity->longest_edge},
                                {"length", report.fidelity->longest_edge_length},
                                {"at", point(report.fidelity->longest_edge_at)}};
    fidelity["longest_edge_off_tubes"] = {{"relative", report.fidelity->longest_edge_off_tubes},
                                          {"at", point(report.fidelity->longest_edge_off_tubes_at)}};
    fidelity["missing_axis"] = {{"relative", report.fidelity->missing_axis},
                                {"at", point(report.fidelity->missing_axis_at)}};
  }
  return j.dump(indent);
}

}  // namespace vesselmesh
