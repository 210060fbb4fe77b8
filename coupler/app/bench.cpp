#include "coupler/app/bench.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "core/case/settings.hpp"
#include "coupler/app/bench_inputs.hpp"
#include "coupler/app/case.hpp"
#include "coupler/app/run.hpp"

namespace cocopp {

namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const char* const kReferenceName = "reference";

/// What the bench file's top level, a case or a variant changes in the base case.
struct Changes {
  YAML::Node settings;  ///< merged into the base case's settings (may be null)
  std::vector<SolverInput> solver_inputs;
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
  fs::path reference_results;  ///< kGiven
  double reference_tolerance = 1e-10;
  Changes changes;  ///< applied to every run, the references included
  std::vector<BenchCase> cases;
  std::vector<Variant> variants;
};

/// One row of the table, bench.csv and bench.json.
struct RunResult {
  std::string case_name;  ///< empty without `cases`
  std::string name;
  std::string coupled_solver;
  std::string status = "not_run";
  std::string message;
  bool completed = false;
  int steps_completed = 0;
  double average_iterations = kNaN;
  int maximum_iterations = 0;
  long solver_calls = 0;
  double wall_time = kNaN;
  double coupler_time = kNaN;
  double displacement_error = kNaN;
  double pressure_error = kNaN;
  std::string note;
  /// converged, stalled (steps accepted at the iteration limit), diverged, solver_failed, ...
  std::string outcome;
  std::string reason;  ///< why it diverged or stalled, e.g. "residual growth in step 3"
  int unconverged_steps = 0;
};

// ---------------------------------------------------------------------------------------------
// The bench file

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

Changes read_changes(const Settings& s) {
  return {raw_mapping(s, "settings"), read_solver_inputs(s)};
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

/// `reference: none`, `reference: {results: file}` or `reference: {tolerance: t}` (default).
void read_reference(const Settings& root, BenchFile& b) {
  const YAML::Node node = root.node()["reference"];
  if (node && node.IsScalar()) {
    root.allow("reference");
    if (node.as<std::string>() != "none")
      root.fail("reference", "must be 'none' or a mapping with 'results' or 'tolerance'");
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
  } else {
    b.reference_tolerance = reference.get_in_range("tolerance", 1e-10, Range::positive());
  }
}

BenchFile read_bench_file(const fs::path& file) {
  const Settings root = Settings::load_file(file);
  BenchFile b;
  b.file = file;
  const fs::path dir = root.base_directory();
  b.base_case = dir / root.required<std::string>("base_case");
  if (!fs::is_regular_file(b.base_case))
    root.fail("base_case", "no such file: " + b.base_case.string());
  b.output_directory = dir / root.get<std::string>("output_directory", "bench_results");
  read_reference(root, b);
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

// ---------------------------------------------------------------------------------------------
// Building the case of one run

/// The base case's coupled solver with a tight tolerance: a converged solution to compare with.
YAML::Node reference_coupled_solver(const YAML::Node& base, double tolerance) {
  YAML::Node criterion =
      YAML::Load(fmt::format("{{type: or, criteria: [{{type: relative_norm, tolerance: {:.17g}}}, "
                             "{{type: iteration_limit, maximum: 100}}]}}",
                             tolerance));
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
  add(base_dir / results);
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

std::vector<SolverInput> solver_inputs(const BenchFile& bench, const BenchCase& bench_case,
                                       const Changes& run) {
  std::vector<SolverInput> all = bench.changes.solver_inputs;
  all.insert(all.end(), bench_case.changes.solver_inputs.begin(),
             bench_case.changes.solver_inputs.end());
  all.insert(all.end(), run.solver_inputs.begin(), run.solver_inputs.end());
  return all;
}

struct PlannedRun {
  std::string case_name;
  std::string name;
  fs::path case_file;
  std::string changed_inputs;  ///< input files changed by solver_inputs, and from where
};

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
          apply_solver_inputs(file, solver_inputs(bench, bench_case, run))};
}

// ---------------------------------------------------------------------------------------------
// Reading results

struct Field {
  std::vector<double> values;
  std::size_t row_size = 0;  ///< values per time step
};

/// What the error needs from a results file.
struct Results {
  double delta_t = kNaN;
  std::vector<int> steps;
  std::map<std::string, Field> displacement;  ///< by model part
  std::map<std::string, Field> pressure;
};

class H5File {
 public:
  explicit H5File(const fs::path& file) : id_(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {
    if (id_ < 0) throw std::runtime_error("cannot open " + file.string());
  }
  ~H5File() { H5Fclose(id_); }
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;
  hid_t id() const { return id_; }

 private:
  hid_t id_;
};

Field read_field(hid_t file, const std::string& name) {
  const hid_t dataset = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  if (dataset < 0) throw std::runtime_error("no dataset " + name);
  const hid_t space = H5Dget_space(dataset);
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 1)), 0);
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  Field f;
  f.values.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  f.row_size = dims[0] > 0 ? f.values.size() / dims[0] : 0;
  if (!f.values.empty())
    H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, f.values.data());
  H5Sclose(space);
  H5Dclose(dataset);
  return f;
}

std::vector<std::string> group_members(hid_t file, const std::string& group) {
  std::vector<std::string> names;
  if (H5Lexists(file, group.c_str(), H5P_DEFAULT) <= 0) return names;
  const hid_t g = H5Gopen2(file, group.c_str(), H5P_DEFAULT);
  H5G_info_t info;
  H5Gget_info(g, &info);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[1024] = {};
    H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof(name), H5P_DEFAULT);
    names.emplace_back(name);
  }
  H5Gclose(g);
  return names;
}

std::map<std::string, Field> read_variable(hid_t file, const std::string& group,
                                           const std::string& variable) {
  std::map<std::string, Field> fields;
  for (const std::string& part : group_members(file, group)) {
    const std::string name = group + "/" + part + "/" + variable;
    if (H5Lexists(file, (group + "/" + part).c_str(), H5P_DEFAULT) > 0 &&
        H5Lexists(file, name.c_str(), H5P_DEFAULT) > 0)
      fields[part] = read_field(file, name);
  }
  return fields;
}

Results read_results(const fs::path& path) {
  const H5File file(path);
  Results r;
  if (H5Aexists(file.id(), "delta_t") > 0) {
    const hid_t attribute = H5Aopen(file.id(), "delta_t", H5P_DEFAULT);
    H5Aread(attribute, H5T_NATIVE_DOUBLE, &r.delta_t);
    H5Aclose(attribute);
  }
  if (H5Lexists(file.id(), "steps", H5P_DEFAULT) > 0 &&
      H5Lexists(file.id(), "steps/step", H5P_DEFAULT) > 0) {
    const Field steps = read_field(file.id(), "steps/step");
    for (double s : steps.values) r.steps.push_back(static_cast<int>(s));
  }
  r.displacement = read_variable(file.id(), "x", "displacement");
  r.pressure = read_variable(file.id(), "y", "pressure");
  return r;
}

/// ||v - r|| / ||r|| over every model part and every time step both runs have; NaN if they
/// share no step or do not have the same parts and sizes.
double relative_error(const Results& v, const std::map<std::string, Field>& variant,
                      const Results& ref, const std::map<std::string, Field>& reference) {
  if (reference.empty() || variant.size() != reference.size()) return kNaN;
  std::map<int, std::size_t> reference_row;
  for (std::size_t i = 0; i < ref.steps.size(); ++i) reference_row[ref.steps[i]] = i;
  double difference = 0.0, norm = 0.0;
  bool any = false;
  for (const auto& [part, r] : reference) {
    const auto found = variant.find(part);
    if (found == variant.end() || found->second.row_size != r.row_size) return kNaN;
    const Field& f = found->second;
    for (std::size_t i = 0; i < v.steps.size(); ++i) {
      const auto row = reference_row.find(v.steps[i]);
      if (row == reference_row.end()) continue;
      const std::size_t a = i * f.row_size, b = row->second * r.row_size;
      if (a + f.row_size > f.values.size() || b + r.row_size > r.values.size()) continue;
      any = true;
      for (std::size_t k = 0; k < r.row_size; ++k) {
        const double d = f.values[a + k] - r.values[b + k];
        difference += d * d;
        norm += r.values[b + k] * r.values[b + k];
      }
    }
  }
  if (!any) return kNaN;
  if (norm == 0.0) return difference == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return std::sqrt(difference / norm);
}

void add_note(RunResult& result, const std::string& note) {
  result.note += (result.note.empty() ? "" : "; ") + note;
}

void compute_errors(RunResult& result, const fs::path& results_file, const Results& reference) {
  if (!fs::exists(results_file)) return add_note(result, "no results file");
  Results v;
  try {
    v = read_results(results_file);
  } catch (const std::exception& e) {
    return add_note(result, e.what());
  }
  if (v.steps.empty()) return;
  if (!(std::abs(v.delta_t - reference.delta_t) <= 1e-12 * std::abs(reference.delta_t)))
    return add_note(result, fmt::format("delta_t {:g} differs from the reference's {:g}: no error",
                                        v.delta_t, reference.delta_t));
  result.displacement_error = relative_error(v, v.displacement, reference, reference.displacement);
  result.pressure_error = relative_error(v, v.pressure, reference, reference.pressure);
  if (std::isnan(result.displacement_error)) add_note(result, "no step in common with reference");
}

/// converged / stalled / diverged (why) / solver_failed, from the summary's status and message.
/// The reason of a divergence is read from the coupler's message (coupled_solver.cpp): a
/// non-finite value a solver returned or a residual that became non-finite, else the residual's
/// growth (by the factor or persistently).
void classify(RunResult& result, int failed_step) {
  if (result.status == "completed") {
    result.outcome = result.unconverged_steps == 0 ? "converged" : "stalled";
    if (result.unconverged_steps > 0)
      result.reason = fmt::format("{} of {} steps at the iteration limit", result.unconverged_steps,
                                  result.steps_completed);
    return;
  }
  result.outcome = result.status;
  if (result.status == "diverged") {
    const std::string& m = result.message;
    const bool non_finite = m.find("non-finite") != std::string::npos ||
                            m.find("to nan") != std::string::npos ||
                            m.find("to inf") != std::string::npos;
    result.reason = fmt::format("{} in step {}",
                                non_finite ? "non-finite values" : "residual growth", failed_step);
  } else if (result.status == "solver_failed") {
    result.reason = fmt::format("solver failure after {} steps", result.steps_completed);
  }
}

/// Fill a row from the summary JSON of a run.
void read_summary(RunResult& result, const fs::path& file) {
  std::ifstream in(file);
  if (!in) return add_note(result, "no summary " + file.string());
  const nlohmann::json j = nlohmann::json::parse(in);
  auto number = [&](const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
  };
  result.coupled_solver = j.value("coupled_solver", "");
  result.status = j.value("status", "");
  result.message = j.value("message", "");
  result.completed = j.value("completed", false);
  result.steps_completed = j.value("steps_completed", 0);
  result.average_iterations = number("average_iterations");
  result.wall_time = number("wall_time");
  result.coupler_time = number("step_coupler_time");
  long total = 0;
  for (const auto& n : j.value("iterations_per_step", std::vector<int>{})) {
    total += n;
    result.maximum_iterations = std::max(result.maximum_iterations, n);
  }
  result.solver_calls = 2 * total;  // one call of each solver per coupling iteration
  const auto unconverged = j.value("unconverged_steps", std::vector<int>{});
  result.unconverged_steps = static_cast<int>(unconverged.size());
  if (!unconverged.empty())
    add_note(result, fmt::format("{} step{} accepted unconverged at the iteration limit",
                                 unconverged.size(), unconverged.size() == 1 ? "" : "s"));
  classify(result, j.value("timestep_start", 0) + result.steps_completed + 1);
}

// ---------------------------------------------------------------------------------------------
// Output

std::string format_number(double value, const char* format = "{:.3g}") {
  return std::isfinite(value) ? fmt::format(fmt::runtime(format), value) : "-";
}

std::string label(const RunResult& r) {
  return r.case_name.empty() ? r.name : r.case_name + "/" + r.name;
}

/// "converged", "stalled 20", "diverged"; the reasons follow below the table.
std::string short_outcome(const RunResult& r) {
  return r.outcome == "stalled" ? fmt::format("stalled {}", r.unconverged_steps) : r.outcome;
}

void print_table(const std::vector<RunResult>& rows) {
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

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json to_json(const RunResult& r) {
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
                                           "unconverged_steps"};

std::string csv_field(const nlohmann::json& value) {
  if (value.is_null()) return "";
  if (!value.is_string()) return value.dump();
  std::string text = value.get<std::string>();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void write_outputs(const BenchFile& bench, const nlohmann::json& reference,
                   const std::vector<RunResult>& rows) {
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

std::string quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// The plot script is installed next to the executable's tree (<prefix>/share/cocopp), in the
/// build tree and in an install alike: an installed cocopp never reaches into the sources.
fs::path plot_script() {
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  return executable.parent_path().parent_path() / "share" / "cocopp" / "plot_bench.py";
}

void plot(const BenchFile& bench) {
  const fs::path script = plot_script();
  const std::string command = fmt::format("/usr/bin/python3 {} {} -o {}", quote(script.string()),
                                          quote((bench.output_directory / "bench.json").string()),
                                          quote((bench.output_directory / "bench.png").string()));
  std::fflush(stdout);
  if (std::system(command.c_str()) != 0)
    fmt::print(stderr, "warning: the plot failed; draw it by hand with\n  {}\n", command);
  else
    fmt::print("plot     : {}\n", (bench.output_directory / "bench.png").string());
}

// ---------------------------------------------------------------------------------------------
// The bench

/// Write every case first and validate it, so that a mistake in the last variant is found
/// before the first run, not an hour later.
std::vector<PlannedRun> prepare(const BenchFile& bench) {
  const YAML::Node base = YAML::LoadFile(bench.base_case.string());
  check_working_directories(base, bench.base_case);
  std::vector<PlannedRun> runs;
  for (const BenchCase& c : bench.cases) {
    if (bench.reference == ReferenceKind::kComputed)
      runs.push_back(prepare_run(
          bench, base, c, kReferenceName,
          reference_coupled_solver(base["coupled_solver"], bench.reference_tolerance), Changes{}));
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

/// Run every case in turn; returns false if the bench has to stop (interrupt, no reference).
bool run_all(const std::vector<PlannedRun>& runs, std::vector<RunResult>& rows) {
  for (std::size_t i = 0; i < runs.size(); ++i) {
    RunResult row;
    row.case_name = runs[i].case_name;
    row.name = runs[i].name;
    fmt::print("\n=== bench run {} of {}: {} ===\n", i + 1, runs.size(), label(row));
    std::fflush(stdout);
    run_case(runs[i].case_file, RunOptions{true});
    read_summary(row, runs[i].case_file.parent_path() / "results" / "case.summary.json");
    // A solver names its input file relative to its directory: say which copy it read.
    if (row.status == "solver_failed" && !runs[i].changed_inputs.empty())
      add_note(row, "input changed by the bench: " + runs[i].changed_inputs);
    rows.push_back(row);
    if (row.status == "interrupted") return false;
    if (row.name == kReferenceName && row.steps_completed == 0) {
      fmt::print(stderr, "error: the reference run {} computed no time step: {}\n", label(row),
                 row.message);
      return false;
    }
  }
  return true;
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

void compare_with_references(const BenchFile& bench, const std::vector<PlannedRun>& runs,
                             std::vector<RunResult>& rows) {
  if (bench.reference == ReferenceKind::kNone) return;
  for (const BenchCase& c : bench.cases) {
    const fs::path reference = reference_of(bench, c.name);
    try {
      const Results reference_results = read_results(reference);
      for (std::size_t i = 0; i < rows.size(); ++i)
        if (rows[i].case_name == c.name)
          compute_errors(rows[i], runs[i].case_file.parent_path() / "results" / "case.h5",
                         reference_results);
    } catch (const std::exception& e) {
      fmt::print(stderr, "warning: cannot read the reference {}: {}\n", reference.string(),
                 e.what());
    }
  }
}

/// bench.json's `reference`: the results file, "none", or one file per case of a sweep.
nlohmann::json describe_references(const BenchFile& bench) {
  if (bench.reference == ReferenceKind::kNone) return "none";
  if (bench.cases.size() == 1) return reference_of(bench, bench.cases.front().name).string();
  nlohmann::json by_case = nlohmann::json::object();
  for (const BenchCase& c : bench.cases) by_case[c.name] = reference_of(bench, c.name).string();
  return by_case;
}

}  // namespace

int run_bench(const fs::path& bench_file, const BenchOptions& options) {
  BenchFile bench;
  std::vector<PlannedRun> runs;
  try {
    bench = read_bench_file(bench_file);
    fs::create_directories(bench.output_directory);
    runs = prepare(bench);
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  }
  std::vector<RunResult> rows;
  const bool finished = run_all(runs, rows);
  compare_with_references(bench, runs, rows);
  print_table(rows);
  const nlohmann::json reference = describe_references(bench);
  write_outputs(bench, reference, rows);
  fmt::print("\nreference: {}\ntable    : {}\n",
             reference.is_string() ? reference.get<std::string>() : "one per case (bench.json)",
             (bench.output_directory / "bench.csv").string());
  if (bench.reference == ReferenceKind::kNone)
    fmt::print("no plot of error against time: reference: none\n");
  else if (options.plot && finished)
    plot(bench);
  return finished ? 0 : 1;
}

}  // namespace cocopp
