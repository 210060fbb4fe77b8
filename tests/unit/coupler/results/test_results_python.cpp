// The results file as Python users see it: h5py reads the documented layout
// (tests/unit/coupler/results/read_results.py), and scripts/plot_results.py turns it into a PNG.
// h5py and matplotlib are project requirements: a missing one fails these tests, never skips.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/unit/coupler/results/results_fixture.hpp"

namespace cocopp::test {
namespace {

using nlohmann::json;

constexpr const char* kPython = "/usr/bin/python3";
constexpr int kSteps = 12;  // so that step 10 of the docs example exists

std::filesystem::path source_dir() {
  return COCOPP_TEST_SOURCE_DIR;
}

std::string quoted(const std::filesystem::path& path) {
  std::string out = "'";
  for (char c : path.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct Output {
  int status;
  std::string text;  // stdout and stderr
};

Output run(const std::string& command) {
  Output out{-1, ""};
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) out.text += buffer;
  const int status = ::pclose(pipe);
  out.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

/// Empty if /usr/bin/python3 imports `modules`, else why not and what to do.
std::string missing(const std::string& modules) {
  const Output out = run(std::string(kPython) + " -c 'import " + modules + "'");
  if (out.status == 0) return "";
  return std::string(kPython) + " cannot import " + modules + ":\n" + out.text +
         "Run the project's setup script, scripts/setup.sh (or just "
         "scripts/install-dependencies.sh), to install the Python requirements (Debian "
         "packages python3-h5py and python3-matplotlib).";
}

/// The run of results_fixture.hpp as read_results.py --expect wants it.
json expected_values() {
  const RunDescription run = make_run(kSteps);
  json e = {{"case_file", run.case_file},
            {"coupled_solver", run.coupled_solver},
            {"solver_names", run.solver_names},
            {"delta_t", run.delta_t},
            {"status", "completed"},
            {"message", "all 12 steps done"},
            {"cocopp_version", "0.1.0"}};
  Interfaces interfaces = make_interfaces();
  for (const char* name : {"x", "y"}) {
    const Interface& interface = std::string(name) == "x" ? interfaces.x : interfaces.y;
    for (const auto& part : interface.parts()) {
      e[name]["model_parts"].push_back(part.model_part->name);
      e[name]["ids"][part.model_part->name] = part.model_part->ids;
    }
  }
  for (int step = 1; step <= kSteps; ++step) {
    const StepRecord r = make_record(step);
    fill(interfaces, step);
    e["step"].push_back(r.step);
    e["time"].push_back(r.time);
    e["iterations"].push_back(r.iterations);
    e["converged"].push_back(r.converged ? 1 : 0);
    e["wall_time"].push_back(r.wall_time);
    e["coupler_time"].push_back(r.coupler_time);
    e["solver_times"].push_back(r.solver_times);
    e["residuals"].push_back(r.residual_norms);
    const auto& x = interfaces.x.data();
    const auto& y = interfaces.y.data();
    e["x"]["data"].push_back(std::vector<double>(x.data(), x.data() + x.size()));
    e["y"]["data"].push_back(std::vector<double>(y.data(), y.data() + y.size()));
  }
  return e;
}

class ResultsPythonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test_directory();
    results_ = dir_ / "run.h5";
    write_run(results_, kSteps);
    std::ofstream(dir_ / "expected.json") << expected_values().dump(1);
  }
  /// Runs /usr/bin/python3 with a private matplotlib cache (the home directory may be
  /// read-only in CI, and a shared cache would race between parallel tests).
  Output python(const std::string& arguments) const {
    return run("MPLCONFIGDIR=" + quoted(dir_ / "mpl") + " " + kPython + " " + arguments);
  }
  std::filesystem::path dir_, results_;
};

TEST_F(ResultsPythonTest, H5pyAndMatplotlibAreInstalled) {
  const std::string why = missing("h5py, matplotlib");
  EXPECT_TRUE(why.empty()) << why;
}

TEST_F(ResultsPythonTest, H5pyReadsTheDocumentedLayout) {
  const std::string why = missing("h5py");
  ASSERT_TRUE(why.empty()) << why;
  const auto script = source_dir() / "tests/unit/coupler/results/read_results.py";
  const Output out = python(quoted(script) + " " + quoted(results_) + " --expect " +
                            quoted(dir_ / "expected.json"));
  EXPECT_EQ(out.status, 0) << out.text;
  EXPECT_NE(out.text.find(": OK"), std::string::npos) << out.text;
}

TEST_F(ResultsPythonTest, H5pyReadsACopyOfAFileStillBeingWritten) {
  const std::string why = missing("h5py");
  ASSERT_TRUE(why.empty()) << why;
  const auto open_file = dir_ / "open.h5";
  auto writer = write_run(open_file, 3, "");
  std::filesystem::copy_file(open_file, dir_ / "copy.h5");
  const auto script = source_dir() / "tests/unit/coupler/results/read_results.py";
  const Output out = python(quoted(script) + " " + quoted(dir_ / "copy.h5"));
  EXPECT_EQ(out.status, 0) << out.text;
  // The writer holds an HDF5 file lock; readers that skip it see every flushed step.
  const Output live =
      python("-c " +
             quoted("import h5py, sys; f = h5py.File(sys.argv[1], 'r', locking=False); "
                    "assert f['steps/step'].shape == (3,), f['steps/step'].shape") +
             " " + quoted(open_file));
  EXPECT_EQ(live.status, 0) << live.text;
}

TEST_F(ResultsPythonTest, PlotScriptWritesAPng) {
  const std::string why = missing("h5py, matplotlib");
  ASSERT_TRUE(why.empty()) << why;
  const auto script = source_dir() / "scripts/plot_results.py";
  const Output help = python(quoted(script) + " --help");
  EXPECT_EQ(help.status, 0) << help.text;
  EXPECT_NE(help.text.find("--steps"), std::string::npos) << help.text;

  const auto png = dir_ / "plot.png";
  const Output out =
      python(quoted(script) + " " + quoted(results_) + " --steps 1 5 10 -o " + quoted(png));
  ASSERT_EQ(out.status, 0) << out.text;
  std::ifstream in(png, std::ios::binary);
  char magic[8] = {};
  in.read(magic, sizeof magic);
  EXPECT_EQ(std::string(magic, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << png;

  const Output missing_step = python(quoted(script) + " " + quoted(results_) + " --steps 99");
  EXPECT_NE(missing_step.status, 0);
  EXPECT_NE(missing_step.text.find("1 .. 12"), std::string::npos) << missing_step.text;
}

}  // namespace
}  // namespace cocopp::test
