#pragma once
// A deterministic synthetic arterial network: the built-in default input and the input of scale tests.

#include <cstdint>

#include "vesselmesh/centerline.hpp"

namespace vesselmesh {

struct SynthOptions {
  int64_t sections = 2000;  ///< about this many cross-sections (points) in all
  int loops = 0;            ///< anastomoses added between branches, each one independent loop
  uint64_t seed = 1;        ///< same seed, same network, on every platform
};

/// One rooted tree of curved branches (radii by Murray's law, branching angles from its optimality
/// condition) plus `loops` anastomosis vessels; radius per point; units are millimetres
/// (root radius 1.5 mm). Points are spaced about half a local radius apart, as in real centerlines.
///
/// The result has `sections` points, or one fewer, unless the tree runs out of room first (not seen in
/// practice) or the anastomoses need more points than set aside for them (about 30 each). Root: point 0,
/// degree 1. Every point has degree at most 3: branchings (r0^3 = r1^3 + r2^3 at the branch point and the
/// children's first points) and the two ends of each anastomosis, which attach to interior points of
/// tree branches. Bend radii are at least 8 local radii. Tubes keep 1.5 (r_a + r_b) apart except where a
/// path of under 3 (r_a + r_b) joins them (at a junction). Throws std::invalid_argument for sections
/// outside [2, 2^31 - 1] or negative loops, and std::runtime_error, saying how many fit, when fewer than
/// `loops` anastomoses can be placed (one per 200 sections can, from a few hundred sections up).
CenterlineData synthesize_network(const SynthOptions& options);

}  // namespace vesselmesh
