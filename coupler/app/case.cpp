#include "coupler/app/case.hpp"

#include <cmath>

namespace cocopp {

namespace {

/// Time settings: delta_t, a start step, and either a number of steps or an end time.
RunSettings read_run_settings(const Settings& s, const std::filesystem::path& case_directory) {
  RunSettings run;
  run.case_directory = case_directory;
  run.delta_t = s.required_in_range("delta_t", Range::positive());
  run.timestep_start = s.get_int_in_range("timestep_start", 0, 0);
  const bool has_steps = s.has("number_of_timesteps");
  const bool has_end = s.has("end_time");
  if (has_steps == has_end) s.fail("", "give exactly one of 'number_of_timesteps' and 'end_time'");
  if (has_steps) {
    run.number_of_timesteps = s.get_int_in_range("number_of_timesteps", 1, 1);
  } else {
    const double start_time = run.timestep_start * run.delta_t;
    const double end_time =
        s.required_in_range("end_time", Range::at_least(start_time + run.delta_t));
    const double steps = (end_time - start_time) / run.delta_t;
    // Round to the nearest step; an end time between steps is a mistake worth reporting.
    if (std::abs(steps - std::round(steps)) > 1e-6 * steps)
      s.fail("end_time", "is not a whole number of time steps after the start (" +
                             std::to_string(steps) + " steps of delta_t)");
    run.number_of_timesteps = static_cast<int>(std::round(steps));
  }
  return run;
}

}  // namespace

Case load_case(const std::filesystem::path& file) {
  Settings root = Settings::load_file(file);
  Case c;
  c.file = file;
  const Settings settings = root.child("settings");
  c.run = read_run_settings(settings, root.base_directory());
  c.results_directory =
      root.base_directory() / settings.get<std::string>("results_directory", "results");
  c.results_name = settings.get<std::string>("results_name", file.stem().string());
  c.state_interval = settings.get_int_in_range("state_interval", 0, 0);

  const Settings coupled = root.child("coupled_solver");
  c.coupled_solver_type = coupled.required<std::string>("type");
  c.coupled_solver = CoupledSolverRegistry::instance().create(coupled);

  const auto wrappers = root.list("solver_wrappers");
  if (wrappers.size() != 2)
    root.fail("solver_wrappers",
              "needs exactly two solver wrappers (the first takes displacement and gives loads, "
              "the second takes loads and gives displacement), got " +
                  std::to_string(wrappers.size()));
  for (const auto& w : wrappers)
    c.solvers.push_back(SolverWrapperRegistry::instance().create(w, c.run));
  if (c.solvers[0]->name() == c.solvers[1]->name())
    wrappers[1].fail("name", "both solver wrappers are called '" + c.solvers[0]->name() +
                                 "': give them different names");
  c.coupled_solver->create_own_solvers(c.run);

  root.check_unused_keys();
  return c;
}

}  // namespace cocopp
