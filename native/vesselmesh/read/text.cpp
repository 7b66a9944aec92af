#include "vesselmesh/read/text.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "vesselmesh/error.hpp"

namespace vesselmesh {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  std::string bytes = buffer.str();
  if (bytes.empty()) throw InputError(path, "", "the file is empty");
  return bytes;
}

LineCursor::LineCursor(std::string_view text) : text_(text) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

bool LineCursor::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', pos_);
  std::size_t next = end == std::string_view::npos ? text_.size() : end + 1;
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = next;
  ++number_;
  return true;
}

std::string_view trim(std::string_view s) {
  const char* ws = " \t\r\n";
  std::size_t b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return {};
  std::size_t e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

std::vector<std::string_view> split(std::string_view line, std::string_view separators, bool collapse) {
  std::vector<std::string_view> tokens;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || separators.find(line[i]) != std::string_view::npos) {
      if (!collapse || i > start) tokens.push_back(line.substr(start, i - start));
      start = i + 1;
    }
  }
  return tokens;
}

namespace {

/// The token as it may appear in a message: at most 40 bytes, unprintable bytes as \xNN.
std::string shown(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string out;
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return token.size() > kMax ? out + "..." : out;
}

}  // namespace

double parse_double(std::string_view token, const std::string& file, std::size_t line, const char* what) {
  std::string_view t = trim(token);
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double value = 0.0;
  auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size())
    throw InputError(file, at_line(line), std::string("expected a number for ") + what + ", found '" +
                                             shown(token) + "'");
  if (!std::isfinite(value))
    throw InputError(file, at_line(line), std::string(what) + " is not a finite number ('" + shown(token) + "')");
  return value;
}

int64_t parse_int(std::string_view token, const std::string& file, std::size_t line, const char* what) {
  std::string_view t = trim(token);
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  int64_t value = 0;
  auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  // Some writers print integer columns as "3.0"; accept a fraction of zeros only.
  if (!t.empty() && ec == std::errc() && end != t.data() + t.size() && *end == '.') {
    const char* p = end + 1;
    while (p != t.data() + t.size() && *p == '0') ++p;
    if (p == t.data() + t.size()) end = p;
  }
  if (t.empty() || ec != std::errc() || end != t.data() + t.size())
    throw InputError(file, at_line(line), std::string("expected an integer for ") + what + ", found '" +
                                             shown(token) + "'");
  return value;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace vesselmesh
