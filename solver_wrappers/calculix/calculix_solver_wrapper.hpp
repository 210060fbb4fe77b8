#pragma once
// CalculixSolverWrapper (case-file type `calculix`): a CalculiX (ccx) structural model behind
// the coupler. The user gives a normal ccx input deck with one step and names the interface:
// an element-face surface (loads) and a node set (displacements).
//
// How ccx solves each coupling iteration from the step's start is the mode's (ccx_mode.hpp):
// `per_iteration` runs ccx once per iteration (per_iteration_ccx.hpp), `persistent` keeps one
// cocopp-ccx for the run (persistent_ccx.hpp), `auto` (the default) is persistent where
// cocopp-ccx is built and the deck and keys allow it. The wrapper keeps the rest: the case's
// keys, the deck, the interfaces and the loads on the faces as they move (CalculixModel).
//
// `interface_drive: displacement` drives the nodes the other solver covers by its wall
// position and returns the position that balances the forces (displacement_drive.hpp).
//
// Runs in the coupler process (no protocol): ccx is started through ChildProcess, like every
// solver process, with the same timeout, log and clean-up rules.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "solver_wrappers/calculix/ccx_mode.hpp"
#include "solver_wrappers/calculix/displacement_drive.hpp"
#include "solver_wrappers/calculix/per_iteration_ccx.hpp"
#include "solver_wrappers/calculix/persistent_ccx.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {

class CalculixSolverWrapper : public SolverWrapper {
 public:
  /// How ccx's state goes back to the step's start for each coupling iteration: from restart
  /// files or by replay (mode per_iteration), in memory (mode persistent).
  enum class StateReset { kRestart, kReplay, kInMemory };
  using Timing = calculix::CcxTiming;

  CalculixSolverWrapper(const Settings& settings, const RunSettings& run);
  ~CalculixSolverWrapper() override;

  const std::string& name() const override { return model_.name; }
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

  const Timing& last_timing() const;
  const std::filesystem::path& working_directory() const { return model_.working_directory; }
  /// After initialize().
  StateReset state_reset() const;
  bool persistent() const { return persistent_; }

 private:
  void read_mode(const Settings& settings);
  bool has_coupled_executable() const;
  void choose_auto_mode();
  void read_deck();
  void build_interfaces();
  std::unique_ptr<calculix::CcxMode> create_mode();

  calculix::CalculixModel model_;
  bool name_given_ = false;      ///< `name` is in the case
  bool log_file_given_ = false;  ///< `log_file` is in the case
  std::string working_directory_where_, input_file_where_;
  calculix::PerIterationCcx::Options per_iteration_;
  // interface_drive: displacement
  bool displacement_drive_ = false;
  int driven_dof_ = 1;
  std::string driven_node_set_name_;  ///< the nodes that may be driven (default: the interface's)
  double surface_stiffness_ = 0.0;
  std::string surface_compliance_file_;  ///< empty: the drive's stiffness per line
  double surface_compliance_scale_ = 1.0;
  bool reynolds_film_ = false;    ///< film_stiffness: reynolds
  std::string probed_film_file_;  ///< film_stiffness: probed: film_probe, the film's probe file
  std::string drive_log_;         ///< drive_log: the drive's lines per iteration (empty: none)
  std::vector<std::int64_t> driven_node_set_;
  std::unique_ptr<calculix::DisplacementDrive> drive_;
  // mode
  bool persistent_ = false;  ///< mode: persistent (or auto, chosen so)
  bool auto_mode_ = false;   ///< mode: auto
  std::string coupled_executable_;
  std::string mode_where_;

  std::unique_ptr<calculix::CcxMode> mode_;
  calculix::PerIterationCcx* per_iteration_mode_ = nullptr;  ///< mode_, when it is one
  Interface input_interface_;
  Interface output_interface_;
};

}  // namespace cocopp
