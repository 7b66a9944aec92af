#include "vesselmesh/write/centerline_vtk.hpp"

#include "vesselmesh/write/buffered_file.hpp"

#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace vesselmesh {

namespace {

/// Values as legacy VTK wants them: decimal text, or big-endian binary with a newline after each block.
class Output {
 public:
  Output(const std::string& path, bool binary) : file_(path), binary_(binary) {}

  void text(std::string_view s) { file_.text(s); }

  /// A double: 17 significant digits and then `separator` (ASCII), or 8 big-endian bytes (BINARY).
  void real(double value, char separator) {
    if (!binary_) return file_.decimal(value, 17, separator);
    uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    file_.big_endian(bits, sizeof bits);
  }

  /// A 32-bit integer: decimal and then `separator` (ASCII), or 4 big-endian bytes (BINARY).
  void integer(int32_t value, char separator) {
    if (!binary_) return file_.decimal(int64_t{value}, separator);
    file_.big_endian(static_cast<uint32_t>(value), sizeof value);
  }

  /// Ends a block of values: BINARY data is followed by a newline before the next keyword.
  void end_block() {
    if (binary_) text("\n");
  }

  void close() { file_.close(); }

 private:
  BufferedFile file_;
  bool binary_;
};

/// An attribute section holding one "radius" array.
void write_radius(Output& out, const char* section, const std::vector<double>& radius) {
  out.text(std::string(section) + " " + std::to_string(radius.size()) +
           "\nSCALARS radius double 1\nLOOKUP_TABLE default\n");
  for (double r : radius) out.real(r, '\n');
  out.end_block();
}

}  // namespace

void write_centerline_vtk(const CenterlineData& data, const std::string& path, bool binary) {
  Output out(path, binary);
  out.text(std::string("# vtk DataFile Version 4.2\nvesselmesh centerline\n") +
           (binary ? "BINARY" : "ASCII") + "\nDATASET POLYDATA\nPOINTS " +
           std::to_string(data.points.size()) + " double\n");
  for (const Vec3& p : data.points) {
    out.real(p.x(), ' ');
    out.real(p.y(), ' ');
    out.real(p.z(), '\n');
  }
  out.end_block();

  out.text("LINES " + std::to_string(data.edges.size()) + " " + std::to_string(3 * data.edges.size()) + "\n");
  for (const Edge& e : data.edges) {
    out.integer(2, ' ');
    out.integer(e[0], ' ');
    out.integer(e[1], '\n');
  }
  out.end_block();

  // VTK's own order: cell data before point data.
  if (!data.edge_radius.empty()) write_radius(out, "CELL_DATA", data.edge_radius);
  if (!data.radius.empty()) write_radius(out, "POINT_DATA", data.radius);
  out.close();
}

}  // namespace vesselmesh
