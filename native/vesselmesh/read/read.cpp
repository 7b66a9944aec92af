#include "vesselmesh/read/read.hpp"

#include <filesystem>
#include <optional>

#include "vesselmesh/error.hpp"
#include "vesselmesh/read/text.hpp"

namespace vesselmesh {

namespace fs = std::filesystem;

namespace {

/// The vertices and edges tables of a CSV graph, from either file or the folder that holds both.
std::pair<fs::path, fs::path> csv_pair(const fs::path& given) {
  const char* vertex_names[] = {"vertices", "nodes"};
  if (fs::is_directory(given)) {
    for (const char* v : vertex_names)
      if (fs::exists(given / (std::string(v) + ".csv")) && fs::exists(given / "edges.csv"))
        return {given / (std::string(v) + ".csv"), given / "edges.csv"};
    throw InputError(given.string(), "", "folder has no vertices.csv (or nodes.csv) and edges.csv");
  }
  const std::string name = given.filename().string();
  auto swapped = [&](const std::string& from, const std::string& to) -> std::optional<fs::path> {
    std::size_t at = lower(name).find(from);
    if (at == std::string::npos) return std::nullopt;
    return given.parent_path() / (name.substr(0, at) + to + name.substr(at + from.size()));
  };
  if (auto vertices_file = swapped("edges", "vertices")) {
    if (fs::exists(*vertices_file)) return {*vertices_file, given};
    if (auto nodes_file = swapped("edges", "nodes"); fs::exists(*nodes_file)) return {*nodes_file, given};
    throw InputError(given.string(), "", "no matching vertices table (looked for " + vertices_file->string() + ")");
  }
  for (const char* v : vertex_names)
    if (auto edges_file = swapped(v, "edges")) {
      if (fs::exists(*edges_file)) return {given, *edges_file};
      throw InputError(given.string(), "", "no matching edges table (looked for " + edges_file->string() + ")");
    }
  throw InputError(given.string(), "",
                   "a CSV graph is a vertices (or nodes) table and an edges table; the file name says neither");
}

}  // namespace

CenterlineData read_centerline(const std::string& path, const ReadOptions& options) {
  const fs::path p(path);
  const std::string ext = lower(p.extension().string());
  CenterlineData data;
  if (ext == ".csv" || fs::is_directory(p)) {
    auto [vertices, edges] = csv_pair(p);
    data = parse_csv_graph(read_file(vertices.string()), vertices.string(), read_file(edges.string()),
                           edges.string(), options);
  } else if (ext == ".swc") {
    data = parse_swc(read_file(path), path);
  } else if (ext == ".vtk") {
    data = parse_vtk(read_file(path), path, options);
  } else if (ext == ".vtp") {
    data = parse_vtp(read_file(path), path, options);
  } else {
    if (!fs::exists(p)) throw InputError(path, "", "no such file");
    throw InputError(path, "", "unknown format '" + ext + "': expected .swc, .vtk, .vtp or .csv");
  }
  validate(data, path);
  return data;
}

}  // namespace vesselmesh
