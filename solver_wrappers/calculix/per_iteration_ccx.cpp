#include "solver_wrappers/calculix/per_iteration_ccx.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <set>

#include "core/case/settings.hpp"
#include "core/data/restart_file.hpp"
#include "solver_wrappers/calculix/ccx_run.hpp"
#include "solver_wrappers/calculix/dat_file.hpp"
#include "solver_wrappers/calculix/sta_file.hpp"
#include "solver_wrappers/process/child_process.hpp"

namespace cocopp::calculix {

namespace {

using Clock = std::chrono::steady_clock;

/// An output FREQUENCY no step reaches (ccx takes at most this many increments a step only if
/// told so), so that only the step's last increment is written.
constexpr int kStepEndOnly = 1000000;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void write_lines(std::ofstream& out, const std::vector<DeckLine>& lines) {
  for (const auto& line : lines) out << line.text << "\n";
}

/// ccx's output cards, whose FREQUENCY says at which increments they write.
bool is_output_card(const std::string& text) {
  if (text.empty() || text[0] != '*' || text.rfind("**", 0) == 0) return false;
  const std::string card = upper(text.substr(0, text.find(',')));
  for (const char* name :
       {"*NODE FILE", "*EL FILE", "*NODE PRINT", "*EL PRINT", "*NODE OUTPUT", "*ELEMENT OUTPUT",
        "*CONTACT FILE", "*CONTACT PRINT", "*CONTACT OUTPUT", "*SECTION PRINT"})
    if (card.rfind(name, 0) == 0 && card.size() == std::string(name).size()) return true;
  return false;
}

/// A coupling iteration's results are read at the step's end only, and ccx always writes the
/// step's last increment: the deck's output cards without a FREQUENCY (or TIME POINTS, which
/// a deck that sets either keeps on all its cards) write nothing before it. A step of the wire
/// drawing case took 4 increments, and its output a seventh of ccx's time.
void output_at_step_end(std::vector<DeckLine>& step) {
  for (const auto& line : step)
    if (is_output_card(line.text)) {
      const std::string card = upper(line.text);
      if (card.find("FREQUENCY") != std::string::npos ||
          card.find("TIME POINTS") != std::string::npos)
        return;
    }
  for (auto& line : step)
    if (is_output_card(line.text)) line.text += fmt::format(", FREQUENCY={}", kStepEndOnly);
}

/// Whether results depend on the load path through material state variables.
bool has_material_history(const InputDeck& deck) {
  for (const char* keyword : {"PLASTIC", "CREEP", "CYCLIC HARDENING", "USER MATERIAL", "DEPVAR"})
    if (deck.has_keyword(keyword)) return true;
  return false;
}

using DeckElement = std::pair<const std::int64_t, Element>;

/// The deck's first element (by number) whose type satisfies `is`, or null.
template <class Predicate>
const DeckElement* first_element(const InputDeck& deck, Predicate is) {
  for (const auto& element : deck.elements())
    if (is(element.second.type)) return &element;
  return nullptr;
}

/// Whether ccx integrates this element type with reduced integration (2D, shell and beam
/// elements are expanded to C3D8R or C3D20R).
bool is_reduced_integration(const std::string& type) {
  static const std::set<std::string> reduced = {"C3D8R", "C3D20R", "CPS4R", "CPE4R",
                                                "CPS8R", "CPE8R",  "CAX4R", "CAX8R",
                                                "S4R",   "S8R",    "B31R",  "B32R"};
  return reduced.count(type) != 0;
}

bool is_axisymmetric(const std::string& type) {
  return type.rfind("CAX", 0) == 0;
}

}  // namespace

PerIterationCcx::PerIterationCcx(CalculixModel& model, Options options, Drive drive)
    : model_(model), options_(std::move(options)), drive_(std::move(drive)) {
  check_deck();
}

void PerIterationCcx::check_deck() const {
  const InputDeck& deck = *model_.deck;
  if (deck.procedure() == "DYNAMIC" &&
      std::abs(deck.step_time_period() - model_.run.delta_t) > 1e-9 * model_.run.delta_t)
    throw DeckError(fmt::format(
        "{}: the *DYNAMIC step's time period is {}, the coupling time step delta_t is {}: "
        "they must be equal",
        deck.step().front().where, deck.step_time_period(), model_.run.delta_t));
  check_dynamic_elements();
  if (options_.carry_initial_increment && !deck.procedure_data_line())
    throw CaseError(fmt::format(
        "{}: initial_increment: previous_iteration, but the *{} card of {} has no data line "
        "to carry the increment on: give it one (initial increment, time period, ...) or "
        "remove the key",
        options_.initial_increment_where, deck.procedure(), model_.input_file));
}

// ccx starts every *DYNAMIC step by solving for the acceleration with the internal forces of
// reduced-integration elements integrated at the full set of points (nonlingeo.c: intscheme =
// 1), not at the reduced points its increments use. One step per coupling time step makes that
// mismatch repeat every step, and it grows without bound (docs/solver-wrappers-calculix.md).
void PerIterationCcx::check_dynamic_elements() const {
  const InputDeck& deck = *model_.deck;
  if (deck.procedure() != "DYNAMIC" || options_.allow_reduced_integration) return;
  if (const auto* element = first_element(deck, is_reduced_integration))
    throw DeckError(fmt::format(
        "{}: element {} is a {} (reduced integration) in a *DYNAMIC deck: ccx 2.20 computes "
        "the acceleration at the start of each step with full integration, and over a series "
        "of one-step coupling time steps this mismatch grows without bound (a C3D20R tube "
        "wall blows up after 8 to 40 steps). Use the fully integrated element ({}), or set "
        "allow_reduced_integration: true in the case file to run it anyway",
        deck.step().front().where, element->first, element->second.type,
        element->second.type.substr(0, element->second.type.size() - 1)));
}

void PerIterationCcx::start(const Interface& /*input*/, Interface& output) {
  ccx_path_ = find_executable(options_.executable, model_.working_directory);
  choose_state_reset();
  check_warm_start();
  std::filesystem::remove(model_.file(kConvergedRestart));
  std::filesystem::remove(model_.file(kGuess));
  std::filesystem::remove(model_.file(kNextGuess));
  if (model_.run.timestep_start > 0) restore(model_.run.timestep_start, output);
}

// Restart files reset the model exactly when this ccx restarts what the deck needs: Debian's
// ccx drops the material state variables and crashes on axisymmetric models; the patched one
// (scripts/calculix/) does neither. `auto` replays where restarting would be wrong.
void PerIterationCcx::choose_state_reset() {
  const InputDeck& deck = *model_.deck;
  state_reset_ = options_.state_reset == "replay" ? StateReset::kReplay : StateReset::kRestart;
  const bool history = has_material_history(deck);
  const auto* axisymmetric = first_element(deck, is_axisymmetric);
  if (state_reset_ == StateReset::kReplay || (!history && axisymmetric == nullptr)) return;
  const CcxRestartSupport& support = ccx_support();
  const bool crashes = axisymmetric != nullptr && !support.axisymmetry;
  const bool forgets = history && !support.state_variables;
  if (options_.state_reset == "auto") {
    if (crashes || forgets) state_reset_ = StateReset::kReplay;
    return;
  }
  // An explicit restart that would forget the plastic state is the user's choice (documented);
  // one that would crash is not.
  if (crashes)
    throw CaseError(fmt::format(
        "{}: solver '{}': state_reset: restart, but {} crashes when it restarts an "
        "axisymmetric model (element {} is a {}): use the ccx that scripts/install-calculix.sh "
        "builds (the default executable), or state_reset: auto or replay",
        options_.state_reset_where, model_.name, ccx_path_.string(), axisymmetric->first,
        axisymmetric->second.type));
}

// `ccx -v` is a process start: asked once, by whichever check needs it first.
const CcxRestartSupport& PerIterationCcx::ccx_support() const {
  if (!ccx_support_) ccx_support_ = restart_support(ccx_path_, model_.working_directory);
  return *ccx_support_;
}

// A guess is recorded per increment, by the fraction of the step it ends at: replayed steps
// would take the guess of the step being solved, and a ccx without the patch would ignore it.
void PerIterationCcx::check_warm_start() const {
  if (!options_.warm_start) return;
  if (state_reset_ == StateReset::kReplay)
    throw CaseError(fmt::format(
        "{}: solver '{}': warm_start: true needs state_reset: restart (each ccx run solves one "
        "time step), but this run replays the committed steps{}: remove warm_start or use the "
        "ccx that scripts/install-calculix.sh builds",
        options_.warm_start_where, model_.name,
        options_.state_reset == "replay" ? "" : " (the ccx cannot restart what the deck needs)"));
  if (!ccx_support().warm_start)
    throw CaseError(fmt::format(
        "{}: solver '{}': warm_start: true, but {} does not report cocopp's warm start patch "
        "(scripts/calculix/07-warm-start.patch): use the ccx that scripts/install-calculix.sh "
        "builds (the default executable), or remove warm_start",
        options_.warm_start_where, model_.name, ccx_path_.string()));
}

void PerIterationCcx::initialize_step(int /*step*/, double /*time*/) {
  carried_increment_.reset();  // a new step tries the deck's initial increment first
  std::filesystem::remove(model_.file(kGuess));  // the last step's increments are no guess
}

void PerIterationCcx::solve(const Interface& input, Interface& output) {
  const auto start = Clock::now();
  write_loads(input);
  write_iteration_deck();
  const std::filesystem::path results = model_.file(std::string(kJob) + ".dat");
  std::filesystem::remove(results);  // never read an earlier iteration's results
  std::filesystem::remove(model_.file(std::string(kJob) + ".rout"));
  if (has_converged_restart_)
    std::filesystem::copy_file(model_.file(kConvergedRestart),
                               model_.file(std::string(kJob) + ".rin"),
                               std::filesystem::copy_options::overwrite_existing);
  const double prepare_seconds = seconds_since(start);

  run_ccx();

  const auto read_start = Clock::now();
  // Where ccx's first attempt at the deck's increment failed and it cut back, the step's next
  // iterations (loads close to this one's) start at the increment that converged: the same
  // increments, so the same answer, without the failed attempt's Newton iterations.
  if (options_.carry_initial_increment) {
    const auto increment = carried_initial_increment(
        read_sta(model_.file(std::string(kJob) + ".sta")), model_.deck->initial_increment());
    if (increment) carried_increment_ = increment;
  }
  try {
    read_output(output);
  } catch (const std::runtime_error& e) {
    model_.fail(fmt::format("solver '{}' at {}: {}", model_.name, model_.position(), e.what()));
  }
  timing_.wrapper_seconds = prepare_seconds + seconds_since(read_start);
}

void PerIterationCcx::read_output(Interface& output) {
  const std::filesystem::path results = model_.file(std::string(kJob) + ".dat");
  const RowMatrix displacement =
      read_node_print(results, "displacements", model_.node_set_name, model_.interface_nodes);
  if (!drive_.drive) {
    output.values(model_.node_set_name, "displacement") = displacement;
    return;
  }
  surface_displacement_ =
      read_node_print(results, "displacements", drive_.node_set_name, drive_.nodes);
  output.values(model_.node_set_name, "displacement") = drive_.drive->balance(
      displacement, read_node_print(results, "forces", drive_.node_set_name, drive_.nodes));
  auto driven = output.values(model_.node_set_name, "driven");
  for (std::size_t i = 0; i < model_.interface_nodes.size(); ++i)
    driven(static_cast<Eigen::Index>(i), 0) =
        drive_.drive->drives(model_.interface_nodes[i]) ? 1.0 : 0.0;
}

void PerIterationCcx::write_loads(const Interface& input) const {
  const auto [pressure, traction, force] = model_.face_loads(input);
  const auto loads_file = model_.file(kLoadsFile);
  if (!drive_.drive) {
    model_.loads->write(loads_file, pressure, traction, force);
    return;
  }
  DisplacementDrive::Inputs inputs{
      pressure,
      traction,
      force,
      input.values(model_.surface_name, "gap").col(0),
      input.values(model_.surface_name, "coverage").col(0),
      input.values(drive_.node_set_name, DisplacementDrive::kNodeVariable)};
  if (!inputs.gap.allFinite() || !inputs.coverage.allFinite() ||
      !inputs.wall_displacement.allFinite())
    model_.fail(
        fmt::format("solver '{}' at {}: the gap, wall displacement or coverage contain NaN or "
                    "infinity",
                    model_.name, model_.position()));
  drive_.drive->plan(inputs, converged_surface_);
  std::ofstream out(loads_file);
  out << "** Interface loads of this coupling iteration, written by cocopp\n";
  drive_.drive->write(out);
  if (!out.flush()) model_.fail("cannot write the loads file " + loads_file.string());
}

void PerIterationCcx::write_iteration_deck() const {
  const std::filesystem::path deck_file = model_.file(std::string(kJob) + ".inp");
  std::ofstream out(deck_file);
  out << "** Coupling iteration deck written by cocopp from " << model_.input_file << "\n";
  if (state_reset_ == StateReset::kRestart) {
    if (has_converged_restart_) {
      out << "** Restart from the converged state of the previous time step\n*RESTART, READ\n";
    } else {
      out << "*INCLUDE, INPUT=" << kModelFile << "\n";
    }
    out << "*RESTART, WRITE, FREQUENCY=1\n";
  } else {
    out << "*INCLUDE, INPUT=" << kModelFile << "\n";
    out << "** The committed time steps again, with their converged loads\n";
    for (const auto& loads : committed_loads_) write_step(out, loads, false);
  }
  write_step(out, kLoadsFile, true);
  if (!out.flush()) model_.fail("cannot write " + deck_file.string());
}

void PerIterationCcx::write_step(std::ofstream& out, const std::string& loads_file,
                                 bool print) const {
  std::vector<DeckLine> step = model_.deck->step();
  // The step being solved starts with the carried increment; replayed steps as the deck says.
  if (print && carried_increment_) {
    std::string& data = step.at(*model_.deck->procedure_data_line()).text;
    const auto comma = data.find(',');
    data = ccx_number(*carried_increment_) + (comma == std::string::npos ? "" : data.substr(comma));
  }
  std::vector<DeckLine> added = {{"*INCLUDE, INPUT=" + loads_file, ""}};
  const auto node_print = [&](const std::string& set, const char* global, const char* what) {
    added.push_back({"*NODE PRINT, NSET=" + set + ", GLOBAL=" + global, ""});
    added.push_back({what, ""});
  };
  if (print) node_print(model_.node_set_name, "YES", "U");
  // The forces the driven nodes take, in their own systems (the driven direction's).
  if (print && drive_.drive) {
    node_print(drive_.node_set_name, "NO", "RF");
    node_print(drive_.node_set_name, "YES", "U");
  }
  step.insert(step.end() - 1, added.begin(), added.end());  // before *END STEP
  output_at_step_end(step);
  write_lines(out, step);
}

void PerIterationCcx::run_ccx() {
  CcxRunOptions options{ccx_path_,       model_.working_directory, kJob,
                        model_.log_file, model_.threads,           model_.timeout};
  if (options_.warm_start) {
    std::filesystem::remove(model_.file(kNextGuess));
    options.environment.emplace_back("COCOPP_CCX_GUESS_OUT", model_.file(kNextGuess).string());
    if (std::filesystem::exists(model_.file(kGuess)))
      options.environment.emplace_back("COCOPP_CCX_GUESS_IN", model_.file(kGuess).string());
  }
  CcxRunResult result;
  try {
    result = calculix::run_ccx(options);
  } catch (const std::runtime_error& e) {
    model_.fail(fmt::format("solver '{}': cannot start ccx at {}: {}", model_.name,
                            model_.position(), e.what()));
  }
  timing_.ccx_seconds = result.seconds;
  const std::string deck = model_.file(std::string(kJob) + ".inp").string();
  using Status = CcxRunResult::Status;
  switch (result.status) {
    case Status::kSuccess:
      // This run's increments are the next iteration's guess; a failed run keeps the last.
      if (options_.warm_start && std::filesystem::exists(model_.file(kNextGuess)))
        std::filesystem::rename(model_.file(kNextGuess), model_.file(kGuess));
      return;
    case Status::kNotConverged:
      // The step starts from the converged restart (or the replayed steps) again at the next
      // solve, so the coupled solver may retry with other loads.
      throw model_.not_converged(result.exit_description, deck, result.details);
    case Status::kDeckError:
      model_.fail(fmt::format(
          "solver '{}': ccx rejected the input deck at {} ({}); deck {} (built from {}), "
          "ccx says:\n{}(full output in {})",
          model_.name, model_.position(), result.exit_description, deck, model_.input_file,
          result.details, model_.log_file.string()));
    case Status::kTimedOut:
      model_.fail(
          fmt::format("solver '{}': ccx did not finish within {} s at {} and was stopped; "
                      "last lines of {}:\n{}",
                      model_.name, model_.timeout, model_.position(), model_.log_file.string(),
                      result.details));
    case Status::kFailed:
      break;
  }
  model_.fail(fmt::format("solver '{}': ccx {} at {}; deck {}, last lines of {}:\n{}", model_.name,
                          result.exit_description, model_.position(), deck,
                          model_.log_file.string(),
                          result.details.empty() ? "(the log is empty)" : result.details));
}

void PerIterationCcx::commit_surface_displacement() {
  converged_surface_.clear();
  for (std::size_t i = 0; i < drive_.nodes.size(); ++i)
    converged_surface_[drive_.nodes[i]] =
        surface_displacement_.row(static_cast<Eigen::Index>(i)).transpose();
}

void PerIterationCcx::finalize_step() {
  // The last iteration is the converged one: its end state is the next step's start.
  if (drive_.drive) commit_surface_displacement();
  if (state_reset_ == StateReset::kReplay) {
    const std::string loads = fmt::format("cocopp_loads_step{:05d}.inp", model_.step);
    std::filesystem::copy_file(model_.file(kLoadsFile), model_.file(loads),
                               std::filesystem::copy_options::overwrite_existing);
    committed_loads_.push_back(loads);
    return;
  }
  const std::filesystem::path restart = model_.file(std::string(kJob) + ".rout");
  if (!std::filesystem::exists(restart))
    model_.fail(fmt::format("solver '{}': ccx wrote no restart file {} at time step {}",
                            model_.name, restart.string(), model_.step));
  std::filesystem::rename(restart, model_.file(kConvergedRestart));
  has_converged_restart_ = true;
}

void PerIterationCcx::output_step() {
  if (!options_.save_results) return;
  const std::filesystem::path directory = model_.file("results");
  std::filesystem::create_directories(directory);
  for (const char* extension : {".frd", ".dat"}) {
    const std::filesystem::path source = model_.file(std::string(kJob) + extension);
    if (std::filesystem::exists(source))
      std::filesystem::copy_file(source,
                                 directory / fmt::format("step_{:05d}{}", model_.step, extension),
                                 std::filesystem::copy_options::overwrite_existing);
  }
}

// What a restart after `step` needs besides the deck: the interface displacement (the faces of
// an NLGEOM model follow it, the coupler starts from it) and the committed ccx state: the
// converged restart file, or (replay) the loads of every committed step, which stay in the
// working directory anyway.
void PerIterationCcx::save_restart(int step, const Interface& output) {
  const RowMatrix u = output.values(model_.node_set_name, "displacement");
  RestartData data = {{"displacement", Eigen::Map<const Eigen::VectorXd>(u.data(), u.size())}};
  // Driven by displacement: where the next step's faces start (every surface node's).
  if (drive_.drive)
    data["surface_displacement"] = Eigen::Map<const Eigen::VectorXd>(surface_displacement_.data(),
                                                                     surface_displacement_.size());
  write_restart_file(model_.file(restart_file_name(model_.name, step).string()), model_.name, step,
                     data);
  if (state_reset_ == StateReset::kRestart && has_converged_restart_)
    std::filesystem::copy_file(model_.file(kConvergedRestart), saved_restart(step),
                               std::filesystem::copy_options::overwrite_existing);
}

void PerIterationCcx::restore(int step, Interface& output) {
  const std::filesystem::path data_file =
      model_.file(restart_file_name(model_.name, step).string());
  auto u = output.values(model_.node_set_name, "displacement");
  try {
    const RestartData data = read_restart_file(data_file, model_.name, step);
    const Eigen::VectorXd saved = restart_array(data, "displacement", u.size(), data_file);
    u = Eigen::Map<const RowMatrix>(saved.data(), u.rows(), u.cols());
    if (drive_.drive) {
      const auto rows = static_cast<Eigen::Index>(drive_.nodes.size());
      const Eigen::VectorXd surface =
          restart_array(data, "surface_displacement", 3 * rows, data_file);
      surface_displacement_ = Eigen::Map<const RowMatrix>(surface.data(), rows, 3);
      commit_surface_displacement();
    }
  } catch (const std::runtime_error& e) {
    model_.fail(fmt::format("solver '{}' cannot restart after time step {}: {}", model_.name, step,
                            e.what()));
  }
  model_.step = step;
  model_.move_faces_with(output);
  if (state_reset_ == StateReset::kReplay) {
    for (int committed = 1; committed <= step; ++committed) {
      const std::string loads = fmt::format("cocopp_loads_step{:05d}.inp", committed);
      if (!std::filesystem::exists(model_.file(loads)))
        model_.fail(
            fmt::format("solver '{}' cannot restart after time step {} (state_reset: replay): "
                        "the loads of step {}, {}, are gone",
                        model_.name, step, committed, model_.file(loads).string()));
      committed_loads_.push_back(loads);
    }
    return;
  }
  if (!std::filesystem::exists(saved_restart(step)))
    model_.fail(
        fmt::format("solver '{}' cannot restart after time step {}: its ccx restart file {} is "
                    "not there (saved with the coupler's state)",
                    model_.name, step, saved_restart(step).string()));
  std::filesystem::copy_file(saved_restart(step), model_.file(kConvergedRestart),
                             std::filesystem::copy_options::overwrite_existing);
  has_converged_restart_ = true;
}

std::filesystem::path PerIterationCcx::saved_restart(int step) const {
  return model_.file(fmt::format("restart/{}_{:06d}.rout", model_.name, step));
}

}  // namespace cocopp::calculix
