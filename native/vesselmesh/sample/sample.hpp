#pragma once
// Where the cross-sections go along a branch: the paper's curvature-aware spacing (Eq. 1),
//   |x_{i+1} − x_i| = g_{i+1} + g_i,   g = α·r / (1 + β·κ),
// so that sections crowd where the vessel is thin or bends. Bidirectional sampling (the default)
// runs two fronts from both ends towards the middle, so the irregular gap falls mid-branch instead of
// next to a joint, where a short last gap would pinch the tube. Eq. 1 spaces sections for bends of the
// smoothed curve; where a straight piece of tube follows the input more widely (every point of the
// polyline within `tolerance` of the local radius of its chord, the radius within as much of linear, up
// to `max_step` radii long), g grows to half that piece, graded from bends, corners, radius kinks and the
// branch's ends. Then the sharp corners of a coarse polyline (over 30°, standing out a radius) each take
// the nearest section, so that the tube does not cut them.

#include <cstdint>
#include <limits>
#include <vector>

#include "vesselmesh/sample/branch_curve.hpp"

namespace vesselmesh {

enum class Sampling { bidirectional, unidirectional };

struct SamplingOptions {
  Sampling method = Sampling::bidirectional;
  double alpha = 1.0;  ///< spacing scale: on straight parts the spacing is about α × the diameter
  double beta = 4.0;   ///< curvature weight, relative: β = beta × the branch's median radius
  /// Sections further apart than Eq. 1's where a straight piece of tube follows the input to within this
  /// fraction of the local radius (0 = Eq. 1 only). At 0.02 a bend keeps Eq. 1's sections (a torus's
  /// curvature, docs/curvature_accuracy.py, was worse at 0.03).
  double tolerance = 0.02;
  /// The longest such piece, in radii (the mean of its ends').
  double max_step = 32;
  /// A final middle gap shorter than this fraction of its desired length is merged away (0 = literal).
  double meet_min_ratio = 0.5;
  /// sample_branch throws SizeLimitError rather than place more sections than this on one branch.
  int64_t max_sections = std::numeric_limits<int64_t>::max();
};

/// Throws std::invalid_argument naming the option unless alpha is finite and positive, beta finite and
/// not negative, tolerance finite and not negative, max_step at least 2, meet_min_ratio in [0, 1] and
/// max_sections at least 2.
void validate(const SamplingOptions& options);

/// About how many sections sample_branch places on the whole curve: its length over the spacing, summed
/// edge by edge. Linear in the curve's points, so that a surface far too large can be refused before the
/// work; on a tightly bent curve the sampler, which spaces sections by chords, places fewer.
double estimated_sections(const BranchCurve& curve, const SamplingOptions& options);

/// Arc positions of the sections on [start, end] (start and end included, increasing). The step
/// solves |x(s′) − x(s)| = g(s′) + g(s) on the continuous curve (bisection on a bracket, so it always
/// converges); g is clamped to at least r/4 so sections never nearly coincide, and is Eq. 1's at start and
/// end, where the tube meets a joint's patch or a cap. The work is proportional to the sections placed
/// and the curve's points, and stops at options.max_sections (before the work when the estimate over
/// [start, end] is twice that).
std::vector<double> sample_branch(const BranchCurve& curve, double start, double end,
                                  const SamplingOptions& options);

}  // namespace vesselmesh
