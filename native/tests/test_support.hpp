#pragma once
// Helpers for the C++ tests: paths to the project's own fixtures and to ../shared/data (tests that
// need the shared sets skip with a clear reason when it is absent).

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace vesselmesh::test {

/// Path of a file in ../shared/data, or "" when it is absent (then call GTEST_SKIP via SHARED_DATA_OR_SKIP).
inline std::string shared_data(const std::string& relative) {
  std::filesystem::path p = std::filesystem::path(VESSELMESH_SHARED_DATA) / relative;
  return std::filesystem::exists(p) ? p.string() : std::string();
}

/// Path of one of the project's own fixtures in native/tests/data.
inline std::string test_data(const std::string& relative) {
  return (std::filesystem::path(VESSELMESH_TEST_DATA) / relative).string();
}

/// Path of a file `name` in the test temporary directory, unique to the running test: ctest runs the tests
/// as parallel processes that share the directory.
inline std::string temp_path(const std::string& name) {
  const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
  std::string test = std::string(info->test_suite_name()) + "." + info->name();
  for (char& c : test)
    if (c == '/') c = '_';
  return testing::TempDir() + test + "." + name;
}

}  // namespace vesselmesh::test

/// Declares `var` as the path of a shared data file, or skips the test when ../shared/data lacks it.
#define SHARED_DATA_OR_SKIP(var, relative)                                                           \
  const std::string var = ::vesselmesh::test::shared_data(relative);                                 \
  if (var.empty()) GTEST_SKIP() << "../shared/data/" << (relative) << " is absent (shared data sets " \
                                                                     "are not part of the project)"
