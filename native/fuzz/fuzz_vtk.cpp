// parse_vtk on the input as a legacy VTK file (ASCII or BINARY), then validate() and build_graph().
#include "fuzz_support.hpp"
#include "vesselmesh/read/read.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vesselmesh;
  const std::string source = "fuzz.vtk";
  try {
    fuzz::check_centerline(parse_vtk(fuzz::as_text(data, size), source, ReadOptions{}), source);
  } catch (const InputError& e) {
    fuzz::refused(e);
  }
  return 0;
}
