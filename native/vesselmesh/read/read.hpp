#pragma once
// Readers: one per file format, each returning CenterlineData (see centerline.hpp) or throwing an
// InputError that names the file and the line or byte offset. The parse_* functions read from memory
// (so tests can use inline fixtures); read_centerline picks the format by the file name.

#include <string>
#include <string_view>

#include "vesselmesh/centerline.hpp"

namespace vesselmesh {

struct ReadOptions {
  /// Name of the array or column that holds the radius; empty: choose by name (radius_array.hpp).
  std::string radius_array;
};

/// Reads .swc, .vtk (legacy), .vtp (VTK XML PolyData), or a node/edge CSV pair (a vertices/nodes .csv,
/// an edges .csv, or the folder holding both). The result has passed validate().
CenterlineData read_centerline(const std::string& path, const ReadOptions& options = {});

/// SWC: `id type x y z radius parent` per line; '#' comments, blank lines, CRLF, a BOM, several roots.
CenterlineData parse_swc(std::string_view text, const std::string& source);

/// Legacy VTK 3.0 to 5.1, ASCII or BINARY: POLYDATA with LINES, or UNSTRUCTURED_GRID with line and
/// poly-line cells; radius from POINT_DATA or CELL_DATA (SCALARS or FIELD arrays).
CenterlineData parse_vtk(std::string_view bytes, const std::string& source, const ReadOptions& options);

/// VTK XML PolyData: ascii, base64 binary or appended (raw or base64) data, zlib-compressed or not,
/// UInt32 or UInt64 headers, either byte order.
CenterlineData parse_vtp(std::string_view bytes, const std::string& source, const ReadOptions& options);

/// VesselGraph-style tables: vertices (id, x, y, z [, radius]) and edges (node1, node2 [, radius]),
/// ';' or ',' separated, with a header row naming the columns.
CenterlineData parse_csv_graph(std::string_view vertices, const std::string& vertices_source,
                               std::string_view edges, const std::string& edges_source, const ReadOptions& options);

}  // namespace vesselmesh
