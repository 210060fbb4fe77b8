#pragma once
// What cocopp bench changes in a run's inputs: the base case's sections merged with the bench
// file's (deep merge), and `solver_inputs` merged into the solvers' own input files
// (docs/bench.md, "Merging" and "Solver inputs").
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

namespace cocopp {

/// New values for keys of one solver's input file, given at one place of the bench file.
struct SolverInput {
  std::string solver;  ///< the solver wrapper's `name` in the base case
  YAML::Node values;   ///< merged into the solver's input file
  std::string where;   ///< "bench.yaml:12:7", for messages
};

/// Keys given in `override` replace those of `base`, recursively for mappings; the rest of
/// `base` is kept. Lists are replaced whole, and so is a mapping of another `type`.
YAML::Node deep_merge(const YAML::Node& base, const YAML::Node& override);

/// deep_merge, except that an override of another coupled-solver type keeps only the keys every
/// coupled solver reads (predictor, convergence_criterion, divergence).
YAML::Node merge_coupled_solver(const YAML::Node& base, const YAML::Node& override);

/// Merge `inputs` into the input files of the solvers of the case in `case_file` (the run's
/// copy). Throws CaseError, naming the bench file's line, for a solver the case does not have or
/// one whose input file cocopp does not know. Returns which files were changed and from where.
std::string apply_solver_inputs(const std::filesystem::path& case_file,
                                const std::vector<SolverInput>& inputs);

}  // namespace cocopp
