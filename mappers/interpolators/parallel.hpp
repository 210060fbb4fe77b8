#pragma once
// parallel_chunks: split a loop over [0, count) into one contiguous chunk per hardware thread.
// Building a mapping for a million points is per-point work that needs no synchronisation.
#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace cocopp {

/// Run work(begin, end) on contiguous chunks covering [0, count), in parallel when the work is
/// large enough to pay for the threads: `size` items (default: count), at least 20000 per
/// thread. The first exception of any chunk is rethrown here.
template <class Work>
void parallel_chunks(std::size_t count, Work work, std::size_t size = 0) {
  constexpr std::size_t kMinimumPerThread = 20000;
  const std::size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t wanted = (size ? size : count) / kMinimumPerThread;
  const std::size_t threads = std::min(count, std::clamp<std::size_t>(wanted, 1, hardware));
  if (threads <= 1) {
    work(std::size_t{0}, count);
    return;
  }
  std::vector<std::exception_ptr> errors(threads);
  std::vector<std::thread> pool;
  for (std::size_t i = 0; i < threads; ++i)
    pool.emplace_back([&, i] {
      try {
        work(count * i / threads, count * (i + 1) / threads);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    });
  for (auto& thread : pool) thread.join();
  for (const auto& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace cocopp
