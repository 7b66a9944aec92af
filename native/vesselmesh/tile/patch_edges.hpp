#pragma once
// Long joint-patch edges split before subdivision. A joint patch is the convex hull of its squares: where
// branches leave at a narrow angle or a thick vessel meets a thin one, its faces are chords of the union of
// the tubes two to four radii long, which one Loop level leaves as flat facets up to 20 % of the radius off
// the tubes (vmtk-aorta-centerline's bifurcation, the cohort's trees with over 0.2 % of their area half a
// radius off). Each such edge gets a vertex on the tubes near its middle, so that the faces follow them.
//
// Longest-edge bisection: an edge is split only where it is the longest of both its triangles, in two rounds,
// which never takes a triangle's smallest angle below half what it was; edges over four radii are left (they
// span clusters of merged joints, where the tubes' surface is not near the chord's middle). The new vertex
// goes to the nearest point of the tubes, pushed out as a tube section's corners are (`scale`), only where
// that lies within a fifth of the edge's length of its middle: further moves, into a crotch or out to another
// vessel, folded the patch into its neighbours (brava-records trees crossed themselves), and only where it
// turns none of the four triangles over (a fork of brava-bg0003 traced through voxels crossed itself so);
// elsewhere it stays at the middle.

#include "vesselmesh/geometry/round_cones.hpp"
#include "vesselmesh/tile/base_mesh.hpp"

namespace vesselmesh {

/// `base` (octagonal sections, no `squares`) with the inner edges of its joint patches (between two
/// triangles, both ends of TubeAxis weight 0) that are 2 to 4 local radii long (the smaller TubeAxis radius
/// of their ends) and the longest of both their triangles split in two, twice over. The new vertex carries
/// the mean of its ends' TubeAxis, its offset to the mean of their centres. Closed and oriented wherever
/// `base` is, with the same genus.
BaseMesh split_long_patch_edges(BaseMesh base, const RoundCones& cones, double scale);

}  // namespace vesselmesh
