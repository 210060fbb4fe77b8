// More than two solvers: a `group` of solvers on one side, each owning its part of the
// interface. The ring-model tube's wall split along the axis into two processes
// (examples/tube/flow_ringmodel_split) against the one-wall run (examples/tube/flow_ringmodel):
// the rings are independent, so both solve the same problem and must agree to the coupling
// tolerance, one after the other and side by side. Then the case errors of a group.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/integration/run_helpers.hpp"
#include "tests/integration/variant_runs.hpp"
#include "tests/support/temporary_directory.hpp"

using namespace cocopp::testing;
namespace fs = std::filesystem;

namespace {

/// max |a - b| / max |a| over two runs' datasets.
double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double largest = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    largest = std::max(largest, std::abs(a[i]));
    difference = std::max(difference, std::abs(a[i] - b[i]));
  }
  return difference / largest;
}

/// Switch a copied example's case to the side-by-side scheme, with criteria that mean
/// something there (docs/coupling.md, "Schemes"): 4.24 iterations a step on the one wall.
void side_by_side(const fs::path& case_file) {
  edit(case_file, "  type: iqni\n",
       "  type: iqni\n  scheme: parallel\n"
       "  load_criterion: {type: value_relative_norm, tolerance: 1.0e-8}\n");
  edit(case_file, "      - type: relative_norm\n        tolerance: 1.0e-6\n",
       "      - type: value_relative_norm\n        tolerance: 1.0e-8\n");
  edit(case_file, "maximum: 15", "maximum: 50");
}

struct Runs {
  fs::path one_wall, split;
};

Runs run_both(const std::string& tag, bool parallel) {
  Runs runs{copy_example("tube/flow_ringmodel", tag + "_one"),
            copy_example("tube/flow_ringmodel_split", tag + "_split")};
  for (const fs::path& dir : {runs.one_wall, runs.split}) {
    if (parallel) side_by_side(dir / "case.yaml");
    const CommandResult run = run_cocopp("run -q " + (dir / "case.yaml").string());
    EXPECT_EQ(run.exit_code, 0) << run.output;
  }
  return runs;
}

void expect_same_solution(const Runs& runs) {
  const fs::path a = runs.one_wall / "results" / "case.h5", b = runs.split / "results" / "case.h5";
  // The coupling stops at a relative residual of 1e-6: both runs are that close to the same
  // fixed point, and to each other.
  EXPECT_LT(largest_difference(read_dataset(a, "x/wall/displacement"),
                               read_dataset(b, "x/wall/displacement")),
            1e-6);
  EXPECT_LT(
      largest_difference(read_dataset(a, "y/wall/pressure"), read_dataset(b, "y/wall/pressure")),
      1e-6);
  const auto one = read_json(runs.one_wall / "results" / "case.summary.json");
  const auto split = read_json(runs.split / "results" / "case.summary.json");
  EXPECT_TRUE(split["unconverged_steps"].empty()) << split["unconverged_steps"];
  // The same iterates up to round-off in the mapping: the same iterations, give or take
  // a step where the last residual sits at the tolerance.
  EXPECT_NEAR(total_iterations(split), total_iterations(one), 0.01 * total_iterations(one));
}

TEST(SolverGroup, TheTubeWallInTwoProcessesGivesTheOneWallRun) {
  const Runs runs = run_both("group_serial", false);
  expect_same_solution(runs);
  // Each member solved in its own working directory, with its own log and output.
  for (const char* member : {"wall_a", "wall_b"}) {
    EXPECT_TRUE(fs::exists(runs.split / member / (std::string(member) + ".log")));
    EXPECT_TRUE(fs::exists(runs.split / member / "output" / "tube_ringmodel_000010.vtk"));
  }
  fs::remove_all(runs.one_wall);
  fs::remove_all(runs.split);
}

TEST(SolverGroup, SideBySideWithTheFlowAsWell) {
  const Runs runs = run_both("group_parallel", true);
  expect_same_solution(runs);
  fs::remove_all(runs.one_wall);
  fs::remove_all(runs.split);
}

// Each member keeps its own restart files: 50 steps, then --restart to 100, gives the
// uninterrupted run bit for bit.
TEST(SolverGroup, ARestartedGroupContinuesAsTheUninterruptedRun) {
  const fs::path whole = copy_example("tube/flow_ringmodel_split", "group_whole");
  const fs::path parts = copy_example("tube/flow_ringmodel_split", "group_parts");
  ASSERT_EQ(run_cocopp("run -q " + (whole / "case.yaml").string()).exit_code, 0);
  edit(parts / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 50");
  ASSERT_EQ(run_cocopp("run -q " + (parts / "case.yaml").string()).exit_code, 0);
  edit(parts / "case.yaml", "number_of_timesteps: 50", "number_of_timesteps: 100");
  const CommandResult restarted = run_cocopp("run -q --restart " + (parts / "case.yaml").string());
  ASSERT_EQ(restarted.exit_code, 0) << restarted.output;
  EXPECT_EQ(read_dataset(whole / "results" / "case.h5", "x/wall/displacement"),
            read_dataset(parts / "results" / "case.h5", "x/wall/displacement"));
  EXPECT_EQ(read_dataset(whole / "results" / "case.h5", "y/wall/pressure"),
            read_dataset(parts / "results" / "case.h5", "y/wall/pressure"));
  fs::remove_all(whole);
  fs::remove_all(parts);
}

// A group whose members take substeps: each member's window mapped as a whole; the one-wall
// run with the same substeps, to the coupling tolerance.
TEST(SolverGroup, MembersTakeTheirWindowsOfSubsteps) {
  const fs::path one = copy_example("tube/flow_ringmodel", "group_substeps_one");
  const fs::path split = copy_example("tube/flow_ringmodel_split", "group_substeps_split");
  edit(one / "case.yaml", "    working_directory: structure\n",
       "    working_directory: structure\n    substeps: 2\n");
  for (const std::string member : {"wall_a", "wall_b"})
    edit(split / "case.yaml", "working_directory: " + member + "}",
         "working_directory: " + member + ", substeps: 2}");
  for (const fs::path& dir : {one, split}) {
    edit(dir / "case.yaml", "tolerance: 1.0e-6", "tolerance: 1.0e-5");  // a stall at 2.4e-6
    const CommandResult run = run_cocopp("run -q " + (dir / "case.yaml").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  EXPECT_LT(largest_difference(read_dataset(one / "results" / "case.h5", "x/wall/displacement"),
                               read_dataset(split / "results" / "case.h5", "x/wall/displacement")),
            1e-5);
  const CommandResult mixed = [&] {
    edit(split / "case.yaml", "working_directory: wall_b, substeps: 2}",
         "working_directory: wall_b, substeps: 3}");
    return run_cocopp("check " + (split / "case.yaml").string());
  }();
  EXPECT_NE(mixed.output.find("member 'wall_b' of group 'wall' takes 3 substeps a time step, "
                              "'wall_a' 2: the members of a group share the window's substeps"),
            std::string::npos)
      << mixed.output;
  fs::remove_all(one);
  fs::remove_all(split);
}

/// `cocopp check` (and run) of the split example with one edit; the message it gives.
std::string error_after(const std::string& tag, const std::string& from, const std::string& to,
                        const std::string& command = "run -q") {
  const fs::path dir = copy_example("tube/flow_ringmodel_split", tag);
  edit(dir / "case.yaml", from, to);
  const CommandResult run = run_cocopp(command + " " + (dir / "case.yaml").string());
  EXPECT_NE(run.exit_code, 0) << run.output;
  fs::remove_all(dir);
  return run.output;
}

constexpr const char* kWallB =
    "      - type: mapped\n"
    "        name: wall_b\n"
    "        frame_origin: [0.0, 0.0, 0.0125]\n"
    "        solver_wrapper: {type: tube_ringmodel, working_directory: wall_b}\n"
    "        input_mapper: {type: linear, directions: [z]}\n"
    "        output_mapper: {type: linear, directions: [z]}\n";

bool has(const std::string& output, const std::string& text) {
  return output.find(text) != std::string::npos;
}

TEST(SolverGroup, CaseErrorsNameTheMemberAndSayWhatToChange) {
  // Both halves at one place: the upstream points are covered twice, the downstream ones by
  // nobody from inside.
  std::string out = error_after("group_tie", "frame_origin: [0.0, 0.0, 0.0125]",
                                "frame_origin: [0.0, 0.0, -0.0125]");
  EXPECT_TRUE(has(out,
                  "group 'wall': point 0 (0, 0.005, -0.02475) of model part 'wall' is "
                  "covered equally by members 'wall_a' and 'wall_b'"))
      << out;
  out = error_after("group_plain", kWallB,
                    "      - {type: tube_ringmodel, name: wall_b, working_directory: wall_b}\n",
                    "check");
  EXPECT_TRUE(has(out, "solver_wrappers[1].solver_wrappers[1].type"));
  EXPECT_TRUE(has(out, "member 'wall_b' of group 'wall' keeps its own interface")) << out;
  out = error_after("group_name", "name: wall_b", "name: wall_a", "check");
  EXPECT_TRUE(has(out, "group 'wall' has two members (or itself) called 'wall_a'")) << out;
  out = error_after("group_directory", "working_directory: wall_b}", "working_directory: wall_a}",
                    "check");
  EXPECT_TRUE(has(out, "solver_wrappers[1].solver_wrappers[1].solver_wrapper.working_directory"))
      << out;
  EXPECT_TRUE(has(out, "is also another solver's")) << out;
  out = error_after("group_one", kWallB, "", "check");
  EXPECT_TRUE(has(out, "a group needs at least two solver wrappers, got 1")) << out;
}

// A member that fails stops the run with its own name (the other member and the flow are
// stopped as for any failure: tests/integration/test_solver_failures.cpp).
TEST(SolverGroup, AFailingMemberIsNamed) {
  const fs::path dir = copy_example("tube/flow_ringmodel_split", "group_failure");
  // Far too soft a downstream half: its tube law has no area for the flow's pressure.
  edit(dir / "wall_b" / "tube_ringmodel.yaml", "e: 3.0e5", "e: 30.0");
  const CommandResult run = run_cocopp("run -q " + (dir / "case.yaml").string());
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_TRUE(has(run.output, "solver 'wall_b' reported an error: unphysical pressure"))
      << run.output;
  fs::remove_all(dir);
}

}  // namespace
