#include "solver_wrappers/calculix/persistent_ccx.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <regex>
#include <set>

#include "core/case/settings.hpp"
#include "core/data/restart_file.hpp"
#include "solver_wrappers/calculix/ccx_run.hpp"
#include "solver_wrappers/process/child_process.hpp"
#include "solver_wrappers/process/process_solver_wrapper.hpp"
#include "solver_wrappers/solver_error.hpp"

namespace cocopp::calculix {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string join_fields(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? ", " : "") + fields[i];
  return line;
}

/// Whether the deck's model is linear: no NLGEOM, no material that makes it nonlinear
/// (calinput.f raises iperturb for those), no *GAP or spring that could.
bool linear(const InputDeck& deck) {
  if (deck.nonlinear_geometry()) return false;
  for (const char* keyword :
       {"PLASTIC", "CREEP", "CYCLIC HARDENING", "USER MATERIAL", "DEPVAR", "HYPERELASTIC",
        "HYPERFOAM", "DEFORMATION PLASTICITY", "GAP", "SPRING", "USER ELEMENT"})
    if (deck.has_keyword(keyword)) return false;
  return true;
}

/// Whether ccx solves the deck's step as linear static (linstatic.c).
bool linear_static(const InputDeck& deck) {
  return deck.procedure() == "STATIC" && linear(deck);
}

/// Whether the deck's loads ramp over a step (ccx's default in a static step) or jump.
bool ramps(const InputDeck& deck) {
  const std::string card = upper(deck.step().front().text);
  if (card.find("AMPLITUDE=STEP") != std::string::npos) return false;
  if (card.find("AMPLITUDE=RAMP") != std::string::npos) return true;
  return deck.procedure() == "STATIC";
}

/// The *STEP card of the long step: AMPLITUDE=STEP, so that the deck's own loads and boundary
/// values hold their value from the first increment on, as at the end of each step of one ccx
/// run per time step (over the whole run a ramp would still be rising). The interface loads
/// ramp (or not) as the deck says: cocopp-ccx sets them itself.
std::string long_step_card(const std::string& card) {
  static const std::regex amplitude(R"(,\s*AMPLITUDE\s*=\s*\w+)", std::regex::icase);
  return std::regex_replace(card, amplitude, "") + ", AMPLITUDE=STEP";
}

}  // namespace

PersistentCcx::PersistentCcx(CalculixModel& model, Options options)
    : model_(model), options_(std::move(options)) {
  if (const std::string why = unsupported(*model_.deck); !why.empty())
    throw CaseError(
        fmt::format("{}: solver '{}': mode: persistent cannot run {}: {}; use mode: "
                    "per_iteration",
                    options_.mode_where, model_.name, model_.input_file, why));
  std::set<std::int64_t> nodes;
  for (const auto& face : model_.loads->geometry())
    nodes.insert(face.nodes.begin(), face.nodes.end());
  force_nodes_.assign(nodes.begin(), nodes.end());
}

PersistentCcx::~PersistentCcx() = default;

std::string PersistentCcx::unsupported(const InputDeck& deck) {
  if (deck.procedure() != "STATIC" && deck.procedure() != "DYNAMIC")
    return fmt::format("its step is a *{} (persistent runs *STATIC and *DYNAMIC steps)",
                       deck.procedure());
  if (upper(deck.step().at(deck.procedure_line()).text).find("EXPLICIT") != std::string::npos)
    return "its *DYNAMIC step is explicit (persistent runs implicit dynamics)";
  for (const char* keyword : {"CONTACT PAIR", "TIE", "SURFACE INTERACTION"})
    if (deck.has_keyword(keyword))
      return fmt::format("it has *{} (contact's state is not in the in-memory reset)", keyword);
  return "";
}

void PersistentCcx::start(const Interface& input, Interface& output) {
  input_layout_ = input;
  start_process();
  if (model_.run.timestep_start > 0) replay_committed_steps(model_.run.timestep_start, output);
}

void PersistentCcx::start_process() {
  write_deck(end_time());
  try {
    interface_file().write(model_.file(InterfaceFile::kName));
  } catch (const std::runtime_error& e) {
    model_.fail(e.what());
  }
  DefaultCommand command{
      options_.executable, "", {"-i", kJob}, ccx_thread_environment(model_.threads), {}};
  // ccx's Fortran writes unbuffered: in the log in order with its C output (cocopp-ccx makes
  // stdout line-buffered), so that its last lines say why it stopped; in the .dat file as each
  // step commits.
  command.environment.emplace_back("GFORTRAN_UNBUFFERED_ALL", "y");
  const Settings settings = Settings::load_string(
      fmt::format("type: process\nname: '{}'\nworking_directory: '{}'\ntimeout: {}\n"
                  "log_file: '{}'\n",
                  model_.name, model_.working_directory.string(), model_.timeout,
                  model_.log_file.string()),
      "(the calculix wrapper's cocopp-ccx)");
  // cocopp-ccx always starts from the deck; a restart replays the committed steps through it.
  RunSettings from_start = model_.run;
  from_start.timestep_start = 0;
  process_ = std::make_unique<ProcessSolverWrapper>(settings, from_start, command);
  process_->initialize();
}

double PersistentCcx::end_time() const {
  const RunSettings& run = model_.run;
  const int steps =
      run.number_of_timesteps > 0 ? run.timestep_start + run.number_of_timesteps : 1000;
  return steps * run.delta_t;
}

void PersistentCcx::write_deck(double end_time) const {
  const auto path = model_.file(std::string(kJob) + ".inp");
  std::ofstream out(path);
  out << "** The coupled run's deck, written by cocopp (calculix wrapper, mode: persistent): the\n"
         "** step of the user's deck as one step of the whole run's length, which cocopp-ccx\n"
         "** advances by the coupler's time steps; the interface loads' placeholders last.\n"
      << "*INCLUDE, INPUT=" << kModelFile << "\n";
  for (const auto& line : long_step(end_time)) out << line.text << "\n";
  if (!out.flush()) model_.fail("cannot write " + path.string());
}

std::vector<DeckLine> PersistentCcx::long_step(double end_time) const {
  const InputDeck& deck = *model_.deck;
  std::vector<DeckLine> step = deck.step();
  step.front().text = long_step_card(step.front().text);
  // Time period: the run's. The increments (initial, minimum, maximum) are the deck's, scaled
  // from its step to a coupler time step.
  const std::string increment = ccx_number(initial_increment());
  const std::string period = ccx_number(end_time);
  if (const auto data = deck.procedure_data_line()) {
    auto fields = split_commas(step[*data].text);
    fields.resize(std::max<std::size_t>(fields.size(), 2));
    fields[0] = increment;
    fields[1] = period;
    for (std::size_t i = 2; i < std::min<std::size_t>(fields.size(), 4); ++i)
      if (!fields[i].empty()) fields[i] = ccx_number(std::stod(fields[i]) * time_scale());
    step[*data].text = join_fields(fields);
  } else {
    step.insert(step.begin() + static_cast<std::ptrdiff_t>(deck.procedure_line()) + 1,
                DeckLine{increment + ", " + period, "(cocopp)"});
  }
  std::vector<DeckLine> placeholders;
  const auto add = [&](std::string text) { placeholders.push_back({std::move(text), "(cocopp)"}); };
  const InterfaceLoads& loads = *model_.loads;
  if (model_.takes("pressure")) {
    add("** cocopp: the interface's pressure, set by the coupler");
    add("*DLOAD");
    for (const auto& face : loads.faces()) add(fmt::format("{}, P{}, 0.", face.element, face.face));
  }
  add("** cocopp: the interface's nodal forces, set by the coupler");
  add("*CLOAD");
  for (const auto node : force_nodes_)
    for (int dof = 1; dof <= (loads.plane() ? 2 : 3); ++dof)
      add(fmt::format("{}, {}, 0.", node, dof));
  step.insert(step.end() - 1, placeholders.begin(), placeholders.end());
  return step;
}

InterfaceFile PersistentCcx::interface_file() const {
  const InputDeck& deck = *model_.deck;
  const InterfaceLoads& loads = *model_.loads;
  InterfaceFile file;
  file.ramp = ramps(deck);
  // As the deck's step gives it: ccx and cocopp-ccx start every time step with the same
  // increment.
  file.initial_increment = std::stod(ccx_number(initial_increment()));
  // ccx reads a *CLOAD of an axisymmetric model per 360 degrees and divides it by 180 for the
  // 2 degree wedge it solves (cloads.f); the placeholders' values are set after that.
  bool axisymmetric = false;
  for (const auto& [id, element] : deck.elements())
    axisymmetric = axisymmetric || element.type.rfind("CAX", 0) == 0;
  file.force_scale = std::stod(ccx_number(axisymmetric ? 1.0 / 180.0 : 1.0));
  file.linear = linear(deck);
  file.face_offset = loads.plane() ? 2 : 0;
  if (model_.takes("pressure"))
    for (const auto& face : loads.faces())
      file.pressure_faces.emplace_back(static_cast<int>(face.element), face.face);
  file.force_dofs = loads.plane() ? 2 : 3;
  file.force_nodes.assign(force_nodes_.begin(), force_nodes_.end());
  file.displacement_nodes.assign(model_.interface_nodes.begin(), model_.interface_nodes.end());
  return file;
}

double PersistentCcx::time_scale() const {
  return model_.run.delta_t / model_.deck->step_time_period();
}

double PersistentCcx::initial_increment() const {
  // A linear static step is one solve for ccx, whatever its increments say (linstatic.c): one
  // increment per time step here too.
  if (linear_static(*model_.deck)) return model_.run.delta_t;
  return std::min(model_.deck->initial_increment(), model_.deck->step_time_period()) * time_scale();
}

void PersistentCcx::initialize_step(int step, double time) {
  process_->initialize_step(step, time);
  step_time_ = time;
}

void PersistentCcx::solve(const Interface& input, Interface& output) {
  const auto start = Clock::now();
  last_input_ = input.data();
  try {
    output.values(model_.node_set_name, "displacement") = solve_in_process(input);
  } catch (const SolverError& e) {
    // ccx ends when it gives up a step: a new cocopp-ccx takes the committed steps again, so
    // that the coupler may retry with other loads, as with a ccx run per iteration.
    const std::string tail = read_last_lines(model_.log_file, 20);
    if (!gave_up(tail)) throw;
    restart_process(output);
    throw model_.not_converged("cocopp-ccx exited; restarted with the committed steps",
                               model_.file(std::string(kJob) + ".inp").string(), tail);
  }
  timing_ = {process_seconds_, seconds_since(start) - process_seconds_};
}

RowMatrix PersistentCcx::solve_in_process(const Interface& input) {
  const auto [pressure, traction, force] = model_.face_loads(input);
  const auto forces = traction.size() > 0 ? model_.loads->nodal_forces(traction)
                      : force.size() > 0  ? model_.loads->nodal_forces_of_totals(force)
                                          : std::map<std::int64_t, Eigen::Vector3d>{};
  Interface request = process_->input_interface();
  if (model_.takes("pressure")) request.values("pressure_faces", "pressure").col(0) = pressure;
  auto nodal = request.values("force_nodes", "force");
  for (std::size_t i = 0; i < force_nodes_.size(); ++i) {
    const auto found = forces.find(force_nodes_[i]);
    const Eigen::Vector3d global = found == forces.end() ? Eigen::Vector3d::Zero() : found->second;
    nodal.row(static_cast<Eigen::Index>(i)) =
        model_.loads->in_node_system(force_nodes_[i], global).transpose();
  }
  // ccx keeps displacements in global x, y, z (a *TRANSFORM applies to loads and constraints).
  const auto start = Clock::now();
  RowMatrix u = process_->solve(request).values("displacement_nodes", "displacement");
  process_seconds_ = seconds_since(start);
  return u;
}

void PersistentCcx::finalize_step() {
  process_->finalize_step();
  committed_inputs_.push_back(last_input_);
  committed_times_.push_back(step_time_);
}

void PersistentCcx::finalize() {
  if (process_) process_->finalize();
}

// A restart replays the committed steps: their times and inputs, besides the displacement that
// checks the replay.
void PersistentCcx::save_restart(int step, const Interface& output) {
  const RowMatrix u = output.values(model_.node_set_name, "displacement");
  const Eigen::Index size = input_layout_.size();
  Eigen::VectorXd inputs(static_cast<Eigen::Index>(committed_inputs_.size()) * size);
  for (std::size_t k = 0; k < committed_inputs_.size(); ++k)
    inputs.segment(static_cast<Eigen::Index>(k) * size, size) = committed_inputs_[k];
  write_restart_file(
      model_.file(restart_file_name(model_.name, step).string()), model_.name, step,
      {{"displacement", Eigen::Map<const Eigen::VectorXd>(u.data(), u.size())},
       {"times", Eigen::Map<const Eigen::VectorXd>(
                     committed_times_.data(), static_cast<Eigen::Index>(committed_times_.size()))},
       {"inputs", inputs}});
}

void PersistentCcx::replay_committed_steps(int step, Interface& output) {
  const std::filesystem::path data_file =
      model_.file(restart_file_name(model_.name, step).string());
  const Eigen::Index size = input_layout_.size();
  Eigen::VectorXd times, inputs, displacement;
  try {
    const RestartData data = read_restart_file(data_file, model_.name, step);
    if (data.count("inputs") == 0)
      throw std::runtime_error(
          "it has no committed inputs (was the run per_iteration? restart "
          "it with mode: per_iteration)");
    times = restart_array(data, "times", step, data_file);
    inputs = restart_array(data, "inputs", step * size, data_file);
    displacement =
        restart_array(data, "displacement",
                      output.values(model_.node_set_name, "displacement").size(), data_file);
  } catch (const std::runtime_error& e) {
    model_.fail(fmt::format("solver '{}' cannot restart after time step {}: {}", model_.name, step,
                            e.what()));
  }
  std::vector<double> step_times(times.data(), times.data() + times.size());
  std::vector<Eigen::VectorXd> step_inputs;
  for (int k = 0; k < step; ++k) step_inputs.push_back(inputs.segment(k * size, size));
  replay(step_times, step_inputs, output);
  const auto u = output.values(model_.node_set_name, "displacement");
  const double scale = std::max(displacement.cwiseAbs().maxCoeff(), 1e-300);
  const double off =
      (Eigen::Map<const Eigen::VectorXd>(u.data(), u.size()) - displacement).cwiseAbs().maxCoeff();
  if (off > 1e-9 * scale)
    model_.fail(
        fmt::format("solver '{}': replaying time steps 1 to {} for the restart ends {:.2e} "
                    "(relative) away from the displacement the run saved in {}: the deck or "
                    "the ccx changed since",
                    model_.name, step, off / scale, data_file.string()));
}

// Each committed step again, one coupling iteration with its converged input (and the faces
// moved as the wrapper moves them after a step): the same increments, so the same state.
void PersistentCcx::replay(const std::vector<double>& times,
                           const std::vector<Eigen::VectorXd>& inputs, Interface& output) {
  committed_times_.clear();
  committed_inputs_.clear();
  Interface input = input_layout_;
  for (std::size_t k = 0; k < times.size(); ++k) {
    model_.step = static_cast<int>(k + 1);
    model_.iteration = 1;
    initialize_step(model_.step, times[k]);
    input.set_data(inputs[k]);
    solve(input, output);
    model_.move_faces_with(output);
    finalize_step();
  }
}

void PersistentCcx::restart_process(Interface& output) {
  const int step = model_.step;
  const int iteration = model_.iteration;
  const double time = step_time_;
  const auto times = committed_times_;
  const auto inputs = committed_inputs_;
  process_->finalize();
  model_.loads->move_faces({});  // the deck's geometry: the replay moves the faces again
  start_process();
  replay(times, inputs, output);
  // The step that did not converge, ready for another input.
  model_.step = step;
  model_.iteration = iteration;
  initialize_step(step, time);
}

}  // namespace cocopp::calculix
