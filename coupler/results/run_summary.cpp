#include "coupler/results/run_summary.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <system_error>
#include <utility>

#ifndef COCOPP_VERSION
#define COCOPP_VERSION "unknown"  // set from PROJECT_VERSION in coupler/CMakeLists.txt
#endif

namespace cocopp {
namespace {

using nlohmann::json;

/// `numerator / denominator`, or null when there is nothing to divide by.
json ratio(double numerator, double denominator) {
  if (denominator == 0) return nullptr;
  return numerator / denominator;
}

[[noreturn]] void throw_errno(const std::string& what, const std::filesystem::path& file) {
  throw std::runtime_error("cannot write run summary '" + file.string() + "': " + what + ": " +
                           std::strerror(errno));
}

/// Writes all of `text` to a new file and fsyncs it, so the rename that follows publishes
/// complete contents even if the machine goes down right after.
void write_synced(const std::filesystem::path& file, const std::string& text) {
  // A new file (O_EXCL), never through a link planted at the name.
  ::unlink(file.c_str());
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) throw_errno("open", file);
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int saved = errno;
      ::close(fd);
      errno = saved;
      throw_errno("write", file);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int saved = errno;
    ::close(fd);
    errno = saved;
    throw_errno("fsync", file);
  }
  if (::close(fd) != 0) throw_errno("close", file);
}

}  // namespace

RunSummary::RunSummary(RunDescription run)
    : run_(std::move(run)), solver_times_(run_.solver_names.size(), 0.0) {}

void RunSummary::check_solver_times(const std::vector<double>& times, const char* what) const {
  if (times.size() != run_.solver_names.size())
    throw std::invalid_argument(std::string("run summary: ") + what + " has " +
                                std::to_string(times.size()) +
                                " solver times, expected one per solver (" +
                                std::to_string(run_.solver_names.size()) + ")");
}

void RunSummary::add_step(const StepRecord& record) {
  check_solver_times(record.solver_times, ("step " + std::to_string(record.step)).c_str());
  steps_.push_back(record.step);
  iterations_.push_back(record.iterations);
  if (record.surrogate_iterations > 0) surrogate_iterations_.push_back(record.surrogate_iterations);
  residuals_.push_back(record.residual_norms);
  if (!record.converged) unconverged_steps_.push_back(record.step);
  if (record.at_noise) steps_at_noise_.push_back(record.step);
  for (const auto& warning : record.warnings)
    warnings_.push_back("step " + std::to_string(record.step) + ": " + warning);
  wall_time_ += record.wall_time;
  steps_wall_time_ += record.wall_time;
  coupler_time_ += record.coupler_time;
  iteration_coupler_time_ += record.coupler_time;
  for (std::size_t i = 0; i < solver_times_.size(); ++i) solver_times_[i] += record.solver_times[i];
}

void RunSummary::finish(const RunOutcome& outcome, double total_wall_time,
                        const std::vector<double>& total_solver_times, double total_coupler_time) {
  check_solver_times(total_solver_times, "finish");
  finished_ = true;
  outcome_ = outcome;
  wall_time_ = total_wall_time;
  solver_times_ = total_solver_times;
  coupler_time_ = total_coupler_time;
}

double RunSummary::solver_time() const {
  return std::accumulate(solver_times_.begin(), solver_times_.end(), 0.0);
}

json RunSummary::solver_times_json() const {
  // Keyed by solver name; a repeated name gets a suffix ("tube", "tube_2") rather than
  // silently replacing the first solver's time.
  json out = json::object();
  for (std::size_t i = 0; i < solver_times_.size(); ++i) {
    std::string key = run_.solver_names[i];
    for (int n = 2; out.contains(key); ++n) key = run_.solver_names[i] + "_" + std::to_string(n);
    out[key] = solver_times_[i];
  }
  return out;
}

long RunSummary::total_iterations() const {
  return std::accumulate(iterations_.begin(), iterations_.end(), 0L);
}

double RunSummary::average_iterations() const {
  return steps_.empty() ? std::numeric_limits<double>::quiet_NaN()
                        : static_cast<double>(total_iterations()) / steps_.size();
}

json RunSummary::to_json() const {
  const long total_iterations = this->total_iterations();
  const auto steps = static_cast<double>(steps_.size());
  json out;
  out["cocopp_version"] = COCOPP_VERSION;
  out["case"] = run_.case_file;
  out["coupled_solver"] = run_.coupled_solver;
  out["solvers"] = run_.solver_names;
  out["delta_t"] = run_.delta_t;
  out["timestep_start"] = run_.timestep_start;
  out["number_of_timesteps"] = run_.number_of_timesteps;
  out["restarted"] = run_.restarted;
  out["completed"] = finished_ && ran_all_steps(outcome_.status);
  out["status"] = finished_ ? to_string(outcome_.status) : "running";
  out["message"] = outcome_.message;
  out["reason"] = outcome_.reason;
  // Where a stopped run stopped: the step, and the coupling iteration where it is known.
  json stopped_at = nullptr;
  if (outcome_.step > 0)
    stopped_at = {{"step", outcome_.step},
                  {"iteration", outcome_.iteration > 0 ? json(outcome_.iteration) : json(nullptr)}};
  out["stopped_at"] = stopped_at;
  out["steps_completed"] = steps_.size();
  out["steps_written"] = steps_written_ ? json(*steps_written_) : json(nullptr);
  out["last_step"] = steps_.empty() ? json(nullptr) : json(steps_.back());
  out["iterations_per_step"] = iterations_;
  out["average_iterations"] = ratio(static_cast<double>(total_iterations), steps);
  if (!surrogate_iterations_.empty()) out["surrogate_iterations_per_step"] = surrogate_iterations_;
  out["unconverged_steps"] = unconverged_steps_;
  out["steps_at_noise"] = steps_at_noise_;
  out["warnings"] = warnings_;
  out["residual_history"] = residuals_;
  out["wall_time"] = wall_time_;
  out["solver_times"] = solver_times_json();
  out["coupler_time"] = coupler_time_;
  out["coupler_time_per_iteration"] = ratio(coupler_time_, static_cast<double>(total_iterations));
  // The coupling algorithm's own cost inside the time steps (no start-up, no results I/O).
  out["step_coupler_time"] = iteration_coupler_time_;
  out["step_coupler_time_per_iteration"] =
      ratio(iteration_coupler_time_, static_cast<double>(total_iterations));
  return out;
}

void RunSummary::write(const std::filesystem::path& file) const {
  // Invalid UTF-8 (e.g. solver output quoted in the message) is replaced, not thrown on.
  const std::string text = to_json().dump(2, ' ', false, json::error_handler_t::replace) + "\n";
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  // Same directory, so the rename stays on one file system and is atomic.
  std::filesystem::path temporary = file;
  temporary += ".tmp." + std::to_string(::getpid());
  std::error_code ignored;
  try {
    write_synced(temporary, text);
  } catch (...) {
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  std::error_code error;
  std::filesystem::rename(temporary, file, error);
  if (error) {
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write run summary '" + file.string() + "': renaming '" +
                             temporary.string() + "' to it failed: " + error.message());
  }
}

}  // namespace cocopp
