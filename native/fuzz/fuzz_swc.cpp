// parse_swc on the input as an SWC file, then validate() and build_graph().
#include "fuzz_support.hpp"
#include "vesselmesh/read/read.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vesselmesh;
  const std::string source = "fuzz.swc";
  try {
    fuzz::check_centerline(parse_swc(fuzz::as_text(data, size), source), source);
  } catch (const InputError& e) {
    fuzz::refused(e);
  }
  return 0;
}
