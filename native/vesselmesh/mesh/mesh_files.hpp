#pragma once
// Triangle mesh files: binary PLY (with per-vertex float properties), OBJ and STL, chosen by the file
// name's extension. Readers accept what the writers write and what common tools write (PLY ascii and
// binary of either byte order, with faces of any size triangulated as fans; OBJ with v/vt/vn indices
// and negative indices; STL binary and ascii, with coincident vertices welded exactly).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "vesselmesh/mesh/tri_mesh.hpp"

namespace vesselmesh {

/// What single precision would do to a mesh's positions: the vertices that would land on another
/// vertex's position, and the faces with an area that would lose it, turn over or tilt by more than 30°
/// (their normal from the rounded positions no longer points about the way the exact one does, as when
/// float steps flatten a small surface lying far out along one axis). A tree of size 10 lying 1e7 from
/// the origin has some; at 1e9 every face is one.
struct FloatRounding {
  int64_t merged_vertices = 0;
  int64_t degenerate_faces = 0;
  bool changes_mesh() const { return merged_vertices > 0 || degenerate_faces > 0; }
};
FloatRounding float_rounding(const TriMesh& mesh);

/// Besides the mesh's vertex properties, what write_mesh can store.
struct WriteOptions {
  /// Empty, or one 8-bit sRGB colour per vertex (red, green, blue, alpha): PLY `uchar red green blue`
  /// (and `alpha` when `alpha` is set), OBJ `v x y z r g b` (in 0-1, as MeshLab and Blender read them).
  std::vector<std::array<uint8_t, 4>> colors;
  bool alpha = false;
  /// OBJ: when not empty, a material of this name, written to the file's .mtl twin (white, so that the
  /// vertex colours show as they are) and used by every face.
  std::string material;
  /// Lines the file keeps about the surface, as PLY `comment` lines or OBJ `#` lines (STL has no place for
  /// them): `vesselmesh mesh` writes there the loops the surface closed, for `vesselmesh check` to name.
  /// Line breaks in them are written as spaces.
  std::vector<std::string> comments;
};

/// Writes by the lower-case extension:
///  - .ply: binary little-endian; x y z as float, or as double where float would change the mesh
///    (float_rounding); then the colours, then one float property per vertex property, in order;
///    faces as `list uchar int vertex_indices`.
///  - .obj: `v x y z [r g b]` with the shortest text that reads back as the same double; `f a b c`, 1-based.
///  - .stl: binary; per triangle the unit normal from the vertex order (zero when degenerate). STL
///    holds only float positions: a mesh that float would change is refused, saying to write PLY or OBJ.
/// OBJ and STL cannot hold vertex properties and leave them out; STL leaves colours out and does not
/// share vertices (read_mesh welds them back).
/// Throws std::runtime_error naming the path when the extension is unknown, a vertex property does not
/// have one value per vertex, the colours are not one per vertex, a face index is out of range, an STL
/// file would lose faces to float rounding, or the file cannot be written.
void write_mesh(const TriMesh& mesh, const std::string& path, const WriteOptions& options = {});

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

/// The comment lines of a .ply header (after `comment `) or the `#` lines of an .obj before its first
/// vertex (after `# `), in order, the writer's own `VesselMesh` line left out; none for .stl or a file
/// that cannot be opened.
std::vector<std::string> read_mesh_comments(const std::string& path);

}  // namespace vesselmesh
