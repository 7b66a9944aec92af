#include "vesselmesh/error.hpp"

#include <sstream>

namespace vesselmesh {

static std::string compose(const std::string& file, const std::string& where, const std::string& what) {
  return where.empty() ? file + ": " + what : file + ": " + where + ": " + what;
}

InputError::InputError(const std::string& file, const std::string& where, const std::string& what)
    : std::runtime_error(compose(file, where, what)) {}

std::string number_text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

}  // namespace vesselmesh
