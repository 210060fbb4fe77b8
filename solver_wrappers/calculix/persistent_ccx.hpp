#pragma once
// PersistentCcx: the calculix wrapper's `mode: persistent`. One cocopp-ccx process
// (solvers/calculix/coupled_ccx.cpp, ccx with patch 05) runs for the whole simulation: the deck's
// step becomes one ccx step as long as the run, which the coupler's time steps advance
// increment by increment, and every coupling iteration is solved from an in-memory checkpoint
// of the step's start. So ccx's dynamic integrator carries its state from step to step (no
// restart of *DYNAMIC every time step), and no process start, deck parsing or restart file
// costs time per coupling iteration.
//
// The wrapper keeps everything else (deck reading, loads on the faces as they move, messages):
// this class writes the long step's deck (`cocopp_persistent.inp`: the model definition, the
// deck's step with its time period set to the run's and a zero placeholder *DLOAD and *CLOAD
// for every interface load, which cocopp-ccx overwrites) and the interface list
// (`cocopp_interface.txt`), and talks to cocopp-ccx over the solver protocol through a
// ProcessSolverWrapper (its timeouts, crash reports and clean-up).
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "solver_wrappers/calculix/input_deck.hpp"
#include "solver_wrappers/calculix/interface_loads.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {
class ProcessSolverWrapper;
}

namespace cocopp::calculix {

class PersistentCcx {
 public:
  static constexpr const char* kJob = "cocopp_persistent";
  static constexpr const char* kInterfaceFile = "cocopp_interface.txt";

  struct Options {
    std::string name;  ///< the wrapper's, for messages
    std::filesystem::path executable;
    std::filesystem::path working_directory;
    std::filesystem::path log_file;
    int threads = 1;
    double timeout = 600.0;
    bool pressure = true;  ///< whether pressure is an input (a *DLOAD per face)
  };

  /// `model_file`: the deck's model definition, written by the wrapper in the working directory.
  PersistentCcx(Options options, const InputDeck& deck, const InterfaceLoads& loads,
                std::vector<std::int64_t> output_nodes, std::string model_file);
  ~PersistentCcx();

  /// Why the deck cannot run persistent (empty if it can): a procedure other than *STATIC or
  /// *DYNAMIC, contact (its state is not in the checkpoint).
  static std::string unsupported(const InputDeck& deck);

  /// Write the deck and the interface list for a run that ends at `end_time`, start cocopp-ccx.
  void start(const RunSettings& run, double end_time);
  void initialize_step(int step, double time);
  /// One coupling iteration: a pressure per face (empty if pressure is no input) and nodal
  /// forces (global, per face node; empty map: none). The output nodes' displacements (global).
  RowMatrix solve(const Eigen::VectorXd& pressure,
                  const std::map<std::int64_t, Eigen::Vector3d>& forces);
  void finalize_step();
  void finalize();
  /// The last solve()'s time in cocopp-ccx's process (its solve and the protocol round trip).
  double process_seconds() const { return process_seconds_; }

 private:
  void write_deck(double end_time) const;
  void write_interface() const;
  std::vector<DeckLine> long_step(double end_time) const;
  /// A coupler time step over the deck step's time period: the deck's increments scale by it.
  double time_scale() const;
  /// The first increment of every coupler time step (the deck's, scaled).
  double initial_increment() const;

  Options options_;
  const InputDeck& deck_;
  const InterfaceLoads& loads_;
  std::vector<std::int64_t> output_nodes_;
  std::vector<std::int64_t> force_nodes_;  ///< every node of the interface faces, sorted
  std::string model_file_;
  RunSettings run_;
  std::unique_ptr<ProcessSolverWrapper> process_;
  double process_seconds_ = 0.0;
};

}  // namespace cocopp::calculix
