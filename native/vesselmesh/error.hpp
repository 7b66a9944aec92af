#pragma once
// The one error type for bad input. Its message always names the file and, where known, the line,
// byte offset or element, so that a user can go straight to the fault.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace vesselmesh {

class InputError : public std::runtime_error {
 public:
  /// Message "file: where: what" ("file: what" when `where` is empty).
  InputError(const std::string& file, const std::string& where, const std::string& what);
};

/// A surface that would be larger than the limit the caller set (MeshOptions::max_triangles): thrown
/// before the work, with a message that says what to change.
class SizeLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// `x` as a message shows it: up to six significant digits, exponent only where needed (1e-300, 0.25).
std::string number_text(double x);

inline std::string at_line(std::size_t line) { return "line " + std::to_string(line); }
inline std::string at_byte(std::size_t offset) { return "byte " + std::to_string(offset); }

}  // namespace vesselmesh
