#pragma once
// Stopwatch: adds the wall time of its scope to a step's and a run's total, also when the scope
// is left by an exception (a rejected input, an interrupted surrogate step took that time too).
#include <chrono>

namespace cocopp {

class Stopwatch {
 public:
  Stopwatch(double& step_total, double& run_total) : step_(step_total), run_(run_total) {}
  ~Stopwatch() {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    step_ += elapsed;
    run_ += elapsed;
  }
  Stopwatch(const Stopwatch&) = delete;
  Stopwatch& operator=(const Stopwatch&) = delete;

 private:
  double& step_;
  double& run_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace cocopp
