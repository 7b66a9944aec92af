// parse_csv_graph on two tables: the input up to its first NUL byte is the vertices table, the rest
// the edges table (no NUL: an empty edges table). Then validate() and build_graph().
#include <cstring>

#include "fuzz_support.hpp"
#include "vesselmesh/read/read.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vesselmesh;
  const std::string_view input = fuzz::as_text(data, size);
  const std::size_t cut = input.find('\0');
  const std::string_view vertices = input.substr(0, cut);
  const std::string_view edges = cut == std::string_view::npos ? std::string_view() : input.substr(cut + 1);
  try {
    CenterlineData centerline =
        parse_csv_graph(vertices, "fuzz_vertices.csv", edges, "fuzz_edges.csv", ReadOptions{});
    fuzz::check_centerline(centerline, "fuzz_vertices.csv");
  } catch (const InputError& e) {
    fuzz::refused(e);
  }
  return 0;
}
