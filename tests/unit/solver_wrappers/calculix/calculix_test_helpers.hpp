#pragma once
// Driving the calculix wrapper in tests: a case directory with the deck in `wall/`, the
// wrapper created through the registry (as a case file would), loads set on its interface.
#include <Eigen/Core>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "core/case/settings.hpp"
#include "solver_wrappers/calculix/calculix_solver_wrapper.hpp"
#include "solver_wrappers/solver_error.hpp"
#include "solver_wrappers/solver_wrapper.hpp"
#include "tests/support/calculix_models.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp::testing {

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)

class CalculixCase {
 public:
  /// `number_of_timesteps`: the run's, which mode: persistent makes its ccx step as long as.
  explicit CalculixCase(double delta_t = 1.0, int number_of_timesteps = 100) {
    run_.delta_t = delta_t;
    run_.number_of_timesteps = number_of_timesteps;
    run_.case_directory = directory_.path();
    std::filesystem::create_directory(directory_ / "wall");
  }

  /// A wrapper for `deck` (written to wall/wall.inp); `keys` are added to its settings.
  SolverWrapper& create(const std::string& deck, const std::string& keys = "",
                        const std::string& surface = "INNER",
                        const std::string& node_set = "INNERN") {
    write_text(directory_ / "wall/wall.inp", deck);
    axisymmetric_ = deck.find("TYPE=CAX") != std::string::npos;
    settings_ = std::make_unique<Settings>(Settings::load_string(
        "type: calculix\nname: wall\nworking_directory: wall\ninput_file: wall.inp\n"
        "interface_surface: " +
            surface + "\ninterface_node_set: " + node_set + "\nsave_results: false\n" + keys,
        "case.yaml"));
    wrapper_ = SolverWrapperRegistry::instance().create(*settings_, run_);
    settings_->check_unused_keys();
    return *wrapper_;
  }

  /// create(), initialize() and the first time step: a wrapper ready to solve().
  SolverWrapper& start(const std::string& deck, const std::string& keys = "",
                       const std::string& surface = "INNER",
                       const std::string& node_set = "INNERN") {
    create(deck, keys, surface, node_set);
    wrapper_->initialize();
    wrapper_->initialize_step(1, run_.delta_t);
    step_ = 1;
    committed_ = false;
    return *wrapper_;
  }

  /// Commit the time step (unless printed_results() did) and begin the next.
  void next_step() {
    if (!committed_) wrapper_->finalize_step();
    ++step_;
    wrapper_->initialize_step(step_, step_ * run_.delta_t);
    committed_ = false;
  }

  /// The .dat file with what the deck's *NODE PRINT cards printed for the last solve(): per
  /// iteration, that iteration's ccx run's; persistent, cocopp-ccx prints at commits, so the
  /// step is committed here (the next solve() begins the next step).
  std::filesystem::path printed_results() {
    if (!dynamic_cast<const CalculixSolverWrapper&>(*wrapper_).persistent())
      return directory_ / "wall/cocopp_iteration.dat";
    if (!committed_) wrapper_->finalize_step();
    committed_ = true;
    return directory_ / "wall/cocopp_persistent.dat";
  }

  SolverWrapper& wrapper() { return *wrapper_; }
  /// The run settings the next create() passes (e.g. timestep_start for a restart).
  RunSettings& run() { return run_; }
  std::filesystem::path path(const std::string& name) const { return directory_ / name; }

  /// The wrapper's input with a uniform pressure and traction on every face (the model part
  /// that takes them: the first, or the faces after a driven wrapper's nodes).
  Interface loads(double pressure, const Eigen::Vector3d& traction = Eigen::Vector3d::Zero()) {
    Interface input = wrapper_->input_interface();
    const std::string part = input.parts().back().model_part->name;
    input.values(part, "pressure").setConstant(pressure);
    auto t = input.values(part, "traction");
    for (Eigen::Index i = 0; i < t.rows(); ++i) t.row(i) = traction.transpose();
    return input;
  }

  /// One coupling iteration with a uniform pressure; the displacements (nodes x 3).
  RowMatrix solve(double pressure, const Eigen::Vector3d& traction = Eigen::Vector3d::Zero()) {
    if (committed_) next_step();
    const Interface& output = wrapper_->solve(loads(pressure, traction));
    const auto& part = output.parts().front().model_part->name;
    return output.values(part, "displacement");
  }

  /// Radial displacement of each interface node (about the z axis; x in a CAX model).
  Eigen::VectorXd radial(const RowMatrix& displacement) const {
    if (axisymmetric_) return displacement.col(0);
    const auto& nodes = *wrapper_->output_interface().parts().front().model_part;
    Eigen::VectorXd result(displacement.rows());
    for (Eigen::Index i = 0; i < displacement.rows(); ++i) {
      Eigen::Vector3d e_r(nodes.coordinates(i, 0), nodes.coordinates(i, 1), 0.0);
      result[i] = displacement.row(i).dot(e_r.normalized().transpose());
    }
    return result;
  }

  const ModelPart& nodes() const {
    return *wrapper_->output_interface().parts().front().model_part;
  }

 private:
  TemporaryDirectory directory_;
  RunSettings run_;
  std::unique_ptr<Settings> settings_;
  std::unique_ptr<SolverWrapper> wrapper_;
  bool axisymmetric_ = false;  ///< a CAX deck: x is the radius, y the axis
  int step_ = 0;
  bool committed_ = false;  ///< printed_results() committed the step
};

/// The wrapper's keys for a mode ("per_iteration" or "persistent").
inline std::string mode_keys(const std::string& mode) {
  return "mode: " + mode + "\n";
}

/// Every "<quantity> ... for set <set> and time <t>" block of a .dat file: time -> rows of
/// numbers (node id first for nodal values; the totals line alone for totals).
inline std::map<double, std::vector<std::vector<double>>> dat_blocks(
    const std::filesystem::path& file, const std::string& quantity, const std::string& set) {
  std::ifstream in(file);
  std::map<double, std::vector<std::vector<double>>> blocks;
  std::vector<std::vector<double>>* block = nullptr;
  std::string line;
  while (std::getline(in, line)) {
    const auto at = line.find("for set " + set + " and time ");  // "...,pe)for set": no space
    if (line.find(quantity) != std::string::npos && at != std::string::npos) {
      const double time = std::stod(line.substr(line.rfind(' ')));
      block = &blocks[time];
      block->clear();
      continue;
    }
    if (block == nullptr) continue;
    std::istringstream fields(line);
    std::vector<double> row;
    double value;
    while (fields >> value) row.push_back(value);
    if (row.empty()) {
      if (!block->empty()) block = nullptr;
      continue;
    }
    block->push_back(row);
  }
  return blocks;
}

/// The total force ccx printed last for `set` (*NODE PRINT, TOTALS=ONLY).
inline Eigen::Vector3d last_total_force(const std::filesystem::path& file, const std::string& set) {
  const auto blocks = dat_blocks(file, "total force", set);
  if (blocks.empty() || blocks.rbegin()->second.empty()) return Eigen::Vector3d::Constant(NAN);
  const auto& row = blocks.rbegin()->second.front();
  return {row.at(0), row.at(1), row.at(2)};
}

/// The yield stress of the plastic test models.
inline constexpr double kYield = 250e6;
/// The .dat file prints 7 significant digits.
inline constexpr double kDatPrecision = 1e-6;

inline double max_abs(const Eigen::VectorXd& values) {
  return values.cwiseAbs().maxCoeff();
}

}  // namespace cocopp::testing
