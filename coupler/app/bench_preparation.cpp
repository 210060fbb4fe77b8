#include "coupler/app/bench_preparation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>

#include "core/case/settings.hpp"
#include "core/case/suggest.hpp"
#include "coupler/app/case.hpp"
#include "coupler/results/run_files.hpp"

namespace cocopp {

namespace {

/// The base case's coupled solver with the bench file's tight criterion: a converged solution
/// to compare with; an iteration limit of 100 too, so that a reference that cannot get there
/// still ends.
YAML::Node reference_coupled_solver(const YAML::Node& base, const BenchFile& bench) {
  YAML::Node criterion = YAML::Load("{type: or}");
  criterion["criteria"].push_back(YAML::Clone(bench.reference_criterion));
  criterion["criteria"].push_back(YAML::Load("{type: iteration_limit, maximum: 100}"));
  YAML::Node out = YAML::Clone(base);
  out["convergence_criterion"] = criterion;
  return out;
}

/// The solvers' working directories, relative to the base case's directory.
std::vector<fs::path> working_directories(const YAML::Node& base_case) {
  std::vector<fs::path> dirs;
  for (const auto& wrapper : base_case["solver_wrappers"])
    if (wrapper.IsMap() && wrapper["working_directory"])
      dirs.emplace_back(wrapper["working_directory"].as<std::string>());
  return dirs;
}

/// Copy the base case's directory without what earlier runs left there (results, solver
/// output, logs), so that every run starts from the same inputs in its own directories.
void copy_case_directory(const fs::path& from, const fs::path& to,
                         const std::vector<fs::path>& skip) {
  fs::create_directories(to);
  for (auto it = fs::recursive_directory_iterator(from); it != fs::recursive_directory_iterator();
       ++it) {
    const fs::path relative = fs::relative(it->path(), from);
    const bool skipped =
        std::any_of(skip.begin(), skip.end(),
                    [&](const fs::path& s) { return fs::equivalent(s, it->path()); }) ||
        (it->is_regular_file() && it->path().extension() == ".log");
    if (skipped) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_directory())
      fs::create_directories(to / relative);
    else
      fs::copy_file(it->path(), to / relative, fs::copy_options::overwrite_existing);
  }
}

std::vector<fs::path> paths_not_to_copy(const BenchFile& bench, const YAML::Node& base_case) {
  const fs::path base_dir = bench.base_case.parent_path();
  std::vector<fs::path> skip;
  auto add = [&](const fs::path& p) {
    if (fs::exists(p)) skip.push_back(p);
  };
  std::string results = "results";
  if (base_case["settings"] && base_case["settings"]["results_directory"])
    results = base_case["settings"]["results_directory"].as<std::string>();
  if (!bench.start_from_state) add(base_dir / results);  // else the state every run continues
  for (const fs::path& w : working_directories(base_case)) add(base_dir / w / "output");
  add(bench.output_directory);  // an output directory inside the base case's directory
  return skip;
}

/// Working directories outside the base case's directory would not be copied, and sharing
/// them between runs would mix the runs' files.
void check_working_directories(const YAML::Node& base_case, const fs::path& base_file) {
  for (const fs::path& w : working_directories(base_case)) {
    const fs::path normal = w.lexically_normal();
    if (normal.is_absolute() || (!normal.empty() && *normal.begin() == ".."))
      throw CaseError(fmt::format(
          "{}: solver working directory '{}' lies outside the case's directory; cocopp bench "
          "copies that directory for every run, so keep the working directories inside it",
          base_file.string(), w.string()));
  }
}

/// The name a solver wrapper of a case goes by: its `name`, or its type.
std::string wrapper_name(const YAML::Node& wrapper) {
  if (wrapper["name"]) return wrapper["name"].as<std::string>();
  return wrapper["type"] ? wrapper["type"].as<std::string>() : std::string();
}

/// The base case's solver wrappers with the `solver_wrappers` changes (of the bench file, the
/// case and the run, in that order) merged into the one of each name.
YAML::Node changed_solver_wrappers(const BenchFile& bench, const YAML::Node& wrappers,
                                   const std::vector<const Changes*>& all_changes) {
  YAML::Node out = YAML::Clone(wrappers);
  if (!out.IsSequence()) return out;  // the case's own check reports it
  std::vector<std::string> names;
  for (const auto& wrapper : out) names.push_back(wrapper_name(wrapper));
  for (const Changes* changes : all_changes)
    for (const auto& entry : changes->solver_wrappers) {
      const std::string name = entry.first.as<std::string>();
      const auto found = std::find(names.begin(), names.end(), name);
      if (found == names.end())
        throw CaseError(fmt::format(
            "{}: solver_wrappers: the base case has no solver wrapper named '{}'{}; its solver "
            "wrappers are {}",
            bench.file.string(), name, did_you_mean(name, names), join(names)));
      const auto index = static_cast<std::size_t>(found - names.begin());
      out[index] = deep_merge(out[index], entry.second);
    }
  return out;
}

std::vector<SolverInput> solver_inputs(const BenchFile& bench, const BenchCase& bench_case,
                                       const Changes& run) {
  std::vector<SolverInput> all = bench.changes.solver_inputs;
  all.insert(all.end(), bench_case.changes.solver_inputs.begin(),
             bench_case.changes.solver_inputs.end());
  all.insert(all.end(), run.solver_inputs.begin(), run.solver_inputs.end());
  return all;
}

/// Write <output_directory>/[<case>/]<name>/case.yaml next to a fresh copy of the base case's
/// files, with the solver inputs changed as the bench file says.
PlannedRun prepare_run(const BenchFile& bench, const YAML::Node& base_case,
                       const BenchCase& bench_case, const std::string& name,
                       const YAML::Node& coupled_solver, const Changes& run) {
  const fs::path dir = bench.output_directory / bench_case.name / name;
  fs::remove_all(dir);
  copy_case_directory(bench.base_case.parent_path(), dir, paths_not_to_copy(bench, base_case));
  YAML::Node c = YAML::Clone(base_case);
  c["coupled_solver"] = coupled_solver;
  c["solver_wrappers"] = changed_solver_wrappers(bench, base_case["solver_wrappers"],
                                                 {&bench.changes, &bench_case.changes, &run});
  // Nested, not by assigning to a YAML::Node: that would write through into base_case.
  YAML::Node s = deep_merge(deep_merge(deep_merge(base_case["settings"], bench.changes.settings),
                                       bench_case.changes.settings),
                            run.settings);
  s["results_directory"] = "results";
  s["results_name"] = "case";
  c["settings"] = s;
  YAML::Emitter out;
  out << c;
  const fs::path file = dir / "case.yaml";
  std::ofstream(file) << "# written by cocopp bench from " << bench.file.string() << "\n"
                      << out.c_str() << "\n";
  return {bench_case.name, name, file,
          apply_solver_inputs(file, solver_inputs(bench, bench_case, run)), bench.start_from_state};
}

}  // namespace

/// start_from_state: every run continues the base case's state, in the results location
/// every bench run has (results/case).
void check_saved_state(const YAML::Node& base_case, const BenchFile& bench) {
  const YAML::Node settings = base_case["settings"];
  const auto setting = [&](const char* key, const std::string& fallback) {
    return settings && settings[key] ? settings[key].as<std::string>() : fallback;
  };
  const std::string directory = setting("results_directory", "results");
  const std::string name = setting("results_name", "case");
  if (fs::path(directory).lexically_normal() != fs::path("results") || name != "case")
    throw CaseError(fmt::format(
        "{}: start_from_state: the base case writes its results as {}/{}; the bench's runs "
        "continue them as results/case: run the base case with the default results_directory "
        "and results_name",
        bench.file.string(), directory, name));
  const fs::path state =
      RunFiles{bench.base_case.parent_path() / directory, name}.state().lexically_normal();
  if (!fs::is_regular_file(state))
    throw CaseError(
        fmt::format("{}: start_from_state: no saved state {} (run the base case "
                    "first; it saves one at its end and every state_interval steps)",
                    bench.file.string(), state.string()));
}

std::vector<PlannedRun> prepare_runs(const BenchFile& bench) {
  const YAML::Node base = YAML::LoadFile(bench.base_case.string());
  check_working_directories(base, bench.base_case);
  if (bench.start_from_state) check_saved_state(base, bench);
  std::vector<PlannedRun> runs;
  for (const BenchCase& c : bench.cases) {
    if (bench.reference == ReferenceKind::kComputed)
      runs.push_back(prepare_run(bench, base, c, kReferenceName,
                                 reference_coupled_solver(base["coupled_solver"], bench),
                                 bench.reference_changes));
    for (const Variant& v : bench.variants)
      runs.push_back(prepare_run(bench, base, c, v.name,
                                 merge_coupled_solver(base["coupled_solver"], v.coupled_solver),
                                 v.changes));
  }
  for (const PlannedRun& run : runs) {
    const Case c = load_case(run.case_file);
    for (const auto& solver : c.solvers) solver->check();
  }
  return runs;
}

}  // namespace cocopp
