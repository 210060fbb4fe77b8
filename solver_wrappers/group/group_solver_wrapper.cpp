// `group`: several solvers on one side of the coupling, side by side, each owning the part of
// the interface it covers: a tube wall split along its axis into two processes, a fluid with
// two independent bodies in it. To the coupler the group is one solver wrapper.
//
//   - type: group
//     name: wall
//     solver_wrappers:        # each a wrapper that adopts the other side's interface (mapped)
//       - {type: mapped, name: wall_a, frame_origin: [0, 0, -0.0125], ...}
//       - {type: mapped, name: wall_b, frame_origin: [0, 0, 0.0125], ...}
//
// Interfaces. Every member maps the whole input of the other side onto its own mesh (a
// consistent input mapping; a conservative one needs the member's `max_distance` so that it
// takes no load from outside itself). Each point of the other side's input is given by the
// member that covers it: the one whose output mapper's stencil is nearest (0 inside its
// mesh). A point that no member covers (every member's mapper unmatched there), or that two
// cover equally from outside, is a case error that names it. A member then maps its output
// onto its own points only, and the group puts the members' parts together. Who owns a point
// is decided once, when the interfaces are fitted: on a sliding interface the members keep
// their points.
//
// Solving. The members solve side by side, one on the calling thread and each other on its
// own long-lived WorkerThread, so that the group's time is the slowest member's. Each keeps
// its own process, log, restart and timeout; an error names the member. Every request reaches
// every member even when one fails, so that all stop in the same state.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <set>
#include <vector>

#include "solver_wrappers/solver_wrapper.hpp"
#include "solver_wrappers/worker_thread.hpp"

namespace cocopp {
namespace {

class GroupSolverWrapper : public SolverWrapper {
 public:
  GroupSolverWrapper(const Settings& settings, const RunSettings& run)
      : name_(settings.get_name("name", "group")) {
    const auto entries = settings.list("solver_wrappers");
    if (entries.size() < 2)
      settings.fail("solver_wrappers",
                    fmt::format("a group needs at least two solver wrappers, got {}: a single "
                                "solver takes the group's place directly",
                                entries.size()));
    std::set<std::string> names;
    for (const auto& entry : entries) {
      members_.push_back(SolverWrapperRegistry::instance().create(entry, run));
      const SolverWrapper& member = *members_.back();
      if (!member.adopts_interfaces())
        entry.fail("type", fmt::format("member '{}' of group '{}' keeps its own interface: a "
                                       "member maps the other side's interface onto its own "
                                       "mesh, so make it a `mapped` wrapper around the solver",
                                       member.name(), name_));
      if (!names.insert(member.name()).second || member.name() == name_)
        entry.fail("name", fmt::format("group '{}' has two members (or itself) called '{}': give "
                                       "each member its own name, which its log and restart "
                                       "files carry",
                                       name_, member.name()));
    }
    for (std::size_t k = 1; k < members_.size(); ++k)
      if (members_[k]->substeps() != members_[0]->substeps())
        entries[k].fail("solver_wrapper",
                        fmt::format("member '{}' of group '{}' takes {} substeps a time step, '{}' "
                                    "{}: the members of a "
                                    "group share the window's substeps",
                                    members_[k]->name(), name_, members_[k]->substeps(),
                                    members_[0]->name(), members_[0]->substeps()));
    for (std::size_t i = 1; i < members_.size(); ++i)
      workers_.push_back(std::make_unique<WorkerThread>());
    solve_seconds_.assign(members_.size(), 0.0);
  }

  const std::string& name() const override { return name_; }
  std::string describe() const override {
    std::vector<std::string> parts;
    for (const auto& member : members_) parts.push_back(member->describe());
    // One member a line, under the run header's "solver 2       : ".
    return fmt::format("{}: a group of {} side by side:\n                   {}", name_,
                       members_.size(), fmt::join(parts, "\n                   "));
  }
  std::string started() const override {
    std::vector<std::string> parts;
    for (const auto& member : members_) parts.push_back(member->started());
    return fmt::format("{}", fmt::join(parts, ", "));
  }
  void check() const override {
    for (const auto& member : members_) member->check();
  }
  void check_solver_input() const override {
    for (const auto& member : members_) member->check_solver_input();
  }

  // Started from the calling thread, which lives for the whole run: a child process dies with
  // the thread that started it (WorkerThread).
  void start() override {
    for_each([](SolverWrapper& m) { m.start(); });
  }
  void initialize() override {
    for_each([](SolverWrapper& m) { m.initialize(); });
  }
  void overlap_step_requests() override {
    for_each([](SolverWrapper& m) { m.overlap_step_requests(); });
  }
  void complete_step_requests() override {
    for_each([](SolverWrapper& m) { m.complete_step_requests(); });
  }

  bool adopts_interfaces() const override { return true; }

  void adopt_interfaces(const Interface& input, const Interface& output) override {
    input_ = input;
    output_ = output;
    for (auto& member : members_) member->adopt_interfaces(input_, output_);
    assign_points();
    member_inputs_.clear();
    for (std::size_t k = 0; k < members_.size(); ++k) {
      members_[k]->adopt_interfaces(input_, owned_output(k));
      member_inputs_.push_back(members_[k]->input_interface());
    }
    gather_output();
  }

  const Interface& input_interface() const override { return input_; }
  const Interface& output_interface() const override { return output_; }
  Eigen::VectorXd output_distances(const std::string& part) const override {
    Eigen::VectorXd distances;
    const auto& parts = output_.parts();
    if (std::none_of(parts.begin(), parts.end(),
                     [&](const Interface::Part& p) { return p.model_part->name == part; }))
      return distances;
    for (std::size_t k = 0; k < members_.size(); ++k) {
      const Eigen::VectorXd own = members_[k]->output_distances(part);
      const std::vector<Eigen::Index>& rows = owned_rows_[k].at(part_index(part));
      if (distances.size() == 0)
        distances = Eigen::VectorXd::Constant(output_block_points(part),
                                              std::numeric_limits<double>::infinity());
      for (std::size_t i = 0; i < rows.size(); ++i)
        distances(rows[i]) = own(static_cast<Eigen::Index>(i));
    }
    return distances;
  }

  void initialize_step(int step, double time) override {
    for_each([&](SolverWrapper& m) { m.initialize_step(step, time); });
  }

  const Interface& solve(const Interface& input) override {
    input_.set_data(input.data());
    for (std::size_t k = 0; k < members_.size(); ++k) copy_blocks(input_, member_inputs_[k]);
    side_by_side([&](std::size_t k) {
      const auto start = std::chrono::steady_clock::now();
      members_[k]->solve(member_inputs_[k]);
      solve_seconds_[k] +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    });
    gather_output();
    ++solves_;
    return output_;
  }

  int substeps() const override { return members_.front()->substeps(); }

  /// As solve(), for each substep's column: each member its own part of every input column,
  /// its own points of every output column.
  Eigen::MatrixXd solve_substeps(const Eigen::MatrixXd& inputs) override {
    if (substeps() == 1) return SolverWrapper::solve_substeps(inputs);
    std::vector<Eigen::MatrixXd> member_inputs(members_.size()), member_outputs(members_.size());
    for (std::size_t k = 0; k < members_.size(); ++k) {
      member_inputs[k].resize(member_inputs_[k].size(), inputs.cols());
      for (Eigen::Index j = 0; j < inputs.cols(); ++j) {
        input_.set_data(inputs.col(j));
        copy_blocks(input_, member_inputs_[k]);
        member_inputs[k].col(j) = member_inputs_[k].data();
      }
    }
    side_by_side([&](std::size_t k) {
      const auto start = std::chrono::steady_clock::now();
      member_outputs[k] = members_[k]->solve_substeps(member_inputs[k]);
      solve_seconds_[k] +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    });
    Eigen::MatrixXd outputs(output_.size(), inputs.cols());
    for (Eigen::Index j = 0; j < inputs.cols(); ++j) {
      for (std::size_t k = 0; k < members_.size(); ++k) {
        Interface own = members_[k]->output_interface();
        own.set_data(member_outputs[k].col(j));
        gather_from(k, own);
      }
      outputs.col(j) = output_.data();
    }
    ++solves_;
    return outputs;
  }

  void start_reporting_convergence() override {
    for_each([](SolverWrapper& m) { m.start_reporting_convergence(); });
  }
  bool converged_at_first_iteration() const override {
    for (const auto& member : members_)
      if (!member->converged_at_first_iteration()) return false;
    return true;
  }
  void finalize_step() override {
    for_each([](SolverWrapper& m) { m.finalize_step(); });
  }
  void output_step() override {
    for_each([](SolverWrapper& m) { m.output_step(); });
  }
  void save_restart(int step) override {
    for_each([&](SolverWrapper& m) { m.save_restart(step); });
  }

  void finalize() override {
    for_each([](SolverWrapper& m) { m.finalize(); });
    if (solves_ == 0) return;
    std::vector<std::string> times;
    for (std::size_t k = 0; k < members_.size(); ++k)
      times.push_back(
          fmt::format("{} {:.3g} ms", members_[k]->name(), 1e3 * solve_seconds_[k] / solves_));
    fmt::print("  group          : {}: per coupling iteration, side by side: {}\n", name_,
               fmt::join(times, ", "));
  }

 private:
  /// `task(member)` for every member in order, all of them even when one throws; then the
  /// first error is rethrown.
  void for_each(const std::function<void(SolverWrapper&)>& task) {
    std::exception_ptr first;
    for (auto& member : members_) {
      try {
        task(*member);
      } catch (...) {
        if (!first) first = std::current_exception();
      }
    }
    if (first) std::rethrow_exception(first);
  }

  /// `task(k)` for every member k at once: member 0 on this thread, the others on theirs.
  /// Waits for all; the first error (in member order) is rethrown, as thrown (a rejected
  /// input stays one, so that the coupled solver can step back).
  void side_by_side(const std::function<void(std::size_t)>& task) {
    for (std::size_t k = 1; k < members_.size(); ++k)
      workers_[k - 1]->post([&task, k] { task(k); });
    std::vector<std::exception_ptr> errors(members_.size());
    try {
      task(0);
    } catch (...) {
      errors[0] = std::current_exception();
    }
    for (std::size_t k = 1; k < members_.size(); ++k) {
      try {
        workers_[k - 1]->wait();
      } catch (...) {
        errors[k] = std::current_exception();
      }
    }
    for (const auto& error : errors)
      if (error) std::rethrow_exception(error);
  }

  std::size_t part_index(const std::string& part) const {
    const auto& parts = output_.parts();
    for (std::size_t j = 0; j < parts.size(); ++j)
      if (parts[j].model_part->name == part) return j;
    throw std::out_of_range(fmt::format("group '{}': no output model part '{}'", name_, part));
  }

  Eigen::Index output_block_points(const std::string& part) const {
    return static_cast<Eigen::Index>(output_.parts()[part_index(part)].model_part->size());
  }

  /// Each point of every output model part to the member that covers it best.
  void assign_points() {
    const auto& parts = output_.parts();
    owned_rows_.assign(members_.size(), std::vector<std::vector<Eigen::Index>>(parts.size()));
    for (std::size_t j = 0; j < parts.size(); ++j) {
      const ModelPart& part = *parts[j].model_part;
      std::vector<Eigen::VectorXd> distances;
      for (const auto& member : members_) {
        Eigen::VectorXd own = member->output_distances(part.name);
        if (own.size() == 0)  // a part the member does not map (`model_parts`)
          own = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(part.size()),
                                          std::numeric_limits<double>::infinity());
        distances.push_back(std::move(own));
      }
      for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(part.size()); ++i)
        owned_rows_[owner_of(part, i, distances)][j].push_back(i);
    }
    for (std::size_t k = 0; k < members_.size(); ++k)
      for (std::size_t j = 0; j < parts.size(); ++j)
        if (owned_rows_[k][j].empty() && maps_part(k, parts[j].model_part->name))
          throw std::runtime_error(fmt::format(
              "group '{}': member '{}' covers no point of model part '{}' better than another "
              "member: check where its mesh lies (its mapped wrapper's frame_origin, the "
              "transformers), or leave the part to the others (the member's model_parts)",
              name_, members_[k]->name(), parts[j].model_part->name));
  }

  std::size_t owner_of(const ModelPart& part, Eigen::Index i,
                       const std::vector<Eigen::VectorXd>& distances) const {
    std::size_t best = 0;
    for (std::size_t k = 1; k < members_.size(); ++k)
      if (distances[k](i) < distances[best](i)) best = k;
    const double nearest = distances[best](i);
    const auto point = part.coordinates.row(i);
    if (!std::isfinite(nearest))
      throw std::runtime_error(fmt::format(
          "group '{}': point {} ({:g}, {:g}, {:g}) of model part '{}' lies outside every "
          "member (each member's output mapper leaves it unmatched, or does not map the part: "
          "model_parts): every point of the other "
          "side's interface needs a member that covers it",
          name_, part.ids[static_cast<std::size_t>(i)], point(0), point(1), point(2), part.name));
    // Inside a member (distance 0) it is that member's; from outside, a tie is ambiguous.
    const double scale =
        1e-9 *
        (part.coordinates.colwise().maxCoeff() - part.coordinates.colwise().minCoeff()).norm();
    for (std::size_t k = 0; k < members_.size(); ++k)
      if (k != best && distances[k](i) - nearest <= scale)
        throw std::runtime_error(fmt::format(
            "group '{}': point {} ({:g}, {:g}, {:g}) of model part '{}' is covered equally by "
            "members '{}' and '{}' (distance {:g}): the members' meshes overlap there or leave "
            "it between them; let one member's mesh reach it",
            name_, part.ids[static_cast<std::size_t>(i)], point(0), point(1), point(2), part.name,
            members_[best]->name(), members_[k]->name(), nearest));
    return best;
  }

  /// Whether member k maps model part `part` (its `model_parts`), as it adopted the output.
  bool maps_part(std::size_t k, const std::string& part) const {
    for (const auto& block : members_[k]->output_interface().blocks())
      if (block.model_part == part) return true;
    return false;
  }

  static void copy_blocks(const Interface& from, Interface& to) {
    for (const auto& block : to.blocks())
      to.values(block.model_part, block.variable) = from.values(block.model_part, block.variable);
  }

  /// The output interface restricted to the points member k owns (ids and coordinates kept),
  /// on the model parts it maps.
  Interface owned_output(std::size_t k) const {
    std::vector<Interface::Part> parts;
    const auto& all = output_.parts();
    for (std::size_t j = 0; j < all.size(); ++j) {
      if (!maps_part(k, all[j].model_part->name)) continue;
      const ModelPart& whole = *all[j].model_part;
      const auto& rows = owned_rows_[k][j];
      auto part = std::make_shared<ModelPart>();
      part->name = whole.name;
      part->coordinates.resize(static_cast<Eigen::Index>(rows.size()), 3);
      for (std::size_t r = 0; r < rows.size(); ++r) {
        part->ids.push_back(whole.ids[static_cast<std::size_t>(rows[r])]);
        part->coordinates.row(static_cast<Eigen::Index>(r)) = whole.coordinates.row(rows[r]);
      }
      parts.push_back({part, all[j].variables});
    }
    return Interface(std::move(parts));
  }

  /// The members' outputs, each on its own points, into the group's output.
  void gather_output() {
    for (std::size_t k = 0; k < members_.size(); ++k)
      gather_from(k, members_[k]->output_interface());
  }

  /// Member k's output `own` (laid out as its output interface) into the group's output.
  void gather_from(std::size_t k, const Interface& own) {
    for (const auto& block : output_.blocks()) {
      if (!maps_part(k, block.model_part)) continue;
      const auto& rows = owned_rows_[k][part_index(block.model_part)];
      const auto from = own.values(block.model_part, block.variable);
      auto to = output_.values(block.model_part, block.variable);
      for (std::size_t r = 0; r < rows.size(); ++r)
        to.row(rows[r]) = from.row(static_cast<Eigen::Index>(r));
    }
  }

  std::string name_;
  std::vector<std::unique_ptr<SolverWrapper>> members_;
  std::vector<std::unique_ptr<WorkerThread>> workers_;  ///< for members 1..n-1
  /// Per member, per output model part: the rows of the group's output that it gives.
  std::vector<std::vector<std::vector<Eigen::Index>>> owned_rows_;
  Interface input_, output_;
  /// Each member's input: the group's, on the model parts the member maps.
  std::vector<Interface> member_inputs_;
  std::vector<double> solve_seconds_;
  int solves_ = 0;
};

}  // namespace

COCOPP_REGISTER(SolverWrapperRegistry, "group", GroupSolverWrapper)

}  // namespace cocopp
