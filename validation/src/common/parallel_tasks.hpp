#pragma once
// Independent tasks 0 … count − 1 on up to `threads` threads (this one among them), each task
// taken by the next free thread. Every task runs even when another throws; then the exception
// of the lowest-numbered failing task is rethrown, so which error the caller sees does not
// depend on the threads' timing. swell's one thread pool: the frame readers (frame_io.cpp), the
// groups of checks and the shared analysis (ocean_checks.cpp, checks/ocean/), a cascade set's
// analyses (cascade_checks.cpp) and the periodogram's transforms (periodogram.cpp).
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
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

// The same, on helper threads kept for many calls: the analysis's passes over the frames run a
// few tasks per frame, and run_tasks' threads, made afresh on each call, took their scratch
// arrays with them (each thread keeps its transform's scratch; fresh ones cost their page
// faults and the kernel's zeroing on every frame). run() has run_tasks' semantics: this thread
// takes tasks too, and the lowest-numbered failing task's exception is rethrown.
class TaskPool {
 public:
  explicit TaskPool(int threads) {
    for (int t = 1; t < std::max(1, threads); ++t) helpers_.emplace_back([this] { serve(); });
  }
  ~TaskPool() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (auto& helper : helpers_) helper.join();
  }
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  void run(std::size_t count, const std::function<void(std::size_t)>& task) {
    std::vector<std::exception_ptr> errors(count);
    {
      std::lock_guard lock(mutex_);
      task_ = &task;
      errors_ = &errors;
      count_ = count;
      next_ = 0;
      busy_ = helpers_.size();
      ++generation_;
    }
    wake_.notify_all();
    work();
    {
      std::unique_lock lock(mutex_);
      finished_.wait(lock, [&] { return busy_ == 0; });
    }
    for (const auto& error : errors) {
      if (error) std::rethrow_exception(error);
    }
  }

 private:
  void work() {
    for (std::size_t i; (i = next_++) < count_;) {
      try {
        (*task_)(i);
      } catch (...) {
        (*errors_)[i] = std::current_exception();
      }
    }
  }
  void serve() {
    std::size_t seen = 0;
    for (;;) {
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
        if (stopping_) return;
        seen = generation_;
      }
      work();
      {
        std::lock_guard lock(mutex_);
        --busy_;
      }
      finished_.notify_all();
    }
  }

  std::vector<std::thread> helpers_;
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  const std::function<void(std::size_t)>* task_ = nullptr;
  std::vector<std::exception_ptr>* errors_ = nullptr;
  std::size_t count_ = 0, busy_ = 0, generation_ = 0;
  std::atomic<std::size_t> next_{0};
  bool stopping_ = false;
};

}  // namespace swell::validation::detail
