// Cost of one IQN-ILS update (model add + predict, what iqni does per coupling iteration) on a
// large interface with many secant columns, against the time of one solver call it must stay
// well under.
//
//   bench_qn_update [--points 100000] [--columns 100] [--model ls|mv|mvmf]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/case/settings.hpp"
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

std::unique_ptr<cocopp::Model> make_model(const std::string& yaml) {
  return cocopp::ModelRegistry::instance().create(
      cocopp::Settings::load_string(yaml + "\nmin_significant: 0", "bench.yaml"));
}

/// "18.3 us" below a millisecond (small interfaces), "16.25 ms" above.
std::string duration_text(double seconds) {
  char text[32];
  if (seconds < 1e-3)
    std::snprintf(text, sizeof text, "%.1f us", 1e6 * seconds);
  else
    std::snprintf(text, sizeof text, "%.2f ms", 1e3 * seconds);
  return text;
}

double timed_update(cocopp::Model& model, int points) {
  const Eigen::VectorXd r = Eigen::VectorXd::Random(points);
  const Eigen::VectorXd xt = Eigen::VectorXd::Random(points);
  const auto start = Clock::now();
  model.add(r, xt);
  const Eigen::VectorXd dx = model.predict(-r);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (!dx.allFinite()) throw std::runtime_error("non-finite prediction");
  return seconds;
}

/// `columns` secant pairs in one step, then 10 more updates, each adding a column.
void one_step_growing(const std::string& model_type, int points, int columns) {
  auto model = make_model("type: " + model_type);
  model->initialize_step();
  for (int i = 0; i <= columns; ++i)
    model->add(Eigen::VectorXd::Random(points), Eigen::VectorXd::Random(points));
  const int repetitions = 10;
  double best = 1e30, total = 0.0;
  for (int i = 0; i < repetitions; ++i) {
    const double seconds = timed_update(*model, points);
    best = std::min(best, seconds);
    total += seconds;
  }
  std::printf("%s model, %d points, %d-%d columns: one update (add + predict) best %s, mean %s\n",
              model_type.c_str(), points, columns, columns + repetitions,
              duration_text(best).c_str(), duration_text(total / repetitions).c_str());
}

/// IQN-ILS as a run uses it: 5 iterations (4 new columns) a time step and q = columns / 4
/// reused steps, so columns come and go. Measured once the model is full: every update
/// and every finalize_step (which drops the oldest step's columns) of 10 steps, so the
/// occasional rebuild of the orthonormal basis is included.
void steady_reuse(int points, int columns) {
  const int q = columns / 4, iterations = 5, measured_steps = 10;
  auto model = make_model("type: ls\nq: " + std::to_string(q));
  double total = 0.0;
  int updates = 0;
  for (int step = 0; step < q + 1 + measured_steps; ++step) {
    const bool measured = step > q;
    model->initialize_step();
    for (int i = 0; i < iterations; ++i) {
      const double seconds = timed_update(*model, points);
      if (!measured) continue;
      total += seconds;
      ++updates;
    }
    const auto start = Clock::now();
    model->finalize_step();
    if (measured) total += std::chrono::duration<double>(Clock::now() - start).count();
  }
  std::printf(
      "ls model, %d points, q %d (%d columns at the end of a step): mean cost per update in "
      "steady state, finalize_step and basis rebuilds included: %s\n",
      points, q, model->columns(), duration_text(total / updates).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--help") {
    std::puts(
        "usage: bench_qn_update [--points 100000] [--columns 100] [--model ls|mv|mvmf]\n"
        "Time of one quasi-Newton update (add the iteration's residual and output, predict the\n"
        "next input) with the given number of secant columns already in the model; random data.\n"
        "For ls also the steady state of a run with reuse (q = columns / 4, 5 iterations a step).");
    return 0;
  }
  const int points = option(argc, argv, "--points", 100000);
  const int columns = option(argc, argv, "--columns", 100);
  const std::string model_type = text_option(argc, argv, "--model", "ls");
  std::srand(1);
  one_step_growing(model_type, points, columns);
  if (model_type == "ls") steady_reuse(points, columns);
  return 0;
}
