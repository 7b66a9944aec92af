// Every input the pipeline fuzz target found a fault with (native/fuzz/findings/pipeline, docs/fuzzing.md),
// run again through the same entry point, built without the fuzzer: each now ends in a refusal or in a
// surface that passes the target's checks, never in another exception, an abort, a crash or a hang
// (ctest's timeout).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size);

TEST(FuzzFindings, EveryPipelineFindingEndsInARefusalOrASurface) {
  const std::filesystem::path folder = std::filesystem::path(VESSELMESH_FUZZ_FINDINGS) / "pipeline";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
    ++files;
    try {
      LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
    } catch (const std::exception& e) {
      ADD_FAILURE() << name << ": " << e.what();
    }
  }
  EXPECT_GE(files, 18);
}
