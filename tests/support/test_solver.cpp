// cocopp-test-solver: a tiny solver for the protocol tests, and a minimal example of the SDK.
//
// Interface: one model part `wall` of N points on the x axis; input {displacement}, output
// {pressure, traction}, with
//   pressure_i = 1000 * displacement_y_i + step,   traction_i = 2 * displacement_i,
// and initial output pressure_i = 100 + i + timestep_start, traction_i = (delta_t, 0, 0).
//
// Its input file (argument 1, default test_solver.in) holds `key value` lines:
//   points 5            number of points (default 4)
//   fail none           none | crash | hang | nan | error | exit | reject
//   fail_step 1         step at which to fail; 0 = during initialize
//   fail_iteration 1    coupling iteration (solve call within the step, from 1) at which to fail
//   fail_in solve       solve | initialize_step | finalize_step | output_step: the request in
//                       which to fail at fail_step (fail_iteration counts for solve only)
// crash = SIGSEGV, hang = sleep forever, nan = NaN outputs, error = throw, exit = exit(3),
// reject = reject that input (sdk::InputRejected) and serve on.
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/sdk/solver_sdk.hpp"

// In sanitizer builds, let a requested crash be a real SIGSEGV (as users see it) instead of
// AddressSanitizer's report and exit code 1. Unused without a sanitizer.
extern "C" const char* __asan_default_options() {
  return "handle_segv=0";
}

namespace {

using cocopp::sdk::InterfaceDescription;
using cocopp::sdk::RunInfo;

struct Options {
  int points = 4;
  std::string fail = "none";
  int fail_step = 1;
  int fail_iteration = 1;
  std::string fail_in = "solve";
  std::size_t error_bytes = 0;  ///< > 0: the error text is this long, with escape sequences
};

Options read_options(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("test solver: cannot open the input file " + file);
  Options options;
  std::string key;
  while (in >> key) {
    if (key == "points")
      in >> options.points;
    else if (key == "fail")
      in >> options.fail;
    else if (key == "fail_step")
      in >> options.fail_step;
    else if (key == "fail_iteration")
      in >> options.fail_iteration;
    else if (key == "fail_in")
      in >> options.fail_in;
    else if (key == "error_bytes")
      in >> options.error_bytes;
    else
      throw std::runtime_error("test solver: " + file + ": unknown key '" + key + "'");
    if (!in) throw std::runtime_error("test solver: " + file + ": bad value for '" + key + "'");
  }
  static const std::set<std::string> modes = {"none",  "crash", "hang",  "nan",
                                              "error", "exit",  "reject"};
  if (!modes.count(options.fail))
    throw std::runtime_error("test solver: unknown fail mode '" + options.fail + "'");
  static const std::set<std::string> requests = {"solve", "initialize_step", "finalize_step",
                                                 "output_step"};
  if (!requests.count(options.fail_in))
    throw std::runtime_error("test solver: unknown request '" + options.fail_in + "'");
  if (options.points < 0) throw std::runtime_error("test solver: points must be >= 0");
  return options;
}

class TestSolver : public cocopp::sdk::Solver {
 public:
  explicit TestSolver(std::string input_file) : input_file_(std::move(input_file)) {}

  InterfaceDescription initialize(const RunInfo& run) override {
    options_ = read_options(input_file_);
    std::cout << "test solver: initialize, delta_t " << run.delta_t << ", timestep_start "
              << run.timestep_start << ", " << options_.points << " points" << std::endl;
    if (const char* busy_wait = std::getenv("COCOPP_BUSY_WAIT"))
      std::cout << "test solver: COCOPP_BUSY_WAIT=" << busy_wait << std::endl;
    cocopp::sdk::ModelPart wall;
    wall.name = "wall";
    wall.input_variables = {"displacement"};
    wall.output_variables = {"pressure", "traction"};
    InterfaceDescription description;
    std::vector<double> initial_traction;
    for (int i = 0; i < options_.points; ++i) {
      wall.ids.push_back(i + 1);
      wall.coordinates.insert(wall.coordinates.end(), {0.1 * i, 0.005, 0.0});
      description.initial_output.push_back(100.0 + i + run.timestep_start);
      initial_traction.insert(initial_traction.end(), {run.delta_t, 0.0, 0.0});
    }
    description.initial_output.insert(description.initial_output.end(), initial_traction.begin(),
                                      initial_traction.end());
    description.model_parts.push_back(wall);
    if (options_.fail_step == 0) fail_now();
    if (options_.fail_step == 0 && options_.fail == "nan")
      description.initial_output.assign(description.initial_output.size(), nan());
    return description;
  }

  // Its output depends on the step and the input only: a restart needs nothing saved.
  bool can_restart() const override { return true; }

  void initialize_step(std::int32_t step, double time) override {
    step_ = step;
    iteration_ = 0;
    std::cout << "test solver: step " << step << ", time " << time << std::endl;
    fail_in("initialize_step");
  }

  std::vector<double> solve(const std::vector<double>& displacement) override {
    ++iteration_;
    std::cout << "test solver: step " << step_ << " iteration " << iteration_ << std::endl;
    const bool failing = options_.fail_in == "solve" && step_ == options_.fail_step &&
                         iteration_ == options_.fail_iteration;
    if (failing) fail_now();
    const std::size_t n = displacement.size() / 3;
    std::vector<double> output(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
      output[i] = 1000.0 * displacement[3 * i + 1] + step_;
      for (int c = 0; c < 3; ++c) output[n + 3 * i + c] = 2.0 * displacement[3 * i + c];
    }
    if (failing && options_.fail == "nan") output.assign(output.size(), nan());
    return output;
  }

  void finalize_step() override { fail_in("finalize_step"); }
  void output_step() override { fail_in("output_step"); }
  void finalize() override { std::cout << "test solver: finalize" << std::endl; }

 private:
  static double nan() { return std::numeric_limits<double>::quiet_NaN(); }

  /// Fail here if this is the request and step asked for (nan and reject do not apply).
  void fail_in(const std::string& request) {
    if (options_.fail_in == request && step_ == options_.fail_step) fail_now();
  }

  /// The failures that do not return (nan is applied by the caller).
  void fail_now() {
    const std::string where =
        "step " + std::to_string(step_) + " iteration " + std::to_string(iteration_);
    std::cout << "test solver: failing (" << options_.fail << ") at " << where << std::endl;
    if (options_.fail == "crash") std::raise(SIGSEGV);
    if (options_.fail == "exit") std::exit(3);
    if (options_.fail == "error" && options_.error_bytes > 0) {
      // A solver's text is untrusted: long, and with escape sequences for the terminal.
      std::string text = "test solver: \x1b[2J requested long error at " + where + " ";
      text.resize(options_.error_bytes, 'e');
      throw std::runtime_error(text);
    }
    if (options_.fail == "error")
      throw std::runtime_error("test solver: requested error at " + where);
    if (options_.fail == "reject")
      throw cocopp::sdk::InputRejected("test solver: requested rejection at " + where);
    if (options_.fail == "hang")
      for (;;) ::pause();
  }

  std::string input_file_;
  Options options_;
  std::int32_t step_ = 0;
  int iteration_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  std::string input_file = "test_solver.in";
  for (int i = 1; i < argc; ++i)
    if (argv[i][0] != '-') input_file = argv[i];
  TestSolver solver(input_file);
  return cocopp::sdk::serve(solver, argc, argv);
}
