#pragma once
// Terminal branches hidden inside other vessels' tubes, dropped before the surface is built. A terminal
// branch whose tube lies wholly inside the tubes of other branches (a short thin twig traced inside the
// vessel it leaves, a vessel's end traced twice) adds nothing to the union of the tubes, and a closed
// surface that follows its tube as well as the one round it must cross that one. Dropping it leaves the
// union of the tubes, the vessel the file describes, as it is.

#include <cstdint>
#include <optional>

#include "vesselmesh/geometry/round_cones.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"

namespace vesselmesh {

struct HiddenTerminals {
  CenterlineGraph graph;  ///< `g` without them; empty when none was dropped
  int64_t dropped = 0;    ///< terminal branches dropped
};

/// Drops the terminal branches of `g` (whose round cones `cones` holds), from a terminal point to a joint,
/// whose tube lies inside cones of other branches: taken a quarter of its radius apart along it, every two
/// consecutive spheres of the branch's own family lie in one such cone (convex: so does the tube between
/// them). Branches hidden only in each other (a vessel's end traced twice) are kept, and so is the third
/// branch of a joint whose other two are one loop back to it. A branch that a dropped one leaves terminal
/// is looked at again, in rounds until none is left. The other branches, the components, the loops and the
/// roots that remain stay.
HiddenTerminals drop_hidden_terminals(const CenterlineGraph& g, const RoundCones& cones);

/// The same for the pipeline, which keeps the tubes it looked at last: `cones` holds g's round cones; where
/// branches are dropped, `kept` receives g without them and `cones` those of `kept` (built for the last
/// round), which refer to it. Returns how many were dropped (`kept` untouched when none).
int64_t drop_hidden_terminals(const CenterlineGraph& g, std::optional<RoundCones>& cones,
                              CenterlineGraph& kept);

}  // namespace vesselmesh
