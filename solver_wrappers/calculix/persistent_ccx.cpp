#include "solver_wrappers/calculix/persistent_ccx.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <regex>
#include <set>

#include "core/case/settings.hpp"
#include "solver_wrappers/calculix/ccx_run.hpp"
#include "solver_wrappers/process/process_solver_wrapper.hpp"
#include "solver_wrappers/solver_error.hpp"

namespace cocopp::calculix {

namespace {

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

PersistentCcx::PersistentCcx(Options options, const InputDeck& deck, const InterfaceLoads& loads,
                             std::vector<std::int64_t> output_nodes, std::string model_file)
    : options_(std::move(options)),
      deck_(deck),
      loads_(loads),
      output_nodes_(std::move(output_nodes)),
      model_file_(std::move(model_file)) {
  std::set<std::int64_t> nodes;
  for (const auto& face : loads_.geometry()) nodes.insert(face.nodes.begin(), face.nodes.end());
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

void PersistentCcx::start(const RunSettings& run, double end_time) {
  run_ = run;
  write_deck(end_time);
  write_interface();
  DefaultCommand command{
      options_.executable, "", {"-i", kJob}, ccx_thread_environment(options_.threads), {}};
  // ccx's Fortran writes unbuffered: in the log in order with its C output (cocopp-ccx makes
  // stdout line-buffered), so that its last lines say why it stopped; in the .dat file as each
  // step commits.
  command.environment.emplace_back("GFORTRAN_UNBUFFERED_ALL", "y");
  const Settings settings = Settings::load_string(
      fmt::format("type: process\nname: '{}'\nworking_directory: '{}'\ntimeout: {}\n"
                  "log_file: '{}'\n",
                  options_.name, options_.working_directory.string(), options_.timeout,
                  options_.log_file.string()),
      "(the calculix wrapper's cocopp-ccx)");
  // cocopp-ccx always starts from the deck; a restart replays the committed steps through it.
  RunSettings from_start = run;
  from_start.timestep_start = 0;
  process_ = std::make_unique<ProcessSolverWrapper>(settings, from_start, command);
  process_->initialize();
}

void PersistentCcx::write_deck(double end_time) const {
  const auto path = options_.working_directory / (std::string(kJob) + ".inp");
  std::ofstream out(path);
  out << "** The coupled run's deck, written by cocopp (calculix wrapper, mode: persistent): the\n"
         "** step of the user's deck as one step of the whole run's length, which cocopp-ccx\n"
         "** advances by the coupler's time steps; the interface loads' placeholders last.\n"
      << "*INCLUDE, INPUT=" << model_file_ << "\n";
  for (const auto& line : long_step(end_time)) out << line.text << "\n";
  if (!out.flush()) throw SolverError(options_.name, "cannot write " + path.string());
}

std::vector<DeckLine> PersistentCcx::long_step(double end_time) const {
  std::vector<DeckLine> step = deck_.step();
  step.front().text = long_step_card(step.front().text);
  // Time period: the run's. The increments (initial, minimum, maximum) are the deck's, scaled
  // from its step to a coupler time step.
  const std::string increment = ccx_number(initial_increment());
  const std::string period = ccx_number(end_time);
  if (const auto data = deck_.procedure_data_line()) {
    auto fields = split_commas(step[*data].text);
    fields.resize(std::max<std::size_t>(fields.size(), 2));
    fields[0] = increment;
    fields[1] = period;
    for (std::size_t i = 2; i < std::min<std::size_t>(fields.size(), 4); ++i)
      if (!fields[i].empty()) fields[i] = ccx_number(std::stod(fields[i]) * time_scale());
    step[*data].text = join_fields(fields);
  } else {
    step.insert(step.begin() + static_cast<std::ptrdiff_t>(deck_.procedure_line()) + 1,
                DeckLine{increment + ", " + period, "(cocopp)"});
  }
  std::vector<DeckLine> placeholders;
  const auto add = [&](std::string text) { placeholders.push_back({std::move(text), "(cocopp)"}); };
  if (options_.pressure) {
    add("** cocopp: the interface's pressure, set by the coupler");
    add("*DLOAD");
    for (const auto& face : loads_.faces())
      add(fmt::format("{}, P{}, 0.", face.element, face.face));
  }
  add("** cocopp: the interface's nodal forces, set by the coupler");
  add("*CLOAD");
  for (const auto node : force_nodes_)
    for (int dof = 1; dof <= (loads_.plane() ? 2 : 3); ++dof)
      add(fmt::format("{}, {}, 0.", node, dof));
  step.insert(step.end() - 1, placeholders.begin(), placeholders.end());
  return step;
}

void PersistentCcx::write_interface() const {
  const auto path = options_.working_directory / kInterfaceFile;
  std::ofstream out(path);
  out << "amplitude " << (ramps(deck_) ? "ramp" : "step") << "\n";
  out << "initial_increment " << ccx_number(initial_increment()) << "\n";
  // ccx reads a *CLOAD of an axisymmetric model per 360 degrees and divides it by 180 for the
  // 2 degree wedge it solves (cloads.f); the placeholders' values are set after that.
  bool axisymmetric = false;
  for (const auto& [id, element] : deck_.elements())
    axisymmetric = axisymmetric || element.type.rfind("CAX", 0) == 0;
  out << "force_scale " << ccx_number(axisymmetric ? 1.0 / 180.0 : 1.0) << "\n";
  out << "linear " << (linear(deck_) ? 1 : 0) << "\n";
  out << "pressure_faces " << (options_.pressure ? loads_.faces().size() : 0) << " "
      << (loads_.plane() ? 2 : 0) << "\n";
  if (options_.pressure)
    for (const auto& face : loads_.faces()) out << face.element << " " << face.face << "\n";
  out << "force_nodes " << force_nodes_.size() << " " << (loads_.plane() ? 2 : 3) << "\n";
  for (const auto node : force_nodes_) out << node << "\n";
  out << "displacement_nodes " << output_nodes_.size() << "\n";
  for (const auto node : output_nodes_) out << node << "\n";
  if (!out.flush()) throw SolverError(options_.name, "cannot write " + path.string());
}

double PersistentCcx::time_scale() const {
  return run_.delta_t / deck_.step_time_period();
}

double PersistentCcx::initial_increment() const {
  // A linear static step is one solve for ccx, whatever its increments say (linstatic.c): one
  // increment per time step here too.
  if (linear_static(deck_)) return run_.delta_t;
  return std::min(deck_.initial_increment(), deck_.step_time_period()) * time_scale();
}

void PersistentCcx::initialize_step(int step, double time) {
  process_->initialize_step(step, time);
}

RowMatrix PersistentCcx::solve(const Eigen::VectorXd& pressure,
                               const std::map<std::int64_t, Eigen::Vector3d>& forces) {
  Interface input = process_->input_interface();
  if (options_.pressure) input.values("pressure_faces", "pressure").col(0) = pressure;
  auto nodal = input.values("force_nodes", "force");
  for (std::size_t i = 0; i < force_nodes_.size(); ++i) {
    const auto found = forces.find(force_nodes_[i]);
    const Eigen::Vector3d global = found == forces.end() ? Eigen::Vector3d::Zero() : found->second;
    nodal.row(static_cast<Eigen::Index>(i)) =
        loads_.in_node_system(force_nodes_[i], global).transpose();
  }
  // ccx keeps displacements in global x, y, z (a *TRANSFORM applies to loads and constraints).
  const auto start = std::chrono::steady_clock::now();
  RowMatrix u = process_->solve(input).values("displacement_nodes", "displacement");
  process_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return u;
}

void PersistentCcx::finalize_step() {
  process_->finalize_step();
}

void PersistentCcx::finalize() {
  if (process_) process_->finalize();
}

}  // namespace cocopp::calculix
