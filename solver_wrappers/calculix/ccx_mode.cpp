#include "solver_wrappers/calculix/ccx_mode.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace cocopp::calculix {

bool CalculixModel::takes(const char* variable) const {
  return std::find(input_variables.begin(), input_variables.end(), variable) !=
         input_variables.end();
}

std::string CalculixModel::position() const {
  return fmt::format("time step {}, coupling iteration {}", step, iteration);
}

void CalculixModel::fail(const std::string& message) const {
  throw SolverError(name, message);
}

CalculixModel::FaceLoads CalculixModel::face_loads(const Interface& input) const {
  FaceLoads face;
  if (takes("pressure")) face.pressure = input.values(surface_name, "pressure").col(0);
  if (takes("traction")) face.traction = input.values(surface_name, "traction");
  if (takes("force")) face.force = input.values(surface_name, "force");
  if (!face.pressure.allFinite() || !face.traction.allFinite() || !face.force.allFinite())
    fail(fmt::format("solver '{}' at {}: the interface loads contain NaN or infinity", name,
                     position()));
  return face;
}

void CalculixModel::move_faces_with(const Interface& output) const {
  if (!deck->nonlinear_geometry()) return;
  const auto u = output.values(node_set_name, "displacement");
  NodeDisplacements displacement;
  for (std::size_t i = 0; i < interface_nodes.size(); ++i)
    displacement[interface_nodes[i]] = u.row(static_cast<Eigen::Index>(i)).transpose();
  loads->move_faces(displacement);
}

SolverRejectedInput CalculixModel::not_converged(const std::string& exit,
                                                 const std::string& deck_file,
                                                 const std::string& log_tail) const {
  return SolverRejectedInput(
      name,
      fmt::format("solver '{}': ccx did not converge at {} ({}: the increment size fell below the "
                  "minimum, it was cut back too often or the step needed more increments than "
                  "*STEP, INC= allows); what to change: a smaller time step "
                  "(settings.delta_t), a smaller minimum "
                  "increment on the deck's *STATIC or *DYNAMIC line, or loads the structure can "
                  "carry (a coupled load far beyond its limit load diverges); deck {}, last lines "
                  "of {}:\n{}",
                  name, position(), exit, deck_file, log_file.string(), log_tail));
}

}  // namespace cocopp::calculix
