// The `cocopp` command: run, check, bench, plot and list what a case file can name.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "coupler/app/bench.hpp"
#include "coupler/app/components.hpp"
#include "coupler/app/export_vtk.hpp"
#include "coupler/app/plot.hpp"
#include "coupler/app/run.hpp"

int main(int argc, char** argv) {
  // `cocopp plot FILE ...`: everything after the file is the script's, --help included (CLI11
  // would take that as the subcommand's own).
  if (argc >= 3 && std::string(argv[1]) == "plot" && argv[2][0] != '-' &&
      std::filesystem::is_regular_file(argv[2]))
    return cocopp::plot_file(argv[2], std::vector<std::string>(argv + 3, argv + argc));
  using cocopp::documentation;
  CLI::App app{
      "cocopp: partitioned fluid-structure interaction.\n"
      "A coupler process drives two solver executables (the first maps interface displacement "
      "to loads, the second loads to displacement) and iterates every time step until they "
      "agree. Everything is set in one case file (YAML or JSON); see " +
      documentation("case-file.md") + "."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cocopp " COCOPP_VERSION);

  std::string case_file;
  cocopp::RunOptions options;
  auto* run = app.add_subcommand(
      "run",
      "Run a case: start the solvers, march in time with the coupled solver, write "
      "<results_directory>/<name>.h5 (HDF5, " +
          documentation("results.md") +
          ") and <name>.summary.json. Prints "
          "one progress line per time step (a * marks a step accepted at the iteration limit, a ~ "
          "one "
          "accepted there with the residual at the solvers' noise) and a timing summary. Exit code "
          "0: "
          "completed; 3: stalled (every step computed, some accepted at the iteration limit above "
          "the solvers' noise); 1: the run stopped (divergence, solver failure, interrupt, results "
          "that cannot "
          "be written; results so far are kept) or did not start (another run holds the case, the "
          "results location cannot be used); 2: invalid case file or command line.");
  run->add_option("case", case_file, "case file (.yaml, .yml or .json)")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_flag("-q,--quiet", options.quiet, "no progress line per time step");
  run->add_flag("-v,--verbose", options.verbose,
                "also one line per coupling iteration (residual, and the time into the step)");
  run->add_flag("--restart", options.restart,
                "continue a run from its saved state (<results_directory>/<name>.state.h5, "
                "written at the end of a run and every settings.state_interval steps) up to the "
                "case's end: the solvers restart from what they saved with it, the results file "
                "is continued after the saved step (" +
                    documentation("results.md") + ")");
  run->add_flag("--fresh-coupling", options.fresh_coupling,
                "with --restart: the coupled solver's own memory (secant columns, Aitken's "
                "factor, scaling) starts afresh and only the predictor's history is taken, so "
                "that another coupled solver can continue the run")
      ->needs("--restart");

  auto* check = app.add_subcommand(
      "check",
      "Validate a case file without running it: every key, type, range and component name, "
      "and that the solvers' working directories and executables exist. Exit code 0 if valid, "
      "2 otherwise, with an error naming the file, line and key.");
  check->add_option("case", case_file, "case file (.yaml, .yml or .json)")
      ->required()
      ->check(CLI::ExistingFile);

  std::string bench_file;
  cocopp::BenchOptions bench_options;
  auto* bench = app.add_subcommand(
      "bench",
      "Compare coupling algorithms on one case: run a base case with every variant of a "
      "benchmark file, and a tightly converged reference (or take a given results file), then "
      "print and write (bench.csv, bench.json, bench.png) iterations, run time and the error "
      "against the reference. Benchmark file (YAML/JSON): base_case: <case file>; "
      "output_directory: <dir> (default results/bench); reference: {results: <file.h5>} or "
      "{tolerance: 1e-10}; settings: {...} (merged into every run); variants: [{name: ..., "
      "coupled_solver: {...}, settings: {...}}, ...]. See " +
          documentation("bench.md") +
          ". Exit code 0: all runs "
          "made (diverging variants included); 1: stopped; 2: invalid file.");
  bench->add_option("bench", bench_file, "benchmark file (.yaml, .yml or .json)")
      ->required()
      ->check(CLI::ExistingFile);
  bool no_plot = false;
  bench->add_flag("--no-plot", no_plot, "do not draw bench.png");
  bool bench_quiet = false;
  bench->add_flag("-q,--quiet", bench_quiet,
                  "one line per run instead of each run's header and summary");

  std::string results_file;
  std::string vtk_directory;
  auto* export_vtk = app.add_subcommand(
      "export-vtk",
      "Write the interface of every time step of a results file for ParaView: one VTU file "
      "per model part and step (the points at their initial coordinates, the variables of x and "
      "y as point arrays) in <name>_vtk/, and the time series <name>.pvd next to them, as a run "
      "with settings.vtk_output: true writes them while it goes (" +
          documentation("results.md") +
          "). Exit code 0, "
          "or 1 if the file cannot be read or the files cannot be written.");
  export_vtk->add_option("results", results_file, "results file (<name>.h5)")
      ->required()
      ->check(CLI::ExistingFile);
  export_vtk->add_option("-o,--output-directory", vtk_directory,
                         "where to write (default: the results file's directory)");

  app.add_subcommand("components", "List the component types a case file can name.");

  std::string plot_target;
  auto* plot = app.add_subcommand(
      "plot",
      "Draw a results file (<name>.h5: the residuals, the interface at chosen steps, a "
      "space-time map; scripts/plot_results.py) or a bench's bench.json (error against time; "
      "scripts/plot_bench.py) with the script installed with cocopp, run by Debian's "
      "/usr/bin/python3. Options after the file go to the script: cocopp plot results/case.h5 "
      "--help lists them. Exit code: the script's; 2 for a file of another kind.");
  plot->add_option("file", plot_target, "results file (.h5) or bench.json")
      ->required()
      ->check(CLI::ExistingFile);
  plot->allow_extras();  // reached only without a file (main's first lines take the rest)

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end here with 0; a command-line error is invalid input, exit 2,
    // like an invalid case (CLI11's own codes, 105 and up, are not documented ones).
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (*run) return cocopp::run_case(case_file, options).outcome.exit_code();
  if (*check) return cocopp::check_case(case_file);
  if (*export_vtk) return cocopp::export_vtk(results_file, vtk_directory);
  if (*plot) return cocopp::plot_file(plot_target, plot->remaining());
  if (*bench) {
    bench_options.plot = !no_plot;
    bench_options.quiet = bench_quiet;
    return cocopp::run_bench(bench_file, bench_options);
  }
  cocopp::print_components();
  return 0;
}
