#include "coupler/results/results_writer.hpp"

#include <sys/statvfs.h>

#include <algorithm>
#include <cstdint>
#include <ctime>
#include <exception>
#include <stdexcept>
#include <utility>

#include "core/data/variables.hpp"
#include "coupler/results/hdf5_copy.hpp"
#include "coupler/results/results_reader.hpp"

#ifndef COCOPP_VERSION
#define COCOPP_VERSION "unknown"  // set from PROJECT_VERSION in coupler/CMakeLists.txt
#endif

namespace cocopp {
namespace {

using namespace hdf5;

std::string iso_time_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

/// Rows per chunk: about 8 KiB of values, at least one row. Small series then do not cost one
/// chunk per step, and an interface block larger than that is one chunk per step.
hsize_t rows_per_chunk(const std::vector<hsize_t>& row_shape) {
  hsize_t row = 1;
  for (hsize_t extent : row_shape) row *= std::max<hsize_t>(extent, 1);
  return std::max<hsize_t>(1, 1024 / row);
}

H5Handle create_extendible(hid_t parent, const std::string& name, hid_t file_type,
                           const std::vector<hsize_t>& row_shape) {
  std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk{rows_per_chunk(row_shape)};
  for (hsize_t extent : row_shape) {
    dims.push_back(extent);
    // Chunks cannot be larger than a fixed dimension, and 0 is no chunk size: a dimension of
    // length 0 (a model part without points) is declared extendible instead; it never grows.
    max_dims.push_back(extent > 0 ? extent : H5S_UNLIMITED);
    chunk.push_back(std::max<hsize_t>(extent, 1));
  }
  const H5Handle space = dataspace(dims, max_dims.data());
  const H5Handle properties(checked(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate"), H5Pclose);
  checked(H5Pset_chunk(properties.get(), static_cast<int>(chunk.size()), chunk.data()),
          "H5Pset_chunk " + name);
  return {checked(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                             properties.get(), H5P_DEFAULT),
                  "creating dataset " + name),
          H5Dclose};
}

/// Sets the dataset to first + rows rows and writes `rows` rows from `data` at row `first`.
/// Setting (not growing) the extent lets a retried step overwrite a partially written one.
void write_rows(hid_t dataset, const std::vector<hsize_t>& row_shape, hsize_t first, hsize_t rows,
                hid_t memory_type, const void* data) {
  std::vector<hsize_t> extent{first + rows};
  extent.insert(extent.end(), row_shape.begin(), row_shape.end());
  const std::string what = "writing " + object_name(dataset);
  checked(H5Dset_extent(dataset, extent.data()), what);
  std::vector<hsize_t> count = extent;
  count[0] = rows;
  if (std::find(count.begin(), count.end(), hsize_t{0}) != count.end()) return;
  std::vector<hsize_t> start(extent.size(), 0);
  start[0] = first;
  const H5Handle file_space(checked(H5Dget_space(dataset), what), H5Sclose);
  checked(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                              nullptr),
          what);
  const H5Handle memory_space = dataspace(count);
  checked(H5Dwrite(dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data),
          what);
}

/// Model part and variable names become HDF5 link names: no '/', not empty, not ".".
void check_link_name(const std::string& name, const std::string& what) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos)
    throw std::invalid_argument("cannot write " + what + " '" + name +
                                "' to the results file: names must be non-empty, not '.', and "
                                "without '/'");
}

void check_names(const Interface& interface) {
  for (const auto& part : interface.parts()) {
    check_link_name(part.model_part->name, "model part");
    for (const auto& variable : part.variables)
      if (variable == "ids" || variable == "coordinates")
        throw std::invalid_argument("variable '" + variable +
                                    "' clashes with the model part "
                                    "dataset of the same name in the results file");
  }
}

bool same_blocks(const Interface::Block& a, const Interface::Block& b) {
  return a.model_part == b.model_part && a.variable == b.variable && a.offset == b.offset &&
         a.points == b.points && a.components == b.components;
}

std::string describe(const std::vector<Interface::Block>& blocks) {
  std::string out;
  for (const auto& b : blocks) {
    if (!out.empty()) out += "; ";
    out += b.model_part + ": " + b.variable + " (" + std::to_string(b.points) + " x " +
           std::to_string(b.components) + ")";
  }
  return out.empty() ? "empty" : out;
}

constexpr const char* kXRole = "displacement interface: input of the flow solver";
constexpr const char* kYRole = "loads interface: output of the flow solver";
constexpr const char* kWatchpointsRole =
    "watchpoints: the variables of x and y interpolated at points (settings.watchpoints)";

}  // namespace

ResultsWriter::ResultsWriter(const std::filesystem::path& file, const RunDescription& run,
                             const Interface& x, const Interface& y, const Interface& watchpoints)
    : path_(file), solver_count_(run.solver_names.size()) {
  check_names(x);
  check_names(y);
  check_names(watchpoints);
  if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path());
  const QuietErrors quiet;
  try {
    create_file();
    write_run_attributes(run);
    x_blocks_ = create_interface("x", kXRole, x);
    y_blocks_ = create_interface("y", kYRole, y);
    if (!watchpoints.parts().empty())
      watchpoint_blocks_ = create_interface("watchpoints", kWatchpointsRole, watchpoints);
    create_step_series();
    flush();
  } catch (const H5Error& error) {
    release();
    fail(error);
  }
}

ResultsWriter::ResultsWriter(const std::filesystem::path& file, const RunDescription& run,
                             const Interface& x, const Interface& y, int continue_after_step,
                             const Interface& watchpoints)
    : path_(file), solver_count_(run.solver_names.size()) {
  check_continuable(run, continue_after_step);
  // check_continuable left rows_ at the rows to keep: the steps up to continue_after_step.
  const QuietErrors quiet;
  // A run killed in a flush can leave the file's metadata behind its data: it still reads, but
  // the first flush into it fails ("addr overflow"). The kept steps go into a new file, which
  // replaces the old one once it has everything this run needs.
  std::filesystem::path fresh = path_;
  fresh += ".continued";
  const auto abandon_copy = [&] {
    release();
    std::error_code ignored;
    std::filesystem::remove(fresh, ignored);
  };
  try {
    copy_kept_rows(fresh);
    file_ = H5Handle(checked(H5Fopen(fresh.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "opening the copy"),
                     H5Fclose);
    x_blocks_ = open_interface("x", x);
    y_blocks_ = open_interface("y", y);
    if (!watchpoints.parts().empty())
      watchpoint_blocks_ = open_interface("watchpoints", watchpoints);
    open_step_series();
    mark_continued(continue_after_step);
    flush();
    std::error_code error;
    std::filesystem::rename(fresh, path_, error);
    if (error) throw H5Error("replacing it by " + fresh.string() + " failed: " + error.message());
  } catch (const H5Error& error) {
    abandon_copy();
    fail(error);
  } catch (...) {  // a case that does not fit the file: its message names the file already
    abandon_copy();
    throw;
  }
}

void ResultsWriter::check_continuable(const RunDescription& run, int step) {
  const auto mismatch = [&](const std::string& what) {
    throw std::runtime_error("results file '" + path_.string() + "' cannot be continued after " +
                             "step " + std::to_string(step) + ": " + what);
  };
  if (!std::filesystem::exists(path_))
    mismatch("it is not there (the restart appends to the results of the run it continues)");
  const ResultsReader reader(path_);
  if (reader.delta_t() != run.delta_t)
    mismatch("it was written with delta_t " + std::to_string(reader.delta_t()) + ", the case has " +
             std::to_string(run.delta_t));
  const std::vector<int> steps = reader.steps();
  const auto found = std::find(steps.begin(), steps.end(), step);
  if (found == steps.end())
    mismatch(steps.empty() ? std::string("it holds no steps")
                           : "it holds steps " + std::to_string(steps.front()) + " to " +
                                 std::to_string(steps.back()));
  rows_before_ = rows_ = static_cast<int>(found - steps.begin()) + 1;
  const auto offsets = reader.dataset("residuals/offset").values;
  const auto counts = reader.dataset("residuals/count").values;
  if (offsets.size() < std::size_t(rows_) || counts.size() < std::size_t(rows_))
    mismatch("its residuals hold fewer steps than its step list");
  norms_written_ = static_cast<hsize_t>(offsets[rows_ - 1] + counts[rows_ - 1]);
}

void ResultsWriter::copy_kept_rows(const std::filesystem::path& copy) const {
  try {
    copy_file(path_, copy,
              [&](const std::string& dataset, hsize_t) {
                return dataset == "residuals/norms" ? norms_written_ : static_cast<hsize_t>(rows_);
              },
              {"unfinished_step"});
  } catch (const H5Error& error) {
    throw H5Error(std::string("copying its steps up to the saved state into a new file: ") +
                  error.what() + " (the file is unchanged)");
  }
}

void ResultsWriter::mark_continued(int step) {
  const hid_t root = file_.get();
  set_string(root, "status", "running");
  set_string(root, "message", "");
  set_int(root, "restarted_after_step", step);
  // The step the continued run stopped in lies after the saved state: this run computes it
  // again, and may stop in a step of its own.
  if (checked(H5Lexists(root, "unfinished_step", H5P_DEFAULT), "looking for unfinished_step") > 0)
    checked(H5Ldelete(root, "unfinished_step", H5P_DEFAULT), "removing the old unfinished_step");
}

std::vector<ResultsWriter::BlockSeries> ResultsWriter::open_interface(const char* name,
                                                                      const Interface& interface) {
  std::vector<BlockSeries> out;
  for (const auto& b : interface.blocks()) {
    const std::string dataset = std::string(name) + "/" + b.model_part + "/" + b.variable;
    Series series = open_series(dataset);
    const std::vector<hsize_t> row{static_cast<hsize_t>(b.points),
                                   static_cast<hsize_t>(b.components)};
    if (series.row_shape != row)
      throw std::runtime_error("results file '" + path_.string() + "': " + dataset +
                               " does not have the layout of this run's interface " + name + " (" +
                               interface.describe() + "): was the case changed?");
    out.push_back({b, std::move(series)});
  }
  return out;
}

ResultsWriter::Series ResultsWriter::open_series(const std::string& name) {
  if (H5Lexists(file_.get(), name.substr(0, name.find('/')).c_str(), H5P_DEFAULT) <= 0 ||
      H5Oexists_by_name(file_.get(), name.c_str(), H5P_DEFAULT) <= 0)
    throw std::runtime_error("results file '" + path_.string() + "' has no dataset " + name +
                             ": was the case changed?");
  H5Handle dataset(checked(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), "opening " + name),
                   H5Dclose);
  std::vector<hsize_t> shape = dataset_shape(dataset.get());
  shape.erase(shape.begin());
  return {std::move(dataset), std::move(shape)};
}

void ResultsWriter::open_step_series() {
  steps_.step = open_series("steps/step");
  steps_.time = open_series("steps/time");
  steps_.iterations = open_series("steps/iterations");
  steps_.converged = open_series("steps/converged");
  steps_.wall_time = open_series("steps/wall_time");
  steps_.coupler_time = open_series("steps/coupler_time");
  steps_.solver_times = open_series("steps/solver_times");
  steps_.norms = open_series("residuals/norms");
  steps_.offset = open_series("residuals/offset");
  steps_.count = open_series("residuals/count");
  if (steps_.solver_times.row_shape != std::vector<hsize_t>{solver_count_})
    throw std::runtime_error("results file '" + path_.string() + "' was written for " +
                             std::to_string(steps_.solver_times.row_shape.at(0)) + " solvers");
}

ResultsWriter::~ResultsWriter() {
  if (!is_open()) return;
  try {
    close("incomplete",
          "the results writer was destroyed without close(): the run ended without saying how");
  } catch (...) {
    // A destructor must not throw; the file keeps what the last flush wrote.
  }
}

void ResultsWriter::create_file() {
  // Default (earliest) format bounds on purpose: the superblock then has no "open for writing"
  // flag, so a copy taken after a flush, while the run still writes, opens like any other file.
  const H5Handle properties(checked(H5Pcreate(H5P_FILE_CREATE), "H5Pcreate"), H5Pclose);
  checked(
      H5Pset_link_creation_order(properties.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
      "H5Pset_link_creation_order");
  file_ = H5Handle(checked(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, properties.get(), H5P_DEFAULT),
                           "creating the file"),
                   H5Fclose);
}

void ResultsWriter::write_run_attributes(const RunDescription& run) {
  const hid_t root = file_.get();
  set_string(root, "cocopp_version", COCOPP_VERSION);
  set_string(root, "case_file", run.case_file);
  set_string(root, "coupled_solver", run.coupled_solver);
  set_strings(root, "solver_names", run.solver_names);
  set_double(root, "delta_t", run.delta_t);
  set_int(root, "timestep_start", run.timestep_start);
  set_int(root, "number_of_timesteps", run.number_of_timesteps);
  // The criterion, so that plots can draw the residuals as it measures them, with its tolerance.
  set_string(root, "convergence_criterion", run.convergence_criterion);
  std::vector<std::string> measures, orders;
  std::vector<double> tolerances;
  for (const auto& t : run.tolerances) {
    measures.push_back(t.relative ? "relative" : "absolute");
    orders.push_back(t.order);
    tolerances.push_back(t.value);
  }
  set_strings(root, "tolerance_measure", measures);
  set_strings(root, "tolerance_order", orders);
  set_attribute(root, "tolerance", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {tolerances.size()},
                tolerances.data());
  set_string(root, "created", iso_time_now());
  set_string(root, "status", "running");
  set_string(root, "message", "");
}

std::vector<ResultsWriter::BlockSeries> ResultsWriter::create_interface(
    const char* name, const char* role, const Interface& interface) {
  const H5Handle group = create_group(file_.get(), name);
  set_string(group.get(), "role", role);
  std::vector<std::string> parts;
  for (const auto& part : interface.parts()) parts.push_back(part.model_part->name);
  set_strings(group.get(), "model_parts", parts);
  set_int(group.get(), "size", interface.size());

  // The flat layout of Interface::data(), so a reader can rebuild the vector the coupled
  // solver works on: values[offset:offset + size] = group[model_part][variable][row].ravel().
  std::vector<std::string> model_parts, variables;
  std::vector<std::int64_t> offsets, sizes, points, components;
  for (const auto& b : interface.blocks()) {
    model_parts.push_back(b.model_part);
    variables.push_back(b.variable);
    offsets.push_back(b.offset);
    sizes.push_back(b.points * b.components);
    points.push_back(b.points);
    components.push_back(b.components);
  }
  set_strings(group.get(), "block_model_part", model_parts);
  set_strings(group.get(), "block_variable", variables);
  set_ints(group.get(), "block_offset", offsets);
  set_ints(group.get(), "block_size", sizes);
  set_ints(group.get(), "block_points", points);
  set_ints(group.get(), "block_components", components);

  std::vector<BlockSeries> out;
  for (const auto& part : interface.parts()) {
    const ModelPart& model_part = *part.model_part;
    const H5Handle part_group = create_group(group.get(), model_part.name);
    const hsize_t n = model_part.size();
    write_fixed(part_group.get(), "ids", H5T_STD_I64LE, H5T_NATIVE_INT64, {n},
                model_part.ids.data(), nullptr);
    // Coordinates is row-major n x 3, the layout HDF5 expects.
    write_fixed(part_group.get(), "coordinates", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n, 3},
                model_part.coordinates.data(), "m");
    for (const auto& variable : part.variables) {
      const Interface::Block& b = interface.block(model_part.name, variable);
      const std::vector<hsize_t> row{n, static_cast<hsize_t>(b.components)};
      out.push_back({b, create_series(part_group.get(), variable.c_str(), H5T_IEEE_F64LE, row,
                                      variable_info(variable).unit.c_str())});
    }
  }
  return out;
}

ResultsWriter::Series ResultsWriter::create_series(hid_t group, const char* name, hid_t file_type,
                                                   std::vector<hsize_t> row_shape,
                                                   const char* unit) {
  Series series{create_extendible(group, name, file_type, row_shape), std::move(row_shape)};
  if (unit) set_string(series.dataset.get(), "unit", unit);
  return series;
}

void ResultsWriter::create_step_series() {
  const H5Handle steps = create_group(file_.get(), "steps");
  const hid_t g = steps.get();
  const H5Handle boolean = bool_type();
  steps_.step = create_series(g, "step", H5T_STD_I32LE, {}, nullptr);
  steps_.time = create_series(g, "time", H5T_IEEE_F64LE, {}, "s");
  steps_.iterations = create_series(g, "iterations", H5T_STD_I32LE, {}, nullptr);
  steps_.converged = create_series(g, "converged", boolean.get(), {}, nullptr);
  steps_.wall_time = create_series(g, "wall_time", H5T_IEEE_F64LE, {}, "s");
  steps_.coupler_time = create_series(g, "coupler_time", H5T_IEEE_F64LE, {}, "s");
  steps_.solver_times = create_series(g, "solver_times", H5T_IEEE_F64LE, {solver_count_}, "s");

  const H5Handle residuals = create_group(file_.get(), "residuals");
  const hid_t r = residuals.get();
  steps_.norms = create_series(r, "norms", H5T_IEEE_F64LE, {}, nullptr);
  steps_.offset = create_series(r, "offset", H5T_STD_I64LE, {}, nullptr);
  steps_.count = create_series(r, "count", H5T_STD_I64LE, {}, nullptr);
}

void ResultsWriter::write_step(const StepRecord& record, const Interface& x, const Interface& y,
                               const Interface& watchpoints) {
  check_layouts(record, x, y, watchpoints);
  StepRecord with_values = record;
  with_values.x = x.data();
  with_values.y = y.data();
  with_values.watchpoints = watchpoints.data();
  write_step(with_values);
}

void ResultsWriter::write_step(const StepRecord& record) {
  if (!is_open())
    throw std::logic_error("results file '" + path_.string() + "': write_step after close");
  check_step(record);
  kept_.push_back(record);
  kept_values_ += values_of(record);
  const std::chrono::duration<double> since_write = std::chrono::steady_clock::now() - last_write_;
  constexpr std::size_t kMaxKeptValues = 8 << 20;  // 64 MB of doubles
  if (since_write.count() >= write_interval_ || kept_values_ >= kMaxKeptValues ||
      kept_.size() >= kMaxKeptSteps)
    write_kept_steps();
}

void ResultsWriter::write_kept_steps() {
  if (kept_.empty() || !is_open()) return;
  const std::size_t room = steps_with_room();
  if (room == kept_.size()) return write_batch();
  // The disk is nearly full: every step that fits is written, the rest named in the error.
  const int first = kept_[room].step, last = kept_.back().step;
  const std::string steps = first == last
                                ? "step " + std::to_string(first)
                                : "steps " + std::to_string(first) + " to " + std::to_string(last);
  const auto available = available_bytes();
  kept_.resize(room);
  kept_values_ = 0;
  for (const auto& step : kept_) kept_values_ += values_of(step);
  write_batch();
  throw std::runtime_error("results file '" + path_.string() + "': the disk has " +
                           std::to_string(available.value_or(0)) + " bytes left, too few for " +
                           steps + " and closing the file: stopped before writing them, so " +
                           "that the " + std::to_string(rows_) +
                           " steps written stay readable; free space and restart the run");
}

void ResultsWriter::write_batch() {
  if (kept_.empty()) return;
  const QuietErrors quiet;
  try {
    write_interface(x_blocks_, &StepRecord::x);
    write_interface(y_blocks_, &StepRecord::y);
    if (!watchpoint_blocks_.empty()) write_interface(watchpoint_blocks_, &StepRecord::watchpoints);
    write_residuals();
    write_step_scalars();
    flush();
  } catch (const H5Error& error) {
    fail(error);
  }
  rows_ += static_cast<int>(kept_.size());
  for (const auto& step : kept_) norms_written_ += step.residual_norms.size();
  kept_.clear();
  kept_values_ = 0;
  last_write_ = std::chrono::steady_clock::now();
}

void ResultsWriter::check_layouts(const StepRecord& record, const Interface& x, const Interface& y,
                                  const Interface& watchpoints) const {
  const auto check_layout = [&](const char* name, const std::vector<BlockSeries>& expected,
                                const Interface& given) {
    std::vector<Interface::Block> blocks;
    for (const auto& b : expected) blocks.push_back(b.block);
    const auto& actual = given.blocks();
    if (!std::equal(blocks.begin(), blocks.end(), actual.begin(), actual.end(), same_blocks))
      throw std::invalid_argument("results file '" + path_.string() + "': interface " + name +
                                  " of step " + std::to_string(record.step) + " has layout " +
                                  given.describe() + ", the file was created for " +
                                  describe(blocks));
  };
  check_layout("x", x_blocks_, x);
  check_layout("y", y_blocks_, y);
  if (!watchpoint_blocks_.empty()) check_layout("watchpoints", watchpoint_blocks_, watchpoints);
}

void ResultsWriter::check_step(const StepRecord& record) const {
  const auto check_size = [&](const char* name, const std::vector<BlockSeries>& blocks,
                              const Eigen::VectorXd& values) {
    Eigen::Index size = 0;
    for (const auto& b : blocks) size += b.block.points * b.block.components;
    if (values.size() != size)
      throw std::invalid_argument("results file '" + path_.string() + "': step " +
                                  std::to_string(record.step) + " has " +
                                  std::to_string(values.size()) + " values of " + name +
                                  ", the file was created for " + std::to_string(size));
  };
  check_size("x", x_blocks_, record.x);
  check_size("y", y_blocks_, record.y);
  check_size("the watchpoints", watchpoint_blocks_, record.watchpoints);
  if (record.solver_times.size() != solver_count_)
    throw std::invalid_argument(
        "results file '" + path_.string() + "': step " + std::to_string(record.step) + " has " +
        std::to_string(record.solver_times.size()) + " solver times, expected one per solver (" +
        std::to_string(solver_count_) + ")");
}

std::optional<std::uint64_t> ResultsWriter::available_bytes() const {
  struct statvfs disk {};
  const auto directory = path_.has_parent_path() ? path_.parent_path() : ".";
  if (::statvfs(directory.c_str(), &disk) != 0) return std::nullopt;
  return std::uint64_t(disk.f_bavail) * disk.f_frsize;
}

std::size_t ResultsWriter::values_of(const StepRecord& step) {
  return static_cast<std::size_t>(step.x.size() + step.y.size() + step.watchpoints.size()) +
         step.residual_norms.size();
}

// HDF5 leaves a file it could not finish writing (its metadata half updated) unreadable, and
// with it every step flushed before. So a step is written only where the disk clearly has
// room for it and for closing the file: its values and row scalars, a quarter more for the
// chunk index and the metadata, and per batch a new chunk (8 KiB) of every series and the
// closing reserve.
std::size_t ResultsWriter::steps_with_room() const {
  const auto available = available_bytes();
  if (!available) return kept_.size();  // nothing known: write and see
  const std::uint64_t batch = 8192 * (series_count() + 1) + kClosingReserveBytes;
  if (*available < batch) return 0;
  std::uint64_t left = *available - batch;
  std::size_t room = 0;
  for (const auto& step : kept_) {
    const std::uint64_t needed = 10 * (values_of(step) + 16);  // 8 bytes, and a quarter
    if (needed > left) break;
    left -= needed;
    ++room;
  }
  return room;
}

void ResultsWriter::write_interface(const std::vector<BlockSeries>& blocks,
                                    Eigen::VectorXd StepRecord::*interface) {
  for (const auto& b : blocks) {
    const auto size = static_cast<std::size_t>(b.block.points * b.block.components);
    write_kept<double>(b.series, H5T_NATIVE_DOUBLE, size, [&](const StepRecord& step) {
      return (step.*interface).data() + b.block.offset;
    });
  }
}

void ResultsWriter::write_residuals() {
  std::vector<double> norms;
  std::int64_t offset = static_cast<std::int64_t>(norms_written_);
  std::vector<std::int64_t> offsets, counts;
  for (const auto& step : kept_) {
    const auto& step_norms = step.residual_norms;
    norms.insert(norms.end(), step_norms.begin(), step_norms.end());
    offsets.push_back(offset);
    counts.push_back(static_cast<std::int64_t>(step_norms.size()));
    offset += counts.back();
  }
  write_rows(steps_.norms.dataset.get(), {}, norms_written_, norms.size(), H5T_NATIVE_DOUBLE,
             norms.data());
  write_kept_rows(steps_.offset, H5T_NATIVE_INT64, offsets.data());
  write_kept_rows(steps_.count, H5T_NATIVE_INT64, counts.data());
}

void ResultsWriter::write_step_scalars() {
  const H5Handle boolean = bool_type();
  std::vector<std::int8_t> converged;
  for (const auto& step : kept_) converged.push_back(step.converged ? 1 : 0);
  const auto of = [](auto member) {
    return [member](const StepRecord& step) { return &(step.*member); };
  };
  write_kept<double>(steps_.time, H5T_NATIVE_DOUBLE, 1, of(&StepRecord::time));
  write_kept<int>(steps_.iterations, H5T_NATIVE_INT, 1, of(&StepRecord::iterations));
  write_kept_rows(steps_.converged, boolean.get(), converged.data());
  write_kept<double>(steps_.wall_time, H5T_NATIVE_DOUBLE, 1, of(&StepRecord::wall_time));
  write_kept<double>(steps_.coupler_time, H5T_NATIVE_DOUBLE, 1, of(&StepRecord::coupler_time));
  write_kept<double>(steps_.solver_times, H5T_NATIVE_DOUBLE, solver_count_,
                     [](const StepRecord& step) { return step.solver_times.data(); });
  // Last, so that the length of steps/step counts the rows that are complete everywhere.
  write_kept<int>(steps_.step, H5T_NATIVE_INT, 1, of(&StepRecord::step));
}

template <class T, class Value>
void ResultsWriter::write_kept(const Series& series, hid_t memory_type, std::size_t row_size,
                               Value value) {
  std::vector<T> rows;
  rows.reserve(kept_.size() * row_size);
  for (const auto& step : kept_) {
    const T* row = value(step);
    rows.insert(rows.end(), row, row + row_size);
  }
  write_kept_rows(series, memory_type, rows.data());
}

void ResultsWriter::write_kept_rows(const Series& series, hid_t memory_type, const void* rows) {
  write_rows(series.dataset.get(), series.row_shape, static_cast<hsize_t>(rows_), kept_.size(),
             memory_type, rows);
}

void ResultsWriter::flush() {
  checked(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), "flushing the file");
}

void ResultsWriter::write_unfinished_step(int step, double time,
                                          const std::vector<double>& residual_norms) {
  if (!is_open()) return;
  write_kept_steps();
  const QuietErrors quiet;
  try {
    const H5Handle group = create_group(file_.get(), "unfinished_step");
    set_int(group.get(), "step", step);
    set_double(group.get(), "time", time);
    write_fixed(group.get(), "residual_norms", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                {residual_norms.size()}, residual_norms.data(), nullptr);
    flush();
  } catch (const H5Error& error) {
    fail(error);
  }
}

void ResultsWriter::close(const std::string& status, const std::string& message) {
  if (!is_open()) return;
  if (status.empty()) throw std::invalid_argument("results file status must not be empty");
  // The kept steps first. If they cannot be written, the file still closes with its status
  // and the steps written before, and the error follows.
  std::exception_ptr kept_steps_error;
  try {
    write_kept_steps();
  } catch (const std::exception&) {
    kept_steps_error = std::current_exception();
    kept_.clear();
  }
  const QuietErrors quiet;
  try {
    const hid_t root = file_.get();
    set_string(root, "status", status);
    set_string(root, "message", message);
    set_string(root, "finished", iso_time_now());
    set_int(root, "steps_written", rows_);
    checked(release(), "closing the file");
  } catch (const H5Error& error) {
    release();
    fail(error);
  }
  if (kept_steps_error) std::rethrow_exception(kept_steps_error);
}

herr_t ResultsWriter::release() {
  // Datasets first: with the default (weak) close degree the file stays open while they are.
  x_blocks_.clear();
  y_blocks_.clear();
  steps_ = StepSeries{};
  return file_.reset();
}

void ResultsWriter::fail(const std::exception& error) const {
  throw std::runtime_error("results file '" + path_.string() + "': " + error.what());
}

}  // namespace cocopp
