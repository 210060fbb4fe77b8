// How long the coupler takes to start a solver process and notice that it has exited: the
// per-iteration cost a wrapper pays when it runs its solver once per coupling iteration, as
// the calculix wrapper runs ccx. The child is `sleep <seconds>`, so the time past <seconds>
// is process start plus exit detection (ChildProcess::wait_for_exit).
//
//   bench_child_process_wait [runs=50] [seconds=0.05]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "solver_wrappers/process/child_process.hpp"

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 50;
  const double seconds = argc > 2 ? std::atof(argv[2]) : 0.05;
  if (runs < 1 || seconds < 0) {
    std::fprintf(stderr, "usage: bench_child_process_wait [runs=50] [seconds=0.05]\n");
    return 2;
  }
  cocopp::ChildOptions options;
  options.command = {"sleep", std::to_string(seconds)};
  options.working_directory = std::filesystem::temp_directory_path();
  options.log_file = "/dev/null";
  std::vector<double> extra;
  for (int run = 0; run < runs; ++run) {
    const auto start = std::chrono::steady_clock::now();
    cocopp::ChildProcess child(options);
    if (!child.wait_for_exit(60.0) || child.exit_code() != 0) {
      std::fprintf(stderr, "sleep did not exit cleanly: %s\n", child.describe_exit().c_str());
      return 1;
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    extra.push_back(elapsed - seconds);
  }
  std::sort(extra.begin(), extra.end());
  double sum = 0;
  for (double value : extra) sum += value;
  std::printf("child runs %d of `sleep %g`\n", runs, seconds);
  std::printf("start + exit detection   median %.2f ms, mean %.2f ms, max %.2f ms\n",
              1e3 * extra[extra.size() / 2], 1e3 * sum / runs, 1e3 * extra.back());
  return 0;
}
