#pragma once
// Triangle mesh files: binary PLY (with per-vertex float properties), OBJ and STL, chosen by the file
// name's extension. Readers accept what the writers write and what common tools write (PLY ascii and
// binary of either byte order, with faces of any size triangulated as fans; OBJ with v/vt/vn indices
// and negative indices; STL binary and ascii, with coincident vertices welded exactly).

#include <string>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// Writes by the lower-case extension:
///  - .ply: binary little-endian; float x y z, then one float property per vertex property, in order;
///    faces as `list uchar int vertex_indices`.
///  - .obj: `v x y z` with the shortest text that reads back as the same float; `f a b c`, 1-based.
///  - .stl: binary; per triangle the unit normal from the vertex order (zero when degenerate).
/// Positions are stored as float in every format. OBJ and STL cannot hold vertex properties and leave
/// them out; STL does not share vertices (read_mesh welds them back).
/// Throws std::runtime_error naming the path when the extension is unknown, a vertex property does not
/// have one value per vertex, a face index is out of range, or the file cannot be written.
void write_mesh(const TriMesh& mesh, const std::string& path);

/// Reads .ply, .obj or .stl (by the lower-case extension).
///  - .ply: ascii, binary_little_endian, binary_big_endian; x y z of any numeric type; other scalar
///    vertex properties become vertex_properties (as float); lists on vertices and elements other than
///    vertex and face are skipped; faces from a `vertex_indices` or `vertex_index` list.
///  - .obj: `v` and `f` lines (`i`, `i/t`, `i//n`, `i/t/n`, negative indices); everything else ignored.
///  - .stl: binary when the size is exactly 84 + 50·n bytes, otherwise ascii; bit-identical vertices
///    are welded, so a closed surface reads back closed.
/// Polygons are triangulated as fans. Throws InputError naming the file and the line or byte offset
/// for an empty or malformed file, counts the file cannot hold, truncated data, indices out of range,
/// non-finite coordinates and faces with fewer than 3 vertices.
TriMesh read_mesh(const std::string& path);

}  // namespace vesselmesh
