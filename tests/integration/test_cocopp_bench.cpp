// `cocopp bench` end to end: a small benchmark of the tube with a computed reference, a
// diverging variant and a variant identical to the reference; then a given reference file; a
// sweep of cases x variants with solver_inputs and no reference; errors in the bench file.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/integration/run_helpers.hpp"

using namespace cocopp::testing;
namespace fs = std::filesystem;

namespace {

/// The first variant has the reference's own coupled solver: its error must be exactly 0.
const std::string kVariants = R"(settings: {number_of_timesteps: 10}
variants:
  - name: same_as_reference
    coupled_solver:
      convergence_criterion:
        type: or
        criteria: [{type: relative_norm, tolerance: 1.0e-8}, {type: iteration_limit, maximum: 100}]
  - name: iqni_ls_q10
  - name: gauss_seidel
    coupled_solver: {type: gauss_seidel}
)";
const std::string kBench =
    "base_case: flow_structure/case.yaml\nreference: {tolerance: 1.0e-8}\n" + kVariants;

/// A temporary directory holding flow_structure/ and bench.yaml.
fs::path bench_directory(const std::string& tag, const std::string& bench) {
  const fs::path example = copy_example("tube/flow_structure", tag + "_case");
  const fs::path dir = example.parent_path() / ("cocopp_test_" + tag);
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::rename(example, dir / "flow_structure");
  write_text(dir / "bench.yaml", bench);
  return dir;
}

const nlohmann::json& run_named(const nlohmann::json& bench, const std::string& name) {
  for (const auto& run : bench["runs"])
    if (run["name"] == name) return run;
  throw std::runtime_error("no run " + name);
}

TEST(CocoppBench, ComparesVariantsWithComputedReference) {
  ASSERT_EQ(run_command("/usr/bin/python3 -c 'import matplotlib'").exit_code, 0)
      << "bench.png needs matplotlib for /usr/bin/python3";
  const fs::path dir = bench_directory("bench", kBench);
  const auto result = run_cocopp("bench " + (dir / "bench.yaml").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;

  const fs::path out = dir / "results" / "bench";
  for (const char* name : {"reference", "same_as_reference", "iqni_ls_q10", "gauss_seidel"}) {
    EXPECT_NE(result.output.find(std::string("\n") + name + " "), std::string::npos) << name;
    EXPECT_TRUE(fs::exists(out / name / "results" / "case.h5")) << name;
  }
  // Every run has its own copy of the case's directory.
  EXPECT_TRUE(fs::exists(out / "iqni_ls_q10" / "flow" / "tube_flow.yaml"));
  EXPECT_TRUE(fs::exists(out / "iqni_ls_q10" / "case.yaml"));

  const nlohmann::json bench = read_json(out / "bench.json");
  ASSERT_EQ(bench["runs"].size(), 4u);
  const auto& same = run_named(bench, "same_as_reference");
  EXPECT_TRUE(same["completed"].get<bool>());
  EXPECT_EQ(same["displacement_error"].get<double>(), 0.0);
  EXPECT_EQ(same["pressure_error"].get<double>(), 0.0);
  EXPECT_EQ(same["steps_completed"], 10);
  EXPECT_EQ(same["solver_calls"].get<long>() % 2, 0);

  const auto& iqni = run_named(bench, "iqni_ls_q10");
  EXPECT_TRUE(iqni["completed"].get<bool>());
  const double error = iqni["displacement_error"].get<double>();
  EXPECT_GT(error, 0.0);
  EXPECT_LT(error, 1e-3);
  EXPECT_LE(iqni["average_iterations"].get<double>(), iqni["maximum_iterations"].get<double>());
  EXPECT_LE(iqni["average_iterations"].get<double>(),
            run_named(bench, "reference")["average_iterations"].get<double>());

  const auto& gs = run_named(bench, "gauss_seidel");
  EXPECT_FALSE(gs["completed"].get<bool>());
  EXPECT_EQ(gs["status"], "diverged");
  EXPECT_FALSE(gs["message"].get<std::string>().empty());
  EXPECT_NE(result.output.find("diverged"), std::string::npos);

  const std::string csv = read_text(out / "bench.csv");
  EXPECT_EQ(csv.rfind("name,coupled_solver,status,completed,message,steps_completed,", 0), 0u)
      << csv;
  for (const char* field : {"average_iterations", "maximum_iterations", "solver_calls", "wall_time",
                            "coupler_time", "displacement_error", "pressure_error"})
    EXPECT_NE(csv.find(field), std::string::npos) << field;
  EXPECT_NE(csv.find("\ngauss_seidel,gauss_seidel,diverged,false,"), std::string::npos) << csv;

  const std::string png = read_text(out / "bench.png");
  ASSERT_GE(png.size(), 8u) << result.output;
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));

  // The same variant against the reference's results file, given this time.
  const fs::path reference = out / "reference" / "results" / "case.h5";
  write_text(dir / "given.yaml",
             "base_case: flow_structure/case.yaml\n"
             "output_directory: given_results\n"
             "reference: {results: " +
                 reference.string() + "}\n" + kVariants);
  const auto given = run_cocopp("bench --no-plot " + (dir / "given.yaml").string());
  ASSERT_EQ(given.exit_code, 0) << given.output;
  const nlohmann::json second = read_json(dir / "given_results" / "bench.json");
  EXPECT_EQ(second["runs"].size(), 3u);  // no reference run
  EXPECT_EQ(run_named(second, "same_as_reference")["displacement_error"].get<double>(), 0.0);
  EXPECT_FALSE(fs::exists(dir / "given_results" / "bench.png"));
  fs::remove_all(dir);
}

/// A reference with its own criterion (an absolute floor where solver noise makes a relative
/// one unreachable): the variant with the same criterion reproduces it exactly.
TEST(CocoppBench, ReferenceTakesTheBenchFilesConvergenceCriterion) {
  const fs::path dir = bench_directory("bench_criterion", R"(base_case: flow_structure/case.yaml
reference:
  convergence_criterion: {type: absolute_norm, tolerance: 1.0e-9}
settings: {number_of_timesteps: 3}
variants:
  - name: same_as_reference
    coupled_solver:
      convergence_criterion:
        type: or
        criteria: [{type: absolute_norm, tolerance: 1.0e-9}, {type: iteration_limit, maximum: 100}]
  - name: default_criterion
)");
  auto result = run_cocopp("bench --no-plot " + (dir / "bench.yaml").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json bench = read_json(dir / "results" / "bench" / "bench.json");
  EXPECT_EQ(run_named(bench, "same_as_reference")["displacement_error"].get<double>(), 0.0);
  EXPECT_GT(run_named(bench, "default_criterion")["displacement_error"].get<double>(), 0.0);
  EXPECT_EQ(run_named(bench, "reference")["average_iterations"],
            run_named(bench, "same_as_reference")["average_iterations"]);

  write_text(dir / "bench.yaml", R"(base_case: flow_structure/case.yaml
reference:
  tolerance: 1.0e-8
  convergence_criterion: {type: absolute_norm, tolerance: 1.0e-9}
variants: [{name: a}]
)");
  result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("bench.yaml:3:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("not both"), std::string::npos) << result.output;

  write_text(dir / "bench.yaml", R"(base_case: flow_structure/case.yaml
reference: {convergence_criterion: 1.0e-9}
variants: [{name: a}]
)");
  result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("reference.convergence_criterion"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("absolute_norm"), std::string::npos) << result.output;
  fs::remove_all(dir);
}

/// Substeps in the bench: variants change a solver wrapper (`solver_wrappers`), and the
/// reference runs at a finer delta_t (its `settings`), compared at the variants' steps.
/// Windows of 4 substeps on both solvers are the reference's own discrete problem (both at a
/// quarter of the step): within the coupling tolerance of it.
TEST(CocoppBench, SubstepVariantsAgainstAFinerReference) {
  const fs::path dir = bench_directory("bench_substeps", R"(base_case: flow_structure/case.yaml
reference:
  convergence_criterion: {type: absolute_norm, tolerance: 1.0e-12}
  settings: {delta_t: 2.5e-5, number_of_timesteps: 40}
settings: {number_of_timesteps: 10}
variants:
  - name: both_at_the_step
  - name: windows_of_4
    solver_wrappers: {flow: {substeps: 4}, structure: {substeps: 4}}
    coupled_solver:
      convergence_criterion:
        type: or
        criteria: [{type: absolute_norm, tolerance: 1.0e-12}, {type: iteration_limit, maximum: 100}]
)");
  auto result = run_cocopp("bench --no-plot " + (dir / "bench.yaml").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json bench = read_json(dir / "results" / "bench" / "bench.json");
  EXPECT_LT(run_named(bench, "windows_of_4")["displacement_error"].get<double>(), 1e-8);
  EXPECT_GT(run_named(bench, "both_at_the_step")["displacement_error"].get<double>(), 1e-2);
  const std::string written = read_text(dir / "results" / "bench" / "windows_of_4" / "case.yaml");
  EXPECT_NE(written.find("substeps: 4"), std::string::npos) << written;

  write_text(dir / "bench.yaml", R"(base_case: flow_structure/case.yaml
variants:
  - {name: a, solver_wrappers: {flw: {substeps: 4}}}
)");
  result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_NE(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("solver_wrappers: the base case has no solver wrapper named "
                               "'flw'; did you mean 'flow'?"),
            std::string::npos)
      << result.output;
  fs::remove_all(dir);
}

TEST(CocoppBench, InvalidFileNamesTheKey) {
  const fs::path dir = bench_directory("bench_invalid", R"(base_case: flow_structure/case.yaml
variants:
  - name: a
    coupled_solver: {model: {q: -1}}
  - {name: a}
)");
  auto result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("'a' is used twice"), std::string::npos) << result.output;

  write_text(dir / "bench.yaml", "base_case: flow_structure/case.yaml\nvariantz: []\n");
  result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("variants"), std::string::npos) << result.output;

  // A variant whose merged case is invalid is found before any run starts.
  write_text(dir / "bench.yaml",
             "base_case: flow_structure/case.yaml\nvariants:\n  - name: bad\n"
             "    coupled_solver: {model: {q: -1}}\n");
  result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("coupled_solver.model.q"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir / "results" / "bench" / "reference" / "results"));
  fs::remove_all(dir);
}

/// A tiny stability sweep: two cases x three variants, no reference. Gauss-Seidel must diverge
/// on the light wall (the linear analysis gives 12 unstable modes at rho_s = 500) and converge at
/// dt = 1e-2 (|lambda_1| = 0.08: no unstable mode); IQN-ILS converges on both; an iteration
/// limit of 2 leaves every step unconverged.
const std::string kSweep = R"(base_case: flow_structure/case.yaml
reference: none
settings: {number_of_timesteps: 3}
cases:
  - name: light
    solver_inputs: {structure: {rho_s: 500.0}}
  - name: dt_1e-2
    settings: {delta_t: 1.0e-2}
    solver_inputs: {flow: {inlet: {period: 0.05}}}
variants:
  - name: gauss_seidel
    coupled_solver: {type: gauss_seidel}
  - name: iqni_ls_q10
  - name: limit_2
    coupled_solver: {convergence_criterion: {type: iteration_limit, maximum: 2}}
)";

const nlohmann::json& run_of(const nlohmann::json& bench, const std::string& case_name,
                             const std::string& name) {
  for (const auto& run : bench["runs"])
    if (run["case"] == case_name && run["name"] == name) return run;
  throw std::runtime_error("no run " + case_name + "/" + name);
}

TEST(CocoppBench, SweepsCasesWithSolverInputsWithoutReference) {
  const fs::path dir = bench_directory("bench_sweep", kSweep);
  const auto result = run_cocopp("bench " + (dir / "bench.yaml").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const fs::path out = dir / "results" / "bench";

  // The new values are in the copied input files, the base case's files are untouched.
  const std::string light =
      read_text(out / "light" / "iqni_ls_q10" / "structure" / "tube_structure.yaml");
  EXPECT_NE(light.find("rho_s: 500"), std::string::npos) << light;
  EXPECT_NE(light.find("e: 3.0e5"), std::string::npos) << light;       // the other keys are kept
  EXPECT_NE(light.find("bench.yaml:6:"), std::string::npos) << light;  // where the value came from
  EXPECT_NE(
      read_text(dir / "flow_structure" / "structure" / "tube_structure.yaml").find("rho_s: 1200.0"),
      std::string::npos);
  const std::string flow = read_text(out / "dt_1e-2" / "gauss_seidel" / "flow" / "tube_flow.yaml");
  EXPECT_NE(flow.find("period: 0.05"), std::string::npos) << flow;
  EXPECT_NE(flow.find("amplitude: 1333.2"), std::string::npos) << flow;  // merged, not replaced

  const nlohmann::json bench = read_json(out / "bench.json");
  EXPECT_EQ(bench["reference"], "none");
  ASSERT_EQ(bench["runs"].size(), 6u);  // no reference runs
  const auto& gs_light = run_of(bench, "light", "gauss_seidel");
  EXPECT_EQ(gs_light["outcome"], "diverged");
  EXPECT_EQ(gs_light["reason"], "residual growth in step 1, iteration 4");
  const auto& gs_dt = run_of(bench, "dt_1e-2", "gauss_seidel");
  EXPECT_EQ(gs_dt["outcome"], "converged") << gs_dt.dump();
  EXPECT_EQ(gs_dt["steps_completed"], 3);
  for (const char* c : {"light", "dt_1e-2"}) {
    const auto& iqni = run_of(bench, c, "iqni_ls_q10");
    EXPECT_EQ(iqni["outcome"], "converged") << c;
    EXPECT_EQ(iqni["unconverged_steps"], 0) << c;
    EXPECT_TRUE(iqni["displacement_error"].is_null()) << c;
    const auto& limited = run_of(bench, c, "limit_2");
    EXPECT_EQ(limited["outcome"], "stalled") << c;
    EXPECT_EQ(limited["unconverged_steps"], 3) << c;
    EXPECT_EQ(limited["reason"], "3 of 3 steps at the iteration limit") << c;
    EXPECT_EQ(limited["maximum_iterations"], 2) << c;
  }
  // A heavier wall answers the same pressure pulse with another motion: the solver input acts.
  const double light_iterations = run_of(bench, "light", "iqni_ls_q10")["average_iterations"];
  EXPECT_GT(light_iterations, 0.0);

  // The table: one line per run, with the case first.
  const auto line = result.output.find("\nlight ");
  ASSERT_NE(line, std::string::npos) << result.output;
  const std::string first =
      result.output.substr(line + 1, result.output.find('\n', line + 1) - line);
  EXPECT_NE(first.find(" gauss_seidel "), std::string::npos) << first;
  EXPECT_NE(first.find(" diverged "), std::string::npos) << first;
  EXPECT_NE(result.output.find("stalled 3"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("no plot"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(out / "bench.png"));
  const std::string csv = read_text(out / "bench.csv");
  EXPECT_NE(csv.find(",light,diverged,\"residual growth in step 1, iteration 4\",0"),
            std::string::npos)
      << csv;

  // The linear analysis next to the sweep (scripts/tube_modes.py). By hand: at rho_s = 500,
  // omega_r^2 dt^2 = 3e5 / (500 * 0.005^2) * 1e-8 = 0.24 and |lambda_j| = 2 * 1000 /
  // (500 * 1e-3 * 0.005 * (j pi / 0.05)^2) / 1.24 = 163.4 / j^2: modes 1..12 are unstable; at
  // dt = 1e-2 (rho_s = 1200), |lambda_1| = 84.4 / (1 + 1e7 * 1e-4) = 0.0843: none. Gauss-Seidel
  // diverged in the first case and converged in the second.
  const auto modes = run_command(
      "/usr/bin/python3 " COCOPP_TEST_SOURCE_DIR "/scripts/tube_modes.py " + out.string());
  ASSERT_EQ(modes.exit_code, 0) << modes.output;
  EXPECT_NE(
      modes.output.find("| light | 0.5 | 300000 | 0.0001 | 0.05 | 163 | 12 | **div.** step 1 |"),
      std::string::npos)
      << modes.output;
  EXPECT_NE(modes.output.find("| dt_1e-2 | 1.2 | 300000 | 0.01 | 0.05 | 0.0843 | 0 | "),
            std::string::npos)
      << modes.output;
  fs::remove_all(dir);
}

TEST(CocoppBench, SolverInputErrorsNameTheBenchFileAndTheKey) {
  const std::string head =
      "base_case: flow_structure/case.yaml\nreference: none\n"
      "settings: {number_of_timesteps: 1}\n";
  const fs::path dir = bench_directory("bench_inputs", head + R"(variants:
  - name: typo
    solver_inputs: {strucure: {rho_s: 500.0}}
)");
  auto result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("bench.yaml:6:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("no solver named 'strucure'; did you mean 'structure'?"),
            std::string::npos)
      << result.output;

  write_text(dir / "bench.yaml", head + "variants:\n  - {name: a, solver_inputs: {flow: 3}}\n");
  result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("solver_inputs.flow"), std::string::npos) << result.output;

  write_text(dir / "bench.yaml",
             "base_case: flow_structure/case.yaml\nreference: nothing\nvariants: [{name: a}]\n");
  result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("must be 'none'"), std::string::npos) << result.output;

  // An unknown key of the solver's own input: the solver rejects it when it reads the file,
  // naming the run's copy of the file, the line and the nearest key; the bench goes on.
  write_text(dir / "bench.yaml", head + R"(variants:
  - name: bad_key
    solver_inputs: {structure: {rho_z: 500.0}}
  - name: fine
)");
  result = run_cocopp("bench " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json bench = read_json(dir / "results" / "bench" / "bench.json");
  const auto& bad = run_named(bench, "bad_key");
  EXPECT_EQ(bad["outcome"], "solver_failed");
  const std::string message = bad["message"];
  EXPECT_NE(message.find("tube_structure.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown key 'rho_z'; did you mean 'rho_s'"), std::string::npos)
      << message;
  // ... and the bench says which copy of the file that is and where the change came from.
  const std::string note = bad["note"];
  EXPECT_NE(note.find("bad_key/structure/tube_structure.yaml"), std::string::npos) << note;
  EXPECT_NE(note.find("bench.yaml:6:"), std::string::npos) << note;
  EXPECT_NE(result.output.find(note), std::string::npos) << result.output;
  EXPECT_EQ(run_named(bench, "fine")["outcome"], "converged");
  fs::remove_all(dir);
}

}  // namespace

namespace {

// start_from_state: a window of a long run. The base case runs 20 steps and saves its state;
// every bench run continues it to step 30 with its own coupled solver, Aitken too (another
// type, whose memory starts afresh), and counts only its own 10 steps.
TEST(CocoppBench, StartFromStateContinuesTheBaseCaseWithEveryVariant) {
  const fs::path dir = bench_directory("bench_state", R"(base_case: flow_structure/case.yaml
start_from_state: true
reference: {tolerance: 1.0e-8}
settings: {number_of_timesteps: 30}
variants:
  - name: iqni_ls_q10
  - name: aitken
    coupled_solver: {type: aitken, omega_max: 0.05}
)");
  const fs::path base = dir / "flow_structure" / "case.yaml";
  std::string text = read_text(base);
  const std::string steps = "number_of_timesteps: 100";
  ASSERT_NE(text.find(steps), std::string::npos);
  text.replace(text.find(steps), steps.size(), "number_of_timesteps: 20");
  write_text(base, text);

  auto result = run_cocopp("bench --no-plot " + (dir / "bench.yaml").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("start_from_state: no saved state"), std::string::npos)
      << result.output;

  ASSERT_EQ(run_cocopp("run -q " + base.string()).exit_code, 0);
  result = run_cocopp("bench --no-plot " + (dir / "bench.yaml").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json bench = read_json(dir / "results" / "bench" / "bench.json");
  for (const char* name : {"reference", "iqni_ls_q10", "aitken"}) {
    const nlohmann::json& run = run_named(bench, name);
    EXPECT_EQ(run["steps_completed"], 10) << name;
    const auto h5 = run_command("/usr/bin/python3 -c \"import h5py; f = h5py.File('" +
                                (dir / "results/bench" / name / "results/case.h5").string() +
                                "'); print(list(f['steps/step'][:]), "
                                "f.attrs['restarted_after_step'])\"");
    EXPECT_NE(h5.output.find("[1, 2, 3,"), std::string::npos) << name << h5.output;
    EXPECT_NE(h5.output.find("30] 20"), std::string::npos) << name << h5.output;
    // The run's time is its steps': less than the whole run's, which includes the restart.
    const nlohmann::json summary =
        read_json(dir / "results/bench" / name / "results/case.summary.json");
    EXPECT_LT(run["wall_time"].get<double>(), summary["wall_time"].get<double>()) << name;
  }
  // The error is that of the run's own steps 21-30 (steps 1-20 are the base run's in both).
  const double error = run_named(bench, "iqni_ls_q10")["displacement_error"].get<double>();
  const auto window = run_command(
      "/usr/bin/python3 -c \"import h5py, numpy as np; "
      "a = h5py.File('" +
      (dir / "results/bench/iqni_ls_q10/results/case.h5").string() +
      "')['x/wall/displacement'][20:]; "
      "b = h5py.File('" +
      (dir / "results/bench/reference/results/case.h5").string() +
      "')['x/wall/displacement'][20:]; "
      "print(repr(np.linalg.norm(a - b) / np.linalg.norm(b)))\"");
  ASSERT_EQ(window.exit_code, 0) << window.output;
  EXPECT_GT(error, 0.0);
  EXPECT_NEAR(error, std::stod(window.output), 1e-9 * error) << window.output;
  fs::remove_all(dir);
}

}  // namespace
