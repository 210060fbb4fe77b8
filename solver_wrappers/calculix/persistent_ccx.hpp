#pragma once
// PersistentCcx: the calculix wrapper's `mode: persistent`. One cocopp-ccx process
// (solvers/calculix/coupled_ccx.cpp, ccx with patch 05) runs for the whole simulation: the
// deck's step becomes one ccx step as long as the run, which the coupler's time steps advance
// increment by increment, and every coupling iteration is solved from an in-memory checkpoint
// of the step's start. So ccx's dynamic integrator carries its state from step to step (no
// restart of *DYNAMIC every time step), and no process start, deck parsing or restart file
// costs time per coupling iteration.
//
// It writes the long step's deck (`cocopp_persistent.inp`: the model definition, the deck's
// step with its time period set to the run's and a zero placeholder *DLOAD and *CLOAD for every
// interface load, which cocopp-ccx overwrites) and the interface file
// (core/data/calculix_interface_file.hpp), and talks to cocopp-ccx over the solver protocol
// through a ProcessSolverWrapper (its timeouts, crash reports and clean-up). The wrapper's
// shared part turns the interface loads into a pressure per face and nodal forces.
//
// A restarted run, and a cocopp-ccx that gave up a step, solve the committed steps again with
// their converged inputs: one coupling iteration each, so the same increments and the same
// state.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/data/calculix_interface_file.hpp"
#include "solver_wrappers/calculix/ccx_mode.hpp"

namespace cocopp {
class ProcessSolverWrapper;
}

namespace cocopp::calculix {

class PersistentCcx : public CcxMode {
 public:
  static constexpr const char* kJob = "cocopp_persistent";

  /// Its keys of the case file (read by the wrapper with the others).
  struct Options {
    std::filesystem::path executable;  ///< cocopp-ccx
    std::string mode_where;            ///< where the case chose the mode, for messages
  };

  /// Throws CaseError (at options.mode_where) for a deck it cannot run (unsupported()).
  PersistentCcx(CalculixModel& model, Options options);
  ~PersistentCcx() override;

  /// Why the deck cannot run persistent (empty if it can): a procedure other than *STATIC or
  /// *DYNAMIC, contact (its state is not in the checkpoint).
  static std::string unsupported(const InputDeck& deck);

  void start(const Interface& input, Interface& output) override;
  void initialize_step(int step, double time) override;
  void solve(const Interface& input, Interface& output) override;
  void finalize_step() override;
  void save_restart(int step, const Interface& output) override;
  void finalize() override;

 private:
  /// Write the deck and the interface file for a run that ends at `end_time`, start cocopp-ccx.
  void start_process();
  void write_deck(double end_time) const;
  InterfaceFile interface_file() const;
  std::vector<DeckLine> long_step(double end_time) const;
  /// The long step ends with the run; a run of unknown length gets a step of 1000 time steps.
  double end_time() const;
  /// A coupler time step over the deck step's time period: the deck's increments scale by it.
  double time_scale() const;
  /// The first increment of every coupler time step (the deck's, scaled).
  double initial_increment() const;
  /// One coupling iteration in cocopp-ccx: the output nodes' displacements (global); its time
  /// in cocopp-ccx (the solve and the round trip) in process_seconds_.
  RowMatrix solve_in_process(const Interface& input);
  /// A restarted run: the committed steps of the restart data again, checked against its
  /// displacement.
  void replay_committed_steps(int step, Interface& output);
  void replay(const std::vector<double>& times, const std::vector<Eigen::VectorXd>& inputs,
              Interface& output);
  /// A cocopp-ccx that gave up a step ends: a new one takes the committed steps again, ready
  /// for the same step with another input.
  void restart_process(Interface& output);

  CalculixModel& model_;
  Options options_;
  std::vector<std::int64_t> force_nodes_;  ///< every node of the interface faces, sorted
  std::unique_ptr<ProcessSolverWrapper> process_;
  Interface input_layout_;  ///< the input interface, for the replays
  double step_time_ = 0.0;
  double process_seconds_ = 0.0;
  Eigen::VectorXd last_input_;
  /// Every committed step's time and input, for a restart's replay.
  std::vector<double> committed_times_;
  std::vector<Eigen::VectorXd> committed_inputs_;
};

}  // namespace cocopp::calculix
