#include "coupler/app/bench_file.hpp"

#include <fmt/format.h>

#include <regex>
#include <set>

#include "core/case/settings.hpp"

namespace cocopp {

namespace {

/// A mapping given as is (merged into a case later, where the case's own checks read it).
YAML::Node raw_mapping(const Settings& s, const std::string& key) {
  if (!s.has(key)) return YAML::Node();
  s.allow(key);
  const YAML::Node node = s.node()[key];
  if (!node.IsMap()) s.fail(key, "must be a mapping");
  return YAML::Clone(node);
}

/// `solver_inputs: {<solver name>: {<key>: <value>, ...}, ...}`; the names are checked against
/// the base case's solvers when the runs are prepared.
std::vector<SolverInput> read_solver_inputs(const Settings& s) {
  std::vector<SolverInput> inputs;
  if (!s.has("solver_inputs")) return inputs;
  const Settings block = s.child("solver_inputs");
  for (const auto& entry : block.node()) {
    const std::string solver = entry.first.as<std::string>();
    block.allow(solver);
    if (!entry.second.IsMap())
      block.fail(solver, "must be a mapping: keys of the solver's input file and their values");
    inputs.push_back({solver, YAML::Clone(entry.second), block.where(solver)});
  }
  return inputs;
}

/// `solver_wrappers: {<name>: {<key>: <value>, ...}}`; the names are checked against the base
/// case's solver wrappers when the runs are prepared.
YAML::Node read_solver_wrappers(const Settings& s) {
  const YAML::Node changes = raw_mapping(s, "solver_wrappers");
  for (const auto& entry : changes)
    if (!entry.second.IsMap())
      s.child("solver_wrappers")
          .fail(entry.first.as<std::string>(),
                "must be a mapping: keys of the solver wrapper and their values");
  return changes;
}

Changes read_changes(const Settings& s) {
  return {raw_mapping(s, "settings"), read_solver_inputs(s), read_solver_wrappers(s)};
}

/// A case or variant name: it becomes a directory name and a table entry.
std::string read_name(const Settings& s, std::set<std::string>& names) {
  const std::string name = s.required<std::string>("name");
  if (!std::regex_match(name, std::regex("[A-Za-z0-9_.+-]+")) || name == "." || name == "..")
    s.fail("name", "'" + name + "' must be letters, digits and _ . + - only");
  if (name == kReferenceName)
    s.fail("name", "'reference' is the name of the computed reference run; choose another");
  if (!names.insert(name).second) s.fail("name", "'" + name + "' is used twice");
  return name;
}

Variant read_variant(const Settings& s, std::set<std::string>& names) {
  Variant v;
  v.name = read_name(s, names);
  v.coupled_solver = raw_mapping(s, "coupled_solver");
  v.changes = read_changes(s);
  return v;
}

BenchCase read_case(const Settings& s, std::set<std::string>& names) {
  BenchCase c;
  c.name = read_name(s, names);
  c.changes = read_changes(s);
  return c;
}

/// `reference: none`, `reference: {results: file}`, `reference: {convergence_criterion: c}` or
/// `reference: {tolerance: t}` (default).
void read_reference(const Settings& root, BenchFile& b) {
  const YAML::Node node = root.node()["reference"];
  if (node && node.IsScalar()) {
    root.allow("reference");
    if (node.as<std::string>() != "none")
      root.fail("reference",
                "must be 'none' or a mapping with 'results', 'tolerance' or "
                "'convergence_criterion'");
    b.reference = ReferenceKind::kNone;
    return;
  }
  const Settings reference = root.child_or_empty("reference");
  if (reference.has("results")) {
    b.reference = ReferenceKind::kGiven;
    b.reference_results = root.base_directory() / reference.required<std::string>("results");
    if (!fs::is_regular_file(b.reference_results))
      reference.fail("results", "no such file: " + b.reference_results.string());
    if (reference.has("tolerance"))
      reference.fail("tolerance", "give either 'results' or 'tolerance', not both");
    if (reference.has("settings"))
      reference.fail("settings",
                     "changes the reference cocopp bench computes; a given one is "
                     "as it was run");
  } else if (reference.has("convergence_criterion")) {
    // Where solver noise sets a floor, a relative tolerance on the step's first residual is
    // either unreachable or loose: the user then states the reference's criterion outright.
    if (reference.has("tolerance"))
      reference.fail("tolerance", "give either 'convergence_criterion' or 'tolerance', not both");
    reference.allow("convergence_criterion");
    const YAML::Node criterion = reference.node()["convergence_criterion"];
    if (!criterion.IsMap())
      reference.fail(
          "convergence_criterion",
          "must be a criterion's mapping, e.g. {type: absolute_norm, tolerance: 1.0e-9}");
    b.reference_criterion = YAML::Clone(criterion);
  } else {
    b.reference_criterion =
        YAML::Load(fmt::format("{{type: relative_norm, tolerance: {:.17g}}}",
                               reference.get_in_range("tolerance", 1e-10, Range::positive())));
  }
  if (b.reference == ReferenceKind::kComputed)
    b.reference_changes.settings = raw_mapping(reference, "settings");
}

}  // namespace

BenchFile read_bench_file(const fs::path& file) {
  const Settings root = Settings::load_file(file);
  BenchFile b;
  b.file = file;
  const fs::path dir = root.base_directory();
  b.base_case = dir / root.required<std::string>("base_case");
  if (!fs::is_regular_file(b.base_case))
    root.fail("base_case", "no such file: " + b.base_case.string());
  b.output_directory = dir / root.get<std::string>("output_directory", "results/bench");
  read_reference(root, b);
  b.start_from_state = root.get<bool>("start_from_state", false);
  b.changes = read_changes(root);
  std::set<std::string> names;
  for (const Settings& v : root.list("variants")) b.variants.push_back(read_variant(v, names));
  if (b.variants.empty()) root.fail("variants", "needs at least one variant");
  if (root.has("cases")) {
    std::set<std::string> case_names;
    for (const Settings& c : root.list("cases")) b.cases.push_back(read_case(c, case_names));
    if (b.cases.empty()) root.fail("cases", "needs at least one case (or leave 'cases' out)");
  } else {
    b.cases.push_back(BenchCase{});  // the base case as it is
  }
  root.check_unused_keys();
  return b;
}

std::string run_label(const std::string& case_name, const std::string& name) {
  return case_name.empty() ? name : case_name + "/" + name;
}

/// The results file each case's runs are compared with (none for `reference: none`).
fs::path reference_of(const BenchFile& bench, const std::string& case_name) {
  switch (bench.reference) {
    case ReferenceKind::kGiven:
      return bench.reference_results;
    case ReferenceKind::kComputed:
      return bench.output_directory / case_name / kReferenceName / "results" / "case.h5";
    case ReferenceKind::kNone:
      break;
  }
  return {};
}

}  // namespace cocopp
