#include "vesselmesh/write/buffered_file.hpp"

#include <charconv>
#include <stdexcept>

namespace vesselmesh {

namespace {
constexpr std::size_t kChunk = 1 << 20;
}

BufferedFile::BufferedFile(const std::string& path) : path_(path), file_(path, std::ios::binary) {
  if (!file_) throw std::runtime_error("cannot open '" + path + "' for writing");
  buffer_.reserve(kChunk + 64);
}

void BufferedFile::text(std::string_view s) {
  buffer_.append(s);
  flush_when_full();
}

void BufferedFile::little_endian(uint64_t bits, std::size_t size) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  buffer_.append(reinterpret_cast<const char*>(&bits), size);  // a byte at a time took twice as long
#else
  for (std::size_t i = 0; i < size; ++i) buffer_ += static_cast<char>(bits >> (8 * i) & 0xff);
#endif
  flush_when_full();
}

void BufferedFile::big_endian(uint64_t bits, std::size_t size) {
  for (std::size_t i = size; i-- > 0;) buffer_ += static_cast<char>(bits >> (8 * i) & 0xff);
  flush_when_full();
}

void BufferedFile::decimal(float value, char separator) {
  char digits[32];
  buffer_.append(digits, std::to_chars(digits, digits + sizeof digits, value).ptr);
  buffer_ += separator;
  flush_when_full();
}

void BufferedFile::decimal(double value, int precision, char separator) {
  char digits[40];
  buffer_.append(digits,
                 std::to_chars(digits, digits + sizeof digits, value, std::chars_format::general, precision).ptr);
  buffer_ += separator;
  flush_when_full();
}

void BufferedFile::decimal(int64_t value, char separator) {
  char digits[24];
  buffer_.append(digits, std::to_chars(digits, digits + sizeof digits, value).ptr);
  buffer_ += separator;
  flush_when_full();
}

void BufferedFile::close() {
  flush();
  file_.close();
  if (!file_) throw std::runtime_error("cannot write '" + path_ + "'");
}

void BufferedFile::flush_when_full() {
  if (buffer_.size() >= kChunk) flush();
}

void BufferedFile::flush() {
  file_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
}

}  // namespace vesselmesh
