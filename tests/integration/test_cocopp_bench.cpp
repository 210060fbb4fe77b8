// `cocopp bench` end to end: a small benchmark of the tube with a computed reference, a
// diverging variant and a variant identical to the reference; then a given reference file.
#include <gtest/gtest.h>

#include <cmath>

#include "run_helpers.hpp"

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

  const fs::path out = dir / "bench_results";
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
  EXPECT_FALSE(fs::exists(dir / "bench_results" / "reference" / "results"));
  fs::remove_all(dir);
}

}  // namespace
