#include "vesselmesh/read/radius_array.hpp"

#include "vesselmesh/read/text.hpp"

namespace vesselmesh {

namespace {

std::optional<std::size_t> find_lower(const std::vector<std::string>& names, const std::string& wanted) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (lower(names[i]) == wanted) return i;
  return std::nullopt;
}

double scale_for(const std::string& name) { return lower(name).find("diam") != std::string::npos ? 0.5 : 1.0; }

}  // namespace

std::optional<RadiusArray> find_radius_array(const std::vector<std::string>& names, const std::string& requested) {
  if (!requested.empty()) {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == requested) return RadiusArray{i, scale_for(requested)};
    if (auto i = find_lower(names, lower(requested))) return RadiusArray{*i, scale_for(requested)};
    return std::nullopt;
  }
  for (const char* name : {"radius", "radii", "maximuminscribedsphereradius", "r", "avgradiusavg", "meanradius",
                           "avgradius"})
    if (auto i = find_lower(names, name)) return RadiusArray{*i, 1.0};
  for (const char* name : {"diameter", "diam", "d"})
    if (auto i = find_lower(names, name)) return RadiusArray{*i, 0.5};
  for (std::size_t i = 0; i < names.size(); ++i)
    if (lower(names[i]).find("radius") != std::string::npos) return RadiusArray{i, 1.0};
  return std::nullopt;
}

std::string missing_radius_message(const std::vector<std::string>& names, const std::string& requested) {
  std::string found;
  for (const auto& n : names) found += (found.empty() ? "" : ", ") + n;
  if (found.empty()) found = "none";
  if (!requested.empty()) return "no array named '" + requested + "'; found: " + found;
  return "no radius array; found: " + found + "; name one with --radius-array";
}

}  // namespace vesselmesh
