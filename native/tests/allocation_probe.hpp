#pragma once
// Allocation probe: the test program's operator new notes the largest single request made while a
// LargestAllocation is alive, so that a test can show that a reader did not allocate what a file claims.
// It replaces the global operator new, so exactly one source of a test program includes it.
#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<bool> g_probing{false};
std::atomic<std::size_t> g_largest{0};
}  // namespace

void* operator new(std::size_t n) {
  if (g_probing.load(std::memory_order_relaxed)) {
    std::size_t seen = g_largest.load(std::memory_order_relaxed);
    while (n > seen && !g_largest.compare_exchange_weak(seen, n, std::memory_order_relaxed)) {
    }
  }
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

/// The largest single operator new request made during its life.
class LargestAllocation {
 public:
  LargestAllocation() {
    g_largest = 0;
    g_probing = true;
  }
  ~LargestAllocation() { g_probing = false; }
  std::size_t bytes() const { return g_largest; }
};
