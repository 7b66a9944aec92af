#pragma once
// Loop subdivision (Loop 1987) on closed or open triangle meshes: each level splits every triangle
// into four, moving old vertices with the valence-dependent vertex mask and placing edge vertices with
// the 3/8–1/8 edge mask (boundaries: the cubic B-spline rules). The adaptive variant (a later stage)
// shares this code: `refine` marks which triangles split.

#include <vector>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// One uniform Loop level. Vertex properties are subdivided with the same masks as the positions (computed in
/// double, stored as float).
///
/// Masks: an interior vertex of valence n moves to (1 − nβ_n)·v + β_n·Σv_j with
/// β_n = (1/n)(5/8 − (3/8 + cos(2π/n)/4)²); a boundary vertex (two boundary edges) to 3/4·v + 1/8·(b0 + b1);
/// a vertex with more than two boundary edges stays where it is. An interior edge (a, b) with opposite
/// vertices c, d gets 3/8·(a + b) + 1/8·(c + d), a boundary edge its midpoint.
///
/// Numbering, which the adaptive stage relies on:
///  - vertices: the V old vertices keep their indices; then one vertex per edge, V + e, where e numbers the
///    unique edges (lo, hi), lo < hi, in lexicographic order;
///  - faces: face f = (a, b, c) becomes faces 4f..4f+3 = (a, m_ab, m_ca), (m_ab, b, m_bc), (m_ca, m_bc, c),
///    (m_ab, m_bc, m_ca), with the orientation of f.
///
/// Throws std::invalid_argument for a face with an index out of range or a repeated vertex, an edge shared
/// by more than two faces, an edge that two faces traverse the same way (inconsistent orientation), or a
/// vertex property without one value per vertex; std::length_error when the result would not fit 32-bit
/// indices.
TriMesh loop_subdivide(const TriMesh& mesh);

/// One uniform Loop level with every vertex at its Loop limit position: loop_limit(loop_subdivide(mesh)) up
/// to rounding, in one pass over this level's connectivity instead of a second over the next level's.
TriMesh loop_subdivide_to_limit(const TriMesh& mesh);

/// `levels` (≥ 0) uniform Loop levels.
TriMesh loop_subdivide(const TriMesh& mesh, int levels);

/// The mesh with every vertex moved to where it ends up in the Loop limit surface: interior (1 − nχ)·v + χ·Σv_j with
/// χ = 1/(3/(8β_n) + n); boundary 2/3·v + 1/6·(b0 + b1); vertices that subdivision keeps fixed stay fixed.
/// Same input requirements as loop_subdivide.
/// Vertex properties are mapped by the same masks.
TriMesh loop_limit(const TriMesh& mesh);

}  // namespace vesselmesh
