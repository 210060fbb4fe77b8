#pragma once
// RunOutput: one thing a run writes as it goes, behind one interface that Run::march feeds in a
// plain loop: opened once (a restarted run's outputs continue what the run before wrote), given
// every time step's record (and, if it asks, every coupling iteration's), flushed before a
// state file is saved, closed with how the run ended.
//
// The outputs a case asks for through its `settings` are components: one file each, named
// after its type, with one COCOPP_REGISTER(RunOutputRegistry, "<type>", Class) line; its
// constructor reads its keys from the case's `settings` and active() says whether the case
// asked for it. create_outputs() makes every active one, in the registry's (alphabetical) order.
// The summary and the progress lines are Run's own (summary_output.hpp, progress_output.hpp).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/case/registry.hpp"
#include "core/data/interface.hpp"
#include "coupler/results/run_files.hpp"
#include "coupler/results/run_outcome.hpp"
#include "coupler/results/step_record.hpp"

namespace cocopp {

/// What an output is opened with.
struct OutputStart {
  const RunFiles& files;
  const RunDescription& run;
  const Interface& x;            ///< x's layout (its values: the start's)
  const Interface& y;            ///< y's layout
  const Interface& watchpoints;  ///< the watchpoints' layout; empty without watchpoints
  int continue_after_step = -1;  ///< a restarted run: the step it continues after
};

/// How a run ended, for close().
struct RunEnd {
  RunOutcome outcome;
  /// The step the run stopped in (0: none), its time and the residual norms of its iterations.
  int unfinished_step = 0;
  double unfinished_time = 0.0;
  std::vector<double> unfinished_residuals;
  double wall_time = 0.0;            ///< s, the whole run
  std::vector<double> solver_times;  ///< s, per solver
  double coupler_time = 0.0;         ///< s, the rest
  /// The steps of this run in the results file once it is closed (none: no results file).
  std::optional<int> steps_written;
};

/// A file to name in the run's last lines: ("ParaView", <name>.pvd).
using OutputFile = std::pair<std::string, std::filesystem::path>;

class RunOutput {
 public:
  static constexpr const char* kind = "output";
  virtual ~RunOutput() = default;

  /// Whether the case asked for this output (the registered ones; others are always active).
  virtual bool active() const { return true; }
  /// Create or continue what it writes. Throws std::runtime_error naming the file if it cannot.
  virtual void open(const OutputStart& start) = 0;
  virtual void write_step(const StepRecord& record) = 0;
  /// Whether write_iteration() wants every coupling iteration.
  virtual bool wants_iterations() const { return false; }
  virtual void write_iteration(const IterationReport& /*report*/) {}
  /// Everything given so far on disk: a state file is about to be saved, which a restart
  /// continues from.
  virtual void flush() {}
  /// The last call, with how the run ended. Throws std::runtime_error if what it writes cannot
  /// be written.
  virtual void close(const RunEnd& /*end*/) {}
  /// The files to name at the end of the run.
  virtual std::vector<OutputFile> files() const { return {}; }
  /// The results file's steps of this run, for the summary (none: it keeps no steps).
  virtual std::optional<int> steps_written() const { return std::nullopt; }
};

/// Created from the case's `settings` section.
using RunOutputRegistry = Registry<RunOutput>;

/// Every registered output the case's settings ask for.
std::vector<std::unique_ptr<RunOutput>> create_outputs(const Settings& settings);

}  // namespace cocopp
