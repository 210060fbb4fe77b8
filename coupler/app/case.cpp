#include "coupler/app/case.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <utility>

namespace cocopp {

namespace {

/// Time settings: delta_t, a start step, and either a number of steps or an end time.
RunSettings read_run_settings(const Settings& s, const std::filesystem::path& case_directory) {
  RunSettings run;
  run.case_directory = case_directory;
  run.delta_t = s.required_in_range("delta_t", Range::positive());
  // Step numbers up to timestep_start + number_of_timesteps must fit an int: cap both.
  constexpr int kMostSteps = 1'000'000'000;
  run.timestep_start = s.get_int_in_range("timestep_start", 0, 0, kMostSteps);
  const bool has_steps = s.has("number_of_timesteps");
  const bool has_end = s.has("end_time");
  if (has_steps == has_end) {
    const std::string hint =
        has_steps ? "" : s.misspelling_hint("number_of_timesteps") + s.misspelling_hint("end_time");
    s.fail("", "give exactly one of 'number_of_timesteps' and 'end_time'" + hint);
  }
  if (has_steps) {
    run.number_of_timesteps = s.get_int_in_range("number_of_timesteps", 1, 1, kMostSteps);
  } else {
    const double start_time = run.timestep_start * run.delta_t;
    const double end_time =
        s.required_in_range("end_time", Range::at_least(start_time + run.delta_t));
    const double steps = (end_time - start_time) / run.delta_t;
    if (!(steps <= kMostSteps))
      s.fail("end_time", fmt::format("is {:g} time steps of delta_t after the start: at most {} "
                                     "are possible",
                                     steps, kMostSteps));
    // Round to the nearest step; an end time between steps is a mistake worth reporting.
    if (std::abs(steps - std::round(steps)) > 1e-6 * steps)
      s.fail("end_time", "is not a whole number of time steps after the start (" +
                             std::to_string(steps) + " steps of delta_t)");
    run.number_of_timesteps = static_cast<int>(std::round(steps));
  }
  return run;
}

/// The working directories a solver wrapper's settings give (a mapped wrapper's: its inner
/// solver's; a group's: its members'), resolved against the case directory; with the settings
/// that name each.
void collect_working_directories(const Settings& wrapper,
                                 std::vector<std::pair<std::filesystem::path, Settings>>& out) {
  if (wrapper.has("working_directory") &&
      wrapper.required<std::string>("working_directory").empty())
    wrapper.fail("working_directory",
                 "is empty: give the solver's own folder (relative to the case file's), which "
                 "holds its channel to the coupler and its log");
  if (wrapper.has("working_directory"))
    out.emplace_back(
        // (a trailing "/" for every path, so that "flow" and "flow/" compare equal)
        (wrapper.base_directory() / wrapper.required<std::string>("working_directory") / "")
            .lexically_normal(),
        wrapper);
  if (wrapper.has("solver_wrapper"))
    collect_working_directories(wrapper.child("solver_wrapper"), out);
  if (wrapper.has("solver_wrappers") && wrapper.node()["solver_wrappers"].IsSequence())
    for (const auto& member : wrapper.list("solver_wrappers"))
      collect_working_directories(member, out);
}

/// The same folder written two ways ("flow", an absolute path, "../case/flow", a link to it):
/// by name, or, where both exist, by identity (device and inode).
bool same_directory(const std::filesystem::path& a, const std::filesystem::path& b) {
  if (a == b) return true;
  std::error_code error;
  return std::filesystem::equivalent(a, b, error) && !error;
}

/// Two solvers in one working directory would share its channel (the pipes or message files)
/// and their logs: a case error, found before anything starts.
std::vector<std::filesystem::path> own_working_directories(const std::vector<Settings>& wrappers) {
  std::vector<std::pair<std::filesystem::path, Settings>> all;
  for (const auto& wrapper : wrappers) collect_working_directories(wrapper, all);
  std::vector<std::filesystem::path> directories;
  for (std::size_t j = 0; j < all.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i)
      if (same_directory(all[i].first, all[j].first))
        all[j].second.fail("working_directory",
                           "is also another solver's (" + all[i].second.where("working_directory") +
                               "): give each solver its own working directory, which holds its "
                               "channel to the coupler (pipes or message files) and its log");
    directories.push_back(all[j].first);
  }
  return directories;
}

/// Reads the state a restarted run continues from and moves the run's start to its step; the
/// run's end stays where the case puts it.
void prepare_restart(Case& c, bool restart, const Settings& settings) {
  const int case_start = c.run.timestep_start;
  if (!restart && case_start == 0) return;
  const std::string why = restart
                              ? "cocopp run --restart continues from it"
                              : fmt::format(
                                    "{}: settings.timestep_start is {}: the run continues from the "
                                    "state saved after that step",
                                    settings.where("timestep_start"), case_start);
  if (!std::filesystem::exists(c.files.state()))
    throw std::runtime_error(fmt::format(
        "cannot restart: there is no state file {} ({}). A run saves it at its end and every "
        "settings.state_interval steps; {}",
        c.files.state().string(), why,
        restart ? "run the case without --restart first"
                : "set timestep_start to 0 to run from the start"));
  SavedState saved = read_state_file(c.files.state());
  if (!restart && saved.step != case_start)
    throw std::runtime_error(
        fmt::format("cannot restart after step {}: the state file {} holds step {} ({}); set "
                    "timestep_start to {}, or run with --restart",
                    case_start, c.files.state().string(), saved.step, why, saved.step));
  const int end = case_start + c.run.number_of_timesteps;
  if (saved.step >= end)
    throw std::runtime_error(fmt::format(
        "nothing to restart: the state file {} is at step {} and the case ends at step {} "
        "(t = {:g} s): raise settings.number_of_timesteps or settings.end_time to go on",
        c.files.state().string(), saved.step, end, end * c.run.delta_t));
  c.run.timestep_start = saved.step;
  c.run.number_of_timesteps = end - saved.step;
  c.restart = std::move(saved);
}

}  // namespace

Case load_case(const std::filesystem::path& file, bool restart) {
  Settings root = Settings::load_file(file);
  Case c;
  c.file = file;
  const Settings settings = root.child("settings");
  c.run = read_run_settings(settings, root.base_directory());
  // The stem of files the run creates: a plain name when given (not "../x"); the case file's
  // own stem otherwise.
  c.files = {
      root.base_directory() / settings.get<std::string>("results_directory", "results"),
      settings.has("results_name") ? settings.get_name("results_name", "") : file.stem().string()};
  c.results_where = settings.where("results_directory") + ": 'settings.results_directory'";
  c.state_interval = settings.get_int_in_range("state_interval", 0, 0);
  c.watchpoints = Watchpoints(settings);
  c.outputs = create_outputs(settings);
  prepare_restart(c, restart, settings);

  const Settings coupled = root.child("coupled_solver");
  c.coupled_solver_type = coupled.required<std::string>("type");
  c.coupled_solver = CoupledSolverRegistry::instance().create(coupled);

  const auto wrappers = root.list("solver_wrappers");
  if (wrappers.size() != 2)
    root.fail("solver_wrappers",
              "needs exactly two solver wrappers (the first takes displacement and gives loads, "
              "the second takes loads and gives displacement; several solvers on one side: a "
              "`group`), got " +
                  std::to_string(wrappers.size()));
  c.working_directories = own_working_directories(wrappers);
  for (const auto& w : wrappers)
    c.solvers.push_back(SolverWrapperRegistry::instance().create(w, c.run));
  if (c.solvers[0]->name() == c.solvers[1]->name())
    wrappers[1].fail("name", "both solver wrappers are called '" + c.solvers[0]->name() +
                                 "': give them different names");
  c.coupled_solver->check_solvers(*c.solvers[0], *c.solvers[1]);
  c.coupled_solver->create_own_solvers(c.run);

  root.check_unused_keys();
  return c;
}

}  // namespace cocopp
