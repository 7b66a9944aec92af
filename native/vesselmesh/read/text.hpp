#pragma once
// Helpers shared by the readers: whole-file loading, line iteration and strict number parsing.
// Every failure is an InputError naming the file and line.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vesselmesh {

/// The whole file as bytes. Throws InputError when it cannot be opened or is empty.
std::string read_file(const std::string& path);

/// Walks text line by line: LF or CRLF endings, a leading UTF-8 byte-order mark skipped.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text);
  /// The next line without its ending; false at the end of the text.
  bool next(std::string_view& line);
  /// 1-based number of the line last returned.
  std::size_t number() const { return number_; }
  /// Byte offset just past the line last returned (where binary data after a header starts).
  std::size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t number_ = 0;
};

/// `s` without leading and trailing spaces, tabs, CR and LF.
std::string_view trim(std::string_view s);

/// Splits `line` at any of `separators`. With `collapse`, runs of separators count as one and empty
/// tokens are dropped (whitespace-separated formats); without it every separator splits (CSV).
std::vector<std::string_view> split(std::string_view line, std::string_view separators, bool collapse);

/// The whole token as a finite double; otherwise InputError "file: line N: expected <what> ...".
double parse_double(std::string_view token, const std::string& file, std::size_t line, const char* what);

/// The whole token as an integer (a decimal point with only zeros after it is accepted: "3.0").
int64_t parse_int(std::string_view token, const std::string& file, std::size_t line, const char* what);

/// Lower-case ASCII copy, for case-insensitive keyword and name matching.
std::string lower(std::string_view s);

}  // namespace vesselmesh
