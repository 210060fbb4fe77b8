#include "solver_wrappers/calculix/calculix_solver_wrapper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <utility>

#include "core/case/path_problem.hpp"
#include "core/case/suggest.hpp"
#include "core/data/restart_file.hpp"
#include "solver_wrappers/process/child_process.hpp"
#include "solver_wrappers/process/process_solver_wrapper.hpp"

namespace cocopp {

COCOPP_REGISTER(SolverWrapperRegistry, "calculix", CalculixSolverWrapper)

namespace {

using calculix::PerIterationCcx;
using calculix::PersistentCcx;

/// ccx with cocopp's patches: <prefix>/libexec/cocopp/ccx next to the running cocopp's bin/ (so
/// that the install can move; in the build tree a link to where scripts/install-calculix.sh
/// built it); else the Debian package's ccx on PATH.
std::string default_executable() {
  std::error_code error;
  const std::filesystem::path bin = builtin_solver_directory();
  if (!bin.empty()) {
    const std::filesystem::path installed = bin.parent_path() / COCOPP_INSTALLED_CCX;
    if (std::filesystem::is_regular_file(installed, error)) return installed.string();
  }
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

CalculixSolverWrapper::CalculixSolverWrapper(const Settings& settings, const RunSettings& run) {
  model_.run = run;
  model_.name = settings.get_name("name", "calculix");
  name_given_ = settings.has("name");
  log_file_given_ = settings.has("log_file");
  model_.working_directory =
      std::filesystem::absolute(run.case_directory /
                                settings.required<std::string>("working_directory"))
          .lexically_normal();
  working_directory_where_ = settings.where("working_directory");
  model_.input_file = settings.required<std::string>("input_file");
  input_file_where_ = settings.where("input_file");
  if (std::filesystem::path(model_.input_file).stem() == PerIterationCcx::kJob)
    settings.fail("input_file", std::string("the name ") + PerIterationCcx::kJob +
                                    " is the wrapper's own job name: rename the deck");
  model_.surface_name = settings.required<std::string>("interface_surface");
  model_.node_set_name = settings.required<std::string>("interface_node_set");
  per_iteration_.executable = settings.get<std::string>("executable", default_executable());
  per_iteration_.executable_where =
      settings.has("executable") ? settings.where("executable") : settings.where();
  model_.input_variables =
      settings.get<std::vector<std::string>>("input_variables", {"pressure", "traction"});
  if (model_.input_variables.empty())
    settings.fail("input_variables", "give at least one of pressure, traction, or force alone");
  for (const auto& variable : model_.input_variables)
    if (variable != "pressure" && variable != "traction" && variable != "force")
      settings.fail("input_variables",
                    "'" + variable +
                        "': the loads are pressure and traction, or force "
                        "(a total per face)" +
                        did_you_mean(variable, {"pressure", "traction", "force"}));
  if (model_.takes("force") && model_.input_variables.size() > 1)
    settings.fail("input_variables",
                  "force is each face's whole load (the pressure and the traction on it): give "
                  "it alone, or pressure and traction without it");
  displacement_drive_ =
      settings.get_choice("interface_drive", "load", {"load", "displacement"}) == "displacement";
  if (displacement_drive_) {
    driven_dof_ = settings.get_int_in_range("driven_dof", 1, 1, 3);
    driven_node_set_name_ = settings.get<std::string>("driven_node_set", model_.node_set_name);
    surface_stiffness_ = settings.required<double>("surface_stiffness");
    if (!(surface_stiffness_ > 0.0))
      settings.fail("surface_stiffness",
                    "give the structure's stiffness per area against a push of its surface, "
                    "in Pa/m (about its Young's modulus over the faces' length), > 0");
    const std::string film_stiffness =
        settings.get_choice("film_stiffness", "local", {"local", "reynolds", "probed"});
    reynolds_film_ = film_stiffness == "reynolds";
    if (film_stiffness == "probed")
      probed_film_file_ = settings.required<std::string>("film_probe");
    drive_log_ = settings.get<std::string>("drive_log", "");
    surface_compliance_file_ = settings.get<std::string>("surface_compliance", "");
    if (!surface_compliance_file_.empty())
      surface_compliance_scale_ =
          settings.get_in_range("surface_compliance_scale", 1.0, Range::positive());
    if (!model_.takes("pressure") && !model_.takes("force"))
      settings.fail("input_variables",
                    "interface_drive: displacement balances the other solver's pressure: "
                    "include pressure, or give force");
  }
  model_.threads = settings.get_int_in_range("threads", 1, 1, 64);
  model_.timeout = settings.get_in_range("timeout", 600.0, Range::timeout());
  per_iteration_.save_results = settings.get<bool>("save_results", true);
  per_iteration_.allow_reduced_integration = settings.get<bool>("allow_reduced_integration", false);
  per_iteration_.carry_initial_increment =
      settings.get_choice("initial_increment", "deck", {"deck", "previous_iteration"}) ==
      "previous_iteration";
  per_iteration_.initial_increment_where =
      settings.has("initial_increment") ? settings.where("initial_increment") : settings.where();
  per_iteration_.warm_start = settings.get<bool>("warm_start", false);
  per_iteration_.warm_start_where =
      settings.has("warm_start") ? settings.where("warm_start") : settings.where();
  per_iteration_.state_reset =
      settings.get_choice("state_reset", "auto", {"auto", "restart", "replay"});
  per_iteration_.state_reset_where =
      settings.has("state_reset") ? settings.where("state_reset") : settings.where();
  model_.log_file =
      model_.working_directory / settings.get<std::string>("log_file", model_.name + ".log");
  read_mode(settings);
}

bool CalculixSolverWrapper::has_coupled_executable() const {
  try {
    find_executable(coupled_executable_, model_.working_directory);
    return true;
  } catch (const std::runtime_error&) {
    return false;
  }
}

// mode: auto runs per iteration a deck persistent mode cannot run, and the restart of a run that
// ran per iteration (its restart data has no inputs to replay).
void CalculixSolverWrapper::choose_auto_mode() {
  if (!auto_mode_ || !persistent_) return;
  if (!PersistentCcx::unsupported(*model_.deck).empty()) {
    persistent_ = false;
    return;
  }
  if (model_.run.timestep_start == 0) return;
  try {
    const int step = model_.run.timestep_start;
    persistent_ = read_restart_file(model_.file(restart_file_name(model_.name, step).string()),
                                    model_.name, step)
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
                  !settings.has("warm_start") && !settings.has("executable") &&
                  !displacement_drive_ && has_coupled_executable();
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
  refuse("warm_start", "the previous ccx run's solution is handed to the next one");
  if (displacement_drive_)
    settings.fail("interface_drive",
                  "interface_drive: displacement works with mode: per_iteration only (its "
                  "driven nodes change from one coupling iteration to the next)");
}

CalculixSolverWrapper::~CalculixSolverWrapper() = default;

void CalculixSolverWrapper::set_default_name(const std::string& name) {
  if (name_given_) return;
  model_.name = name;
  if (!log_file_given_) model_.log_file = model_.working_directory / (name + ".log");
}

std::string CalculixSolverWrapper::describe() const {
  const std::string where =
      fmt::format("in {}; log {}; {} thread{}", model_.working_directory.string(),
                  model_.log_file.string(), model_.threads, model_.threads == 1 ? "" : "s");
  if (persistent_)
    return fmt::format("{}: {} -i {} for {} ({}; persistent)", model_.name, coupled_executable_,
                       PersistentCcx::kJob, model_.input_file, where);
  return fmt::format("{}: {} -i {} for {} ({}; state reset: {}{})", model_.name,
                     per_iteration_.executable, PerIterationCcx::kJob, model_.input_file, where,
                     per_iteration_.state_reset,
                     displacement_drive_ ? "; driven by displacement under the other solver" : "");
}

void CalculixSolverWrapper::check() const {
  const std::string solver = "solver '" + model_.name + "': ";
  if (const auto why = path_problem(model_.working_directory, PathKind::kDirectory); !why.empty())
    throw CaseError(working_directory_where_ + ": " + solver + "working directory " +
                    model_.working_directory.string() + " " + why);
  const auto deck = model_.file(model_.input_file);
  if (const auto why = path_problem(deck, PathKind::kRegularFile); !why.empty())
    throw CaseError(input_file_where_ + ": " + solver + "input deck " + deck.string() + " " + why);
  if (persistent_) {
    try {
      find_executable(coupled_executable_, model_.working_directory);
    } catch (const std::runtime_error& e) {
      throw CaseError(mode_where_ + ": " + solver +
                      "mode: persistent runs cocopp-ccx, which is not there (" + e.what() +
                      "): build it (scripts/install-calculix.sh, then the cocopp build), give "
                      "its path in 'coupled_executable', or use mode: per_iteration");
    }
    if (!auto_mode_) return;  // auto may still run per iteration: ccx too
  }
  try {
    find_executable(per_iteration_.executable, model_.working_directory);
  } catch (const std::runtime_error& e) {
    throw CaseError(per_iteration_.executable_where + ": " + solver + "CalculiX (" + e.what() +
                    "): install the Debian package calculix-ccx (scripts/install-dependencies.sh "
                    "does) or give its path in 'executable'");
  }
}

void CalculixSolverWrapper::initialize() {
  check();
  read_deck();
  choose_auto_mode();
  build_interfaces();
  // The model definition once; every mode's deck includes it.
  const auto model_file = model_.file(calculix::kModelFile);
  std::ofstream model(model_file);
  for (const auto& line : model_.deck->model_definition()) model << line.text << "\n";
  if (!model.flush()) model_.fail("cannot write " + model_file.string());
  mode_ = create_mode();
  mode_->start(input_interface_, output_interface_);
}

std::unique_ptr<calculix::CcxMode> CalculixSolverWrapper::create_mode() {
  if (persistent_)
    return std::make_unique<PersistentCcx>(
        model_, PersistentCcx::Options{
                    find_executable(coupled_executable_, model_.working_directory), mode_where_});
  try {
    auto mode = std::make_unique<PerIterationCcx>(
        model_, per_iteration_,
        PerIterationCcx::Drive{drive_.get(), driven_node_set_name_, driven_node_set_});
    per_iteration_mode_ = mode.get();
    return mode;
  } catch (const calculix::DeckError& e) {
    throw CaseError(input_file_where_ + ": solver '" + model_.name + "': " + e.what());
  }
}

void CalculixSolverWrapper::read_deck() {
  try {
    model_.deck = std::make_unique<calculix::InputDeck>(
        calculix::InputDeck::read(model_.file(model_.input_file), model_.working_directory));
    model_.loads = std::make_unique<calculix::InterfaceLoads>(
        *model_.deck, model_.deck->surface(model_.surface_name));
    if (model_.loads->faces().empty())
      throw calculix::DeckError("surface " + model_.surface_name + " has no faces");
    model_.interface_nodes = sorted_node_set(*model_.deck, model_.node_set_name);
    if (model_.interface_nodes.empty())
      throw calculix::DeckError("node set " + model_.node_set_name + " is empty");
    if (displacement_drive_) {
      driven_node_set_ = sorted_node_set(*model_.deck, driven_node_set_name_);
      drive_ = std::make_unique<calculix::DisplacementDrive>(
          *model_.deck, *model_.loads, model_.interface_nodes, driven_node_set_, driven_dof_,
          surface_stiffness_);
      if (!surface_compliance_file_.empty())
        drive_->use_compliance(
            calculix::SurfaceCompliance::read(model_.file(surface_compliance_file_)),
            surface_compliance_scale_);
      if (reynolds_film_) drive_->use_reynolds_film();
      if (!probed_film_file_.empty()) drive_->use_probed_film(model_.file(probed_film_file_));
      if (!drive_log_.empty()) {
        std::filesystem::remove(model_.file(drive_log_));
        drive_->log_to(model_.file(drive_log_));
      }
    }
  } catch (const calculix::DeckError& e) {
    throw CaseError(input_file_where_ + ": solver '" + model_.name + "': " + e.what());
  }
}

void CalculixSolverWrapper::build_interfaces() {
  auto faces = std::make_shared<ModelPart>();
  faces->name = model_.surface_name;
  const auto& geometry = model_.loads->geometry();
  faces->coordinates.resize(static_cast<Eigen::Index>(geometry.size()), 3);
  for (std::size_t f = 0; f < geometry.size(); ++f) {
    const auto& face = model_.loads->faces()[f];
    faces->ids.push_back(face.element * 10 + face.face);  // element 12, face S3 -> 123
    faces->coordinates.row(static_cast<Eigen::Index>(f)) = geometry[f].centroid.transpose();
  }
  const auto& deck = *model_.deck;
  // Driven by displacement, the nodes also report whether they were driven.
  output_interface_ = Interface({{node_part(deck, model_.node_set_name, model_.interface_nodes),
                                  drive_ ? std::vector<std::string>{"displacement", "driven"}
                                         : std::vector<std::string>{"displacement"}}});
  if (!drive_) {
    input_interface_ = Interface({{faces, model_.input_variables}});
    return;
  }
  // Driven by displacement: the other solver's wall position at the drivable nodes (first, as
  // a film gives its points before its faces), its loads, gap and coverage on the faces.
  std::vector<std::string> inputs = model_.input_variables;
  for (const auto& variable : calculix::DisplacementDrive::face_variables())
    inputs.push_back(variable);
  input_interface_ = Interface({{node_part(deck, driven_node_set_name_, driven_node_set_),
                                 {calculix::DisplacementDrive::kNodeVariable}},
                                {faces, inputs}});
}

void CalculixSolverWrapper::initialize_step(int step, double time) {
  model_.step = step;
  if (drive_) drive_->start_step(step);
  model_.iteration = 0;
  mode_->initialize_step(step, time);
}

const Interface& CalculixSolverWrapper::solve(const Interface& input) {
  if (!input.same_layout(input_interface_))
    throw std::invalid_argument(
        fmt::format("solver '{}': solve() was given {} but its input interface is {}", model_.name,
                    input.describe(), input_interface_.describe()));
  ++model_.iteration;
  mode_->solve(input, output_interface_);
  return output_interface_;
}

void CalculixSolverWrapper::start_reporting_convergence() {
  throw SolverError(
      model_.name,
      fmt::format("solver '{}' (calculix) cannot report solver-coupling convergence: ccx "
                  "solves every coupling iteration again from the step's start, so its "
                  "Newton iterations never start from the previous iterate. Give this "
                  "solver's side a residual criterion (relative_norm) instead",
                  model_.name));
}

void CalculixSolverWrapper::finalize_step() {
  if (model_.iteration == 0)
    model_.fail(fmt::format("solver '{}': time step {} is committed without a coupling iteration",
                            model_.name, model_.step));
  // Driven by displacement, the drive moves the faces to every iteration's surface itself.
  if (!drive_) model_.move_faces_with(output_interface_);
  mode_->finalize_step();
}

void CalculixSolverWrapper::output_step() {
  mode_->output_step();
}

void CalculixSolverWrapper::save_restart(int step) {
  mode_->save_restart(step, output_interface_);
}

void CalculixSolverWrapper::finalize() {
  if (mode_) mode_->finalize();
}

const CalculixSolverWrapper::Timing& CalculixSolverWrapper::last_timing() const {
  static const Timing none;
  return mode_ ? mode_->last_timing() : none;
}

CalculixSolverWrapper::StateReset CalculixSolverWrapper::state_reset() const {
  if (!per_iteration_mode_) return StateReset::kInMemory;
  return per_iteration_mode_->state_reset() == PerIterationCcx::StateReset::kReplay
             ? StateReset::kReplay
             : StateReset::kRestart;
}

}  // namespace cocopp
