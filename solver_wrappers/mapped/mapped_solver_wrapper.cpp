// `mapped`: input mapper -> a real solver wrapper -> output mapper, so that a solver with its
// own mesh couples to the other solver's interface. The wrapper presents the other solver's
// interface to the coupled solver (adopt_interfaces) and maps, per model part pair (in order)
// and per variable, between that interface and the inner solver's.
//
// Moving and sliding interfaces: with `coordinates: current` the mappers are rebuilt on the
// current positions (initial coordinates plus the latest displacement each side knows of) every
// time step or every coupling iteration (`rebuild`).
//
// `input_mapper` is one mapper for every input model part pair, or a list of one per pair (a
// structure that takes loads on its faces and a position at its nodes needs two kinds).
//
// `coverage`: an inner solver that takes this variable, which the other side does not give,
// receives the input mapper applied to ones (how much of each of its faces the other side
// covers: the calculix wrapper driven by displacement under a film needs it).
//
// `exact_round_trip: [wall_displacement]`: variables that are the other side's record of what
// the output mapper gives it (a film's wall position at its points) are mapped onto the inner
// solver's nodes so that the output mapper gives them back exactly (ExactRoundTrip: a
// structure driven by the wall position then balances the forces at the coupling's fixed point).
//
// A placed frame: `frame_origin: [x, y, z]` says where the inner solver's origin lies in the
// other solver's coordinates (one input file for several bodies, each placed by its own
// wrapper: a group of walls along a tube).
//
// A moving frame: `frame_velocity: [vx, vy, vz]` says that the inner solver describes its
// body in a frame that moves at this velocity (in the inner solver's coordinates, before the
// transformers) relative to the other solver's. Its points are then at their coordinates plus
// displacement plus velocity x time, and the other solver sees that motion in the displacement.
// A body drawn through a fixed tool (the wire drawing example) is solved with its pulled end
// held: CalculiX's static steps converge in a few iterations where a prescribed pull of the end
// makes their first increments diverge once the body yields (docs/wire-drawing.md).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <stdexcept>

#include "core/case/suggest.hpp"
#include "mappers/mapper.hpp"
#include "solver_wrappers/mapped/exact_round_trip.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {
namespace {

class MappedSolverWrapper : public SolverWrapper {
 public:
  MappedSolverWrapper(const Settings& settings, const RunSettings& run)
      : inner_(SolverWrapperRegistry::instance().create(settings.child("solver_wrapper"), run)),
        name_(settings.get_name("name", inner_->name())),
        input_settings_(settings.node()["input_mapper"].IsSequence()
                            ? settings.list("input_mapper")
                            : std::vector<Settings>{settings.child("input_mapper")}),
        input_where_(settings.where("input_mapper")),
        output_settings_(settings.child("output_mapper")),
        rebuild_(settings.get_choice("rebuild", "never", {"never", "time_step", "iteration"})),
        current_(settings.get_choice("coordinates", "initial", {"initial", "current"}) ==
                 "current"),
        report_(settings.get<bool>("report_quality", false)),
        exact_variables_(settings.get<std::vector<std::string>>("exact_round_trip", {})),
        exact_where_(settings.where("exact_round_trip")),
        own_parts_(settings.get<std::vector<std::string>>("model_parts", {})),
        own_parts_where_(settings.where("model_parts")),
        time_(run.timestep_start * run.delta_t) {
    if (settings.has("name")) inner_->set_default_name(name_);
    // Build one mapper now so that `cocopp check` validates the mapper settings.
    if (input_settings_.empty())
      settings.fail("input_mapper", "give a mapper, or a list of one per input model part pair");
    for (const auto& input : input_settings_) Mapper{input};
    Mapper{output_settings_};
    read_frame(settings);
  }

  const std::string& name() const override { return name_; }
  std::string describe() const override { return name_ + " mapped onto " + inner_->describe(); }
  std::string started() const override { return inner_->started(); }
  void check() const override { inner_->check(); }
  void check_solver_input() const override { inner_->check_solver_input(); }
  std::filesystem::path input_file() const override { return inner_->input_file(); }

  void start() override { inner_->start(); }
  void initialize() override { inner_->initialize(); }
  void overlap_step_requests() override { inner_->overlap_step_requests(); }
  void complete_step_requests() override { inner_->complete_step_requests(); }
  bool adopts_interfaces() const override { return true; }

  void adopt_interfaces(const Interface& input, const Interface& output) override {
    input_ = only_own_parts(input);
    output_ = only_own_parts(output);
    builds_ = 0;  // adopted again (a group gives it only its own points): a fresh count
    build_seconds_ = 0.0;
    pair_model_parts();
    build_mappers();
    map_output(inner_->output_interface());  // the initial output, as seen by the coupler
  }

  Eigen::VectorXd output_distances(const std::string& part) const override {
    for (const auto& pair : output_pairs_)
      if (pair.outer == part) {
        try {
          return pair.mapper->target_distances();
        } catch (const std::invalid_argument& e) {
          throw std::runtime_error(fmt::format(
              "mapped solver '{}': which points of '{}' it covers is measured by its output "
              "mapper, and {}",
              name_, part, e.what()));
        }
      }
    return SolverWrapper::output_distances(part);
  }

  const Interface& input_interface() const override { return input_; }
  const Interface& output_interface() const override { return output_; }

  void initialize_step(int step, double time) override {
    inner_->initialize_step(step, time);
    record_round_trips();  // of the last step's converged iterate
    time_ = time;
    if (rebuild_ == "time_step") build_mappers();
  }

  const Interface& solve(const Interface& input) override {
    const Interface& inner_output = inner_->solve(inner_input_for(input));
    const auto output_start = Clock::now();
    map_output(inner_output);
    map_seconds_ += seconds_since(output_start);
    ++solves_;
    return output_;
  }

  int substeps() const override { return inner_->substeps(); }

  /// Each substep's input mapped onto the inner solver's points, its outputs back.
  Eigen::MatrixXd solve_substeps(const Eigen::MatrixXd& inputs) override {
    if (inner_->substeps() == 1) return SolverWrapper::solve_substeps(inputs);
    Eigen::MatrixXd inner_inputs(inner_->input_interface().size(), inputs.cols());
    Interface input = input_;
    for (Eigen::Index j = 0; j < inputs.cols(); ++j) {
      input.set_data(inputs.col(j));
      inner_inputs.col(j) = inner_input_for(input, j == 0).data();
    }
    const Eigen::MatrixXd inner_outputs = inner_->solve_substeps(inner_inputs);
    const auto output_start = Clock::now();
    Interface inner_output = inner_->output_interface();
    Eigen::MatrixXd outputs(output_.size(), inputs.cols());
    for (Eigen::Index j = 0; j < inputs.cols(); ++j) {
      inner_output.set_data(inner_outputs.col(j));
      map_output(inner_output);
      outputs.col(j) = output_.data();
    }
    map_seconds_ += seconds_since(output_start);
    ++solves_;
    return outputs;  // output_ holds the last substep's, as after solve()
  }

  void start_reporting_convergence() override { inner_->start_reporting_convergence(); }
  bool converged_at_first_iteration() const override {
    return inner_->converged_at_first_iteration();
  }
  void finalize_step() override { inner_->finalize_step(); }
  void output_step() override { inner_->output_step(); }
  void save_restart(int step) override { inner_->save_restart(step); }
  void finalize() override {
    inner_->finalize();
    record_round_trips();
    for (const auto& pair : input_pairs_)
      for (const auto& [variable, round_trip] : pair.round_trips) {
        fmt::print(
            "  mapping        : {}: exact round trip of {} at the steps' last iterates: the "
            "mappers alone missed by up to {:.3g}, the exact one by {:.3g}\n",
            name_, variable, plain_round_trip_, exact_round_trip_);
      }
    if (builds_ > 1)  // rebuilt during the run: what the sliding interface costs
      fmt::print(
          "  mapping        : {}: mappers built {} times, {:.3g} ms each; mapping {:.3g} ms "
          "per coupling iteration\n",
          name_, builds_, 1e3 * build_seconds_ / builds_,
          solves_ > 0 ? 1e3 * map_seconds_ / solves_ : 0.0);
  }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  /// The inner solver's input for `input` (laid out as the adopted input interface); the
  /// mappers are rebuilt first with `rebuild: iteration` (once per coupling iteration).
  Interface inner_input_for(const Interface& input, bool new_iteration = true) {
    input_.set_data(input.data());
    if (rebuild_ == "iteration" && new_iteration) build_mappers();
    const auto start = Clock::now();
    Interface inner_input = inner_->input_interface();
    for (auto& pair : input_pairs_)
      for (const auto& variable : variables_of(inner_input, pair.inner))
        inner_input.values(pair.inner, variable) = map_input(pair, variable);
    map_seconds_ += seconds_since(start);
    return inner_input;
  }

  /// The i-th input model part of the coupler side maps to the i-th of the inner solver (with
  /// the i-th input mapper, or the one for all), the j-th output part of the inner solver to the
  /// j-th of the coupler side.
  struct InputPair {
    std::string outer, inner;
    std::unique_ptr<Mapper> mapper;
    /// Where the inner input part (e.g. a structure's faces) has no displacement of its own:
    /// its points take that of the nearest point of an inner output part (its nodes: the i-th,
    /// or the last if there are fewer), so that with `coordinates: current` the faces move
    /// with the body.
    std::string follow_part;
    std::unique_ptr<Mapper> follow_output;
    /// `exact_round_trip` variables of this pair, mapped back by the output pair
    /// `back` (the one onto the same outer part), whose inner nodes are rows `back_rows` here.
    std::map<std::string, ExactRoundTrip> round_trips;
    std::size_t back = 0;
    std::vector<Eigen::Index> back_rows;
  };
  struct OutputPair {
    std::string inner, outer;
    std::unique_ptr<Mapper> mapper;
  };

  /// `model_parts: [flag_a]`: of the other side's model parts only these, in its order (a
  /// body in a group that owns one patch of a fluid with several); all without the key.
  Interface only_own_parts(const Interface& interface) const {
    if (own_parts_.empty()) return interface;
    const auto names = part_names(interface);
    for (const auto& part : own_parts_)
      if (std::find(names.begin(), names.end(), part) == names.end())
        throw std::runtime_error(fmt::format(
            "{}: mapped solver '{}': model_parts: '{}' is not a model part of the other side's "
            "interface (it has: {}){}",
            own_parts_where_, name_, part, fmt::join(names, ", "), did_you_mean(part, names)));
    std::vector<Interface::Part> kept;
    for (const auto& part : interface.parts())
      if (std::find(own_parts_.begin(), own_parts_.end(), part.model_part->name) !=
          own_parts_.end())
        kept.push_back(part);
    Interface only(std::move(kept));
    for (const auto& block : only.blocks())
      only.values(block.model_part, block.variable) =
          interface.values(block.model_part, block.variable);
    return only;
  }

  static std::vector<std::string> part_names(const Interface& interface) {
    std::vector<std::string> names;
    for (const auto& part : interface.parts()) names.push_back(part.model_part->name);
    return names;
  }

  static std::vector<std::string> variables_of(const Interface& interface,
                                               const std::string& part) {
    for (const auto& p : interface.parts())
      if (p.model_part->name == part) return p.variables;
    return {};
  }

  void pair_model_parts() {
    const auto outer_in = part_names(input_), outer_out = part_names(output_);
    const auto inner_in = part_names(inner_->input_interface());
    const auto inner_out = part_names(inner_->output_interface());
    if (outer_in.size() != inner_in.size() || outer_out.size() != inner_out.size())
      throw std::runtime_error(fmt::format(
          "mapped solver '{}': the other solver's interface has {} input and {} output model "
          "parts, '{}' has {} and {}: model parts are mapped pairwise, in order",
          name_, outer_in.size(), outer_out.size(), inner_->name(), inner_in.size(),
          inner_out.size()));
    if (input_settings_.size() > 1 && input_settings_.size() != inner_in.size())
      throw std::runtime_error(fmt::format(
          "{}: mapped solver '{}': {} input mappers for {} input model part pairs ({}): give "
          "one per pair, in order, or one mapper for all",
          input_where_, name_, input_settings_.size(), inner_in.size(), fmt::join(inner_in, ", ")));
    input_pairs_.clear();
    output_pairs_.clear();
    for (std::size_t j = 0; j < inner_out.size(); ++j) {
      output_pairs_.push_back(
          {inner_out[j], outer_out[j], std::make_unique<Mapper>(output_settings_)});
      check_variables(inner_->output_interface(), inner_out[j], output_, outer_out[j]);
    }
    for (std::size_t i = 0; i < inner_in.size(); ++i) {
      InputPair pair;
      pair.outer = outer_in[i];
      pair.inner = inner_in[i];
      pair.mapper =
          std::make_unique<Mapper>(input_settings_[std::min(i, input_settings_.size() - 1)]);
      if (!inner_out.empty()) pair.follow_part = inner_out[std::min(i, inner_out.size() - 1)];
      check_variables(input_, pair.outer, inner_->input_interface(), pair.inner);
      if (current_ && !pair.follow_part.empty() &&
          !has_displacement(inner_->input_interface(), pair.inner) &&
          has_displacement(inner_->output_interface(), pair.follow_part)) {
        // Any distance: the faces of a thin 3D sector lie off the side its output nodes are
        // on (the wire drawing case's sector), beyond the interpolator's default tolerance.
        const Coordinates nodes = initial_coordinates(inner_->output_interface(), pair.follow_part);
        const Coordinates faces = initial_coordinates(inner_->input_interface(), pair.inner);
        Coordinates both(nodes.rows() + faces.rows(), 3);
        both << nodes, faces;
        const double extent = (both.colwise().maxCoeff() - both.colwise().minCoeff()).norm() + 1.0;
        pair.follow_output = std::make_unique<Mapper>(
            Settings::load_string(fmt::format("{{type: nearest, max_distance: {:.17g}}}", extent),
                                  "(the faces follow their nodes)"));
        pair.follow_output->initialize(nodes, faces);
      }
      input_pairs_.push_back(std::move(pair));
    }
    pair_round_trips();
  }

  /// Each `exact_round_trip` variable needs an input pair whose inner part takes it and an
  /// output pair that maps back onto the same outer part, from nodes that the input pair's
  /// inner part holds too.
  void pair_round_trips() {
    std::vector<std::string> taken;
    for (const auto& pair : input_pairs_)
      for (const auto& variable : variables_of(inner_->input_interface(), pair.inner))
        if (std::find(taken.begin(), taken.end(), variable) == taken.end())
          taken.push_back(variable);
    for (const auto& variable : exact_variables_) {
      bool found = false;
      for (auto& pair : input_pairs_) {
        const auto variables = variables_of(inner_->input_interface(), pair.inner);
        if (std::find(variables.begin(), variables.end(), variable) == variables.end()) continue;
        found = true;
        pair.back = output_pair_onto(pair.outer, variable);
        pair.back_rows = rows_of(output_pairs_[pair.back].inner, pair.inner);
        pair.round_trips[variable];
      }
      if (!found)
        throw std::runtime_error(fmt::format(
            "{}: mapped solver '{}': exact_round_trip: '{}' is not a variable that '{}' "
            "takes (it takes: {}){}",
            exact_where_, name_, variable, inner_->name(), fmt::join(taken, ", "),
            did_you_mean(variable, taken)));
    }
  }

  std::size_t output_pair_onto(const std::string& outer, const std::string& variable) const {
    for (std::size_t j = 0; j < output_pairs_.size(); ++j)
      if (output_pairs_[j].outer == outer) return j;
    throw std::runtime_error(fmt::format(
        "{}: mapped solver '{}': exact_round_trip: '{}' comes from model part '{}', onto which "
        "no output model part maps back: the round trip needs both ways",
        exact_where_, name_, variable, outer));
  }

  /// For each point of the inner part `from`, its row in the inner part `in` (by id).
  std::vector<Eigen::Index> rows_of(const std::string& from, const std::string& in) const {
    const auto& from_ids = model_part(inner_->output_interface(), from).ids;
    const auto& in_ids = model_part(inner_->input_interface(), in).ids;
    std::map<std::int64_t, Eigen::Index> row;
    for (std::size_t i = 0; i < in_ids.size(); ++i) row[in_ids[i]] = static_cast<Eigen::Index>(i);
    std::vector<Eigen::Index> rows;
    for (const auto id : from_ids) {
      const auto found = row.find(id);
      if (found == row.end())
        throw std::runtime_error(fmt::format(
            "{}: mapped solver '{}': exact_round_trip: point {} of '{}' (output) is not in "
            "'{}' (input): the nodes that map back must be among those that take the variable",
            exact_where_, name_, id, from, in));
      rows.push_back(found->second);
    }
    return rows;
  }

  static const ModelPart& model_part(const Interface& interface, const std::string& name) {
    for (const auto& p : interface.parts())
      if (p.model_part->name == name) return *p.model_part;
    throw std::logic_error("no model part " + name);
  }

  RowMatrix map_input(InputPair& pair, const std::string& variable) {
    if (is_coverage(variable, pair))
      return pair.mapper->map(RowMatrix::Ones(initial_coordinates(input_, pair.outer).rows(), 1));
    const auto exact = pair.round_trips.find(variable);
    if (exact != pair.round_trips.end()) return map_exactly(pair, exact->second, variable);
    return pair.mapper->map(input_.values(pair.outer, variable), variable);
  }

  /// The exact round trip, with the nodes the inner solver reports as not `driven` (if it
  /// reports that) held at their latest displacement, as the output mapper sees them.
  RowMatrix map_exactly(const InputPair& pair, ExactRoundTrip& round_trip,
                        const std::string& variable) {
    const std::string& nodes = output_pairs_[pair.back].inner;
    const Interface& inner_output = inner_->output_interface();
    const auto reported = variables_of(inner_output, nodes);
    const bool reports = std::find(reported.begin(), reported.end(), "driven") != reported.end();
    const auto rows = static_cast<Eigen::Index>(pair.back_rows.size());
    std::vector<bool> held(pair.back_rows.size(), false);
    RowMatrix base = RowMatrix::Zero(rows, 3);
    base.rowwise() += frame_motion();
    for (Eigen::Index k = 0; reports && k < rows; ++k) {
      held[static_cast<std::size_t>(k)] = inner_output.values(nodes, "driven")(k, 0) == 0.0;
      if (held[static_cast<std::size_t>(k)])
        base.row(k) += inner_output.values(nodes, "displacement").row(k);
    }
    round_trip.hold(held);
    return round_trip.map(input_.values(pair.outer, variable), base);
  }

  /// `coverage`, which the inner solver takes and the other side does not give: the input
  /// mapper applied to ones, the fraction of each inner point's share that the other side's
  /// interface covers (1 inside it, 0 outside, between on the faces across its edge).
  bool is_coverage(const std::string& variable, const InputPair& pair) const {
    const auto given = variables_of(input_, pair.outer);
    return variable == "coverage" && std::find(given.begin(), given.end(), variable) == given.end();
  }

  /// Every variable the receiving side takes must be given by the sending side (`coverage`
  /// the mapper makes itself).
  void check_variables(const Interface& from, const std::string& from_part, const Interface& to,
                       const std::string& to_part) const {
    const auto given = variables_of(from, from_part);
    for (const auto& variable : variables_of(to, to_part))
      if (variable != "coverage" && std::find(given.begin(), given.end(), variable) == given.end())
        throw std::runtime_error(fmt::format(
            "mapped solver '{}': model part '{}' needs '{}', which model part '{}' does not "
            "give (it gives: {})",
            name_, to_part, variable, from_part, fmt::join(given, ", ")));
  }

  void read_frame(const Settings& settings) {
    frame_origin_ = read_vector(settings, "frame_origin");
    frame_velocity_ = read_vector(settings, "frame_velocity");
    if (!frame_velocity_.isZero() && rebuild_ == "never")
      settings.fail("frame_velocity",
                    "a moving frame needs mappings rebuilt as it moves: add 'rebuild: time_step'");
  }

  static Eigen::RowVector3d read_vector(const Settings& settings, const std::string& key) {
    if (!settings.has(key)) return Eigen::RowVector3d::Zero();
    const auto vector = settings.get<std::vector<double>>(key, {});
    if (vector.size() != 3)
      settings.fail(key, fmt::format("give three components [x, y, z], not {}", vector.size()));
    return {vector[0], vector[1], vector[2]};
  }

  /// How far the inner solver's frame has moved by now (from frame_origin).
  Eigen::RowVector3d frame_motion() const { return frame_velocity_ * time_; }

  static bool has_displacement(const Interface& interface, const std::string& part) {
    const auto variables = variables_of(interface, part);
    return std::find(variables.begin(), variables.end(), "displacement") != variables.end();
  }

  static Coordinates initial_coordinates(const Interface& interface, const std::string& part) {
    for (const auto& p : interface.parts())
      if (p.model_part->name == part) return p.model_part->coordinates;
    return {};
  }

  /// Initial coordinates of a model part, plus the latest displacement that either interface
  /// of that side holds for it if `coordinates: current` (for an inner input part without
  /// one: its nodes', see InputPair::follow_output), plus the frame's motion for the inner solver's
  /// parts.
  Coordinates coordinates(const std::string& part, const Interface& a, const Interface& b,
                          bool inner, const InputPair* pair = nullptr) const {
    Coordinates points;
    bool displaced = false;
    for (const Interface* interface : {&a, &b})
      for (const auto& p : interface->parts()) {
        if (p.model_part->name != part) continue;
        if (points.rows() == 0) points = p.model_part->coordinates;
        if (current_ && !displaced && has_displacement(*interface, part)) {
          points += interface->values(part, "displacement");
          displaced = true;
        }
      }
    if (!displaced && pair && pair->follow_output)
      points += pair->follow_output->map(
          inner_->output_interface().values(pair->follow_part, "displacement"));
    if (inner) points.rowwise() += frame_origin_ + frame_motion();
    return points;
  }

  /// Build (or rebuild) the mappers; an interpolator's complaint (no overlap, duplicate
  /// points) is passed on with where the sides stand now.
  void build_mappers() {
    const auto start = Clock::now();
    try {
      build_mappers_on_current_positions();
      build_seconds_ += seconds_since(start);
      ++builds_;
    } catch (const std::invalid_argument& e) {
      const std::string moved =
          frame_velocity_.isZero()
              ? std::string()
              : fmt::format(", {}'s frame has moved by ({:g}, {:g}, {:g})", inner_->name(),
                            frame_motion()(0), frame_motion()(1), frame_motion()(2));
      throw std::runtime_error(fmt::format(
          "mapped solver '{}': the mappers cannot be built on the positions at time {:g}{}: "
          "{}{}",
          name_, time_, moved, e.what(),
          current_ ? "; on a sliding interface this means that one body has left the other's "
                     "interface: shorten the run or lengthen the body"
                   : ""));
    }
  }

  void build_mappers_on_current_positions() {
    const Interface& inner_in = inner_->input_interface();
    const Interface& inner_out = inner_->output_interface();
    for (auto& pair : input_pairs_) {
      pair.mapper->initialize(coordinates(pair.outer, input_, output_, false),
                              coordinates(pair.inner, inner_in, inner_out, true, &pair));
      if (report_) report("input", pair.outer, pair.inner, *pair.mapper);
    }
    for (auto& pair : output_pairs_) {
      pair.mapper->initialize(coordinates(pair.inner, inner_out, inner_in, true),
                              coordinates(pair.outer, output_, input_, false));
      if (report_) report("output", pair.inner, pair.outer, *pair.mapper);
    }
    for (auto& pair : input_pairs_)
      for (auto& [variable, round_trip] : pair.round_trips) {
        const auto block = input_.block(pair.outer, variable);
        round_trip.build(*pair.mapper, pair.back_rows, *output_pairs_[pair.back].mapper,
                         block.points, block.components);
      }
  }

  void record_round_trips() {
    for (const auto& pair : input_pairs_)
      for (const auto& [variable, round_trip] : pair.round_trips) {
        plain_round_trip_ = std::max(plain_round_trip_, round_trip.plain_defect());
        exact_round_trip_ = std::max(exact_round_trip_, round_trip.defect());
      }
  }

  /// The mapping quality report: distance from each target to its source stencil.
  void report(const char* which, const std::string& from, const std::string& to,
              const Mapper& mapper) const {
    const MappingQuality& q = mapper.quality();
    fmt::print(
        "  mapping        : {} {} mapper, {} -> {}: distance to the stencil min {:.3g}, mean "
        "{:.3g}, max {:.3g}; {} fallbacks, {} unmatched\n",
        name_, which, from, to, q.min_distance, q.mean_distance, q.max_distance, q.fallbacks,
        q.unmatched);
  }

  void map_output(const Interface& inner_output) {
    for (const auto& pair : output_pairs_)
      for (const auto& variable : variables_of(output_, pair.outer)) {
        RowMatrix values = inner_output.values(pair.inner, variable);
        if (variable == "displacement" && values.cols() == 3)
          values.rowwise() += frame_motion();  // the other solver sees the frame's motion
        output_.values(pair.outer, variable) = pair.mapper->map(values, variable);
      }
  }

  std::unique_ptr<SolverWrapper> inner_;
  std::string name_;
  std::vector<Settings> input_settings_;
  std::string input_where_;
  Settings output_settings_;
  std::string rebuild_;
  bool current_;
  bool report_;
  std::vector<std::string> exact_variables_;
  std::string exact_where_;
  std::vector<std::string> own_parts_;  ///< `model_parts`: empty for all
  std::string own_parts_where_;
  double time_;  ///< of the time step being solved
  Eigen::RowVector3d frame_origin_ = Eigen::RowVector3d::Zero();
  Eigen::RowVector3d frame_velocity_ = Eigen::RowVector3d::Zero();
  double plain_round_trip_ = 0.0, exact_round_trip_ = 0.0;  ///< largest misses (run)
  double build_seconds_ = 0.0, map_seconds_ = 0.0;          ///< for the line at the end of the run
  int builds_ = 0, solves_ = 0;
  Interface input_, output_;
  std::vector<InputPair> input_pairs_;
  std::vector<OutputPair> output_pairs_;
};

}  // namespace

COCOPP_REGISTER(SolverWrapperRegistry, "mapped", MappedSolverWrapper)

}  // namespace cocopp
