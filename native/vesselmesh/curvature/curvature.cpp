#include "vesselmesh/curvature/curvature.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "vesselmesh/mesh/adjacency.hpp"
#include "vesselmesh/parallel.hpp"

namespace vesselmesh {
namespace {

/// Neighbours whose unit normal makes n_j·n_v ≤ 0 face away from the vertex and are left out of its fit.
/// Normals at right angles, as on square tubes or tubes of 8 vertices round, give dot products of ±1e-17 by
/// rounding: the margin leaves them out whatever the rounding.
constexpr double kFacingMargin = 1e-6;

/// Unit area-weighted vertex normals (the sum of the face cross products), zero for a vertex in no
/// non-degenerate face.
std::vector<Vec3> vertex_normals(const TriMesh& mesh) {
  std::vector<Vec3> normals(mesh.vertices.size(), Vec3::Zero());
  for (const Tri& t : mesh.faces) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a);
    for (int32_t v : t) normals[v] += n;
  }
  for (Vec3& n : normals) {
    const double length = n.norm();
    n = length > 0 ? Vec3(n / length) : Vec3::Zero();
  }
  return normals;
}

/// Least-squares fit of the quadric through the vertex (the origin),
///   F(u, v, w) = a·u² + b·uv + c·v² + d·u + e·v + f·w² + g·uw + h·vw − w = 0,
/// to the points, each weighted by exp(−ρ²/2h²) with ρ its distance from the normal axis: c = (a..h).
/// Unlike a height function w(u, v), which reads a circle sampled 22.5° apart 10 % too tight, a quadric
/// holds spheres and cylinders exactly and a torus to second order (docs/pipeline.md, curvature). Where the
/// points lie nearly in a plane the w terms (f, g, h) are undetermined; a small penalty on them makes the
/// fit there the height function's, continuously, rather than noise-driven. nullopt for fewer than 8 points
/// or a rank-deficient system.
std::optional<Eigen::Matrix<double, 8, 1>> fit_quadric(const std::vector<Vec3>& points, double h2) {
  constexpr double kPenalty = 1e-6;  // square root of the weight of f = g = h = 0, against unit-weight points
  const Eigen::Index n = static_cast<Eigen::Index>(points.size());
  if (n < 8) return std::nullopt;
  Eigen::Matrix<double, Eigen::Dynamic, 8> a = Eigen::Matrix<double, Eigen::Dynamic, 8>::Zero(n + 3, 8);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n + 3);
  for (int k = 0; k < 3; ++k) a(n + k, 5 + k) = kPenalty;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Vec3& p = points[j];
    const double weight = std::sqrt(std::exp(-0.5 * (p.x() * p.x() + p.y() * p.y()) / h2));
    a.row(j) << p.x() * p.x(), p.x() * p.y(), p.y() * p.y(), p.x(), p.y(), p.z() * p.z(), p.x() * p.z(),
        p.y() * p.z();
    a.row(j) *= weight;
    w(j) = weight * p.z();
  }
  Eigen::ColPivHouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, 8>> qr(a.rows(), 8);
  qr.setThreshold(1e-8);
  qr.compute(a);
  if (qr.rank() < 8) return std::nullopt;
  return Eigen::Matrix<double, 8, 1>(qr.solve(w));
}

/// Least-squares fit of the height function w = a·u² + b·uv + c·v² (the vertex normal is trusted), for
/// neighbourhoods too small for the quadric; coefficients it cannot determine (collinear points) are zero.
/// nullopt for fewer than 3 points.
std::optional<Eigen::Matrix<double, 8, 1>> fit_height(const std::vector<Vec3>& points) {
  const Eigen::Index n = static_cast<Eigen::Index>(points.size());
  if (n < 3) return std::nullopt;
  Eigen::Matrix<double, Eigen::Dynamic, 3> a(n, 3);
  Eigen::VectorXd w(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Vec3& p = points[j];
    a.row(j) << p.x() * p.x(), p.x() * p.y(), p.y() * p.y();
    w(j) = p.z();
  }
  Eigen::ColPivHouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, 3>> qr(a.rows(), 3);
  qr.setThreshold(1e-8);
  qr.compute(a);
  const Eigen::Vector3d c = qr.solve(w);
  Eigen::Matrix<double, 8, 1> quadric = Eigen::Matrix<double, 8, 1>::Zero();
  quadric.head<3>() = c;
  return quadric;
}

/// Writes vertex v's curvatures from the fitted quadric c (in the frame e1, e2, n, scaled by `length`):
/// at the origin its gradient is (d, e, −1) and its Hessian [[2a, b, g], [b, 2c, h], [g, h, 2f]]; the
/// shape operator is the Hessian restricted to the tangent plane over the gradient's length.
void store(const Eigen::Matrix<double, 8, 1>& c, const Vec3& e1, const Vec3& e2, const Vec3& n, double length,
           size_t v, VertexCurvature& out) {
  const Eigen::Vector3d gradient(c(3), c(4), -1);
  Eigen::Matrix3d hessian;
  hessian << 2 * c(0), c(1), c(6), c(1), 2 * c(2), c(7), c(6), c(7), 2 * c(5);
  const Eigen::Vector3d normal = gradient.normalized();
  Eigen::Matrix<double, 3, 2> tangent;
  tangent.col(0) = (Eigen::Vector3d::UnitX() - normal.x() * normal).normalized();
  tangent.col(1) = normal.cross(Eigen::Vector3d(tangent.col(0)));
  const Eigen::Matrix2d shape = tangent.transpose() * hessian * tangent / gradient.norm();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(shape);
  // n points outwards, so a convex surface bends towards −n and has negative eigenvalues: flip the signs,
  // which makes the smaller eigenvalue k1.
  out.k1[v] = -solver.eigenvalues()(0) / length;
  out.k2[v] = -solver.eigenvalues()(1) / length;
  out.mean[v] = (out.k1[v] + out.k2[v]) / 2;
  out.gaussian[v] = out.k1[v] * out.k2[v];
  out.rms[v] = std::sqrt((out.k1[v] * out.k1[v] + out.k2[v] * out.k2[v]) / 2);
  const Eigen::Matrix3d frame = (Eigen::Matrix3d() << e1, e2, n).finished();
  out.dir1[v] = (frame * tangent * solver.eigenvectors().col(0)).normalized();
  out.dir2[v] = (frame * tangent * solver.eigenvectors().col(1)).normalized();
}

}  // namespace

VertexCurvature estimate_curvature(const TriMesh& mesh, const std::vector<char>& fitted) {
  const size_t nv = mesh.vertices.size();
  if (!fitted.empty() && fitted.size() != nv)
    throw std::invalid_argument("estimate_curvature: " + std::to_string(fitted.size()) + " flags for " +
                                std::to_string(nv) + " vertices");
  const Csr faces = vertex_faces(mesh);
  const Csr neighbours = vertex_neighbours(mesh, faces);
  const std::vector<Vec3> normals = vertex_normals(mesh);

  VertexCurvature out;
  for (auto* values : {&out.k1, &out.k2, &out.mean, &out.gaussian, &out.rms}) values->assign(nv, 0.0);
  out.dir1.assign(nv, Vec3::Zero());
  out.dir2.assign(nv, Vec3::Zero());

  // Each vertex's fit is its own: the vertices are shared out between threads, each with its own marks.
  parallel_for(nv, [&](size_t begin, size_t end) {
    std::vector<int32_t> mark(nv, -1);  // mark[q] == v: q is already in v's ring (or is v)
    std::vector<int32_t> ring;
    std::vector<Vec3> points;
    for (size_t vi = begin; vi < end; ++vi) {
      const auto v = static_cast<int32_t>(vi);
      const Vec3& n = normals[v];
      if (n.isZero() || (!fitted.empty() && !fitted[vi])) continue;
      // The fit is invariant under rotations about n (its monomials span a rotation-invariant space), so any
      // tangent basis will do.
      const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
      out.dir1[v] = e1;
      out.dir2[v] = e2;

      const Vec3& p = mesh.vertices[v];
      ring.clear();
      mark[v] = v;
      double length = 0;
      for (const int32_t* q = neighbours.begin(v); q != neighbours.end(v); ++q) {
        mark[*q] = v;
        ring.push_back(*q);
        length += (mesh.vertices[*q] - p).norm();
      }
      length /= static_cast<double>(ring.size());
      if (!(length > 0)) continue;
      // Adds the neighbours of ring[from, to): ring k + 1 from ring k and the vertices ring k added.
      const auto grow = [&](size_t from, size_t to) {
        for (size_t i = from; i < to; ++i)
          for (const int32_t* q = neighbours.begin(ring[i]); q != neighbours.end(ring[i]); ++q)
            if (mark[*q] != v) {
              mark[*q] = v;
              ring.push_back(*q);
            }
      };
      // Appends the local coordinates of the facing vertices in ring[from, end).
      const auto collect = [&](size_t from) {
        for (size_t i = from; i < ring.size(); ++i) {
          const int32_t q = ring[i];
          if (normals[q].dot(n) <= kFacingMargin) continue;
          const Vec3 d = (mesh.vertices[q] - p) / length;
          points.emplace_back(d.dot(e1), d.dot(e2), d.dot(n));
        }
      };
      double h2 = 0;  // the mean squared 1-ring edge, in the scaled frame: the weights' width
      for (const int32_t q : ring) h2 += (mesh.vertices[q] - p).squaredNorm();
      h2 /= static_cast<double>(ring.size()) * length * length;
      const size_t one_ring = ring.size();
      grow(0, one_ring);
      const size_t two_ring = ring.size();
      points.clear();
      collect(0);
      if (points.size() < 8) {
        grow(one_ring, two_ring);
        collect(two_ring);
      }
      std::optional<Eigen::Matrix<double, 8, 1>> fit = fit_quadric(points, h2);
      if (!fit) fit = fit_height(points);
      if (fit) store(*fit, e1, e2, n, length, vi, out);
    }
  });
  return out;
}

std::vector<VertexProperty> curvature_properties(const VertexCurvature& curvature) {
  const std::pair<const char*, const std::vector<double>*> measures[] = {{"k1", &curvature.k1},
                                                                         {"k2", &curvature.k2},
                                                                         {"mean", &curvature.mean},
                                                                         {"gaussian", &curvature.gaussian},
                                                                         {"rms", &curvature.rms}};
  std::vector<VertexProperty> properties;
  for (const auto& [name, values] : measures)
    properties.push_back({name, std::vector<float>(values->begin(), values->end())});
  return properties;
}

std::vector<double> measure_values(const VertexCurvature& curvature, CurvatureMeasure measure) {
  const auto absolute = [](std::vector<double> values) {
    for (double& c : values) c = std::abs(c);
    return values;
  };
  switch (measure) {
    case CurvatureMeasure::gaussian:
      return curvature.gaussian;
    case CurvatureMeasure::abs_gaussian:
      return absolute(curvature.gaussian);
    case CurvatureMeasure::mean:
      return curvature.mean;
    case CurvatureMeasure::abs_mean:
      return absolute(curvature.mean);
    case CurvatureMeasure::rms:
      return curvature.rms;
    case CurvatureMeasure::tube_departure: {
      std::vector<double> values(curvature.k1.size());
      for (std::size_t v = 0; v < values.size(); ++v) {
        const double a = std::abs(curvature.k1[v]), b = std::abs(curvature.k2[v]);
        values[v] = std::max(a, b) > 0 ? std::min(a, b) / std::max(a, b) : 0.0;
      }
      return values;
    }
  }
  throw std::invalid_argument("curvature: unknown measure");
}

std::vector<double> scale_to_unit(const std::vector<double>& values) {
  if (values.empty()) return {};
  if (!std::all_of(values.begin(), values.end(), [](double c) { return std::isfinite(c); }))
    throw std::invalid_argument("scale_to_unit: non-finite value");
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  const double min = *lo, range = *hi - *lo;
  std::vector<double> unit(values.size(), 0.0);
  if (range > 0)
    for (size_t i = 0; i < values.size(); ++i) unit[i] = (values[i] - min) / range;
  return unit;
}

std::vector<double> equalize_histogram(const std::vector<double>& unit_values, int bins) {
  if (bins < 1)
    throw std::invalid_argument("equalize_histogram: bins must be at least 1, not " + std::to_string(bins));
  if (unit_values.empty()) return {};
  std::vector<int> bin(unit_values.size());
  std::vector<size_t> cumulative(bins, 0);
  for (size_t i = 0; i < unit_values.size(); ++i) {
    const double c = unit_values[i];
    if (!(c >= 0 && c <= 1))
      throw std::invalid_argument("equalize_histogram: value " + std::to_string(c) + " at " +
                                  std::to_string(i) + " is outside [0, 1]");
    bin[i] = std::min(bins - 1, static_cast<int>(bins * c));
    ++cumulative[bin[i]];
  }
  for (int b = 1; b < bins; ++b) cumulative[b] += cumulative[b - 1];
  const size_t n = unit_values.size();
  // C_min: the count of the lowest occupied bin.
  const size_t c_min = *std::find_if(cumulative.begin(), cumulative.end(), [](size_t c) { return c > 0; });
  std::vector<double> equalized(n, 0.0);
  if (n > c_min)
    for (size_t i = 0; i < n; ++i)
      equalized[i] = static_cast<double>(cumulative[bin[i]] - c_min) / static_cast<double>(n - c_min);
  return equalized;
}

}  // namespace vesselmesh
