#include "tests/integration/run_helpers.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "coupler/results/results_reader.hpp"

namespace cocopp::testing {

namespace fs = std::filesystem;

CommandResult run_command(const std::string& command) {
  CommandResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

CommandResult run_cocopp(const std::string& arguments) {
  return run_command((fs::path(COCOPP_TEST_BIN_DIR) / "cocopp").string() + " " + arguments);
}

fs::path copy_example(const std::string& example, const std::string& tag) {
  const fs::path source = fs::path(COCOPP_TEST_SOURCE_DIR) / "examples" / example;
  const fs::path target =
      fs::temp_directory_path() / ("cocopp_test_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(target);
  fs::create_directories(target);
  for (auto entry = fs::recursive_directory_iterator(source);
       entry != fs::recursive_directory_iterator(); ++entry) {
    const std::string name = entry->path().filename().string();
    const bool run_product = name == "results" || name == "output" || name == "restart" ||
                             name == ".cocopp.lock" || entry->path().extension() == ".log" ||
                             entry->path().extension() == ".fifo";
    if (run_product) {
      entry.disable_recursion_pending();
      continue;
    }
    const fs::path copy = target / fs::relative(entry->path(), source);
    if (entry->is_directory())
      fs::create_directories(copy);
    else
      fs::copy_file(entry->path(), copy);
  }
  return target;
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  return nlohmann::json::parse(in);
}

std::vector<double> read_dataset(const fs::path& file, const std::string& name) {
  return ResultsReader(file).dataset(name).values;
}

void edit(const std::filesystem::path& file, const std::string& from, const std::string& to) {
  std::string text = read_text(file);
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " not in " << file;
  text.replace(at, from.size(), to);
  write_text(file, text);
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double difference = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    difference += (a[i] - b[i]) * (a[i] - b[i]);
    norm += a[i] * a[i];
  }
  return std::sqrt(difference / norm);
}

void use_solver_coupling_convergence(const std::filesystem::path& case_file) {
  edit(case_file, "      - type: relative_norm\n        tolerance: 1.0e-6\n",
       "      - type: and\n"
       "        criteria:\n"
       "          - {type: solver_coupling_convergence, solver_index: 0}\n"
       "          - {type: solver_coupling_convergence, solver_index: 1}\n");
}

}  // namespace cocopp::testing
