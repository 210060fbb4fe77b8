#pragma once
// How the calculix wrapper has ccx solve a coupling iteration from its time step's start, one
// class per mode behind CcxMode:
// - PerIterationCcx (per_iteration_ccx.hpp): a ccx run per coupling iteration, reset from
//   restart files or by replaying the committed steps;
// - PersistentCcx (persistent_ccx.hpp): one cocopp-ccx for the whole run, reset in memory.
// The wrapper (calculix_solver_wrapper.hpp) keeps what both share, in CalculixModel: the case's
// keys, the deck, the interface's faces and nodes, and the loads on the faces as they move.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/data/interface.hpp"
#include "solver_wrappers/calculix/input_deck.hpp"
#include "solver_wrappers/calculix/interface_loads.hpp"
#include "solver_wrappers/solver_error.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp::calculix {

/// The deck's model definition, written once by the wrapper; every mode's deck includes it.
constexpr const char* kModelFile = "cocopp_model.inp";

/// The model both modes solve, owned by the wrapper.
struct CalculixModel {
  std::string name;  ///< the wrapper's, for messages and file names
  std::filesystem::path working_directory;
  std::filesystem::path log_file;
  int threads = 1;
  double timeout = 600.0;  ///< s, for a ccx run or a cocopp-ccx request
  RunSettings run;
  std::string input_file;  ///< the user's deck, relative to working_directory
  std::string surface_name;
  std::string node_set_name;
  std::vector<std::string> input_variables;  ///< pressure and/or traction
  std::unique_ptr<InputDeck> deck;
  std::unique_ptr<InterfaceLoads> loads;
  std::vector<std::int64_t> interface_nodes;  ///< the output nodes, sorted
  /// Where the run is, for messages: set by the wrapper.
  int step = 0;
  int iteration = 0;

  std::filesystem::path file(const std::string& file_name) const {
    return working_directory / file_name;
  }
  /// Whether the input interface holds `variable` ("pressure", "traction").
  bool takes(const char* variable) const;
  /// "time step 3, coupling iteration 2".
  std::string position() const;
  [[noreturn]] void fail(const std::string& message) const;

  struct FaceLoads {
    Eigen::VectorXd pressure;  ///< per face; empty if pressure is no input
    RowMatrix traction;        ///< per face; empty if traction is no input
    RowMatrix force;           ///< the total per face (N); empty if force is no input
  };
  /// The loads of `input` on the faces; a NaN or infinity stops the run, naming the position.
  FaceLoads face_loads(const Interface& input) const;
  /// ccx applies a pressure on the deformed faces in an NLGEOM step; the traction's nodal
  /// forces are the wrapper's, so they follow the faces as `output` (a converged step's
  /// displacement) left them. Nothing without NLGEOM.
  void move_faces_with(const Interface& output) const;
  /// The error for a ccx that gave up a step (SolverRejectedInput: the coupled solver may step
  /// back and try other loads), saying what to change.
  SolverRejectedInput not_converged(const std::string& exit, const std::string& deck_file,
                                    const std::string& log_tail) const;
};

/// Time spent per coupling iteration, for the overhead benchmarks.
struct CcxTiming {
  /// ccx's run (process start to exit); persistent: cocopp-ccx's solve with the round trip
  double ccx_seconds = 0.0;
  /// writing loads and deck, copying restart, reading .dat; persistent: the nodal forces
  double wrapper_seconds = 0.0;
};

class CcxMode {
 public:
  virtual ~CcxMode() = default;
  /// After the deck is read, the interfaces built and the model definition written: get ready
  /// for the first time step or, in a restarted run (run.timestep_start > 0), continue from
  /// what save_restart() kept, setting `output` to the displacement it saved. `input`: the
  /// input interface's layout.
  virtual void start(const Interface& input, Interface& output) = 0;
  virtual void initialize_step(int step, double time) = 0;
  /// One coupling iteration: ccx takes `input`'s loads from the step's start; `output` gets
  /// its values (the displacement, and what a mode adds).
  virtual void solve(const Interface& input, Interface& output) = 0;
  /// Commit the last iteration's state as the next step's start.
  virtual void finalize_step() = 0;
  virtual void output_step() {}
  /// Keep what a run restarted after `step` needs; `output` holds its displacement.
  virtual void save_restart(int step, const Interface& output) = 0;
  virtual void finalize() {}
  const CcxTiming& last_timing() const { return timing_; }

 protected:
  CcxTiming timing_;
};

}  // namespace cocopp::calculix
