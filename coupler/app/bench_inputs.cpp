#include "coupler/app/bench_inputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>

#include "core/case/settings.hpp"
#include "core/case/suggest.hpp"
#include "coupler/app/case.hpp"

namespace cocopp {

namespace fs = std::filesystem;

namespace {

bool other_type(const YAML::Node& base, const YAML::Node& override) {
  return base["type"] && override["type"] &&
         base["type"].as<std::string>() != override["type"].as<std::string>();
}

/// Merge the solver's `inputs` (in order) into its input file in the run's directory. Unknown
/// keys are not checked here: the solver reports them, with file and line, when it reads the
/// file; the comment on top says where the new values came from.
void merge_into_input_file(const fs::path& file, const std::vector<const SolverInput*>& inputs) {
  YAML::Node merged;
  try {
    merged = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    throw CaseError(
        fmt::format("{}: solver_inputs: cannot read the input file of solver '{}', {}: "
                    "{}",
                    inputs.front()->where, inputs.front()->solver, file.string(), e.what()));
  }
  if (!merged.IsMap())
    throw CaseError(
        fmt::format("{}: solver_inputs: the input file of solver '{}', {}, is not a "
                    "YAML mapping, so no keys can be merged into it",
                    inputs.front()->where, inputs.front()->solver, file.string()));
  std::string origin;
  for (const SolverInput* input : inputs) {
    merged = deep_merge(merged, input->values);
    origin += "\n#   solver_inputs." + input->solver + " of " + input->where;
  }
  YAML::Emitter out;
  out << merged;
  std::ofstream(file) << "# written by cocopp bench: " << file.filename().string()
                      << " of the base case with" << origin << "\n"
                      << out.c_str() << "\n";
}

}  // namespace

/// Keys given in `override` replace those of `base`, recursively for mappings; the rest of
/// `base` is kept. Lists are replaced whole, and so is a mapping of another `type` (the keys
/// of an `ls` model mean nothing to an `mvmf` model).
YAML::Node deep_merge(const YAML::Node& base, const YAML::Node& override) {
  if (!override || override.IsNull()) return YAML::Clone(base);
  if (!base || !base.IsMap() || !override.IsMap() || other_type(base, override))
    return YAML::Clone(override);
  YAML::Node out = YAML::Clone(base);
  for (const auto& entry : override) {
    const std::string key = entry.first.as<std::string>();
    const YAML::Node old = base[key];
    out[key] = old ? deep_merge(old, entry.second) : YAML::Clone(entry.second);
  }
  return out;
}

/// A variant of another coupled-solver type keeps only the keys every coupled solver reads
/// (the base's model or omega would be unknown keys of, say, aitken).
YAML::Node merge_coupled_solver(const YAML::Node& base, const YAML::Node& override) {
  if (!override || !base || !other_type(base, override)) return deep_merge(base, override);
  YAML::Node common(YAML::NodeType::Map);
  common["type"] = YAML::Clone(override["type"]);  // first, for whoever reads the case
  for (const char* key : {"predictor", "convergence_criterion", "divergence"})
    if (base[key]) common[key] = YAML::Clone(base[key]);
  return deep_merge(common, override);
}

/// Apply solver_inputs to the input files of the solvers of the run's case. Returns, for the
/// notes of a run that fails, which files were changed and from where.
std::string apply_solver_inputs(const fs::path& case_file, const std::vector<SolverInput>& inputs) {
  if (inputs.empty()) return "";
  const Case c = load_case(case_file);
  std::vector<std::string> names;
  for (const auto& solver : c.solvers) names.push_back(solver->name());
  for (const SolverInput& input : inputs)
    if (std::find(names.begin(), names.end(), input.solver) == names.end())
      throw CaseError(
          fmt::format("{}: solver_inputs: the base case has no solver named '{}'{}; "
                      "its solvers are {}",
                      input.where, input.solver, did_you_mean(input.solver, names), join(names)));
  std::string changed;
  for (const auto& solver : c.solvers) {
    std::vector<const SolverInput*> mine;
    for (const SolverInput& input : inputs)
      if (input.solver == solver->name()) mine.push_back(&input);
    if (mine.empty()) continue;
    const fs::path file = solver->input_file();
    if (file.empty())
      throw CaseError(fmt::format(
          "{}: solver_inputs: cocopp does not know the input file of solver '{}' (a solver with "
          "its own 'command'); solver_inputs need a solver type with an input_file",
          mine.front()->where, solver->name()));
    merge_into_input_file(file, mine);
    std::vector<std::string> wheres;
    for (const SolverInput* input : mine) wheres.push_back(input->where);
    changed += fmt::format("{}{} (solver_inputs.{} of {})", changed.empty() ? "" : ", ",
                           file.string(), solver->name(), join(wheres));
  }
  return changed;
}

}  // namespace cocopp
