#pragma once
// Writes a centerline as legacy VTK POLYDATA (version 4.2): POINTS, 2-point LINES, and the radius as
// POINT_DATA or CELL_DATA "radius", whichever the data carries. parse_vtk reads it back exactly
// (binary) or to 17 significant digits (ASCII).

#include <string>

#include "vesselmesh/centerline.hpp"

namespace vesselmesh {

/// Throws std::runtime_error naming `path` when it cannot be written.
void write_centerline_vtk(const CenterlineData& data, const std::string& path, bool binary);

}  // namespace vesselmesh
