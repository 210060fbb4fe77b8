#pragma once
// PerIterationCcx: the calculix wrapper's `mode: per_iteration`. Every coupling iteration writes
// the loads, runs ccx (a new process per iteration; ccx has no way to take new loads while it
// runs) and reads the interface displacements from the .dat file.
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
// `interface_drive: displacement` drives the nodes the other solver covers by its wall position
// and returns the position that balances the forces (displacement_drive.hpp): this mode only.
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "solver_wrappers/calculix/ccx_mode.hpp"
#include "solver_wrappers/calculix/ccx_run.hpp"
#include "solver_wrappers/calculix/displacement_drive.hpp"

namespace cocopp::calculix {

class PerIterationCcx : public CcxMode {
 public:
  /// Names of the files it writes in the working directory.
  static constexpr const char* kJob = "cocopp_iteration";  ///< ccx job of each iteration
  static constexpr const char* kLoadsFile = "cocopp_loads.inp";
  static constexpr const char* kConvergedRestart = "cocopp_converged.rout";
  /// warm_start: the last iteration's converged increments, and the running one's.
  static constexpr const char* kGuess = "cocopp_guess.bin";
  static constexpr const char* kNextGuess = "cocopp_guess_next.bin";

  enum class StateReset { kRestart, kReplay };

  /// Its keys of the case file (read by the wrapper with the others).
  struct Options {
    std::string executable;
    std::string executable_where;
    std::string state_reset;  ///< auto, restart or replay
    std::string state_reset_where;
    /// initial_increment: previous_iteration: the first increment that converged in this
    /// time step's last ccx run is the next coupling iteration's first.
    bool carry_initial_increment = false;
    std::string initial_increment_where;
    /// warm_start: true: each coupling iteration's Newton iterations start from the previous
    /// iteration's solution of the same time step (scripts/calculix/07-warm-start.patch).
    bool warm_start = false;
    std::string warm_start_where;
    bool allow_reduced_integration = false;
    bool save_results = true;
  };

  /// interface_drive: displacement (else `drive` is null): the drive and the nodes it may
  /// drive.
  struct Drive {
    DisplacementDrive* drive = nullptr;
    std::string node_set_name;
    std::vector<std::int64_t> nodes;  ///< sorted
  };

  /// Checks the deck for what one ccx run per time step needs: throws DeckError naming the
  /// deck's line, or CaseError naming the key.
  PerIterationCcx(CalculixModel& model, Options options, Drive drive);

  void start(const Interface& input, Interface& output) override;
  void initialize_step(int step, double time) override;
  void solve(const Interface& input, Interface& output) override;
  void finalize_step() override;
  void output_step() override;
  void save_restart(int step, const Interface& output) override;

  StateReset state_reset() const { return state_reset_; }

 private:
  void check_deck() const;
  void check_dynamic_elements() const;
  void choose_state_reset();
  void check_warm_start() const;
  const CcxRestartSupport& ccx_support() const;
  void write_loads(const Interface& input) const;
  void write_iteration_deck() const;
  void write_step(std::ofstream& out, const std::string& loads_file, bool print) const;
  void run_ccx();
  void read_output(Interface& output);
  /// A restarted run: the state save_restart(step) kept.
  void restore(int step, Interface& output);
  void commit_surface_displacement();
  std::filesystem::path saved_restart(int step) const;

  CalculixModel& model_;
  Options options_;
  Drive drive_;
  std::filesystem::path ccx_path_;
  StateReset state_reset_ = StateReset::kRestart;
  mutable std::optional<CcxRestartSupport> ccx_support_;  ///< what `ccx -v` reports
  bool has_converged_restart_ = false;        ///< restart: a committed step to restart from
  std::vector<std::string> committed_loads_;  ///< replay: each committed step's loads file
  std::optional<double> carried_increment_;
  /// interface_drive: displacement: every drivable node's displacement (global, rows as
  /// drive_.nodes) at the last iteration, and as a map at the last converged step: where the
  /// next iteration's faces start (DisplacementDrive::plan).
  RowMatrix surface_displacement_;
  NodeDisplacements converged_surface_;
};

}  // namespace cocopp::calculix
