#pragma once
// WorkerThread: one thread that lives as long as its owner and runs one task at a time, so
// that a parallel scheme can run a solver beside the main thread (and a solver group its
// members side by side). A long-lived thread, not one
// per task: a child process started from a thread (ccx, started by the calculix wrapper every
// coupling iteration) is killed when that thread ends (PR_SET_PDEATHSIG, child_process.hpp).
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace cocopp {

class WorkerThread {
 public:
  WorkerThread() : thread_([this] { loop(); }) {}
  ~WorkerThread() {
    {
      const std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }
  WorkerThread(const WorkerThread&) = delete;
  WorkerThread& operator=(const WorkerThread&) = delete;

  /// Start `task` on the worker; the previous task must have been waited for.
  void post(std::function<void()> task) {
    {
      const std::lock_guard lock(mutex_);
      task_ = std::move(task);
      error_ = nullptr;
      busy_ = true;
    }
    changed_.notify_all();
  }
  /// Wait for the posted task; rethrows what it threw.
  void wait() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return !busy_; });
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  }

 private:
  void loop() {
    std::unique_lock lock(mutex_);
    for (;;) {
      changed_.wait(lock, [this] { return stopping_ || busy_; });
      if (busy_) {
        auto task = std::move(task_);
        lock.unlock();
        std::exception_ptr error;
        try {
          task();
        } catch (...) {
          error = std::current_exception();
        }
        lock.lock();
        error_ = error;
        busy_ = false;
        changed_.notify_all();
      } else if (stopping_) {
        return;
      }
    }
  }

  std::mutex mutex_;
  std::condition_variable changed_;
  std::function<void()> task_;
  std::exception_ptr error_;
  bool busy_ = false;
  bool stopping_ = false;
  std::thread thread_;  ///< last: starts once the members above exist
};

}  // namespace cocopp
