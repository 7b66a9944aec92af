#pragma once
// Per-vertex curvature by fitting a quadric to each vertex's 2-ring (paper §2.4 fits a quadratic height
// function; design §6), and the scaling and histogram equalisation that turn one curvature measure into the [0, 1] values the
// adaptive subdivision thresholds (paper §2.4 steps 2–3, design §6.6).

#include <vector>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// Curvatures per vertex (V values each), in 1/length of the mesh's units. Convex is positive, seen from
/// the side the faces' normals point to (outside for faces counter-clockwise from outside): a sphere of
/// radius R has k1 = k2 = 1/R, mean 1/R, gaussian 1/R²; a cylinder of radius r has k1 = 1/r, k2 = 0,
/// mean 1/(2r), gaussian 0.
struct VertexCurvature {
  std::vector<double> k1, k2;    ///< principal curvatures, k1 ≥ k2
  std::vector<double> mean;      ///< (k1 + k2)/2
  std::vector<double> gaussian;  ///< k1·k2, in 1/length²
  std::vector<double> rms;       ///< sqrt((k1² + k2²)/2)
  std::vector<Vec3> dir1, dir2;  ///< unit principal directions of k1 and k2, tangent to the fitted surface
};

/// Fits the quadric a·u² + b·uv + c·v² + d·u + e·v + f·w² + g·uw + h·vw = w through the vertex by weighted
/// least squares in its local frame (area-weighted vertex normal as w, coordinates divided by the mean
/// 1-ring edge length for conditioning; weights exp(−ρ²/2h²), ρ the distance from the normal axis and h² the
/// mean squared 1-ring edge) and takes the curvatures of the fitted surface at the vertex. A quadric holds a
/// sphere or a cylinder exactly however coarsely it is sampled, where a height function w(u, v) reads the
/// circle of a tube sampled 22.5° apart some 10 % too tight.
///
/// Neighbourhood: the 2-ring (the 1-ring plus every vertex of every face touching the 1-ring) without the
/// vertices whose normal faces away (n_j·n_v ≤ 0, and ≤ 1e-6 so that normals at right angles are left out
/// whatever the rounding: on thin coarse tubes the ring wraps round the tube); the 3-ring, filtered the same
/// way, when fewer than 8 remain. With fewer than 8 points, or a rank-deficient system, the height function
/// w = a·u² + b·uv + c·v² (the vertex normal is trusted) is fitted instead.
///
/// Every value is finite. A vertex with no usable neighbourhood (fewer than 3 points, coincident neighbours)
/// gets zero curvatures, with directions an arbitrary tangent basis; a vertex in no non-degenerate face has
/// no normal and gets zero directions as well. Closed and open meshes alike; O(V + F) apart from the fits.
///
/// `fitted`, when not empty (V flags), names the vertices to fit; the others get zero curvatures and
/// directions (the pipeline's tube vertices, whose curvature is their tube's: tube_curvature.hpp).
///
/// Throws std::invalid_argument for a face with a vertex index out of range, or `fitted` of another size.
VertexCurvature estimate_curvature(const TriMesh& mesh, const std::vector<char>& fitted = {});

/// k1, k2, mean, gaussian and rms as float vertex properties of those names (what PLY files and the
/// Python module carry).
std::vector<VertexProperty> curvature_properties(const VertexCurvature& curvature);

/// The per-vertex scalars the adaptive stage can threshold (design §6.6): signed Gaussian curvature is the
/// paper's choice; with it, saddles (K < 0, as at a bifurcation crotch) rank lowest. The others rank a
/// thin vessel above a thick one of the same shape, as curvature is 1/length; tube_departure,
/// min(|k1|, |k2|)/max(|k1|, |k2|), does not: 0 on a straight tube of any radius, about r·κ on a bend of
/// curvature κ, 1 on a sphere or a symmetric saddle.
enum class CurvatureMeasure { gaussian, abs_gaussian, mean, abs_mean, rms, tube_departure };

/// The V values of `measure`.
std::vector<double> measure_values(const VertexCurvature& curvature, CurvatureMeasure measure);

/// (c − min)/(max − min) for each value, so that the smallest maps to 0 and the largest to 1; all zeros
/// when the values are constant, empty for no values. Throws std::invalid_argument for a non-finite value.
std::vector<double> scale_to_unit(const std::vector<double>& values);

/// Binned histogram equalisation of values in [0, 1] (design §6.6): value c goes to bin
/// b = min(bins − 1, ⌊bins·c⌋); with C_b the number of values in bins 0..b and C_min that of the lowest
/// occupied bin, the result is (C_b − C_min)/(N − C_min). Values in one bin share one result (small noise
/// inside a bin changes nothing); all zeros when every value falls in one bin.
/// Throws std::invalid_argument for bins < 1 or a value outside [0, 1] (NaN included).
std::vector<double> equalize_histogram(const std::vector<double>& unit_values, int bins = 256);

}  // namespace vesselmesh
