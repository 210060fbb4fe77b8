// The tube solvers' input files, read with cocopp::Settings: errors are CaseErrors that name
// file, line and key; the examples parse.
#include <gtest/gtest.h>

#include <string>

#include "core/case/settings.hpp"
#include "solvers/tube/tube_flow.hpp"
#include "solvers/tube/tube_input.hpp"
#include "solvers/tube/tube_ringmodel.hpp"
#include "solvers/tube/tube_structure.hpp"

namespace cocopp::tube {
namespace {

const char* const kFlowFile = R"(length: 0.05
diameter: 0.01
cells: 100
rho_f: 1000
e: 3.0e5
h: 1.0e-3
u_ref: 1
u0: 0
p_ref: 0
inlet:
  boundary: pressure
  variable: pulse
  reference: 0
  amplitude: 1333.2
  period: 0.003
outlet:
  boundary: fixed
  pressure: 0
newtonmax: 3
newtontol: 1.0e-14
output:
  interval: 10
)";

TubeFlowParameters read_flow(const std::string& text) {
  const Settings input = Settings::load_string(text, "tube_flow.yaml");
  TubeFlowParameters parameters = TubeFlowParameters::read(input);
  input.check_unused_keys();
  return parameters;
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto position = text.find(from);
  EXPECT_NE(position, std::string::npos) << from;
  return text.replace(position, from.size(), to);
}

// The error message of reading `text`, or "" if it reads fine.
std::string flow_error(const std::string& text) {
  try {
    read_flow(text);
  } catch (const CaseError& error) {
    return error.what();
  }
  return "";
}

TEST(TubeInput, ReadsAFlowFile) {
  const TubeFlowParameters parameters = read_flow(kFlowFile);
  EXPECT_EQ(parameters.geometry.cells, 100);
  EXPECT_DOUBLE_EQ(parameters.geometry.length, 0.05);
  EXPECT_EQ(parameters.inlet.boundary, InletBoundary::kPressure);
  EXPECT_EQ(parameters.inlet.variable, InletFunction::kPulse);
  EXPECT_DOUBLE_EQ(parameters.inlet.amplitude, 1333.2);
  EXPECT_EQ(parameters.outlet.boundary, OutletBoundary::kFixed);
  EXPECT_EQ(parameters.newtonmax, 3);
  EXPECT_EQ(parameters.output.interval, 10);
  EXPECT_EQ(parameters.output.directory, "output");
}

TEST(TubeInput, UnknownKeyNamesFileLineAndKey) {
  const std::string message = flow_error(replace(kFlowFile, "u0: 0", "u_0: 0"));
  EXPECT_NE(message.find("tube_flow.yaml:8:"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown key 'u_0'"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean 'u0'?"), std::string::npos) << message;
}

TEST(TubeInput, UnknownNestedKeyNamesItsPath) {
  const std::string message = flow_error(replace(kFlowFile, "  period: 0.003", "  perod: 0.003"));
  // A pulse needs its period, so the missing key is reported first, at the inlet mapping.
  EXPECT_NE(message.find("tube_flow.yaml:11:"), std::string::npos) << message;
  EXPECT_NE(message.find("missing required key 'inlet.period'"), std::string::npos) << message;
  const std::string unknown = flow_error(replace(kFlowFile, "  reference: 0", "  referance: 0"));
  EXPECT_NE(unknown.find("tube_flow.yaml:13:"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("unknown key 'inlet.referance'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("did you mean 'reference'?"), std::string::npos) << unknown;
}

TEST(TubeInput, MissingKeyIsReported) {
  const std::string message = flow_error(replace(kFlowFile, "rho_f: 1000\n", ""));
  EXPECT_NE(message.find("tube_flow.yaml:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("missing required key 'rho_f'"), std::string::npos) << message;
}

TEST(TubeInput, NonPositiveLengthIsRejected) {
  const std::string message = flow_error(replace(kFlowFile, "length: 0.05", "length: -0.05"));
  EXPECT_NE(message.find("tube_flow.yaml:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("'length': must be > 0, got -0.05"), std::string::npos) << message;
  EXPECT_NE(flow_error(replace(kFlowFile, "length: 0.05", "length: 0")), "");
}

TEST(TubeInput, TooFewCellsAreRejected) {
  // The boundary rows extrapolate from two cells, so one cell is not enough.
  const std::string message = flow_error(replace(kFlowFile, "cells: 100", "cells: 1"));
  EXPECT_NE(message.find("tube_flow.yaml:3:"), std::string::npos) << message;
  EXPECT_NE(message.find("'cells': must be"), std::string::npos) << message;
  EXPECT_NE(message.find("got 1"), std::string::npos) << message;
  EXPECT_EQ(flow_error(replace(kFlowFile, "cells: 100", "cells: 2")), "");
}

TEST(TubeInput, OutputDirectoryMustNotBeEmpty) {
  const std::string message =
      flow_error(replace(kFlowFile, "  interval: 10\n", "  interval: 10\n  directory: \"\"\n"));
  EXPECT_NE(message.find("tube_flow.yaml:23:"), std::string::npos) << message;
  EXPECT_NE(message.find("'output.directory': must not be empty"), std::string::npos) << message;
}

TEST(TubeInput, WrongTypesAndChoicesAreRejected) {
  const std::string cells = flow_error(replace(kFlowFile, "cells: 100", "cells: 10.5"));
  EXPECT_NE(cells.find("tube_flow.yaml:3:"), std::string::npos) << cells;
  EXPECT_NE(cells.find("'cells': expected an integer, got '10.5'"), std::string::npos) << cells;
  const std::string number = flow_error(replace(kFlowFile, "e: 3.0e5", "e: stiff"));
  EXPECT_NE(number.find("tube_flow.yaml:5:"), std::string::npos) << number;
  EXPECT_NE(number.find("'e': expected a number, got 'stiff'"), std::string::npos) << number;
  const std::string choice = flow_error(replace(kFlowFile, "boundary: fixed", "boundary: fixd"));
  EXPECT_NE(choice.find("tube_flow.yaml:17:"), std::string::npos) << choice;
  EXPECT_NE(choice.find("'outlet.boundary': 'fixd' is not one of: fixed, non_reflecting"),
            std::string::npos)
      << choice;
  EXPECT_NE(choice.find("did you mean 'fixed'?"), std::string::npos) << choice;
}

TEST(TubeInput, SyntaxErrorNamesTheLine) {
  const std::string message = flow_error(replace(kFlowFile, "cells: 100", "cells: [100"));
  EXPECT_NE(message.find("tube_flow.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("syntax error"), std::string::npos) << message;
}

TEST(TubeInput, MissingFileIsReported) {
  try {
    TubeFlowParameters::load("/nonexistent/tube_flow.yaml");
    FAIL() << "expected an exception";
  } catch (const CaseError& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/tube_flow.yaml"), std::string::npos);
  }
}

TEST(TubeInput, NewmarkParametersAreChecked) {
  const std::string base = R"(length: 0.05
diameter: 0.01
cells: 100
rho_s: 1200
e: 3.0e5
h: 1.0e-3
nu: 0.3
time_scheme:
  type: newmark
  gamma: 0.6
  beta: 0.25
)";
  const Settings input = Settings::load_string(base, "tube_structure.yaml");
  try {
    TubeStructureParameters::read(input);
    FAIL() << "beta below (1/2 + gamma)^2 / 4 must be rejected";
  } catch (const CaseError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("tube_structure.yaml:11:"), std::string::npos) << message;
    EXPECT_NE(message.find("'time_scheme.beta': must be >= (1/2 + gamma)^2 / 4"), std::string::npos)
        << message;
  }
}

TEST(TubeInput, PoissonRatioIsBelowOneHalf) {
  const std::string base = R"(length: 0.05
diameter: 0.01
cells: 100
rho_s: 1200
e: 3.0e5
h: 1.0e-3
nu: 0.5
)";
  const Settings input = Settings::load_string(base, "tube_structure.yaml");
  try {
    TubeStructureParameters::read(input);
    FAIL() << "nu = 0.5 must be rejected";
  } catch (const CaseError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("tube_structure.yaml:7:"), std::string::npos) << message;
    EXPECT_NE(message.find("'nu': must be in [0, 0.5), got 0.5"), std::string::npos) << message;
  }
}

// The example input files in the source tree parse and contain no unknown keys.
TEST(TubeInput, ExampleFilesParse) {
  const std::string examples = COCOPP_TUBE_EXAMPLES_DIR "/";
  const TubeFlowParameters pulse =
      TubeFlowParameters::load(examples + "flow_structure/flow/tube_flow.yaml");
  EXPECT_EQ(pulse.inlet.variable, InletFunction::kPulse);
  EXPECT_EQ(pulse.output.interval, 10);
  const TubeStructureParameters structure =
      TubeStructureParameters::load(examples + "flow_structure/structure/tube_structure.yaml");
  EXPECT_DOUBLE_EQ(structure.rho_s, 1200.0);
  const TubeFlowParameters velocity =
      TubeFlowParameters::load(examples + "flow_ringmodel/flow/tube_flow.yaml");
  EXPECT_EQ(velocity.outlet.boundary, OutletBoundary::kNonReflecting);
  const TubeRingmodelParameters rings =
      TubeRingmodelParameters::load(examples + "flow_ringmodel/structure/tube_ringmodel.yaml");
  EXPECT_DOUBLE_EQ(rings.e, 3e5);
}

}  // namespace
}  // namespace cocopp::tube
