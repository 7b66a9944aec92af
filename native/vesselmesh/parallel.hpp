#pragma once
// Splitting a loop over independent items across the machine's cores.

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace vesselmesh {

/// Calls body(begin, end) on consecutive ranges that together cover [0, n), each on its own thread
/// (the calling thread takes the first). The ranges must not write to shared state. Ranges are at least
/// `grain` items, so that small inputs run on the calling thread alone. Rethrows the first exception
/// a range threw, once every range is done.
template <typename Body>
void parallel_for(std::size_t n, Body body, std::size_t grain = 4096) {
  const std::size_t threads = std::clamp<std::size_t>(n / std::max<std::size_t>(grain, 1), 1,
                                                      std::max(1u, std::thread::hardware_concurrency()));
  if (threads == 1) {
    body(std::size_t{0}, n);
    return;
  }
  std::vector<std::exception_ptr> errors(threads);
  auto run = [&](std::size_t t) {
    try {
      body(n * t / threads, n * (t + 1) / threads);
    } catch (...) {
      errors[t] = std::current_exception();
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
