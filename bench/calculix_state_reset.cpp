// What the state reset of a plastic CalculiX model costs over a run: `steps` time steps of
// `iterations` coupling iterations each on the plastic thick-walled cylinder sector of the
// tests (loaded past yield and cycled), once with state_reset: restart (ccx runs one step per
// iteration; exact with the patched ccx of scripts/install-calculix.sh) and once with replay
// (every iteration runs all committed steps again; exact with any ccx).
//   bench_calculix_state_reset [steps] [iterations] [radial]
// Prints the ccx time per iteration at the first and the last step and in all, for both, and
// how far apart the two runs' last displacements are.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench/calculix_bench.hpp"
#include "tests/support/calculix_models.hpp"

namespace {

struct RunTimes {
  double first_step = 0.0;  ///< ccx seconds per iteration in step 1
  double last_step = 0.0;   ///< ... in the last step
  double total = 0.0;       ///< ccx seconds over the run
  cocopp::RowMatrix last_displacement;
};

RunTimes run(const std::string& state_reset, int steps, int iterations, int radial) {
  using namespace cocopp;
  testing::SectorCylinder cylinder;
  cylinder.radial = radial;
  cylinder.yield_stress = 250e6;
  const double p_y = cylinder.yield_onset_pressure();
  bench::CalculixBench bench(cylinder.deck(), "state_reset: " + state_reset + "\n");
  CalculixSolverWrapper& wrapper = bench.wrapper();
  Interface input = wrapper.input_interface();
  const std::string faces = input.parts().front().model_part->name;
  RunTimes times;
  for (int step = 1; step <= steps; ++step) {
    wrapper.initialize_step(step, step);
    double step_seconds = 0.0;
    for (int k = 0; k < iterations; ++k) {
      // Cycling between 0.6 and 1.15 p_y, iterations closing in on the step's load.
      const double load = p_y * (0.875 + 0.275 * std::sin(0.7 * step)) * (1.0 + 0.02 / (k + 1));
      input.values(faces, "pressure").setConstant(load);
      times.last_displacement = wrapper.solve(input).values("INNERN", "displacement");
      step_seconds += wrapper.last_timing().ccx_seconds;
    }
    wrapper.finalize_step();
    times.total += step_seconds;
    if (step == 1) times.first_step = step_seconds / iterations;
    if (step == steps) times.last_step = step_seconds / iterations;
  }
  return times;
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 40;
  const int iterations = argc > 2 ? std::atoi(argv[2]) : 4;
  const int radial = argc > 3 ? std::atoi(argv[3]) : 8;
  const RunTimes restart = run("restart", steps, iterations, radial);
  const RunTimes replay = run("replay", steps, iterations, radial);
  std::printf("plastic cylinder sector, %d C3D20R, %d steps x %d iterations\n", radial, steps,
              iterations);
  std::printf("%-8s %14s %14s %12s\n", "reset", "ccx/it step 1", "ccx/it last", "ccx total");
  for (const auto& [name, t] : {std::pair{"restart", restart}, std::pair{"replay", replay}})
    std::printf("%-8s %12.4f s %12.4f s %10.2f s\n", name, t.first_step, t.last_step, t.total);
  const double scale = replay.last_displacement.cwiseAbs().maxCoeff();
  std::printf("last displacements, restart vs replay: %.2e of the largest\n",
              (restart.last_displacement - replay.last_displacement).cwiseAbs().maxCoeff() / scale);
  return 0;
}
