// ring-wall: the wall of a 1D flexible tube as independent massless rings (a tube law), a
// cocopp solver built outside cocopp's tree against the installed SDK (docs/install.md). It is
// the same model as cocopp's built-in tube_ringmodel (docs/tube-solvers.md), so the case here
// gives the built-in example's results (examples/tube/flow_ringmodel).
//
// usage: ring-wall length=0.05 diameter=0.01 cells=100 rho_f=1000 e=3e5 h=1e-3
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/sdk/solver_sdk.hpp"

namespace {

namespace sdk = cocopp::sdk;

constexpr double kPi = 3.14159265358979323846;

constexpr const char* kUsage = R"(usage: ring-wall length=L diameter=D cells=M rho_f=RHO e=E h=H

The wall of a 1D flexible tube of length L and diameter D (m) as M independent massless rings
of Young's modulus E (Pa) and thickness H (m), loaded by a fluid of density RHO (kg/m^3): the
tube law r = r0 * 2 / (2 - p / (RHO c0^2)), c0^2 = E H / (RHO D). A cocopp solver: run it
through `cocopp run case.yaml`. Interface: model part `wall` (M points at the cell centres),
input pressure and traction (ignored), output displacement (0, radial, 0).
)";

/// key=value arguments; every key of `required` must be there, and nothing else.
std::map<std::string, double> read_arguments(int argc, char** argv,
                                             const std::vector<std::string>& required) {
  std::map<std::string, double> values;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    const auto equals = argument.find('=');
    if (equals == std::string::npos) throw std::invalid_argument("not key=value: " + argument);
    values[argument.substr(0, equals)] = std::stod(argument.substr(equals + 1));
  }
  for (const auto& key : required)
    if (!values.count(key)) throw std::invalid_argument("missing argument " + key + "=...");
  if (values.size() != required.size()) throw std::invalid_argument("unknown arguments given");
  return values;
}

class RingWall : public sdk::Solver {
 public:
  explicit RingWall(std::map<std::string, double> p)
      : length_(p.at("length")),
        diameter_(p.at("diameter")),
        radius_(0.5 * p.at("diameter")),
        cells_(static_cast<int>(p.at("cells"))),
        rho_f_(p.at("rho_f")),
        // Moens-Korteweg wave speed squared, E h / (rho_f d), with the wall undeformed at p = 0.
        c02_(p.at("e") * p.at("h") / (p.at("rho_f") * p.at("diameter"))) {}

  sdk::InterfaceDescription initialize(const sdk::RunInfo&) override {
    sdk::ModelPart wall{"wall", {}, {}, {"pressure", "traction"}, {"displacement"}};
    const double dz = length_ / cells_;
    for (int i = 0; i < cells_; ++i) {
      wall.ids.push_back(i);
      wall.coordinates.insert(wall.coordinates.end(),
                              {0.0, radius_, -length_ / 2.0 + dz / 2.0 + i * dz});
    }
    return {{wall}, {}};  // initial output: zeros, the undeformed wall
  }

  void initialize_step(std::int32_t, double) override {}

  // The input is the cells' pressures, then their tractions (ignored); the output the
  // displacement (0, radial, 0) of each cell.
  std::vector<double> solve(const std::vector<double>& input) override {
    std::vector<double> displacement(3 * cells_, 0.0);
    for (int i = 0; i < cells_; ++i) {
      const double p = input[i] / rho_f_;
      if (p >= 2 * c02_) throw std::runtime_error("unphysical pressure: the tube law has no area");
      // The area, then the radius, in the order of operations of cocopp's tube_ringmodel, so
      // that the two give the same results to the last bit.
      const double ratio = 2.0 / (2.0 + (0.0 - p) / c02_);
      const double area = kPi * diameter_ * diameter_ / 4.0 * ratio * ratio;
      displacement[3 * i + 1] = std::sqrt(area / kPi) - radius_;
    }
    return displacement;
  }

  void finalize_step() override {}

 private:
  double length_, diameter_, radius_;
  int cells_;
  double rho_f_, c02_;
};

}  // namespace

int main(int argc, char** argv) {
  if (sdk::wants_help(argc, argv)) {
    std::printf("%s", kUsage);
    return 0;
  }
  try {
    RingWall wall(read_arguments(argc, argv, {"length", "diameter", "cells", "rho_f", "e", "h"}));
    return sdk::serve(wall, argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ring-wall: %s\n", e.what());
    return 2;
  }
}
