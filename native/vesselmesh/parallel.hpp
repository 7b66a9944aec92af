#pragma once
// Splitting a loop over independent items across the machine's cores.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace vesselmesh {

/// Calls body(begin, end) on consecutive ranges that together cover [0, n), from as many threads as
/// the machine has cores (the calling thread is one). The ranges must not write to shared state.
/// Threads take ranges of at least `grain` items from a common counter, four per thread on large
/// inputs, so that a core that other work slows down takes fewer of them instead of holding up the
/// rest; small inputs run on the calling thread alone. Rethrows the first exception a range threw, once
/// every thread is done.
template <typename Body>
void parallel_for(std::size_t n, Body body, std::size_t grain = 4096) {
  grain = std::max<std::size_t>(grain, 1);
  const std::size_t threads =
      std::clamp<std::size_t>(n / grain, 1, std::max(1u, std::thread::hardware_concurrency()));
  if (threads == 1) {
    body(std::size_t{0}, n);
    return;
  }
  const std::size_t chunk = std::max(grain, (n + 4 * threads - 1) / (4 * threads));
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> errors(threads);
  auto run = [&](std::size_t t) {
    try {
      for (std::size_t begin; (begin = next.fetch_add(chunk)) < n;) body(begin, std::min(n, begin + chunk));
    } catch (...) {
      errors[t] = std::current_exception();
      next = n;  // the others stop after their current range
    }
  };
  std::vector<std::thread> workers;
  for (std::size_t t = 1; t < threads; ++t) workers.emplace_back(run, t);
  run(0);
  for (std::thread& w : workers) w.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace vesselmesh
