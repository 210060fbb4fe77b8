// The calculix wrapper's two modes against each other, per coupling iteration: one ccx run per
// iteration (mode: per_iteration, reset by restart files) and one cocopp-ccx process for the
// run, reset in memory (mode: persistent). For each: the median time of a coupling iteration,
// what of it is ccx's run (per iteration) or cocopp-ccx's solve with the protocol round trip
// (persistent), and the wrapper's own part; for persistent also cocopp-ccx's own work between
// ccx and the coupler (checkpoints, loads, displacements: the line it writes to its log).
//   bench_calculix_persistent tube <deck.inp> [iterations] [threads]
//       the tube wall of examples/tube/flow_calculix (interface WALL / WALLMID, dynamic,
//       delta_t 1e-4)
//   bench_calculix_persistent sector <radial> <axial> [iterations] [threads]
//       the tests' elastic C3D20R cylinder sector, static (interface INNER / INNERN)
// Three time steps of `iterations` coupling iterations each; medians over steps 2 and 3.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/case/settings.hpp"
#include "solver_wrappers/calculix/calculix_solver_wrapper.hpp"
#include "tests/support/calculix_models.hpp"
#include "tests/support/temporary_directory.hpp"

namespace {

using cocopp::CalculixSolverWrapper;
using cocopp::Interface;

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

struct Model {
  std::string deck, surface, node_set;
  double delta_t = 1.0;
  int elements = 0;
};

struct Times {
  double total = 0.0, process = 0.0, wrapper = 0.0;
  double own_work_ms = -1.0;  ///< cocopp-ccx's, from its log
};

/// cocopp-ccx's last "own work ... ms per iteration" line in `log`, or -1.
double own_work_ms(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::string line;
  double value = -1.0;
  while (std::getline(in, line)) {
    const auto at = line.find("displacements) ");
    if (line.rfind("cocopp-ccx:", 0) == 0 && at != std::string::npos)
      value = std::atof(line.c_str() + at + 15);
  }
  return value;
}

Times run(const Model& model, const std::string& mode, int iterations, int threads) {
  cocopp::testing::TemporaryDirectory directory;
  std::filesystem::create_directory(directory / "wall");
  cocopp::testing::write_text(directory / "wall/wall.inp", model.deck);
  const cocopp::Settings settings = cocopp::Settings::load_string(
      "type: calculix\nname: wall\nworking_directory: wall\ninput_file: wall.inp\n"
      "interface_surface: " +
          model.surface + "\ninterface_node_set: " + model.node_set +
          "\nsave_results: false\nmode: " + mode + "\nthreads: " + std::to_string(threads) + "\n",
      "bench.yaml");
  cocopp::RunSettings run;
  run.delta_t = model.delta_t;
  run.number_of_timesteps = 3;
  run.case_directory = directory.path();
  Times times;
  {
    CalculixSolverWrapper wrapper(settings, run);
    wrapper.initialize();
    Interface input = wrapper.input_interface();
    const std::string faces = input.parts().front().model_part->name;
    std::vector<double> total, process, own;
    for (int step = 1; step <= 3; ++step) {
      wrapper.initialize_step(step, step * model.delta_t);
      for (int k = 0; k < iterations; ++k) {
        input.values(faces, "pressure").setConstant(1e3 * (step + 0.1 * k));
        const auto start = std::chrono::steady_clock::now();
        wrapper.solve(input);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (step > 1) {
          total.push_back(seconds);
          process.push_back(wrapper.last_timing().ccx_seconds);
          own.push_back(wrapper.last_timing().wrapper_seconds);
        }
      }
      wrapper.finalize_step();
    }
    wrapper.finalize();
    times = {median(total), median(process), median(own)};
  }
  if (mode == "persistent") times.own_work_ms = own_work_ms(directory / "wall/wall.log");
  return times;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string kind = argc > 1 ? argv[1] : "";
  Model model;
  int next = 2;
  if (kind == "tube" && argc > 2) {
    std::ifstream in(argv[2]);
    std::stringstream text;
    text << in.rdbuf();
    model = {text.str(), "WALL", "WALLMID", 1e-4, 50};
    next = 3;
  } else if (kind == "sector" && argc > 3) {
    cocopp::testing::SectorCylinder cylinder;
    cylinder.radial = std::atoi(argv[2]);
    cylinder.axial = std::atoi(argv[3]);
    cylinder.length = 0.001 * cylinder.axial;
    model = {cylinder.deck(), "INNER", "INNERN", 1.0, cylinder.elements()};
    next = 4;
  } else {
    std::fprintf(stderr,
                 "usage: %s tube <deck.inp> [iterations] [threads]\n"
                 "       %s sector <radial> <axial> [iterations] [threads]\n",
                 argv[0], argv[0]);
    return 2;
  }
  const int iterations = argc > next ? std::atoi(argv[next]) : 5;
  const int threads = argc > next + 1 ? std::atoi(argv[next + 1]) : 1;
  const Times per_iteration = run(model, "per_iteration", iterations, threads);
  const Times persistent = run(model, "persistent", iterations, threads);
  std::printf("%s, %d elements, %d thread%s; per coupling iteration (median of steps 2-3):\n",
              kind.c_str(), model.elements, threads, threads == 1 ? "" : "s");
  std::printf("  per_iteration  %9.2f ms  (ccx run %.2f ms, wrapper %.2f ms)\n",
              1e3 * per_iteration.total, 1e3 * per_iteration.process, 1e3 * per_iteration.wrapper);
  std::printf(
      "  persistent     %9.2f ms  (cocopp-ccx solve and round trip %.2f ms, wrapper %.2f ms, "
      "cocopp-ccx's own work %.3f ms)\n",
      1e3 * persistent.total, 1e3 * persistent.process, 1e3 * persistent.wrapper,
      persistent.own_work_ms);
  const double coupling_ms = 1e3 * persistent.wrapper + persistent.own_work_ms;
  std::printf(
      "  speed-up %.1fx; wrapper and hand-over %.3f ms, %.2f %% of the persistent iteration\n",
      per_iteration.total / persistent.total, coupling_ms,
      100 * coupling_ms / (1e3 * persistent.total));
  return 0;
}
