#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <vector>

#include "vesselmesh/parallel.hpp"

namespace vesselmesh {
namespace {

TEST(ParallelFor, EveryIndexIsVisitedExactlyOnce) {
  for (std::size_t n : {0u, 1u, 5u, 4096u, 100003u}) {
    std::vector<int> visits(n, 0);
    parallel_for(
        n,
        [&](std::size_t begin, std::size_t end) {
          ASSERT_LE(begin, end);
          for (std::size_t i = begin; i < end; ++i) ++visits[i];
        },
        1000);
    EXPECT_EQ(std::count(visits.begin(), visits.end(), 1), static_cast<long>(n)) << n;
  }
}

TEST(ParallelFor, SmallInputsStayOnTheCallingThread) {
  std::atomic<int> calls{0};
  parallel_for(100, [&](std::size_t begin, std::size_t end) {
    ++calls;
    EXPECT_EQ(begin, 0u);
    EXPECT_EQ(end, 100u);
  });
  EXPECT_EQ(calls, 1);
}

TEST(ParallelFor, AnExceptionInAnyRangeReachesTheCaller) {
  EXPECT_THROW(parallel_for(
                   100000,
                   [](std::size_t begin, std::size_t end) {
                     if (begin <= 99999 && 99999 < end) throw std::runtime_error("last range");
                   },
                   1000),
               std::runtime_error);
}

}  // namespace
}  // namespace vesselmesh
