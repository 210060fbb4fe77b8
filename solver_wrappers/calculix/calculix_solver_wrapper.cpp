#include "solver_wrappers/calculix/calculix_solver_wrapper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <set>
#include <utility>

#include "core/case/path_problem.hpp"
#include "core/case/suggest.hpp"
#include "core/data/restart_file.hpp"
#include "solver_wrappers/calculix/ccx_run.hpp"
#include "solver_wrappers/calculix/dat_file.hpp"
#include "solver_wrappers/calculix/sta_file.hpp"
#include "solver_wrappers/process/child_process.hpp"
#include "solver_wrappers/process/process_solver_wrapper.hpp"
#include "solver_wrappers/solver_error.hpp"

namespace cocopp {

COCOPP_REGISTER(SolverWrapperRegistry, "calculix", CalculixSolverWrapper)

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void write_lines(std::ofstream& out, const std::vector<calculix::DeckLine>& lines) {
  for (const auto& line : lines) out << line.text << "\n";
}

/// Whether results depend on the load path through material state variables.
bool has_material_history(const calculix::InputDeck& deck) {
  for (const char* keyword : {"PLASTIC", "CREEP", "CYCLIC HARDENING", "USER MATERIAL", "DEPVAR"})
    if (deck.has_keyword(keyword)) return true;
  return false;
}

/// ccx with cocopp's patches: in an install, <prefix>/libexec/cocopp/ccx next to the running
/// cocopp's bin/ (so that the install can move); in the build tree, where
/// scripts/install-calculix.sh built it; else the Debian package's ccx on PATH.
std::string default_executable() {
  std::error_code error;
  const std::filesystem::path bin = builtin_solver_directory();
  if (!bin.empty()) {
    const std::filesystem::path installed = bin.parent_path() / COCOPP_INSTALLED_CCX;
    if (std::filesystem::is_regular_file(installed, error)) return installed.string();
  }
#ifdef COCOPP_PATCHED_CCX
  if (std::filesystem::is_regular_file(COCOPP_PATCHED_CCX, error)) return COCOPP_PATCHED_CCX;
#endif
  return "ccx";
}

/// cocopp-ccx (mode: persistent): next to the running cocopp (the build tree, or an install's
/// bin when COCOPP_BIN_DIR points there), else in an install's libexec/cocopp.
std::string default_coupled_executable() {
  std::error_code error;
  const std::filesystem::path bin = builtin_solver_directory();
  if (bin.empty()) return "cocopp-ccx";
  if (std::filesystem::is_regular_file(bin / "cocopp-ccx", error))
    return (bin / "cocopp-ccx").string();
  return (bin.parent_path() / std::filesystem::path(COCOPP_INSTALLED_CCX).parent_path() /
          "cocopp-ccx")
      .string();
}

using DeckElement = std::pair<const std::int64_t, calculix::Element>;

/// The deck's first element (by number) whose type satisfies `is`, or null.
template <class Predicate>
const DeckElement* first_element(const calculix::InputDeck& deck, Predicate is) {
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

/// A node set's ids, sorted, each once.
std::vector<std::int64_t> sorted_node_set(const calculix::InputDeck& deck,
                                          const std::string& name) {
  std::vector<std::int64_t> nodes = deck.node_set(name);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

/// A model part of the deck's nodes `ids` at their deck coordinates.
std::shared_ptr<ModelPart> node_part(const calculix::InputDeck& deck, const std::string& name,
                                     const std::vector<std::int64_t>& ids) {
  auto part = std::make_shared<ModelPart>();
  part->name = name;
  part->ids = ids;
  part->coordinates.resize(static_cast<Eigen::Index>(ids.size()), 3);
  for (std::size_t i = 0; i < ids.size(); ++i)
    part->coordinates.row(static_cast<Eigen::Index>(i)) = deck.node(ids[i]).transpose();
  return part;
}

}  // namespace

CalculixSolverWrapper::CalculixSolverWrapper(const Settings& settings, const RunSettings& run)
    : run_(run) {
  name_ = settings.get_name("name", "calculix");
  name_given_ = settings.has("name");
  log_file_given_ = settings.has("log_file");
  working_directory_ = std::filesystem::absolute(
                           run.case_directory / settings.required<std::string>("working_directory"))
                           .lexically_normal();
  working_directory_where_ = settings.where("working_directory");
  input_file_ = settings.required<std::string>("input_file");
  input_file_where_ = settings.where("input_file");
  if (std::filesystem::path(input_file_).stem() == kJob)
    settings.fail("input_file", std::string("the name ") + kJob +
                                    " is the wrapper's own job name: rename the deck");
  surface_name_ = settings.required<std::string>("interface_surface");
  node_set_name_ = settings.required<std::string>("interface_node_set");
  executable_ = settings.get<std::string>("executable", default_executable());
  executable_where_ = settings.has("executable") ? settings.where("executable") : settings.where();
  input_variables_ =
      settings.get<std::vector<std::string>>("input_variables", {"pressure", "traction"});
  if (input_variables_.empty())
    settings.fail("input_variables", "give at least one of pressure, traction");
  for (const auto& variable : input_variables_)
    if (variable != "pressure" && variable != "traction")
      settings.fail("input_variables", "'" + variable + "': the loads are pressure and traction");
  displacement_drive_ =
      settings.get_choice("interface_drive", "load", {"load", "displacement"}) == "displacement";
  if (displacement_drive_) {
    driven_dof_ = settings.get_int_in_range("driven_dof", 1, 1, 3);
    driven_node_set_name_ = settings.get<std::string>("driven_node_set", node_set_name_);
    surface_stiffness_ = settings.required<double>("surface_stiffness");
    if (!(surface_stiffness_ > 0.0))
      settings.fail("surface_stiffness",
                    "give the structure's stiffness per area against a push of its surface, "
                    "in Pa/m (about its Young's modulus over the faces' length), > 0");
    if (!takes("pressure"))
      settings.fail("input_variables",
                    "interface_drive: displacement balances the other solver's pressure: "
                    "include pressure");
  }
  threads_ = settings.get_int_in_range("threads", 1, 1, 64);
  timeout_ = settings.get_in_range("timeout", 600.0, Range::timeout());
  save_results_ = settings.get<bool>("save_results", true);
  allow_reduced_integration_ = settings.get<bool>("allow_reduced_integration", false);
  carry_initial_increment_ =
      settings.get_choice("initial_increment", "deck", {"deck", "previous_iteration"}) ==
      "previous_iteration";
  initial_increment_where_ =
      settings.has("initial_increment") ? settings.where("initial_increment") : settings.where();
  state_reset_key_ = settings.get_choice("state_reset", "auto", {"auto", "restart", "replay"});
  state_reset_where_ =
      settings.has("state_reset") ? settings.where("state_reset") : settings.where();
  log_file_ = working_directory_ / settings.get<std::string>("log_file", name_ + ".log");
  read_mode(settings);
}

bool CalculixSolverWrapper::has_coupled_executable() const {
  try {
    find_executable(coupled_executable_, working_directory_);
    return true;
  } catch (const std::runtime_error&) {
    return false;
  }
}

// mode: auto runs per iteration a deck persistent mode cannot run, and the restart of a run that
// ran per iteration (its restart data has no inputs to replay).
void CalculixSolverWrapper::choose_auto_mode() {
  if (!auto_mode_ || !persistent_) return;
  if (!calculix::PersistentCcx::unsupported(*deck_).empty()) {
    persistent_ = false;
    return;
  }
  if (run_.timestep_start == 0) return;
  try {
    const int step = run_.timestep_start;
    persistent_ = read_restart_file(file(restart_file_name(name_, step).string()), name_, step)
                      .count("inputs") != 0;
  } catch (const std::runtime_error&) {
    // Missing or damaged: the restart says so in either mode.
  }
}

// mode: persistent keeps one ccx for the run; what it cannot do is refused here, by key.
void CalculixSolverWrapper::read_mode(const Settings& settings) {
  const std::string mode =
      settings.get_choice("mode", "auto", {"auto", "per_iteration", "persistent"});
  mode_where_ = settings.has("mode") ? settings.where("mode") : settings.where();
  coupled_executable_ =
      settings.get<std::string>("coupled_executable", default_coupled_executable());
  if (mode == "auto") {
    // Persistent where cocopp-ccx is built and no key asks for a ccx run per iteration (a ccx
    // executable of the user's among them); the deck and a restart's data may still say
    // otherwise (choose_auto_mode).
    auto_mode_ = true;
    persistent_ = !settings.has("state_reset") && !settings.has("initial_increment") &&
                  !settings.has("executable") && !displacement_drive_ && has_coupled_executable();
    return;
  }
  persistent_ = mode == "persistent";
  if (!persistent_) return;
  const auto refuse = [&](const char* key, const char* why) {
    if (settings.has(key))
      settings.fail(key, std::string(why) +
                             " with mode: per_iteration only: remove it or use "
                             "that mode");
  };
  refuse("state_reset", "ccx's state is reset from restart files or by replay");
  refuse("initial_increment", "a cut-back increment is carried between ccx runs");
  if (displacement_drive_)
    settings.fail("interface_drive",
                  "interface_drive: displacement works with mode: per_iteration only (its "
                  "driven nodes change from one coupling iteration to the next)");
}

CalculixSolverWrapper::~CalculixSolverWrapper() = default;

void CalculixSolverWrapper::set_default_name(const std::string& name) {
  if (name_given_) return;
  name_ = name;
  if (!log_file_given_) log_file_ = working_directory_ / (name_ + ".log");
}

std::string CalculixSolverWrapper::describe() const {
  if (persistent_)
    return fmt::format("{}: {} -i {} for {} (in {}; log {}; {} thread{}; persistent)", name_,
                       coupled_executable_, calculix::PersistentCcx::kJob, input_file_,
                       working_directory_.string(), log_file_.string(), threads_,
                       threads_ == 1 ? "" : "s");
  return fmt::format("{}: {} -i {} for {} (in {}; log {}; {} thread{}; state reset: {}{})", name_,
                     executable_, kJob, input_file_, working_directory_.string(),
                     log_file_.string(), threads_, threads_ == 1 ? "" : "s", state_reset_key_,
                     displacement_drive_ ? "; driven by displacement under the other solver" : "");
}

void CalculixSolverWrapper::check() const {
  const std::string solver = "solver '" + name_ + "': ";
  if (const auto why = path_problem(working_directory_, PathKind::kDirectory); !why.empty())
    throw CaseError(working_directory_where_ + ": " + solver + "working directory " +
                    working_directory_.string() + " " + why);
  const auto deck = working_directory_ / input_file_;
  if (const auto why = path_problem(deck, PathKind::kRegularFile); !why.empty())
    throw CaseError(input_file_where_ + ": " + solver + "input deck " + deck.string() + " " + why);
  if (persistent_) {
    try {
      find_executable(coupled_executable_, working_directory_);
    } catch (const std::runtime_error& e) {
      throw CaseError(mode_where_ + ": " + solver +
                      "mode: persistent runs cocopp-ccx, which is not there (" + e.what() +
                      "): build it (scripts/install-calculix.sh, then the cocopp build), give "
                      "its path in 'coupled_executable', or use mode: per_iteration");
    }
    if (!auto_mode_) return;  // auto may still run per iteration: ccx too
  }
  try {
    find_executable(executable_, working_directory_);
  } catch (const std::runtime_error& e) {
    throw CaseError(executable_where_ + ": " + solver + "CalculiX (" + e.what() +
                    "): install the Debian package calculix-ccx (scripts/install-dependencies.sh "
                    "does) or give its path in 'executable'");
  }
}

void CalculixSolverWrapper::initialize() {
  check();
  read_deck();
  choose_auto_mode();
  if (!persistent_) {
    ccx_path_ = find_executable(executable_, working_directory_);
    choose_state_reset();
  }
  build_interfaces();
  // The model definition once; every first-step iteration includes it.
  std::ofstream model(file(kModelFile));
  write_lines(model, deck_->model_definition());
  if (!model.flush()) fail("cannot write " + file(kModelFile).string());
  if (persistent_) {
    start_persistent();
    return;
  }
  std::filesystem::remove(file(kConvergedRestart));
  if (run_.timestep_start > 0) restore(run_.timestep_start);
}

// What a restart after `step` needs besides the deck: the interface displacement (the faces
// of an NLGEOM model follow it, the coupler starts from it) and the committed ccx state: the
// converged restart file, or (replay) the loads of every committed step, which stay in the
// working directory anyway.
void CalculixSolverWrapper::save_restart(int step) {
  const RowMatrix u = output_interface_.values(node_set_name_, "displacement");
  if (persistent_) {
    // Persistent, a restart replays the committed steps (replay_committed_steps): their times
    // and inputs, besides the displacement that checks the replay.
    Eigen::VectorXd loads(static_cast<Eigen::Index>(committed_inputs_.size()) *
                          input_interface_.size());
    for (std::size_t k = 0; k < committed_inputs_.size(); ++k)
      loads.segment(static_cast<Eigen::Index>(k) * input_interface_.size(),
                    input_interface_.size()) = committed_inputs_[k];
    write_restart_file(file(restart_file_name(name_, step).string()), name_, step,
                       {{"displacement", Eigen::Map<const Eigen::VectorXd>(u.data(), u.size())},
                        {"times", Eigen::Map<const Eigen::VectorXd>(
                                      committed_times_.data(),
                                      static_cast<Eigen::Index>(committed_times_.size()))},
                        {"inputs", loads}});
    return;
  }
  write_restart_file(file(restart_file_name(name_, step).string()), name_, step,
                     {{"displacement", Eigen::Map<const Eigen::VectorXd>(u.data(), u.size())}});
  if (state_reset_ == StateReset::kRestart && has_converged_restart_)
    std::filesystem::copy_file(file(kConvergedRestart), saved_restart(step),
                               std::filesystem::copy_options::overwrite_existing);
}

void CalculixSolverWrapper::restore(int step) {
  const std::filesystem::path data_file = file(restart_file_name(name_, step).string());
  auto u = output_interface_.values(node_set_name_, "displacement");
  try {
    const Eigen::VectorXd saved = restart_array(read_restart_file(data_file, name_, step),
                                                "displacement", u.size(), data_file);
    u = Eigen::Map<const RowMatrix>(saved.data(), u.rows(), u.cols());
  } catch (const std::runtime_error& e) {
    fail(fmt::format("solver '{}' cannot restart after time step {}: {}", name_, step, e.what()));
  }
  step_ = step;
  if (deck_->nonlinear_geometry()) move_faces_to_converged_state();
  if (state_reset_ == StateReset::kReplay) {
    for (int committed = 1; committed <= step; ++committed) {
      const std::string loads = fmt::format("cocopp_loads_step{:05d}.inp", committed);
      if (!std::filesystem::exists(file(loads)))
        fail(
            fmt::format("solver '{}' cannot restart after time step {} (state_reset: replay): "
                        "the loads of step {}, {}, are gone",
                        name_, step, committed, file(loads).string()));
      committed_loads_.push_back(loads);
    }
    return;
  }
  if (!std::filesystem::exists(saved_restart(step)))
    fail(
        fmt::format("solver '{}' cannot restart after time step {}: its ccx restart file {} is "
                    "not there (saved with the coupler's state)",
                    name_, step, saved_restart(step).string()));
  std::filesystem::copy_file(saved_restart(step), file(kConvergedRestart),
                             std::filesystem::copy_options::overwrite_existing);
  has_converged_restart_ = true;
}

std::filesystem::path CalculixSolverWrapper::saved_restart(int step) const {
  return file(fmt::format("restart/{}_{:06d}.rout", name_, step));
}

void CalculixSolverWrapper::read_deck() {
  try {
    deck_ = std::make_unique<calculix::InputDeck>(
        calculix::InputDeck::read(working_directory_ / input_file_, working_directory_));
    if (!persistent_ && deck_->procedure() == "DYNAMIC" &&
        std::abs(deck_->step_time_period() - run_.delta_t) > 1e-9 * run_.delta_t)
      throw calculix::DeckError(fmt::format(
          "{}: the *DYNAMIC step's time period is {}, the coupling time step delta_t is {}: "
          "they must be equal",
          deck_->step().front().where, deck_->step_time_period(), run_.delta_t));
    if (!persistent_) check_dynamic_elements();  // one long step: nothing restarts *DYNAMIC
    if (carry_initial_increment_ && !deck_->procedure_data_line())
      throw CaseError(fmt::format(
          "{}: initial_increment: previous_iteration, but the *{} card of {} has no data line "
          "to carry the increment on: give it one (initial increment, time period, ...) or "
          "remove the key",
          initial_increment_where_, deck_->procedure(), input_file_));
    loads_ = std::make_unique<calculix::InterfaceLoads>(*deck_, deck_->surface(surface_name_));
    if (loads_->faces().empty())
      throw calculix::DeckError("surface " + surface_name_ + " has no faces");
    interface_nodes_ = sorted_node_set(*deck_, node_set_name_);
    if (interface_nodes_.empty())
      throw calculix::DeckError("node set " + node_set_name_ + " is empty");
    if (displacement_drive_) {
      driven_node_set_ = sorted_node_set(*deck_, driven_node_set_name_);
      drive_ = std::make_unique<calculix::DisplacementDrive>(
          *deck_, *loads_, interface_nodes_, driven_node_set_, driven_dof_, surface_stiffness_);
    }
  } catch (const calculix::DeckError& e) {
    throw CaseError(input_file_where_ + ": solver '" + name_ + "': " + e.what());
  }
}

// Restart files reset the model exactly when this ccx restarts what the deck needs: Debian's
// ccx drops the material state variables and crashes on axisymmetric models; the patched one
// (scripts/calculix/) does neither. `auto` replays where restarting would be wrong.
void CalculixSolverWrapper::choose_state_reset() {
  state_reset_ = state_reset_key_ == "replay" ? StateReset::kReplay : StateReset::kRestart;
  const bool history = has_material_history(*deck_);
  const auto* axisymmetric = first_element(*deck_, is_axisymmetric);
  if (state_reset_ == StateReset::kReplay || (!history && axisymmetric == nullptr)) return;
  const auto support = calculix::restart_support(ccx_path_, working_directory_);
  const bool crashes = axisymmetric != nullptr && !support.axisymmetry;
  const bool forgets = history && !support.state_variables;
  if (state_reset_key_ == "auto") {
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
        state_reset_where_, name_, ccx_path_.string(), axisymmetric->first,
        axisymmetric->second.type));
}

// ccx starts every *DYNAMIC step by solving for the acceleration with the internal forces of
// reduced-integration elements integrated at the full set of points (nonlingeo.c: intscheme =
// 1), not at the reduced points its increments use. One step per coupling time step makes that
// mismatch repeat every step, and it grows without bound (docs/solver-wrappers-calculix.md).
void CalculixSolverWrapper::check_dynamic_elements() const {
  if (deck_->procedure() != "DYNAMIC" || allow_reduced_integration_) return;
  if (const auto* element = first_element(*deck_, is_reduced_integration))
    throw calculix::DeckError(fmt::format(
        "{}: element {} is a {} (reduced integration) in a *DYNAMIC deck: ccx 2.20 computes "
        "the acceleration at the start of each step with full integration, and over a series "
        "of one-step coupling time steps this mismatch grows without bound (a C3D20R tube "
        "wall blows up after 8 to 40 steps). Use the fully integrated element ({}), or set "
        "allow_reduced_integration: true in the case file to run it anyway",
        deck_->step().front().where, element->first, element->second.type,
        element->second.type.substr(0, element->second.type.size() - 1)));
}

void CalculixSolverWrapper::build_interfaces() {
  auto faces = std::make_shared<ModelPart>();
  faces->name = surface_name_;
  const auto& geometry = loads_->geometry();
  faces->coordinates.resize(static_cast<Eigen::Index>(geometry.size()), 3);
  for (std::size_t f = 0; f < geometry.size(); ++f) {
    const auto& face = loads_->faces()[f];
    faces->ids.push_back(face.element * 10 + face.face);  // element 12, face S3 -> 123
    faces->coordinates.row(static_cast<Eigen::Index>(f)) = geometry[f].centroid.transpose();
  }
  // Driven by displacement, the nodes also report whether they were driven.
  output_interface_ = Interface({{node_part(*deck_, node_set_name_, interface_nodes_),
                                  drive_ ? std::vector<std::string>{"displacement", "driven"}
                                         : std::vector<std::string>{"displacement"}}});
  if (!drive_) {
    input_interface_ = Interface({{faces, input_variables_}});
    return;
  }
  // Driven by displacement: the other solver's wall position at the drivable nodes (first, as
  // a film gives its points before its faces), its loads, gap and coverage on the faces.
  std::vector<std::string> inputs = input_variables_;
  for (const auto& variable : calculix::DisplacementDrive::face_variables())
    inputs.push_back(variable);
  input_interface_ = Interface({{node_part(*deck_, driven_node_set_name_, driven_node_set_),
                                 {calculix::DisplacementDrive::kNodeVariable}},
                                {faces, inputs}});
}

void CalculixSolverWrapper::initialize_step(int step, double time) {
  step_ = step;
  iteration_ = 0;
  carried_increment_.reset();  // a new step tries the deck's initial increment first
  if (persistent_ccx_) persistent_ccx_->initialize_step(step, time);
  step_time_ = time;
}

void CalculixSolverWrapper::start_persistent() {
  if (const std::string why = calculix::PersistentCcx::unsupported(*deck_); !why.empty())
    throw CaseError(
        fmt::format("{}: solver '{}': mode: persistent cannot run {}: {}; use mode: "
                    "per_iteration",
                    mode_where_, name_, input_file_, why));

  calculix::PersistentCcx::Options options{name_,
                                           find_executable(coupled_executable_, working_directory_),
                                           working_directory_,
                                           log_file_,
                                           threads_,
                                           timeout_,
                                           takes("pressure")};
  persistent_ccx_ = std::make_unique<calculix::PersistentCcx>(options, *deck_, *loads_,
                                                              interface_nodes_, kModelFile);
  persistent_ccx_->start(run_, persistent_end_time());
  if (run_.timestep_start > 0) replay_committed_steps(run_.timestep_start);
}

// A restarted persistent run solves the committed steps again with their converged inputs: one
// coupling iteration each, so the same increments and the same state as the run had.
void CalculixSolverWrapper::replay_committed_steps(int step) {
  const std::filesystem::path data_file = file(restart_file_name(name_, step).string());
  Eigen::VectorXd times, inputs, displacement;
  try {
    const RestartData data = read_restart_file(data_file, name_, step);
    if (data.count("inputs") == 0)
      throw std::runtime_error(
          "it has no committed inputs (was the run per_iteration? restart "
          "it with mode: per_iteration)");
    times = restart_array(data, "times", step, data_file);
    inputs = restart_array(data, "inputs", step * input_interface_.size(), data_file);
    displacement =
        restart_array(data, "displacement",
                      output_interface_.values(node_set_name_, "displacement").size(), data_file);
  } catch (const std::runtime_error& e) {
    fail(fmt::format("solver '{}' cannot restart after time step {}: {}", name_, step, e.what()));
  }
  std::vector<double> step_times(times.data(), times.data() + times.size());
  std::vector<Eigen::VectorXd> step_inputs;
  for (int k = 0; k < step; ++k)
    step_inputs.push_back(inputs.segment(k * input_interface_.size(), input_interface_.size()));
  replay(step_times, step_inputs);
  const auto u = output_interface_.values(node_set_name_, "displacement");
  const double scale = std::max(displacement.cwiseAbs().maxCoeff(), 1e-300);
  const double off =
      (Eigen::Map<const Eigen::VectorXd>(u.data(), u.size()) - displacement).cwiseAbs().maxCoeff();
  if (off > 1e-9 * scale)
    fail(
        fmt::format("solver '{}': replaying time steps 1 to {} for the restart ends {:.2e} "
                    "(relative) away from the displacement the run saved in {}: the deck or "
                    "the ccx changed since",
                    name_, step, off / scale, data_file.string()));
}

// The long step ends with the run; a run of unknown length gets a step of 1000 time steps.
double CalculixSolverWrapper::persistent_end_time() const {
  const int steps =
      run_.number_of_timesteps > 0 ? run_.timestep_start + run_.number_of_timesteps : 1000;
  return steps * run_.delta_t;
}

RowMatrix CalculixSolverWrapper::solve_persistent(const Interface& input) {
  const auto [pressure, traction] = face_loads(input);
  return persistent_ccx_->solve(pressure, traction.size() > 0
                                              ? loads_->nodal_forces(traction)
                                              : std::map<std::int64_t, Eigen::Vector3d>{});
}

// The committed steps again, one coupling iteration each with its converged input: the same
// increments, so the same state.
void CalculixSolverWrapper::replay(const std::vector<double>& times,
                                   const std::vector<Eigen::VectorXd>& inputs) {
  committed_times_.clear();
  committed_inputs_.clear();
  Interface input = input_interface_;
  for (std::size_t k = 0; k < times.size(); ++k) {
    initialize_step(static_cast<int>(k + 1), times[k]);
    input.set_data(inputs[k]);
    solve(input);
    finalize_step();
  }
}

void CalculixSolverWrapper::restart_persistent() {
  const int step = step_;
  const double time = step_time_;
  const int iteration = iteration_;
  const auto times = committed_times_;
  const auto inputs = committed_inputs_;
  persistent_ccx_->finalize();
  loads_->move_faces({});  // the deck's geometry: the replay moves the faces again
  persistent_ccx_->start(run_, persistent_end_time());
  replay(times, inputs);
  initialize_step(step, time);  // the step that did not converge, ready for another input
  iteration_ = iteration;
}

void CalculixSolverWrapper::finalize() {
  if (persistent_ccx_) persistent_ccx_->finalize();
}

void CalculixSolverWrapper::start_reporting_convergence() {
  throw SolverError(
      name_, fmt::format("solver '{}' (calculix) cannot report solver-coupling convergence: ccx "
                         "solves every coupling iteration again from the step's start, so its "
                         "Newton iterations never start from the previous iterate. Give this "
                         "solver's side a residual criterion (relative_norm) instead",
                         name_));
}

const Interface& CalculixSolverWrapper::solve(const Interface& input) {
  if (!input.same_layout(input_interface_))
    throw std::invalid_argument(
        fmt::format("solver '{}': solve() was given {} but its input interface is {}", name_,
                    input.describe(), input_interface_.describe()));
  ++iteration_;
  const auto start = Clock::now();
  if (persistent_ccx_) {
    last_input_ = input.data();
    try {
      output_interface_.values(node_set_name_, "displacement") = solve_persistent(input);
    } catch (const SolverError& e) {
      // ccx ends when it gives up a step: a new cocopp-ccx takes the committed steps again,
      // so that the coupler may retry with other loads, as with a ccx run per iteration.
      const std::string tail = read_last_lines(log_file_, 20);
      if (!calculix::gave_up(tail)) throw;
      restart_persistent();
      throw not_converged("cocopp-ccx exited; restarted with the committed steps",
                          file(std::string(calculix::PersistentCcx::kJob) + ".inp").string(), tail);
    }
    const double process = persistent_ccx_->process_seconds();
    last_timing_ = {process, seconds_since(start) - process};
    return output_interface_;
  }
  write_loads(input);
  write_iteration_deck();
  const std::filesystem::path results = file(std::string(kJob) + ".dat");
  std::filesystem::remove(results);  // never read an earlier iteration's results
  std::filesystem::remove(file(std::string(kJob) + ".rout"));
  if (has_converged_restart_)
    std::filesystem::copy_file(file(kConvergedRestart), file(std::string(kJob) + ".rin"),
                               std::filesystem::copy_options::overwrite_existing);
  const double prepare_seconds = seconds_since(start);

  run_ccx();

  const auto read_start = Clock::now();
  // Where ccx's first attempt at the deck's increment failed and it cut back, the step's next
  // iterations (loads close to this one's) start at the increment that converged: the same
  // increments, so the same answer, without the failed attempt's Newton iterations.
  if (carry_initial_increment_) {
    const auto increment = calculix::carried_initial_increment(
        calculix::read_sta(file(std::string(kJob) + ".sta")), deck_->initial_increment());
    if (increment) carried_increment_ = increment;
  }
  try {
    const RowMatrix displacement =
        calculix::read_node_print(results, "displacements", node_set_name_, interface_nodes_);
    output_interface_.values(node_set_name_, "displacement") =
        drive_ ? drive_->balance(displacement,
                                 calculix::read_node_print(results, "forces", driven_node_set_name_,
                                                           driven_node_set_))
               : displacement;
    if (drive_) {
      auto driven = output_interface_.values(node_set_name_, "driven");
      for (std::size_t i = 0; i < interface_nodes_.size(); ++i)
        driven(static_cast<Eigen::Index>(i), 0) = drive_->drives(interface_nodes_[i]) ? 1.0 : 0.0;
    }
  } catch (const std::runtime_error& e) {
    fail(fmt::format("solver '{}' at {}: {}", name_, position(), e.what()));
  }
  last_timing_.wrapper_seconds = prepare_seconds + seconds_since(read_start);
  return output_interface_;
}

bool CalculixSolverWrapper::takes(const char* variable) const {
  return std::find(input_variables_.begin(), input_variables_.end(), variable) !=
         input_variables_.end();
}

CalculixSolverWrapper::FaceLoads CalculixSolverWrapper::face_loads(const Interface& input) const {
  FaceLoads loads;
  if (takes("pressure")) loads.pressure = input.values(surface_name_, "pressure").col(0);
  if (takes("traction")) loads.traction = input.values(surface_name_, "traction");
  if (!loads.pressure.allFinite() || !loads.traction.allFinite())
    fail(fmt::format("solver '{}' at {}: the interface loads contain NaN or infinity", name_,
                     position()));
  return loads;
}

void CalculixSolverWrapper::write_loads(const Interface& input) const {
  const auto [pressure, traction] = face_loads(input);
  if (!drive_) {
    loads_->write(file(kLoadsFile), pressure, traction);
    return;
  }
  calculix::DisplacementDrive::Inputs inputs{
      pressure, traction.size() > 0 ? traction : RowMatrix::Zero(pressure.size(), 3),
      input.values(surface_name_, "gap").col(0), input.values(surface_name_, "coverage").col(0),
      input.values(driven_node_set_name_, calculix::DisplacementDrive::kNodeVariable)};
  if (!inputs.gap.allFinite() || !inputs.coverage.allFinite() ||
      !inputs.wall_displacement.allFinite())
    fail(
        fmt::format("solver '{}' at {}: the gap, wall displacement or coverage contain NaN or "
                    "infinity",
                    name_, position()));
  drive_->plan(inputs);
  std::ofstream out(file(kLoadsFile));
  out << "** Interface loads of this coupling iteration, written by cocopp\n";
  drive_->write(out);
  if (!out.flush()) fail("cannot write the loads file " + file(kLoadsFile).string());
}

void CalculixSolverWrapper::write_iteration_deck() const {
  const std::filesystem::path deck_file = file(std::string(kJob) + ".inp");
  std::ofstream out(deck_file);
  out << "** Coupling iteration deck written by cocopp from " << input_file_ << "\n";
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
  if (!out.flush()) fail("cannot write " + deck_file.string());
}

void CalculixSolverWrapper::write_step(std::ofstream& out, const std::string& loads_file,
                                       bool print) const {
  std::vector<calculix::DeckLine> step = deck_->step();
  // The step being solved starts with the carried increment; replayed steps as the deck says.
  if (print && carried_increment_) {
    std::string& data = step.at(*deck_->procedure_data_line()).text;
    const auto comma = data.find(',');
    data = calculix::ccx_number(*carried_increment_) +
           (comma == std::string::npos ? "" : data.substr(comma));
  }
  write_lines(out, {step.begin(), step.end() - 1});  // all but *END STEP
  out << "*INCLUDE, INPUT=" << loads_file << "\n";
  if (print) out << "*NODE PRINT, NSET=" << node_set_name_ << ", GLOBAL=YES\nU\n";
  // The forces the driven nodes take, in their own systems (the driven direction's).
  if (print && drive_) out << "*NODE PRINT, NSET=" << driven_node_set_name_ << ", GLOBAL=NO\nRF\n";
  out << step.back().text << "\n";
}

void CalculixSolverWrapper::run_ccx() {
  calculix::CcxRunOptions options{ccx_path_, working_directory_, kJob,
                                  log_file_, threads_,           timeout_};
  calculix::CcxRunResult result;
  try {
    result = calculix::run_ccx(options);
  } catch (const std::runtime_error& e) {
    fail(fmt::format("solver '{}': cannot start ccx at {}: {}", name_, position(), e.what()));
  }
  last_timing_.ccx_seconds = result.seconds;
  const std::string deck = file(std::string(kJob) + ".inp").string();
  using Status = calculix::CcxRunResult::Status;
  switch (result.status) {
    case Status::kSuccess:
      return;
    case Status::kNotConverged:
      // The step starts from the converged restart (or the replayed steps) again at the next
      // solve, so the coupled solver may retry with other loads.
      throw not_converged(result.exit_description, deck, result.details);
    case Status::kDeckError:
      fail(fmt::format(
          "solver '{}': ccx rejected the input deck at {} ({}); deck {} (built from {}), "
          "ccx says:\n{}(full output in {})",
          name_, position(), result.exit_description, deck, input_file_, result.details,
          log_file_.string()));
    case Status::kTimedOut:
      fail(
          fmt::format("solver '{}': ccx did not finish within {} s at {} and was stopped; "
                      "last lines of {}:\n{}",
                      name_, timeout_, position(), log_file_.string(), result.details));
    case Status::kFailed:
      break;
  }
  fail(fmt::format("solver '{}': ccx {} at {}; deck {}, last lines of {}:\n{}", name_,
                   result.exit_description, position(), deck, log_file_.string(),
                   result.details.empty() ? "(the log is empty)" : result.details));
}

SolverRejectedInput CalculixSolverWrapper::not_converged(const std::string& exit,
                                                         const std::string& deck,
                                                         const std::string& log_tail) const {
  return SolverRejectedInput(
      name_,
      fmt::format("solver '{}': ccx did not converge at {} ({}: the increment size fell below the "
                  "minimum, it was cut back too often or the step needed more increments than "
                  "*STEP, INC= allows); what to change: a smaller time step "
                  "(settings.delta_t), a smaller minimum "
                  "increment on the deck's *STATIC or *DYNAMIC line, or loads the structure can "
                  "carry (a coupled load far beyond its limit load diverges); deck {}, last lines "
                  "of {}:\n{}",
                  name_, position(), exit, deck, log_file_.string(), log_tail));
}

void CalculixSolverWrapper::finalize_step() {
  if (iteration_ == 0)
    fail(fmt::format("solver '{}': time step {} is committed without a coupling iteration", name_,
                     step_));
  if (deck_->nonlinear_geometry()) move_faces_to_converged_state();
  if (persistent_ccx_) {
    persistent_ccx_->finalize_step();
    committed_inputs_.push_back(last_input_);
    committed_times_.push_back(step_time_);
    return;
  }
  // The last iteration is the converged one: its end state is the next step's start.
  if (state_reset_ == StateReset::kReplay) {
    const std::string loads = fmt::format("cocopp_loads_step{:05d}.inp", step_);
    std::filesystem::copy_file(file(kLoadsFile), file(loads),
                               std::filesystem::copy_options::overwrite_existing);
    committed_loads_.push_back(loads);
    return;
  }
  const std::filesystem::path restart = file(std::string(kJob) + ".rout");
  if (!std::filesystem::exists(restart))
    fail(fmt::format("solver '{}': ccx wrote no restart file {} at time step {}", name_,
                     restart.string(), step_));
  std::filesystem::rename(restart, file(kConvergedRestart));
  has_converged_restart_ = true;
}

// ccx applies a pressure on the deformed faces in an NLGEOM step; the traction's nodal forces
// are the wrapper's, so they follow the faces as the last converged step left them (the same
// for every coupling iteration of the next step, as its restart is).
void CalculixSolverWrapper::move_faces_to_converged_state() {
  const RowMatrix& u = output_interface_.values(node_set_name_, "displacement");
  calculix::NodeDisplacements displacement;
  for (std::size_t i = 0; i < interface_nodes_.size(); ++i)
    displacement[interface_nodes_[i]] = u.row(static_cast<Eigen::Index>(i)).transpose();
  loads_->move_faces(displacement);
}

void CalculixSolverWrapper::output_step() {
  // cocopp-ccx writes its results itself, into cocopp_persistent.frd and .dat, at every
  // committed step the deck's output cards ask for.
  if (!save_results_ || persistent_) return;
  const std::filesystem::path directory = file("results");
  std::filesystem::create_directories(directory);
  for (const char* extension : {".frd", ".dat"}) {
    const std::filesystem::path source = file(std::string(kJob) + extension);
    if (std::filesystem::exists(source))
      std::filesystem::copy_file(source, directory / fmt::format("step_{:05d}{}", step_, extension),
                                 std::filesystem::copy_options::overwrite_existing);
  }
}

void CalculixSolverWrapper::fail(const std::string& message) const {
  throw SolverError(name_, message);
}

std::string CalculixSolverWrapper::position() const {
  return fmt::format("time step {}, coupling iteration {}", step_, iteration_);
}

}  // namespace cocopp
