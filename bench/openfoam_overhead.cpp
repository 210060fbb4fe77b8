// What the coupling adds to cocoppPimpleFoam's PIMPLE solve, per coupling iteration, on a 2D
// channel (tests/integration/openfoam/channel) of about 1e3, 1e4 and 1e5 cells.
//
//   build/bin/bench_openfoam_overhead [--steps 3] [--iterations 4] [--sizes 1000,10000,100000]
//
// Per coupling iteration: the time of the `openfoam` wrapper's solve() as the coupler sees it
// (T), and, from the application's log, its PIMPLE solve (P) and its own coupling work:
// restoring the step's start state (R: mesh points and fields) and the interface data
// (I: setting the displacement, computing and gathering the loads). The protocol and wrapper
// cost is T - P - R - I; the coupling's total cost T - P. Medians over the iterations after
// the first of each step (those restore the step's start).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include "core/case/settings.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace fs = std::filesystem;
using namespace cocopp;

namespace {

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

/// The channel with nx x ny cells (aspect ratio kept near the template's 10:1 domain).
fs::path make_channel(const fs::path& directory, int nx, int ny) {
  const fs::path source = fs::path(COCOPP_SOURCE_DIR) / "tests/integration/openfoam/channel";
  fs::remove_all(directory);
  fs::copy(source, directory, fs::copy_options::recursive);
  std::string mesh = read_text(directory / "system/blockMeshDict");
  mesh = std::regex_replace(mesh, std::regex("\\(20 6 1\\)"), fmt::format("({} {} 1)", nx, ny));
  std::ofstream(directory / "system/blockMeshDict") << mesh;
  // Only the last step is written: the benchmark is about solving.
  std::string control = read_text(directory / "system/controlDict");
  control = std::regex_replace(control, std::regex("writeInterval +1;"), "writeInterval 1000;");
  std::ofstream(directory / "system/controlDict") << control;
  const std::string command =
      "cd '" + directory.string() +
      "' && WM_PROJECT_DIR=/usr/share/openfoam blockMesh > log.blockMesh 2>&1";
  if (std::system(command.c_str()) != 0)
    throw std::runtime_error("blockMesh failed in " + directory.string());
  return directory;
}

struct Figures {
  int cells = 0;
  double total = 0, pimple = 0, restore = 0, interface = 0, protocol = 0, overhead = 0;
};

Figures measure(const fs::path& root, int nx, int ny, int steps, int iterations) {
  const fs::path fluid = make_channel(root / fmt::format("channel_{}", nx * ny), nx, ny);
  RunSettings run;
  run.delta_t = 0.001;
  run.case_directory = root;
  const Settings settings = Settings::load_string(
      "type: openfoam\nname: fluid\nworking_directory: " + fluid.filename().string() +
          "\nboundary_names: [wall]\n",
      "bench.yaml");
  auto wrapper = SolverWrapperRegistry::instance().create(settings, run);
  wrapper->initialize();
  std::vector<double> coupler_side;
  std::vector<bool> counted;
  for (int step = 1; step <= steps; ++step) {
    wrapper->initialize_step(step, step * run.delta_t);
    for (int k = 1; k <= iterations; ++k) {
      Interface input = wrapper->input_interface();
      auto displacement = input.values("wall_points", "displacement");
      const auto& x = input.parts()[0].model_part->coordinates;
      for (Eigen::Index i = 0; i < x.rows(); ++i)  // a bump that changes per iteration
        displacement(i, 1) = -1e-5 * k * std::sin(M_PI * x(i, 0) / 0.1);
      const auto start = std::chrono::steady_clock::now();
      wrapper->solve(input);
      coupler_side.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      counted.push_back(k > 1);
    }
    wrapper->finalize_step();
  }
  wrapper->finalize();

  // "cocopp coupling iteration 2: PIMPLE 0.0123 s, restore 0.0004 s, interface 0.0001 s"
  const std::string log = read_text(fluid / "fluid.log");
  const std::regex line(
      R"(cocopp coupling iteration \d+: PIMPLE (\S+) s, restore (\S+) s, interface (\S+) s)");
  std::vector<double> pimple, restore, interface, total;
  std::size_t i = 0;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), line); it != std::sregex_iterator();
       ++it, ++i) {
    if (i >= counted.size()) throw std::runtime_error("more timing lines than solves in the log");
    if (!counted[i]) continue;
    pimple.push_back(std::stod((*it)[1]));
    restore.push_back(std::stod((*it)[2]));
    interface.push_back(std::stod((*it)[3]));
    total.push_back(coupler_side[i]);
  }
  if (i != counted.size()) throw std::runtime_error("the log has fewer timing lines than solves");
  // The differences per iteration, then their medians (medians do not subtract).
  std::vector<double> protocol, overhead;
  for (std::size_t k = 0; k < total.size(); ++k) {
    protocol.push_back(total[k] - pimple[k] - restore[k] - interface[k]);
    overhead.push_back((total[k] - pimple[k]) / pimple[k]);
  }
  return {nx * ny,           median(total),    median(pimple),  median(restore),
          median(interface), median(protocol), median(overhead)};
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 3, iterations = 4;
  std::vector<std::pair<int, int>> sizes = {{50, 20}, {200, 50}, {500, 200}};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--steps")
      steps = std::atoi(argv[i + 1]);
    else if (option == "--iterations")
      iterations = std::atoi(argv[i + 1]);
    else if (option == "--largest")
      sizes.resize(std::atoi(argv[i + 1]));
    else {
      std::cerr << "usage: bench_openfoam_overhead [--steps N] [--iterations N] [--largest 1..3]\n";
      return 2;
    }
  }
  const fs::path root = fs::temp_directory_path() / "cocopp_bench_openfoam";
  fs::create_directories(root);
  std::cout << fmt::format("{:>8} {:>11} {:>11} {:>11} {:>13} {:>13} {:>9}\n", "cells",
                           "solve (ms)", "PIMPLE (ms)", "restore (ms)", "interface (ms)",
                           "protocol (ms)", "overhead");
  for (const auto& [nx, ny] : sizes) {
    const Figures f = measure(root, nx, ny, steps, iterations);
    std::cout << fmt::format("{:>8} {:>11.3f} {:>11.3f} {:>11.3f} {:>13.3f} {:>13.3f} {:>8.2f}%\n",
                             f.cells, 1e3 * f.total, 1e3 * f.pimple, 1e3 * f.restore,
                             1e3 * f.interface, 1e3 * f.protocol, 100 * f.overhead)
              << std::flush;
  }
  fs::remove_all(root);
  return 0;
}
