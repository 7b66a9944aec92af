#pragma once
// Shared by the reader targets: what happens to a file once a reader accepts it. Only InputError may
// leave a target: the project's contract is that bad input gives an InputError naming the file and
// the line, byte or element. Any other exception escapes LLVMFuzzerTestOneInput, std::terminate
// aborts, and libFuzzer reports it (as it does a sanitizer error, a timeout or running out of memory).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "vesselmesh/centerline.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/graph/centerline_graph.hpp"

namespace vesselmesh::fuzz {

inline std::string_view as_text(const uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// validate(), and where it passes, build_graph(): the steps `vesselmesh info` takes after a read.
inline void check_centerline(const CenterlineData& data, const std::string& source) {
  validate(data, source);
  const CenterlineGraph graph = build_graph(data, source);
  // The graph's own invariants (centerline_graph.hpp); a break is a bug, not bad input.
  if (graph.offsets.size() != graph.points.size() + 1 || graph.radius.size() != graph.points.size() ||
      graph.end_radius.size() != graph.edges.size() || graph.incident.size() != 2 * graph.edges.size() ||
      graph.component.size() != graph.points.size())
    __builtin_trap();
}

/// An input refused with an InputError, as it should be; with FUZZ_VERBOSE set, the message is printed
/// (to see why a seed or a saved input is refused: FUZZ_VERBOSE=1 build/fuzz/bin/fuzz_vtp file.vtp).
inline void refused(const InputError& e) {
  static const bool verbose = std::getenv("FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "InputError: %s\n", e.what());
}

}  // namespace vesselmesh::fuzz
