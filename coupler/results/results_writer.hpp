#pragma once
// The HDF5 results file of a run, written step by step while the run goes.
//
// Steps are written in batches, each followed by a flush: every step at once by default, or,
// with set_write_interval(), the steps of the last interval of wall time together (HDF5 writes
// one row and flushes in about 0.1 ms, the whole time of a fast solver's step). So a run that is
// killed leaves a readable file with all steps written so far (its "status" attribute then
// still says "running"), at most the last interval short. The layout (groups, datasets, shapes,
// units, attributes) is documented in docs/results.md; keep the two in sync.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/data/interface.hpp"
#include "coupler/results/hdf5_support.hpp"
#include "coupler/results/step_record.hpp"

namespace cocopp {

class ResultsWriter {
 public:
  /// Creates the directory and the file (truncating an existing one) and writes the run
  /// description and the layout of x (the displacement interface the flow solver takes) and y
  /// (the loads interface), and of the watchpoints (Watchpoints::layout(), group /watchpoints;
  /// none if empty). Throws std::invalid_argument for names HDF5 cannot hold and
  /// std::runtime_error if the file cannot be written.
  ResultsWriter(const std::filesystem::path& file, const RunDescription& run, const Interface& x,
                const Interface& y, const Interface& watchpoints = {});
  /// A run restarted after `step`: opens the existing file of the run it continues, checks
  /// that it was written for the same time step and interfaces and holds `step`, drops the
  /// rows after `step` (computed again now) and appends from there. Throws
  /// std::runtime_error naming the file and what does not fit.
  ResultsWriter(const std::filesystem::path& file, const RunDescription& run, const Interface& x,
                const Interface& y, int continue_after_step, const Interface& watchpoints = {});
  /// Closes with status "incomplete" if close() was not called; never throws.
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// Appends one step, its values in record.x, .y and .watchpoints: writes it and flushes the
  /// file, together with the steps kept before it, once the write interval has passed since
  /// the last write (at once with interval 0). The values must have the sizes of the layouts
  /// given at construction and record.solver_times one entry per solver
  /// (std::invalid_argument otherwise; nothing is kept then). If writing fails half-way, the
  /// next write overwrites the partial rows.
  void write_step(const StepRecord& record);
  /// The same with the values in interfaces, whose layouts must be the file's.
  void write_step(const StepRecord& record, const Interface& x, const Interface& y,
                  const Interface& watchpoints = {});
  /// Keep steps in memory until `seconds` of wall time have passed since the last write (or
  /// they hold 64 MB), then write them in one go; 0 (the default) writes every step at once.
  void set_write_interval(double seconds) { write_interval_ = seconds; }
  /// Write and flush the steps kept so far (before a state file that needs them is saved).
  void write_kept_steps();

  /// Writes the final status ("completed", "diverged", "solver_failed", "interrupted", ...) and
  /// why the run stopped, and closes the file. Calling it again does nothing.
  void close(const std::string& status, const std::string& message);

  /// The step a run stopped in (a divergence, a failed solver, an interrupt): its number, time
  /// and the residual norms of its iterations, as group /unfinished_step, so that the failure
  /// can be plotted. Before close().
  void write_unfinished_step(int step, double time, const std::vector<double>& residual_norms);

  const std::filesystem::path& path() const { return path_; }
  bool is_open() const { return file_.valid(); }
  /// Steps given to this run's writer (a restarted run: since the restart), kept ones included.
  int steps_written() const { return rows_ + static_cast<int>(kept_.size()) - rows_before_; }

 private:
  /// One extendible dataset, grown by one row (or by a run of values) per step.
  struct Series {
    H5Handle dataset;
    std::vector<hsize_t> row_shape;  ///< shape of one row: {} for scalars, {n, c} for a block
  };
  /// Where one (model part, variable) block of an interface goes.
  struct BlockSeries {
    Interface::Block block;
    Series series;
  };
  /// The per-step datasets of the groups "steps" and "residuals".
  struct StepSeries {
    Series step, time, iterations, converged, wall_time, coupler_time, solver_times;
    Series norms, offset, count;
  };

  void create_file();
  void check_continuable(const RunDescription& run, int step);
  /// Writes `copy`: the file with rows_ rows (norms_written_ residual norms), no unfinished step.
  void copy_kept_rows(const std::filesystem::path& copy) const;
  void mark_continued(int step);
  std::vector<BlockSeries> open_interface(const char* name, const Interface& interface);
  void open_step_series();
  Series open_series(const std::string& name);
  void write_run_attributes(const RunDescription& run);
  std::vector<BlockSeries> create_interface(const char* name, const char* role,
                                            const Interface& interface);
  void create_step_series();
  static Series create_series(hid_t group, const char* name, hid_t file_type,
                              std::vector<hsize_t> row_shape, const char* unit);
  void check_layouts(const StepRecord& record, const Interface& x, const Interface& y,
                     const Interface& watchpoints) const;
  void check_step(const StepRecord& record) const;
  /// The free bytes where the file is (none: not known).
  std::optional<std::uint64_t> available_bytes() const;
  /// The values a step adds to the file: x, y, watchpoints and its residual norms.
  static std::size_t values_of(const StepRecord& step);
  std::size_t series_count() const {
    return x_blocks_.size() + y_blocks_.size() + watchpoint_blocks_.size() + 10;
  }
  /// How many of the kept steps, from the first, the disk clearly has room for, with room to
  /// close the file (see the .cpp); all of them when nothing is known.
  std::size_t steps_with_room() const;
  /// Writes the kept steps and flushes.
  void write_batch();
  /// A kept batch is written at the latest after this many steps, whatever the interval: a run
  /// killed at once loses at most these (0.1 ms a flush: under 1 % of 1 ms steps).
  static constexpr std::size_t kMaxKeptSteps = 100;
  /// Room kept for closing the file (attributes, metadata flushed at close).
  static constexpr std::uint64_t kClosingReserveBytes = 256 * 1024;
  void write_interface(const std::vector<BlockSeries>& blocks,
                       Eigen::VectorXd StepRecord::*interface);
  void write_residuals();
  void write_step_scalars();
  /// One value (of `row_size` elements) per kept step, from `value`, as rows rows_, ... .
  template <class T, class Value>
  void write_kept(const Series& series, hid_t memory_type, std::size_t row_size, Value value);
  /// The kept steps' rows of `series`, laid out one after the other in `rows`.
  void write_kept_rows(const Series& series, hid_t memory_type, const void* rows);
  void flush();
  /// Closes every handle, the file last; returns the status of closing the file.
  herr_t release();
  [[noreturn]] void fail(const std::exception& error) const;

  std::filesystem::path path_;
  std::size_t solver_count_ = 0;
  int rows_ = 0;         ///< rows in the file's per-step datasets
  int rows_before_ = 0;  ///< of them, written by the run this one continues
  hsize_t norms_written_ = 0;
  std::vector<StepRecord> kept_;  ///< steps given to write_step() and not yet in the file
  std::size_t kept_values_ = 0;
  double write_interval_ = 0.0;  ///< s
  std::chrono::steady_clock::time_point last_write_ = std::chrono::steady_clock::now();

  // Declared first so that it is destroyed last: the datasets below live in it.
  H5Handle file_;
  std::vector<BlockSeries> x_blocks_, y_blocks_, watchpoint_blocks_;
  StepSeries steps_;
};

}  // namespace cocopp
