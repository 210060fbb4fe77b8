// Cost of one IQN-ILS update (model add + predict, what iqni does per coupling iteration) on a
// large interface with many secant columns, against the time of one solver call it must stay
// well under.
//
//   bench_qn_update [--points 100000] [--columns 100] [--model ls|mv|mvmf]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "coupler/case/settings.hpp"
#include "coupler/coupled_solvers/models/model.hpp"

namespace {

using Clock = std::chrono::steady_clock;

int option(int argc, char** argv, const char* name, int fallback) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], name) == 0) return std::stoi(argv[i + 1]);
  return fallback;
}

std::string text_option(int argc, char** argv, const char* name, const char* fallback) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], name) == 0) return argv[i + 1];
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--help") {
    std::puts(
        "usage: bench_qn_update [--points 100000] [--columns 100] [--model ls|mv|mvmf]\n"
        "Time of one quasi-Newton update (add the iteration's residual and output, predict the\n"
        "next input) with the given number of secant columns already in the model; random data.");
    return 0;
  }
  const int points = option(argc, argv, "--points", 100000);
  const int columns = option(argc, argv, "--columns", 100);
  const std::string model_type = text_option(argc, argv, "--model", "ls");
  auto model = cocopp::ModelRegistry::instance().create(
      cocopp::Settings::load_string("type: " + model_type + "\nmin_significant: 0", "bench.yaml"));
  model->initialize_step();
  std::srand(1);
  // Fill the model with `columns` secant pairs (columns + 1 iterations of one step).
  for (int i = 0; i <= columns; ++i)
    model->add(Eigen::VectorXd::Random(points), Eigen::VectorXd::Random(points));
  // Time further updates at that size: each adds a column, so drop none by starting each
  // measured update from the filled model is not possible; the column count grows by the
  // number of repetitions, which is small against `columns`.
  const int repetitions = 10;
  double best = 1e30, total = 0.0;
  for (int i = 0; i < repetitions; ++i) {
    const Eigen::VectorXd r = Eigen::VectorXd::Random(points);
    const Eigen::VectorXd xt = Eigen::VectorXd::Random(points);
    const auto start = Clock::now();
    model->add(r, xt);
    const Eigen::VectorXd dx = model->predict(-r);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    best = std::min(best, seconds);
    total += seconds;
    if (!dx.allFinite()) return 1;
  }
  std::printf(
      "%s model, %d points, %d-%d columns: one update (add + predict) best %.2f ms, "
      "mean %.2f ms\n",
      model_type.c_str(), points, columns, columns + repetitions, 1e3 * best,
      1e3 * total / repetitions);
  return 0;
}
