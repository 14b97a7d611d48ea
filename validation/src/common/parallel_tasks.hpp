#pragma once
// Independent tasks 0 … count − 1 on up to `threads` threads (this one among them), each task
// taken by the next free thread. Every task runs even when another throws; then the exception
// of the lowest-numbered failing task is rethrown, so which error the caller sees does not
// depend on the threads' timing. swell's one thread pool: the frame readers (frame_io.cpp), the
// groups of checks and the shared analysis (ocean_checks.cpp, checks/ocean/), a cascade set's
// analyses (cascade_checks.cpp) and the periodogram's transforms (periodogram.cpp).
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace swell::validation::detail {

template <typename Task>
void run_tasks(std::size_t count, int threads, const Task& task) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i; (i = next++) < count;) {
      try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  {
    std::vector<std::thread> pool;
    const std::size_t helpers = std::min<std::size_t>(std::size_t(std::max(1, threads)), count);
    for (std::size_t t = 1; t < helpers; ++t) pool.emplace_back(work);
    work();
    for (auto& thread : pool) thread.join();
  }
  for (const auto& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

}  // namespace swell::validation::detail
