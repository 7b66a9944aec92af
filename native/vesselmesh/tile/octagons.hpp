#pragma once
// Octagonal sections: every side of every section's square split at a vertex on the section's circle.
// Loop subdivision of a square tube ends 34 % thinner than its corners and rippled ±2 % four times round
// (test_loop); of an octagonal one, 10 % thinner and ±0.8 %. One Loop level on octagons gives the 16
// vertices round of two levels on squares, at half the triangles: tubes gain vertices round, not along.
//
// The tile stage decides everything (folds, clearances, joint hulls) on squares at the four-sided
// scale; the squares are then shrunk about their centres to the eight-sided one and split (a joint
// patch's at its sides' middles, so that the patch keeps the shape of its hull). Tiled at the smaller scale directly, the choices changed: 37 of the 42
// brava-records trees crossed themselves and the fixture tight_u_bend_into_a_joint came out inside out.
//
// A tube quad, whose two sides on sections are split, becomes two quads; a flat cap becomes an octagon
// of a middle quad and four corner triangles; a joint patch's triangle along a square's side becomes two.
// The result is closed and oriented wherever the input is: each split side is split in every face that
// uses it.

#include "vesselmesh/tile/base_mesh.hpp"

namespace vesselmesh {

/// `base` with its `squares` shrunk by `shrink` (in (0, 1]) about their sections' centres and those of
/// their sides that are edges of its faces split. The new vertex lies on the side's perpendicular
/// bisector in the square's plane, as far from the centre as the side's corners are, or at the side's
/// middle where the square has a side on a joint patch (a triangle's edge); it carries the section's
/// TubeAxis (the offset its own). The result's `squares` is empty: its sections are octagons.
BaseMesh octagonal_sections(BaseMesh base, double shrink);

}  // namespace vesselmesh
