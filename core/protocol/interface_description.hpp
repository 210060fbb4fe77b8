#pragma once
// The plain data a solver and the coupler exchange at initialization: the model parts of the
// interface and the run information. They belong to the protocol (standard library only) and
// keep the namespace cocopp::sdk because they are the SDK's public types: a solver fills them
// (solvers/sdk/solver_sdk.hpp), the protocol encodes them (messages.hpp).
#include <cstdint>
#include <string>
#include <vector>

namespace cocopp::sdk {

struct ModelPart {
  std::string name;
  std::vector<std::int64_t> ids;
  std::vector<double> coordinates;  ///< initial coordinates, x y z per point (3 * ids.size())
  std::vector<std::string> input_variables;   ///< e.g. {"displacement"}
  std::vector<std::string> output_variables;  ///< e.g. {"pressure", "traction"}
};

/// What a solver tells the coupler at initialization.
struct InterfaceDescription {
  std::vector<ModelPart> model_parts;
  /// Initial values of the output interface, in the flattened layout (may be empty: zeros).
  std::vector<double> initial_output;
};

/// Run information the coupler sends with the initialize request.
struct RunInfo {
  double delta_t = 0.0;
  std::int32_t timestep_start = 0;
};

}  // namespace cocopp::sdk
