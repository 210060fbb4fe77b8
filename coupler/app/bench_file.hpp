#pragma once
// `cocopp bench`, part 1: the bench file (docs/bench.md): the base case, the reference, the
// changes made to every run, the cases of a sweep and the variants, read and checked.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

#include "coupler/app/bench_inputs.hpp"

namespace cocopp {

namespace fs = std::filesystem;

/// The name of the computed reference run of each case.
inline constexpr const char* kReferenceName = "reference";

/// What the bench file's top level, a case or a variant changes in the base case.
struct Changes {
  YAML::Node settings;  ///< merged into the base case's settings (may be null)
  std::vector<SolverInput> solver_inputs;
  /// `{<solver wrapper name>: {<key>: <value>}}`, merged into the base case's solver wrapper
  /// of that name (its `substeps`, say; may be null)
  YAML::Node solver_wrappers;
};

struct Variant {
  std::string name;
  YAML::Node coupled_solver;  ///< merged into the base case's coupled_solver (may be null)
  Changes changes;
};

/// One problem of a sweep (`cases`); a bench file without `cases` has one case without name.
struct BenchCase {
  std::string name;
  Changes changes;
};

enum class ReferenceKind { kComputed, kGiven, kNone };

struct BenchFile {
  fs::path file;
  fs::path base_case;
  fs::path output_directory;
  ReferenceKind reference = ReferenceKind::kComputed;
  fs::path reference_results;      ///< kGiven
  YAML::Node reference_criterion;  ///< kComputed: what the reference converges to
  /// kComputed: the reference's own `settings` (a finer delta_t: a fully resolved run, which
  /// the runs are compared with at their own steps)
  Changes reference_changes;
  Changes changes;  ///< applied to every run, the references included
  std::vector<BenchCase> cases;
  std::vector<Variant> variants;
  /// Every run continues the base case's saved state (results/case.state.h5) with its own
  /// coupled solver (cocopp run --restart --fresh-coupling): a window of a long run.
  bool start_from_state = false;
};

/// Read and check a bench file; throws CaseError naming the file, line and key.
BenchFile read_bench_file(const fs::path& file);

/// How the table and the messages name a run: "<case>/<variant>", or the variant without cases.
std::string run_label(const std::string& case_name, const std::string& name);

/// The results file each case's runs are compared with (empty for `reference: none`).
fs::path reference_of(const BenchFile& bench, const std::string& case_name);

}  // namespace cocopp
