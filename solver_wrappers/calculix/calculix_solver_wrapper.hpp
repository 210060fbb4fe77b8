#pragma once
// CalculixSolverWrapper (case-file type `calculix`): a CalculiX (ccx) structural model behind
// the coupler. The user gives a normal ccx input deck with one step and names the interface:
// an element-face surface (loads) and a node set (displacements). Every coupling iteration
// writes the loads, runs ccx (a new process per iteration; ccx has no way to take new loads
// while it runs) and reads the interface displacements from the .dat file.
//
// State reset (docs/solver-wrappers-calculix.md): every coupling iteration of time step n+1
// starts from the converged state of step n, so plastic strain, hardening and geometry of
// unconverged iterations never leak into the result. Two ways, chosen by `state_reset`:
// - restart: each iteration reads the restart file of step n's converged iteration and runs
//   one step; finalize_step() keeps the last iteration's restart as the new base. Exact for
//   every material and for axisymmetric (CAX) models with the ccx that
//   scripts/install-calculix.sh builds (the default executable); Debian's ccx 2.20 drops the
//   material state variables (equivalent plastic strain, back stress) on *RESTART, READ, so
//   with it this is exact only without them, and it crashes restarting a CAX model.
// - replay: each iteration runs all committed steps again with their converged loads, then the
//   new step: a continuous ccx run by construction, exact with any ccx; the ccx time of an
//   iteration grows with the step number.
// `auto` (the default) restarts, except where the ccx's `-v` does not report the patch that a
// history-dependent deck (*PLASTIC, *CREEP, *CYCLIC HARDENING, *USER MATERIAL, *DEPVAR) or an
// axisymmetric one needs: then it replays.
//
// `mode: persistent` runs one cocopp-ccx process for the whole run instead, which resets in
// memory (persistent_ccx.hpp).
//
// `interface_drive: displacement` drives the nodes the other solver covers by its wall
// position and returns the position that balances the forces (displacement_drive.hpp).
//
// Runs in the coupler process (no protocol): ccx is started through ChildProcess, like every
// solver process, with the same timeout, log and clean-up rules.
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver_wrappers/calculix/displacement_drive.hpp"
#include "solver_wrappers/calculix/input_deck.hpp"
#include "solver_wrappers/calculix/interface_loads.hpp"
#include "solver_wrappers/calculix/persistent_ccx.hpp"
#include "solver_wrappers/solver_error.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {

class CalculixSolverWrapper : public SolverWrapper {
 public:
  /// Names of the files the wrapper writes in the working directory.
  static constexpr const char* kJob = "cocopp_iteration";  ///< ccx job of each iteration
  static constexpr const char* kModelFile = "cocopp_model.inp";
  static constexpr const char* kLoadsFile = "cocopp_loads.inp";
  static constexpr const char* kConvergedRestart = "cocopp_converged.rout";

  enum class StateReset { kRestart, kReplay };

  /// Time spent per coupling iteration, for the overhead benchmark.
  struct Timing {
    /// ccx's run (process start to exit); persistent: cocopp-ccx's solve with the round trip
    double ccx_seconds = 0.0;
    /// writing loads and deck, copying restart, reading .dat; persistent: the nodal forces
    double wrapper_seconds = 0.0;
  };

  CalculixSolverWrapper(const Settings& settings, const RunSettings& run);
  ~CalculixSolverWrapper() override;

  const std::string& name() const override { return name_; }
  void set_default_name(const std::string& name) override;
  std::string describe() const override;
  void check() const override;

  void initialize() override;
  const Interface& input_interface() const override { return input_interface_; }
  const Interface& output_interface() const override { return output_interface_; }
  void initialize_step(int step, double time) override;
  const Interface& solve(const Interface& input) override;
  /// ccx solves every coupling iteration again from the step's start, so its Newton count
  /// says nothing about the coupling: the wrapper refuses, saying so.
  void start_reporting_convergence() override;
  void finalize_step() override;
  void output_step() override;
  void save_restart(int step) override;
  void finalize() override;

  const Timing& last_timing() const { return last_timing_; }
  const std::filesystem::path& working_directory() const { return working_directory_; }
  StateReset state_reset() const { return state_reset_; }
  bool persistent() const { return persistent_; }

 private:
  void read_mode(const Settings& settings);
  bool has_coupled_executable() const;
  void choose_auto_mode();
  void read_deck();
  void choose_state_reset();
  void check_dynamic_elements() const;
  void build_interfaces();
  void write_iteration_deck() const;
  void write_step(std::ofstream& out, const std::string& loads_file, bool print) const;
  /// Whether the case's input_variables hold `variable` ("pressure", "traction").
  bool takes(const char* variable) const;
  struct FaceLoads {
    Eigen::VectorXd pressure;  ///< per face; empty if pressure is no input
    RowMatrix traction;        ///< per face; empty if traction is no input
  };
  /// The loads of `input` on the faces; a NaN or infinity stops the run, naming the position.
  FaceLoads face_loads(const Interface& input) const;
  void write_loads(const Interface& input) const;
  void run_ccx();
  void start_persistent();
  void replay_committed_steps(int step);
  void replay(const std::vector<double>& times, const std::vector<Eigen::VectorXd>& inputs);
  void restart_persistent();
  double persistent_end_time() const;
  SolverRejectedInput not_converged(const std::string& exit, const std::string& deck,
                                    const std::string& log_tail) const;
  RowMatrix solve_persistent(const Interface& input);
  void move_faces_to_converged_state();
  /// A restarted run: the state save_restart(step) kept.
  void restore(int step);
  std::filesystem::path saved_restart(int step) const;
  [[noreturn]] void fail(const std::string& message) const;
  std::string position() const;
  std::filesystem::path file(const std::string& name) const { return working_directory_ / name; }

  // From the case file.
  std::string name_;
  bool name_given_ = false;      ///< `name` is in the case
  bool log_file_given_ = false;  ///< `log_file` is in the case
  std::filesystem::path working_directory_;
  std::string input_file_;
  std::string surface_name_;
  std::string node_set_name_;
  std::string executable_;
  std::vector<std::string> input_variables_;
  int threads_ = 1;
  double timeout_ = 600.0;
  bool save_results_ = true;
  bool allow_reduced_integration_ = false;
  std::filesystem::path log_file_;
  std::string state_reset_key_;
  bool displacement_drive_ = false;  ///< interface_drive: displacement
  int driven_dof_ = 1;
  std::string driven_node_set_name_;  ///< the nodes that may be driven (default: the interface's)
  std::vector<std::int64_t> driven_node_set_;
  double surface_stiffness_ = 0.0;
  std::string working_directory_where_, input_file_where_, executable_where_, state_reset_where_,
      initial_increment_where_;
  bool persistent_ = false;  ///< mode: persistent (or auto, chosen so)
  bool auto_mode_ = false;   ///< mode: auto
  std::string coupled_executable_;
  std::string mode_where_;
  RunSettings run_;

  // From the deck.
  std::unique_ptr<calculix::InputDeck> deck_;
  std::unique_ptr<calculix::InterfaceLoads> loads_;
  std::unique_ptr<calculix::DisplacementDrive> drive_;
  std::vector<std::int64_t> interface_nodes_;
  std::filesystem::path ccx_path_;
  StateReset state_reset_ = StateReset::kRestart;
  std::unique_ptr<calculix::PersistentCcx> persistent_ccx_;
  /// Persistent: every committed step's time and input, for a restart's replay.
  std::vector<double> committed_times_;
  std::vector<Eigen::VectorXd> committed_inputs_;
  Eigen::VectorXd last_input_;
  double step_time_ = 0.0;

  // While running.
  int step_ = 0;
  int iteration_ = 0;
  bool has_converged_restart_ = false;        ///< restart: a committed step exists to restart from
  std::vector<std::string> committed_loads_;  ///< replay: each committed step's loads file
  /// initial_increment: previous_iteration: the first increment that converged in this time
  /// step's last ccx run, which the next coupling iteration starts with.
  bool carry_initial_increment_ = false;
  std::optional<double> carried_increment_;
  Interface input_interface_;
  Interface output_interface_;
  Timing last_timing_;
};

}  // namespace cocopp
