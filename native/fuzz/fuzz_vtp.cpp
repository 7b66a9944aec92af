// parse_vtp on the input as a VTK XML PolyData file (ascii, base64, appended raw or base64, zlib), then
// validate() and build_graph().
#include "fuzz_support.hpp"
#include "vesselmesh/read/read.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vesselmesh;
  const std::string source = "fuzz.vtp";
  try {
    fuzz::check_centerline(parse_vtp(fuzz::as_text(data, size), source, ReadOptions{}), source);
  } catch (const InputError& e) {
    fuzz::refused(e);
  }
  return 0;
}
