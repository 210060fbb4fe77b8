#pragma once
// What the CalculiX benchmarks share: a deck of the tests' structures behind a calculix wrapper
// (working directory wall/ in a temporary directory, interface INNER / INNERN, one time unit
// per step), initialized and ready for its first step.
#include <memory>
#include <string>

#include "core/case/settings.hpp"
#include "solver_wrappers/calculix/calculix_solver_wrapper.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp::bench {

class CalculixBench {
 public:
  /// `keys`: more settings of the wrapper, e.g. "threads: 2\n".
  CalculixBench(const std::string& deck, const std::string& keys)
      : settings_(Settings::load_string(
            "type: calculix\nworking_directory: wall\ninput_file: wall.inp\ninterface_surface: "
            "INNER\ninterface_node_set: INNERN\nsave_results: false\n" +
                keys,
            "bench.yaml")) {
    std::filesystem::create_directory(directory_ / "wall");
    testing::write_text(directory_ / "wall/wall.inp", deck);
    RunSettings run;
    run.delta_t = 1.0;
    run.case_directory = directory_.path();
    wrapper_ = std::make_unique<CalculixSolverWrapper>(settings_, run);
    wrapper_->initialize();
  }

  CalculixSolverWrapper& wrapper() { return *wrapper_; }

 private:
  testing::TemporaryDirectory directory_;
  Settings settings_;
  std::unique_ptr<CalculixSolverWrapper> wrapper_;
};

}  // namespace cocopp::bench
