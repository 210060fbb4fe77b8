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

#include "coupler/app/case.hpp"
#include "coupler/app/run.hpp"
#include "coupler/case/settings.hpp"

namespace cocopp {

namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const char* const kReferenceName = "reference";

struct Variant {
  std::string name;
  YAML::Node coupled_solver;  ///< merged into the base case's coupled_solver (may be null)
  YAML::Node settings;        ///< merged into the base case's settings (may be null)
};

struct BenchFile {
  fs::path file;
  fs::path base_case;
  fs::path output_directory;
  fs::path reference_results;  ///< empty: the reference is computed
  double reference_tolerance = 1e-10;
  YAML::Node settings;  ///< merged into the settings of every run, the reference included
  std::vector<Variant> variants;
};

/// One row of the table, bench.csv and bench.json.
struct RunResult {
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

Variant read_variant(const Settings& s, std::set<std::string>& names) {
  Variant v;
  v.name = s.required<std::string>("name");
  // The name becomes a directory name and a table entry.
  if (!std::regex_match(v.name, std::regex("[A-Za-z0-9_.+-]+")) || v.name == "." || v.name == "..")
    s.fail("name", "'" + v.name + "' must be letters, digits and _ . + - only");
  if (v.name == kReferenceName)
    s.fail("name", "'reference' is the name of the computed reference run; choose another");
  if (!names.insert(v.name).second) s.fail("name", "'" + v.name + "' is used twice");
  v.coupled_solver = raw_mapping(s, "coupled_solver");
  v.settings = raw_mapping(s, "settings");
  return v;
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
  const Settings reference = root.child_or_empty("reference");
  if (reference.has("results")) {
    b.reference_results = dir / reference.required<std::string>("results");
    if (!fs::is_regular_file(b.reference_results))
      reference.fail("results", "no such file: " + b.reference_results.string());
    if (reference.has("tolerance"))
      reference.fail("tolerance", "give either 'results' or 'tolerance', not both");
  } else {
    b.reference_tolerance = reference.get_in_range("tolerance", 1e-10, Range::positive());
  }
  b.settings = raw_mapping(root, "settings");
  std::set<std::string> names;
  for (const Settings& v : root.list("variants")) b.variants.push_back(read_variant(v, names));
  if (b.variants.empty()) root.fail("variants", "needs at least one variant");
  root.check_unused_keys();
  return b;
}

// ---------------------------------------------------------------------------------------------
// Building the case of one run

bool other_type(const YAML::Node& base, const YAML::Node& override) {
  return base["type"] && override["type"] &&
         base["type"].as<std::string>() != override["type"].as<std::string>();
}

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

/// Write <output_directory>/<name>/case.yaml next to a fresh copy of the base case's files.
fs::path prepare_run(const BenchFile& bench, const YAML::Node& base_case, const std::string& name,
                     const YAML::Node& coupled_solver, const YAML::Node& settings) {
  const fs::path dir = bench.output_directory / name;
  fs::remove_all(dir);
  copy_case_directory(bench.base_case.parent_path(), dir, paths_not_to_copy(bench, base_case));
  YAML::Node c = YAML::Clone(base_case);
  c["coupled_solver"] = coupled_solver;
  YAML::Node s = deep_merge(deep_merge(base_case["settings"], bench.settings), settings);
  s["results_directory"] = "results";
  s["results_name"] = "case";
  c["settings"] = s;
  YAML::Emitter out;
  out << c;
  const fs::path file = dir / "case.yaml";
  std::ofstream(file) << "# written by cocopp bench from " << bench.file.string() << "\n"
                      << out.c_str() << "\n";
  return file;
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
  if (!unconverged.empty())
    add_note(result, fmt::format("{} step{} accepted unconverged at the iteration limit",
                                 unconverged.size(), unconverged.size() == 1 ? "" : "s"));
}

// ---------------------------------------------------------------------------------------------
// Output

std::string format_number(double value, const char* format = "{:.3g}") {
  return std::isfinite(value) ? fmt::format(fmt::runtime(format), value) : "-";
}

void print_table(const std::vector<RunResult>& rows) {
  std::size_t width = 7;
  for (const auto& r : rows) width = std::max(width, r.name.size());
  fmt::print("\n{:<{}}  {:<12} {:<13} {:>5} {:>7} {:>6} {:>7} {:>9} {:>11} {:>10} {:>10}\n",
             "variant", width, "solver", "status", "steps", "avg it", "max it", "calls", "wall [s]",
             "coupler [s]", "displ err", "press err");
  for (const auto& r : rows)
    fmt::print("{:<{}}  {:<12} {:<13} {:>5} {:>7} {:>6} {:>7} {:>9} {:>11} {:>10} {:>10}\n", r.name,
               width, r.coupled_solver, r.status, r.steps_completed,
               format_number(r.average_iterations, "{:.2f}"), r.maximum_iterations, r.solver_calls,
               format_number(r.wall_time, "{:.3f}"), format_number(r.coupler_time, "{:.4f}"),
               format_number(r.displacement_error), format_number(r.pressure_error));
  for (const auto& r : rows) {
    if (!r.completed && !r.message.empty())
      fmt::print("  {}: {}: {}\n", r.name, r.status, r.message);
    if (!r.note.empty()) fmt::print("  {}: {}\n", r.name, r.note);
  }
}

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json to_json(const RunResult& r) {
  return {{"name", r.name},
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
          {"note", r.note}};
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
                                           "note"};

std::string csv_field(const nlohmann::json& value) {
  if (value.is_null()) return "";
  if (!value.is_string()) return value.dump();
  std::string text = value.get<std::string>();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void write_outputs(const BenchFile& bench, const fs::path& reference,
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
                                   {"reference", reference.string()},
                                   {"runs", runs}};
  std::ofstream(bench.output_directory / "bench.json") << document.dump(2) << "\n";
}

std::string quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

void plot(const BenchFile& bench) {
  const fs::path script = fs::path(COCOPP_SOURCE_DIR) / "scripts" / "plot_bench.py";
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

struct PlannedRun {
  std::string name;
  fs::path case_file;
};

/// Write every case first and validate it, so that a mistake in the last variant is found
/// before the first run, not an hour later.
std::vector<PlannedRun> prepare(const BenchFile& bench) {
  const YAML::Node base = YAML::LoadFile(bench.base_case.string());
  check_working_directories(base, bench.base_case);
  std::vector<PlannedRun> runs;
  if (bench.reference_results.empty())
    runs.push_back({kReferenceName, prepare_run(bench, base, kReferenceName,
                                                reference_coupled_solver(base["coupled_solver"],
                                                                         bench.reference_tolerance),
                                                YAML::Node())});
  for (const Variant& v : bench.variants)
    runs.push_back(
        {v.name,
         prepare_run(bench, base, v.name,
                     merge_coupled_solver(base["coupled_solver"], v.coupled_solver), v.settings)});
  for (const PlannedRun& run : runs) {
    const Case c = load_case(run.case_file);
    for (const auto& solver : c.solvers) solver->check();
  }
  return runs;
}

/// Run every case in turn; returns false if the bench has to stop (interrupt, no reference).
bool run_all(const std::vector<PlannedRun>& runs, std::vector<RunResult>& rows) {
  for (std::size_t i = 0; i < runs.size(); ++i) {
    fmt::print("\n=== bench run {} of {}: {} ===\n", i + 1, runs.size(), runs[i].name);
    std::fflush(stdout);
    RunResult row;
    row.name = runs[i].name;
    run_case(runs[i].case_file, RunOptions{true});
    read_summary(row, runs[i].case_file.parent_path() / "results" / "case.summary.json");
    rows.push_back(row);
    if (row.status == "interrupted") return false;
    if (row.name == kReferenceName && row.steps_completed == 0) {
      fmt::print(stderr, "error: the reference run computed no time step: {}\n", row.message);
      return false;
    }
  }
  return true;
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
  const fs::path reference = bench.reference_results.empty()
                                 ? bench.output_directory / kReferenceName / "results" / "case.h5"
                                 : bench.reference_results;
  try {
    const Results reference_results = read_results(reference);
    for (std::size_t i = 0; i < rows.size(); ++i)
      compute_errors(rows[i], runs[i].case_file.parent_path() / "results" / "case.h5",
                     reference_results);
  } catch (const std::exception& e) {
    fmt::print(stderr, "warning: cannot read the reference {}: {}\n", reference.string(), e.what());
  }
  print_table(rows);
  write_outputs(bench, reference, rows);
  fmt::print("\nreference: {}\ntable    : {}\n", reference.string(),
             (bench.output_directory / "bench.csv").string());
  if (options.plot && finished) plot(bench);
  return finished ? 0 : 1;
}

}  // namespace cocopp
