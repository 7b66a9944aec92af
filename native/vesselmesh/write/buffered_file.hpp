#pragma once
// Output collected in a buffer and written to the file in large pieces: millions of values then cost a
// few dozen writes instead of millions of formatted stream insertions. Shared by the file writers.

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>

namespace vesselmesh {

class BufferedFile {
 public:
  /// Throws std::runtime_error naming `path` when it cannot be opened.
  explicit BufferedFile(const std::string& path);

  void text(std::string_view s);
  /// The low `size` bytes of `bits`, least significant first, whatever the host's byte order.
  void little_endian(uint64_t bits, std::size_t size);
  /// The low `size` bytes of `bits`, most significant first.
  void big_endian(uint64_t bits, std::size_t size);
  /// The shortest decimal text that reads back as the same float, then `separator`.
  void decimal(float value, char separator);
  /// A double with `digits` significant digits, then `separator`.
  void decimal(double value, int digits, char separator);
  void decimal(int64_t value, char separator);
  /// Writes what is left; throws std::runtime_error naming the path when writing failed.
  void close();

 private:
  void flush_when_full();
  void flush();

  std::string path_;
  std::ofstream file_;
  std::string buffer_;
};

}  // namespace vesselmesh
