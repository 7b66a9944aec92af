// Every input the pipeline fuzz target found a fault with (native/fuzz/findings/pipeline, docs/fuzzing.md),
// run again through the same entry point, built without the fuzzer: each now ends in a refusal or a
// surface, never a crash or a hang (ctest's timeout); the few tiling defects still open end in an error
// that names where.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size);

namespace {

/// Findings whose tiling defect is open: they end in an exception whose message says what failed where.
const char* const kOpen[] = {"joint-not-closed-short-edges.bin", "joint-not-closed-far-point.bin",
                             "loop-subdivision-non-manifold.bin", "loop-subdivision-non-manifold-2.bin",
                             "separate-long-edges-timeout.bin"};

}  // namespace

TEST(FuzzFindings, EveryPipelineFindingEndsInARefusalOrASurface) {
  const std::filesystem::path folder = std::filesystem::path(VESSELMESH_FUZZ_FINDINGS) / "pipeline";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
    ++files;
    bool open = false;
    for (const char* o : kOpen) open = open || name == o;
    try {
      LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
    } catch (const std::exception& e) {
      EXPECT_TRUE(open) << name << ": " << e.what();
      const std::string what = e.what();
      EXPECT_TRUE(what.find("joint at (") != std::string::npos || what.find("non-manifold") != std::string::npos)
          << name << ": " << what;
    }
  }
  EXPECT_GE(files, 18);
}
