// The CalculiX wrapper's own time per coupling iteration (writing the loads and the iteration
// deck, copying the restart file, reading the .dat file) against the time of the ccx run it
// starts, on the thick-walled cylinder sector of the tests at a chosen size.
//   bench_calculix_overhead [radial] [axial] [iterations] [threads]
// Two time steps of `iterations` coupling iterations each (the second restarts from the
// first); medians over the second step's iterations. Needs ccx on PATH.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/calculix_bench.hpp"
#include "tests/support/calculix_models.hpp"

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cocopp;
  const int radial = argc > 1 ? std::atoi(argv[1]) : 8;
  const int axial = argc > 2 ? std::atoi(argv[2]) : 25;
  const int iterations = argc > 3 ? std::atoi(argv[3]) : 5;
  const int threads = argc > 4 ? std::atoi(argv[4]) : 1;

  testing::SectorCylinder cylinder;
  cylinder.radial = radial;
  cylinder.axial = axial;
  cylinder.length = 0.001 * axial;
  bench::CalculixBench bench(cylinder.deck(), "threads: " + std::to_string(threads) + "\n");
  CalculixSolverWrapper& wrapper = bench.wrapper();
  Interface input = wrapper.input_interface();
  const std::string faces = input.parts().front().model_part->name;

  std::vector<double> ccx_seconds, wrapper_seconds;
  for (int step = 1; step <= 2; ++step) {
    wrapper.initialize_step(step, step);
    for (int k = 0; k < iterations; ++k) {
      input.values(faces, "pressure").setConstant(1e6 * (step + 0.1 * k));
      wrapper.solve(input);
      if (step == 2) {
        ccx_seconds.push_back(wrapper.last_timing().ccx_seconds);
        wrapper_seconds.push_back(wrapper.last_timing().wrapper_seconds);
      }
    }
    wrapper.finalize_step();
  }
  const double ccx = median(ccx_seconds), own = median(wrapper_seconds);
  std::printf(
      "elements %d (C3D20R), interface faces %lld, interface nodes %lld, threads %d\n"
      "ccx run per iteration      %10.4f s\n"
      "wrapper's own per iteration %10.4f s  (%.1f %% of the ccx run)\n",
      cylinder.elements(), static_cast<long long>(input.size() / 4),
      static_cast<long long>(wrapper.output_interface().size() / 3), threads, ccx, own,
      100 * own / ccx);
  return 0;
}
