// The wire drawing case (examples/wire_drawing) coupled end to end, coarse and short: the case
// as it ships (the wire a sector driven by displacement), 12 steps; and the paper's own coupling
// of the wire, the film (3 x 50 cells) and the wire (4 x 153 CAX8R) loaded by it through the
// sliding interface for 14 time steps,
// the die held for 2 and then closing as the case ships it, so that the wire starts to yield
// under the die (one or two steps later the load-driven coupling stalls: docs/wire-drawing.md).
// Checks that the run completes with the paper's coupling (IQN-ILS, 0.01 um) in a few iterations
// per step; that the film is where Wilson and Walowit's inlet estimate puts it; that the wire is in
// axial equilibrium with the film's loads (which the overlap mapping hands over whole); that the
// equivalent stress stays on the yield surface; and that plot.py and checks.py read the run; that
// the wire answers small load changes deterministically and smoothly (wire_response.py); and that
// it takes a step driven by displacement under the film (displacement_probe.py). The whole 80-step
// case is not a test (docs/wire-drawing.md). Needs OpenFOAM and ccx.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <regex>
#include <string>
#include <vector>

#include "coupler/results/results_reader.hpp"
#include "tests/integration/run_helpers.hpp"
#include "tests/support/wire_drawing_case.hpp"

namespace cocopp {
namespace {

namespace fs = std::filesystem;

// Bands around this test's run (measured: 5.57 on average, at most 9; docs/wire-drawing.md).
constexpr double kAverageIterationsAtMost = 7.0, kIterationsAtMost = 12.0;

const std::string kCoarseMeshes =
    "--set mesh.wire_radial_elements=4 --set mesh.wire_axial_elements=153"
    " --set mesh.film_axial_cells=50 --set mesh.film_radial_cells=3";

double mean(const std::vector<double>& values) {
  return std::accumulate(values.begin(), values.end(), 0.0) / values.size();
}

/// The case of make_case.py `arguments` run for `steps` steps in `directory`, every step
/// converged; its iterations per step (printed: all, their mean and largest).
std::vector<double> run_case(const fs::path& directory, const std::string& arguments, int steps) {
  testing::write_wire_drawing_case(directory, arguments);
  testing::edit(directory / "case.yaml", "number_of_timesteps: 80",
                "number_of_timesteps: " + std::to_string(steps));
  const testing::CommandResult run =
      testing::run_cocopp("run -q " + (directory / "case.yaml").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  const auto summary = testing::read_json(directory / "results/case.summary.json");
  EXPECT_TRUE(summary["unconverged_steps"].empty()) << summary["unconverged_steps"];
  const ResultsReader results(directory / "results/case.h5");
  EXPECT_EQ(results.status(), "completed");
  const auto iterations = results.dataset("steps/iterations").values;
  if (iterations.empty()) return iterations;
  for (double n : iterations) std::printf("%.0f ", n);
  std::printf("iterations per step: %.2f on average, at most %.0f\n", mean(iterations),
              *std::max_element(iterations.begin(), iterations.end()));
  return iterations;
}

/// The expert's checks (examples/wire_drawing/checks.py) of the run in `directory` at its last
/// step, printed. (Through sh -c: run_in sends the command's own output to log.setup.)
nlohmann::json checks_of(const fs::path& directory) {
  testing::run_in(directory, "sh -c '/usr/bin/python3 " +
                                 (testing::kWireDrawingExample / "checks.py").string() +
                                 " . > checks.txt'");
  std::printf("%s\n", testing::read_text(directory / "checks.txt").c_str());
  return testing::read_json(directory / "checks.json");
}

/// The figures of docs/wire-drawing.md come from plot.py: it draws the run in `directory` too.
void expect_plot_draws(const fs::path& directory) {
  testing::run_in(
      directory,
      "/usr/bin/python3 " + (testing::kWireDrawingExample / "plot.py").string() + " . -o plot.png");
  EXPECT_GT(fs::file_size(directory / "plot.png"), 10000u);
}

/// The approach to steady drawing (examples/wire_drawing/steady.py, docs/wire-drawing.md's
/// figure) from the checks.json checks_of() wrote: the run's own per-step histories.
void expect_steady_plot_draws(const fs::path& directory) {
  testing::run_in(directory, "/usr/bin/python3 " +
                                 (testing::kWireDrawingExample / "steady.py").string() +
                                 " . -o steady.png");
  EXPECT_GT(fs::file_size(directory / "steady.png"), 10000u);
}

/// Where the run's time went (examples/wire_drawing/timing.py, docs/wire-drawing.md's
/// performance tables): its totals count the run's own iterations.
void expect_timing_reads(const fs::path& directory, const std::vector<double>& iterations) {
  testing::run_in(directory, "sh -c '/usr/bin/python3 " +
                                 (testing::kWireDrawingExample / "timing.py").string() +
                                 " . --phases 2 > timing.txt'");
  const std::string timing = testing::read_text(directory / "timing.txt");
  std::printf("%s\n", timing.c_str());
  const long total = std::lround(std::accumulate(iterations.begin(), iterations.end(), 0.0));
  EXPECT_NE(timing.find(std::to_string(iterations.size()) + " steps, " + std::to_string(total) +
                        " coupling iterations"),
            std::string::npos);
  EXPECT_NE(timing.find("| 1–2 |"), std::string::npos);  // the held steps, then the rest
  EXPECT_NE(timing.find("| 3–" + std::to_string(iterations.size()) + " |"), std::string::npos);
}

TEST(WireDrawingCase, CoarseShortRunCouplesFilmAndWire) {
  testing::TemporaryDirectory directory;
  const auto iterations = run_case(
      directory.path(), kCoarseMeshes + " --set time.held_steps=2" + testing::kLoadDrivenWire, 14);
  ASSERT_EQ(iterations.size(), 14u);
  EXPECT_LE(mean(iterations), kAverageIterationsAtMost);
  EXPECT_LE(*std::max_element(iterations.begin(), iterations.end()), kIterationsAtMost);

  const auto checks = checks_of(directory.path());
  const auto number = [&](const char* key) { return checks.at(key).get<double>(); };
  // 14 steps: the histories of the last 10, from which steady.py draws.
  EXPECT_EQ(checks.at("drawing_force_history").size(), 14u);
  EXPECT_EQ(checks.at("steady_window").at(0).get<int>(), 5);
  expect_steady_plot_draws(directory.path());
  // The film at the end of the entry cone: of the order of the inlet-zone estimate.
  EXPECT_GT(number("film_thickness_at_cone_end"), 0.7 * number("wilson_walowit_h0"));
  EXPECT_LT(number("film_thickness_at_cone_end"), 1.6 * number("wilson_walowit_h0"));
  // The drawing force (ccx's reaction at the exit end) against the back force and the film's
  // loads, as ccx applied them (measured 7e-5) and integrated on the film (2.3e-3).
  EXPECT_LT(std::abs(number("force_balance_error")), 1e-3);
  EXPECT_LT(std::abs(number("force_balance_error_film")), 1e-2);
  // The film's load reaching the wire: the overlap mapping keeps pressure x length along the
  // axis; over the rings, a wire face 3 film faces long carries one pressure at its own radius,
  // and the shear acts on the faces as the last step left them (measured 3e-4 and 6e-4).
  EXPECT_LT(std::abs(number("transfer_error_shear")), 2e-3);
  EXPECT_LT(std::abs(number("transfer_error_pressure")), 2e-3);
  // The wire has yielded under the die, and its stresses stay on the yield surface.
  EXPECT_GT(number("max_plastic_strain_surface"), 1e-4);
  EXPECT_LT(number("max_equivalent_over_yield"), 1.0 + 1e-3);
  // The drawing force against its terms: back force + ideal work of the reduction drawn now +
  // the film's viscous shear (issue 45's 15 %; measured -2.5 %: the shear is most of it here).
  EXPECT_LT(std::abs(number("drawing_force_error")), 0.15);

  expect_plot_draws(directory.path());

  // The wire's answer to small changes of the last loads (wire_response.py): the same loads give
  // the same displacement, and the response is linear in the load to the print precision of
  // ccx's .dat file (measured: second differences 3e-3 of the first, at 1e-4 of the load), so
  // the coupling sees a deterministic, smooth map.
  testing::run_in(directory.path(),
                  "sh -c '/usr/bin/python3 " +
                      (testing::kWireDrawingExample / "wire_response.py").string() +
                      " . --scale 1.0 > wire_response.txt'");
  const auto response = testing::read_json(directory / "results/wire_response.json");
  std::printf("%s\n", testing::read_text(directory / "wire_response.txt").c_str());
  EXPECT_EQ(response.at("repeat_difference").get<double>(), 0.0);
  EXPECT_GT(response.at("sensitivity").get<double>(), 0.0);
  ASSERT_EQ(response.at("second_over_first").size(), 3u);
  for (const auto& ratio : response.at("second_over_first")) EXPECT_LT(ratio.get<double>(), 0.05);

  // The wire driven by displacement under the film (displacement_probe.py): ccx takes the next
  // step with the nodes under the film held at their last radius, and moved inward by 0.55 and
  // 2 um; the film side's reaction grows with the inward move (the wire resists being squeezed).
  testing::run_in(directory.path(),
                  "sh -c '/usr/bin/python3 " +
                      (testing::kWireDrawingExample / "displacement_probe.py").string() +
                      " . --squeeze 0 0.55e-6 2e-6 > displacement_probe.txt'");
  std::printf("%s\n", testing::read_text(directory / "displacement_probe.txt").c_str());
  const auto probe = testing::read_json(directory / "results/displacement_probe.json");
  ASSERT_EQ(probe.size(), 3u);
  for (const auto& squeeze : probe) ASSERT_TRUE(squeeze.at("converged").get<bool>()) << squeeze;
  const auto reaction = [&](int k) { return -probe[k].at("radial_reaction").get<double>(); };
  EXPECT_GT(reaction(0), 0.0);
  EXPECT_GT(reaction(1), reaction(0));
  EXPECT_GT(reaction(2), reaction(1));
}

// time.steady_steps: after the die's schedule, the die held at its final diameter for that many
// more steps, in the film's table, its end time and the coupler's step count alike (no solver).
TEST(WireDrawingCase, SteadyStepsHoldTheDieClosedAfterItsSchedule) {
  testing::TemporaryDirectory directory;
  testing::write_wire_drawing_case(directory.path(), "--set time.steady_steps=5", false);
  EXPECT_NE(testing::read_text(directory / "case.yaml").find("number_of_timesteps: 85\n"),
            std::string::npos);
  const std::string control = testing::read_text(directory / "fluid/system/controlDict");
  std::smatch end_time;
  ASSERT_TRUE(std::regex_search(control, end_time, std::regex(R"(endTime\s+([0-9.e+-]+);)")));
  EXPECT_NEAR(std::stod(end_time[1]), 0.0085, 1e-12);
  // The die's table: (time radial displacement) pairs; its last two, step 80's and step 85's.
  const std::string motion = testing::read_text(directory / "fluid/0/pointDisplacement");
  const std::regex point(R"(\(([0-9.e+-]+) ([0-9.e+-]+)\))");
  std::vector<std::pair<double, double>> table;
  for (auto it = std::sregex_iterator(motion.begin(), motion.end(), point);
       it != std::sregex_iterator(); ++it)
    table.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  ASSERT_GE(table.size(), 3u) << motion;
  const auto closed = table[table.size() - 2], held = table.back();
  EXPECT_NEAR(closed.first, 0.008, 1e-12);
  EXPECT_NEAR(held.first, 0.0085, 1e-12);
  EXPECT_LT(closed.second, -40e-6);       // the die closed (44.9 um) ...
  EXPECT_EQ(held.second, closed.second);  // ... and held there
}

// The case as it ships (parameters.yaml: the wire a 1 degree sector driven by displacement
// under the film, its outer layer fully integrated), on the coarse meshes: 12 steps, the die
// held for 2 and then closing at the paper's rate. Every step converges to the paper's 0.01 um
// within the bands below (measured 5.75 on average, at most 9), the film at the die's approach end
// is where Wilson and Walowit's inlet estimate puts it (measured 1.23 of it), the wire is in axial
// equilibrium with the loads ccx took (as nodal forces and the drive's reactions), the film's
// radial and axial loads reach the wire, and the stresses stay on or below the yield surface (the
// coarse wire starts to yield by step 12: plastic strain 5e-4).
/// The probe file cocoppPimpleFoam wrote (COCOPP_SENSITIVITY_PROBE): per line, the radial
/// force change of every face (N per m of move).
std::vector<std::vector<double>> read_probe(const fs::path& file, std::size_t& faces) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  faces = std::stoul(line.substr(line.find("faces ") + 6));
  for (std::size_t f = 0; f < faces; ++f) std::getline(in, line);
  std::getline(in, line);
  const std::size_t lines = std::stoul(line.substr(line.find("lines ") + 6));
  std::vector<std::vector<double>> radial(lines, std::vector<double>(faces));
  for (auto& row : radial) {
    double axial = 0.0;
    in >> axial;
    for (double& value : row) in >> value;
    std::getline(in, line);  // the axial changes
  }
  EXPECT_TRUE(in.good()) << file;
  return radial;
}

// Issue 45: the film's sensitivity probe measures the film and changes nothing the coupling
// sees. The coarse case for 3 steps with the probe in step 3 gives the results of the run
// without it bit for bit; the probe has a line per film line (the faces plus one); a line moved
// outward pushes the film's two faces beside it harder inward (a film stiffer for a thinner
// gap); a move twice as large gives the same answer (linear: measured within 1.1e-3); and
// probes shaped as hats over two lines give the lines' answers summed.
TEST(WireDrawingCase, TheFilmsProbeAnswersItsOwnLinesAsAStiffFilm) {
  testing::TemporaryDirectory plain, probed, doubled, hats;
  // The drive that does not read the probe, so that the probe is all that differs (the case as
  // it ships probes every step through its film's sensitivity_probe key).
  const std::string arguments = kCoarseMeshes +
                                " --set time.held_steps=1 --set coupling.film_stiffness=local"
                                " --set coupling.surface_compliance=false";
  run_case(plain.path(), arguments, 3);
  for (const auto& [directory, move] :
       {std::pair{&probed, "1e-8"}, std::pair{&doubled, "2e-8"}, std::pair{&hats, "1e-8"}}) {
    const std::string probe = std::string("3 ") + move + " " + (*directory / "probe.txt").string() +
                              (directory == &hats ? " warm hat=2" : "");
    ::setenv("COCOPP_SENSITIVITY_PROBE", probe.c_str(), 1);
    run_case(directory->path(), arguments, 3);
    ::unsetenv("COCOPP_SENSITIVITY_PROBE");
  }
  const auto displacement = [](const testing::TemporaryDirectory& directory) {
    return ResultsReader(directory / "results/case.h5")
        .dataset("x/wire_points/displacement")
        .values;
  };
  EXPECT_EQ(displacement(probed), displacement(plain));

  std::size_t faces = 0;
  const auto radial = read_probe(probed / "probe.txt", faces);
  const auto radial2 = read_probe(doubled / "probe.txt", faces);
  ASSERT_EQ(radial.size(), faces + 1);
  std::size_t stiff = 0;
  double difference = 0.0, size = 0.0;
  for (std::size_t j = 0; j < radial.size(); ++j) {
    const double beside = (j > 0 ? radial[j][j - 1] : 0.0) + (j < faces ? radial[j][j] : 0.0);
    if (beside < 0.0) ++stiff;
    for (std::size_t f = 0; f < faces; ++f) {
      difference += std::pow(radial2[j][f] - radial[j][f], 2);
      size += std::pow(radial[j][f], 2);
    }
  }
  std::printf("probe: %zu of %zu lines stiff, the doubled move within %.2e\n", stiff, radial.size(),
              std::sqrt(difference / size));
  EXPECT_GE(stiff, radial.size() - 2);  // the film's ends may be at ambient pressure
  EXPECT_LT(std::sqrt(difference / size), 1e-2);

  // hat=2: every other line moved, its neighbours by half: by linearity the lines' answers
  // summed with those shares (warm: each probe from the step's solution; measured within 3e-4).
  const auto hat = read_probe(hats / "probe.txt", faces);
  ASSERT_EQ(hat.size(), faces / 2 + 1);
  difference = size = 0.0;
  for (std::size_t h = 0; h < hat.size(); ++h) {
    const std::size_t j = 2 * h;
    for (std::size_t f = 0; f < faces; ++f) {
      const double summed = radial[j][f] + (j > 0 ? 0.5 * radial[j - 1][f] : 0.0) +
                            (j + 1 < radial.size() ? 0.5 * radial[j + 1][f] : 0.0);
      difference += std::pow(hat[h][f] - summed, 2);
      size += std::pow(summed, 2);
    }
  }
  std::printf("probe: hats of two lines within %.2e of the lines' answers summed\n",
              std::sqrt(difference / size));
  EXPECT_LT(std::sqrt(difference / size), 1e-2);
}

// The case as it ships drives the wire with the film's own sensitivity, which the film probes
// every step (its sensitivity_probe key), and the wire's elastic compliance: measured 3.83
// coupling iterations a step, at most 5, where a stiffness per face and per line takes 5.75
// and 9 (--set coupling.film_stiffness=local --set coupling.surface_compliance=false).
TEST(WireDrawingCase, TheCaseAsShippedRunsCoarse) {
  testing::TemporaryDirectory directory;
  const auto iterations =
      run_case(directory.path(), kCoarseMeshes + " --set time.held_steps=2", 12);
  ASSERT_EQ(iterations.size(), 12u);
  EXPECT_LE(mean(iterations), 4.5);
  EXPECT_LE(*std::max_element(iterations.begin(), iterations.end()), 6.0);
  // The film probed itself in the last step, every third line (a hat over six).
  const std::string probe = testing::read_text(directory / "fluid/sensitivity.txt");
  EXPECT_EQ(probe.rfind("# cocoppPimpleFoam sensitivity probe: step 12, ", 0), 0u)
      << probe.substr(0, 200);
  EXPECT_NE(probe.find("(hat 3)"), std::string::npos);

  const auto checks = checks_of(directory.path());
  const auto number = [&](const char* key) { return checks.at(key).get<double>(); };
  EXPECT_GT(number("film_thickness_at_cone_end"), 0.7 * number("wilson_walowit_h0"));
  EXPECT_LT(number("film_thickness_at_cone_end"), 1.6 * number("wilson_walowit_h0"));
  // ccx's reaction at the exit end against the back force and the loads it took (measured
  // 7.9e-5).
  EXPECT_LT(std::abs(number("force_balance_error")), 1e-3);
  // The film's pressure reaches the wire as the drive's reactions, balanced to what the
  // coupling's 0.01 um leaves: the wire's surface stiffness (6e15 Pa/m) times that is 62 MPa
  // against film pressures of 100-500 MPa (measured 5.5e-3).
  EXPECT_LT(std::abs(number("transfer_error_radial")), 2e-2);
  // The film's axial load reaches the wire as the film summed it on its faces: its force per
  // face mapped conservatively, the wire's nodes take the totals (measured 3.5e-6 at step 12;
  // 6.5e-3 with mean pressures and tractions on the wire's faces, 2.3e-2 before with the
  // faces as the last step left them). And in every step the wire's exit force balances the
  // back force and the film's own axial force (measured 9.9e-5 at most).
  EXPECT_LT(std::abs(number("transfer_error_axial")), 1e-3);
  EXPECT_EQ(number("force_balance_steps"), 12.0);
  EXPECT_LT(std::abs(number("force_balance_error_film_largest")), 1e-3);
  EXPECT_LT(number("max_equivalent_over_yield"), 1.0 + 1e-3);
  expect_plot_draws(directory.path());
  expect_timing_reads(directory.path(), iterations);
}

}  // namespace
}  // namespace cocopp

namespace cocopp {
namespace {

// coupling.type iqnism (IQN-ILSM): make_case.py also writes the surrogate, the same case on the
// coarser meshes of `surrogate` (here 2 x 25 film cells, 2 x 77 wire elements), solved first in
// every step; coupling.type ibqn: IBQN with a model of each solver. Two steps of the case run
// with each, the surrogate's iterations are recorded, and the result is the one IQN-ILS reaches
// without them (all to the paper's 0.01 um).
TEST(WireDrawingCase, IqnIlsmAndIbqnReachIqnIlssSolution) {
  const std::string coarse =
      kCoarseMeshes +
      " --set surrogate.film_axial_cells=25 --set surrogate.film_radial_cells=2"
      " --set surrogate.wire_radial_elements=2 --set surrogate.wire_axial_elements=77"
      " --set time.held_steps=2" +
      testing::kLoadDrivenWire;
  const char* types[] = {"iqnism", "ibqn", "iqni"};
  std::vector<double> solutions[3];
  for (int index = 0; index < 3; ++index) {
    const std::string type = types[index];
    testing::TemporaryDirectory directory;
    testing::write_wire_drawing_case(directory.path(), coarse + " --set coupling.type=" + type);
    testing::edit(directory / "case.yaml", "number_of_timesteps: 80", "number_of_timesteps: 2");
    const testing::CommandResult run =
        testing::run_cocopp("run -q " + (directory / "case.yaml").string());
    ASSERT_EQ(run.exit_code, 0) << type << "\n" << run.output;
    EXPECT_NE(run.output.find("coupled solver : " + type), std::string::npos) << run.output;
    const auto summary = testing::read_json(directory / "results/case.summary.json");
    EXPECT_TRUE(summary["unconverged_steps"].empty()) << type << summary["unconverged_steps"];
    if (type == "iqnism") {
      ASSERT_EQ(summary["surrogate_iterations_per_step"].size(), 2u);
      for (const auto& iterations : summary["surrogate_iterations_per_step"])
        EXPECT_GE(iterations.get<int>(), 1);
    }
    solutions[index] =
        testing::read_dataset(directory / "results/case.h5", "x/wire_points/displacement");
  }
  for (int index = 0; index < 2; ++index) {
    ASSERT_EQ(solutions[index].size(), solutions[2].size());
    double largest = 0.0, difference = 0.0;
    for (std::size_t i = 0; i < solutions[2].size(); ++i) {
      largest = std::max(largest, std::abs(solutions[2][i]));
      difference = std::max(difference, std::abs(solutions[index][i] - solutions[2][i]));
    }
    std::printf("%s against IQN-ILS: largest difference %.3g m of %.3g m\n", types[index],
                difference, largest);
    EXPECT_LT(difference, 1e-8) << types[index];  // all within 0.01 um (2-norm) of the solution
  }
}

// coupling.drive: displacement (docs/wire-drawing.md, "The wire driven by displacement"): the
// film reports its gap and wall position, the mapped wrapper the coverage and the wall mapped
// exactly onto the wire's nodes, the wire (a 3D sector) is driven under the film and returns
// the balancing position. Four steps of the coarse case converge to the paper's 0.01 um, the
// first in at most 10 iterations, the others in at most 8 (measured 9, 8, 6, 5); and the film's
// wall is the one the same sector loaded by the film gives, to 0.03 um (measured 0.014 um of
// the wall's largest move, 0.95 um: what the coupling's 0.01 um leaves in either run).
TEST(WireDrawingCase, DisplacementDrivenWireBalancesAsTheLoadedOne) {
  testing::TemporaryDirectory driven_directory, loaded_directory;
  const auto iterations = run_case(driven_directory.path(), kCoarseMeshes, 4);
  ASSERT_EQ(iterations.size(), 4u);
  EXPECT_LE(iterations[0], 10.0);
  for (std::size_t i = 1; i < iterations.size(); ++i) EXPECT_LE(iterations[i], 8.0) << i + 1;
  run_case(loaded_directory.path(),
           kCoarseMeshes + " --set coupling.drive=load --set coupling.omega=0.01", 4);
  const ResultsReader driven(driven_directory / "results/case.h5");
  const ResultsReader loaded(loaded_directory / "results/case.h5");
  const auto wall = driven.dataset("x/wire_points/displacement");
  const auto loaded_wall = loaded.dataset("x/wire_points/displacement");
  ASSERT_EQ(wall.values.size(), loaded_wall.values.size());
  double largest = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < wall.values.size(); ++i) {
    largest = std::max(largest, std::abs(loaded_wall.values[i]));
    difference = std::max(difference, std::abs(wall.values[i] - loaded_wall.values[i]));
  }
  std::printf("the film's wall, driven against loaded: largest difference %.3g m of %.3g m\n",
              difference, largest);
  EXPECT_GT(largest, 5e-7);  // the wall has moved
  EXPECT_LT(difference, 3e-8);
}

}  // namespace
}  // namespace cocopp
