#include "coupler/app/bench_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "coupler/app/plot.hpp"

namespace cocopp {

namespace {

std::string format_number(double value, const char* format = "{:.3g}") {
  return std::isfinite(value) ? fmt::format(fmt::runtime(format), value) : "-";
}

/// "converged", "stalled 20", "diverged"; the reasons follow below the table.
std::string short_outcome(const BenchRow& r) {
  return r.outcome == "stalled" ? fmt::format("stalled {}", r.unconverged_steps) : r.outcome;
}

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json to_json(const BenchRow& r) {
  return {{"case", r.case_name},
          {"name", r.name},
          {"coupled_solver", r.coupled_solver},
          {"status", r.status},
          {"completed", r.completed},
          {"message", r.message},
          {"steps_completed", r.steps_completed},
          {"average_iterations", number_or_null(r.average_iterations)},
          {"maximum_iterations", r.maximum_iterations},
          {"solver_calls", r.solver_calls},
          {"wall_time", number_or_null(r.wall_time)},
          {"coupler_time", number_or_null(r.coupler_time)},
          {"solver_time", number_or_null(r.solver_time)},
          {"displacement_error", number_or_null(r.displacement_error)},
          {"pressure_error", number_or_null(r.pressure_error)},
          {"note", r.note},
          {"outcome", r.outcome},
          {"reason", r.reason},
          {"unconverged_steps", r.unconverged_steps}};
}

const std::vector<std::string> kColumns = {"name",
                                           "coupled_solver",
                                           "status",
                                           "completed",
                                           "message",
                                           "steps_completed",
                                           "average_iterations",
                                           "maximum_iterations",
                                           "solver_calls",
                                           "wall_time",
                                           "coupler_time",
                                           "displacement_error",
                                           "pressure_error",
                                           "note",
                                           "case",
                                           "outcome",
                                           "reason",
                                           "unconverged_steps",
                                           "solver_time"};

std::string csv_field(const nlohmann::json& value) {
  if (value.is_null()) return "";
  if (!value.is_string()) return value.dump();
  std::string text = value.get<std::string>();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::string label(const BenchRow& r) {
  return run_label(r.case_name, r.name);
}

void print_table(const std::vector<BenchRow>& rows) {
  std::size_t case_width = 0, width = 7;
  for (const auto& r : rows) {
    case_width = std::max(case_width, r.case_name.size());
    width = std::max(width, r.name.size());
  }
  if (case_width > 0) case_width = std::max<std::size_t>(case_width, 4) + 2;
  const std::string case_header = case_width > 0 ? "case" : "";
  fmt::print("\n{:<{}}{:<{}}  {:<12} {:<13} {:>5} {:>7} {:>6} {:>7} {:>9} {:>11} {:>10} {:>10}\n",
             case_header, case_width, "variant", width, "solver", "status", "steps", "avg it",
             "max it", "calls", "wall [s]", "coupler [s]", "displ err", "press err");
  for (const auto& r : rows)
    fmt::print("{:<{}}{:<{}}  {:<12} {:<13} {:>5} {:>7} {:>6} {:>7} {:>9} {:>11} {:>10} {:>10}\n",
               r.case_name, case_width, r.name, width, r.coupled_solver, short_outcome(r),
               r.steps_completed, format_number(r.average_iterations, "{:.2f}"),
               r.maximum_iterations, r.solver_calls, format_number(r.wall_time, "{:.3f}"),
               format_number(r.coupler_time, "{:.4f}"), format_number(r.displacement_error),
               format_number(r.pressure_error));
  for (const auto& r : rows) {
    if (!r.completed && !r.message.empty())
      fmt::print("  {}: {} ({}): {}\n", label(r), r.status, r.reason, r.message);
    if (!r.note.empty()) fmt::print("  {}: {}\n", label(r), r.note);
  }
}

void write_outputs(const BenchFile& bench, const nlohmann::json& reference,
                   const std::vector<BenchRow>& rows) {
  nlohmann::json runs = nlohmann::json::array();
  std::ofstream csv(bench.output_directory / "bench.csv");
  for (std::size_t i = 0; i < kColumns.size(); ++i) csv << (i ? "," : "") << kColumns[i];
  csv << "\n";
  for (const auto& r : rows) {
    const nlohmann::json j = to_json(r);
    runs.push_back(j);
    for (std::size_t i = 0; i < kColumns.size(); ++i)
      csv << (i ? "," : "") << csv_field(j[kColumns[i]]);
    csv << "\n";
  }
  const nlohmann::json document = {{"bench_file", bench.file.string()},
                                   {"base_case", bench.base_case.string()},
                                   {"reference", reference},
                                   {"runs", runs}};
  std::ofstream(bench.output_directory / "bench.json") << document.dump(2) << "\n";
}

void plot(const BenchFile& bench) {
  const fs::path script = shared_script("plot_bench.py");
  const std::string command = fmt::format("/usr/bin/python3 {} {} -o {}", quote(script.string()),
                                          quote((bench.output_directory / "bench.json").string()),
                                          quote((bench.output_directory / "bench.png").string()));
  std::fflush(stdout);
  if (std::system(command.c_str()) != 0)
    fmt::print(stderr, "warning: the plot failed; draw it by hand with\n  {}\n", command);
  else
    fmt::print("plot     : {}\n", (bench.output_directory / "bench.png").string());
}

/// bench.json's `reference`: the results file, "none", or one file per case of a sweep.
nlohmann::json describe_references(const BenchFile& bench) {
  if (bench.reference == ReferenceKind::kNone) return "none";
  if (bench.cases.size() == 1) return reference_of(bench, bench.cases.front().name).string();
  nlohmann::json by_case = nlohmann::json::object();
  for (const BenchCase& c : bench.cases) by_case[c.name] = reference_of(bench, c.name).string();
  return by_case;
}

}  // namespace cocopp
