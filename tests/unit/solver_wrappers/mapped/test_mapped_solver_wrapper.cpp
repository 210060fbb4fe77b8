// The `mapped` solver wrapper on a sliding interface: a wire translates axially through a fixed
// fluid interface; the pressure it receives is the analytic fluid pressure at its current
// positions where it overlaps the fluid, and zero (ambient) outside.
#include <gtest/gtest.h>

#include <algorithm>

#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {
namespace {

constexpr double kStepTranslation = 0.05;  ///< axial displacement of the wire per time step

std::shared_ptr<ModelPart> line(const std::string& name, int points, double z0, double z1) {
  auto part = std::make_shared<ModelPart>();
  part->name = name;
  part->coordinates = Coordinates::Zero(points, 3);
  for (int i = 0; i < points; ++i) {
    part->ids.push_back(i);
    part->coordinates(i, 1) = 1.0;
    part->coordinates(i, 2) = z0 + (z1 - z0) * i / (points - 1);
  }
  return part;
}

double fluid_pressure(double z) {
  return 1.0 + z * z;
}

/// The fixed fluid side: 201 points on z in [0, 1], gives pressure, takes displacement. With
/// `second_part`, it also gives twice the pressure on a second model part of 101 points.
class Fluid : public SolverWrapper {
 public:
  explicit Fluid(bool second_part = false) {
    auto part = line("fluid", 201, 0.0, 1.0);
    input_ = Interface({{part, {"displacement"}}});
    if (second_part) {
      auto other = line("fluid_b", 101, 0.0, 1.0);
      output_ = Interface({{part, {"pressure"}}, {other, {"pressure"}}});
      auto p = output_.values("fluid_b", "pressure");
      for (Eigen::Index i = 0; i < p.rows(); ++i)
        p(i, 0) = 2 * fluid_pressure(other->coordinates(i, 2));
    } else {
      output_ = Interface({{part, {"pressure"}}});
    }
    auto p = output_.values("fluid", "pressure");
    for (Eigen::Index i = 0; i < p.rows(); ++i) p(i, 0) = fluid_pressure(part->coordinates(i, 2));
  }
  const std::string& name() const override { return name_; }
  void initialize() override {}
  const Interface& input_interface() const override { return input_; }
  const Interface& output_interface() const override { return output_; }
  void initialize_step(int, double) override {}
  const Interface& solve(const Interface&) override { return output_; }
  void finalize_step() override {}
  void output_step() override {}
  void finalize() override {}

 private:
  std::string name_ = "fluid";
  Interface input_, output_;
};

/// The wire: 41 points on z in [-0.5, 0.5] moving by `translation` (default kStepTranslation)
/// per step; it records the pressure it receives and reports its axial displacement and a
/// radial displacement of 0.001 per step. With `faces: true` it takes the pressure on its 40
/// face centres and gives the displacement at its 41 nodes: two model parts, as a structure
/// solver presents them.
class TranslatingWire : public SolverWrapper {
 public:
  TranslatingWire(const Settings& settings, const RunSettings&)
      : name_(settings.get<std::string>("name", "wire")),
        translation_(settings.get<double>("translation", kStepTranslation)) {
    auto nodes = line("wire", 41, -0.5, 0.5);
    auto faces =
        settings.get<bool>("faces", false) ? line("faces", 40, -0.5 + 0.0125, 0.5 - 0.0125) : nodes;
    std::vector<std::string> inputs = {"pressure"};
    if (settings.get<bool>("coverage", false)) inputs.push_back("coverage");
    if (settings.get<bool>("second_input", false))  // two input parts, one output part
      input_ = Interface({{faces, inputs}, {line("wire_b", 41, -0.5, 0.5), {"pressure"}}});
    else
      input_ = Interface({{faces, inputs}});
    output_ = Interface({{nodes, {"displacement"}}});
    last = this;
  }
  const std::string& name() const override { return name_; }
  void initialize() override {}
  const Interface& input_interface() const override { return input_; }
  const Interface& output_interface() const override { return output_; }
  void initialize_step(int step, double) override { step_ = step; }
  const Interface& solve(const Interface& input) override {
    received = input.values(input.parts()[0].model_part->name, "pressure");
    if (input.parts().size() > 1) received_b = input.values("wire_b", "pressure");
    const auto& variables = input.parts()[0].variables;
    if (std::find(variables.begin(), variables.end(), "coverage") != variables.end())
      coverage = input.values(input.parts()[0].model_part->name, "coverage");
    auto displacement = output_.values("wire", "displacement");
    displacement.col(1).setConstant(0.001 * step_);
    displacement.col(2).setConstant(translation_ * step_);
    return output_;
  }
  void finalize_step() override {}
  void output_step() override {}
  void finalize() override {}

  static inline TranslatingWire* last = nullptr;
  RowMatrix received, received_b, coverage;

 private:
  std::string name_;
  double translation_;
  Interface input_, output_;
  int step_ = 0;
};

COCOPP_REGISTER(SolverWrapperRegistry, "test_translating_wire", TranslatingWire)

/// A mapped test_translating_wire with `wire_keys` (e.g. ", faces: true") on a sliding
/// interface (mapped along z, rebuilt every step on the current positions), adopted by
/// `fluid`; `components` masks the output mapper, `more` adds keys of the mapped wrapper.
std::unique_ptr<SolverWrapper> mapped_wire(Fluid& fluid, const std::string& wire_keys,
                                           const std::string& components,
                                           const std::string& more = "") {
  const Settings settings = Settings::load_string(
      "type: mapped\nsolver_wrapper: {type: test_translating_wire" + wire_keys +
          "}\ninput_mapper: {type: linear, directions: [z], max_distance: 0.01, unmatched: "
          "zero}\noutput_mapper: {type: nearest, directions: [z], components: " +
          components + "}\ncoordinates: current\nrebuild: time_step\n" + more,
      "case.yaml");
  auto mapped = SolverWrapperRegistry::instance().create(settings, RunSettings{});
  settings.check_unused_keys();
  mapped->initialize();
  mapped->adopt_interfaces(fluid.output_interface(), fluid.input_interface());
  return mapped;
}

/// The wire's load points, at z0 + shift, received the fluid's pressure where they overlap it
/// and zero outside, within `tolerance`; counts the points inside and outside.
void expect_fluid_pressure(const TranslatingWire& wire, double shift, double tolerance, int step,
                           int& inside_total, int& outside_total) {
  const Eigen::VectorXd z0 = wire.input_interface().parts()[0].model_part->coordinates.col(2);
  for (Eigen::Index i = 0; i < z0.size(); ++i) {
    const double z = z0(i) + shift;
    const bool inside = z >= -1e-12 && z <= 1.0 + 1e-12;  // the ends belong to the fluid
    EXPECT_NEAR(wire.received(i, 0), inside ? fluid_pressure(z) : 0.0, tolerance)
        << "step " << step << ", z " << z;
    (inside ? inside_total : outside_total) += 1;
  }
}

TEST(MappedWrapper, SlidingWireGetsTheFluidPressureWhereItOverlaps) {
  // The fluid slips along the wire: only the radial (y) displacement reaches it, so its points
  // stay where they are while the wire's current positions move.
  Fluid fluid;
  auto mapped = mapped_wire(fluid, "", "[y]");
  int inside_total = 0, outside_total = 0;
  for (int step = 1; step <= 30; ++step) {
    mapped->initialize_step(step, step);  // rebuilt on the positions of the previous step
    mapped->solve(fluid.output_interface());
    // Linear interpolation of z^2 on a 0.005 grid: error at most h^2/8 ~ 3e-6.
    expect_fluid_pressure(*TranslatingWire::last, kStepTranslation * (step - 1), 4e-6, step,
                          inside_total, outside_total);
  }
  // The wire went from half outside on one end to half outside on the other.
  EXPECT_GT(inside_total, 0);
  EXPECT_GT(outside_total, 0);
}

// A solver that takes `coverage` gets the input mapper applied to ones: 1 where the fluid
// covers its points, 0 outside; with the overlap mapper the fraction of the face across the
// fluid's end.
TEST(MappedWrapper, CoverageIsTheMappedOne) {
  Fluid fluid;
  auto mapped = mapped_wire(fluid, ", faces: true, coverage: true", "[y]");
  mapped->initialize_step(1, 1.0);
  mapped->solve(fluid.output_interface());
  const auto& wire = *TranslatingWire::last;
  const Eigen::VectorXd z = wire.input_interface().parts()[0].model_part->coordinates.col(2);
  for (Eigen::Index i = 0; i < z.size(); ++i)
    EXPECT_EQ(wire.coverage(i, 0), z(i) >= 0.0 ? 1.0 : 0.0) << "z " << z(i);

  // Overlap: each fluid point stands for the segment half-way to its neighbours, so the fluid
  // covers [-0.0025, 1.0025]; of the wire's face [-0.025, 0], a tenth.
  const Settings settings = Settings::load_string(
      "type: mapped\nsolver_wrapper: {type: test_translating_wire, faces: true, coverage: "
      "true}\ninput_mapper: {type: overlap, directions: [z]}\noutput_mapper: {type: nearest, "
      "directions: [z], components: [y]}\n",
      "case.yaml");
  auto overlap = SolverWrapperRegistry::instance().create(settings, RunSettings{});
  overlap->initialize();
  overlap->adopt_interfaces(fluid.output_interface(), fluid.input_interface());
  overlap->initialize_step(1, 1.0);
  overlap->solve(fluid.output_interface());
  const RowMatrix& fraction = TranslatingWire::last->coverage;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const double expected = std::clamp((z(i) + 0.0125 + 0.0025) / 0.025, 0.0, 1.0);
    EXPECT_NEAR(fraction(i, 0), expected, 1e-12) << "z " << z(i);
  }
}

// Two input model parts and one output part, with an input mapper each: each part gets its
// counterpart's load through its own mapper.
TEST(MappedWrapper, InputMapperPerModelPartPair) {
  Fluid fluid(/*second_part=*/true);
  const auto settings = [](const std::string& mappers) {
    return Settings::load_string(
        "type: mapped\nsolver_wrapper: {type: test_translating_wire, second_input: true}\n"
        "input_mapper: " +
            mappers + "\noutput_mapper: {type: nearest, directions: [z], components: [y]}\n",
        "case.yaml");
  };
  const Settings two = settings(
      "[{type: linear, directions: [z], max_distance: 0.01, unmatched: zero}, "
      "{type: nearest, directions: [z], max_distance: 0.01, unmatched: zero}]");
  auto mapped = SolverWrapperRegistry::instance().create(two, RunSettings{});
  two.check_unused_keys();
  mapped->initialize();
  mapped->adopt_interfaces(fluid.output_interface(), fluid.input_interface());
  mapped->initialize_step(1, 1.0);
  mapped->solve(fluid.output_interface());
  const auto& wire = *TranslatingWire::last;
  const Eigen::VectorXd z = wire.input_interface().parts()[0].model_part->coordinates.col(2);
  int steps = 0;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const bool inside = z(i) >= 0.0;
    // Linear on a 0.005 grid (h^2 / 8); nearest on a 0.01 grid: the value half a grid step
    // away at most, where 2 (1 + z^2) changes by 4 z 0.005 <= 0.02.
    EXPECT_NEAR(wire.received(i, 0), inside ? fluid_pressure(z(i)) : 0.0, 4e-6) << z(i);
    EXPECT_NEAR(wire.received_b(i, 0), inside ? 2 * fluid_pressure(z(i)) : 0.0, 0.021) << z(i);
    if (inside && std::abs(wire.received_b(i, 0) - 2 * fluid_pressure(z(i))) > 1e-4) ++steps;
  }
  // The second part was mapped by its own mapper: nearest's staircase, not linear's line.
  EXPECT_GT(steps, 5);
  // A list must have one mapper per pair.
  const Settings three = settings("[{type: nearest}, {type: nearest}, {type: nearest}]");
  auto wrong = SolverWrapperRegistry::instance().create(three, RunSettings{});
  wrong->initialize();
  try {
    wrong->adopt_interfaces(fluid.output_interface(), fluid.input_interface());
    FAIL() << "three mappers for two pairs were accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("3 input mappers for 2 input model part pairs"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("case.yaml:"), std::string::npos) << e.what();
  }
}

TEST(MappedWrapper, FacesWithoutDisplacementMoveWithTheNodes) {
  // The faces have no displacement of their own: with `coordinates: current` they take their
  // nearest node's, so the loads follow the body, as for a CalculiX surface and node set.
  Fluid fluid;
  auto mapped = mapped_wire(fluid, ", faces: true", "[y]");
  int inside_total = 0, outside_total = 0;
  for (int step = 1; step <= 10; ++step) {
    mapped->initialize_step(step, step);
    mapped->solve(fluid.output_interface());
    // The nodes' displacement so far; linear interpolation of z^2 midway between points
    // 0.005 apart: h^2/4 = 6.25e-6.
    expect_fluid_pressure(*TranslatingWire::last, kStepTranslation * (step - 1), 6.3e-6, step,
                          inside_total, outside_total);
  }
}

/// A mapped test_translating_wire held in its own frame, which moves at 0.05 per unit time
/// along z, adopted by `fluid`; `components` masks the output mapper.
std::unique_ptr<SolverWrapper> wire_in_moving_frame(Fluid& fluid, const std::string& components) {
  return mapped_wire(fluid, ", translation: 0", components, "frame_velocity: [0, 0, 0.05]\n");
}

TEST(MappedWrapper, MovingFrameShiftsTheMapping) {
  // At time t the wire's points are at z0 + 0.05 t (exactly: the frame's motion is known, not
  // lagged by a step as a displacement is), and the fluid takes only the radial displacement.
  Fluid fluid;
  auto mapped = wire_in_moving_frame(fluid, "[x, y]");
  int inside_total = 0, outside_total = 0;
  for (int step = 1; step <= 12; ++step) {
    const double time = 0.5 * step;
    mapped->initialize_step(step, time);
    const Interface& output = mapped->solve(fluid.output_interface());
    expect_fluid_pressure(*TranslatingWire::last, 0.05 * time, 4e-6, step, inside_total,
                          outside_total);
    const RowMatrix displacement = output.values("fluid", "displacement");
    EXPECT_DOUBLE_EQ(displacement.col(1).minCoeff(), 0.001 * step);
    EXPECT_DOUBLE_EQ(displacement.col(1).maxCoeff(), 0.001 * step);
    EXPECT_EQ(displacement.col(2).cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(MappedWrapper, MovingFrameIsInTheDisplacementTheOtherSolverSees) {
  Fluid fluid;
  auto mapped = wire_in_moving_frame(fluid, "[x, y, z]");
  mapped->initialize_step(1, 2.0);
  const RowMatrix displacement =
      mapped->solve(fluid.output_interface()).values("fluid", "displacement");
  EXPECT_DOUBLE_EQ(displacement.col(2).minCoeff(), 0.1);
  EXPECT_DOUBLE_EQ(displacement.col(2).maxCoeff(), 0.1);
  EXPECT_DOUBLE_EQ(displacement.col(1).maxCoeff(), 0.001);
}

TEST(MappedWrapper, BodyThatLeavesTheInterfaceIsReportedWithTheTime) {
  Fluid fluid;
  auto mapped = wire_in_moving_frame(fluid, "[x, y]");
  mapped->initialize_step(1, 1.0);  // the wire at z in [-0.45, 0.55]: overlaps
  try {
    mapped->initialize_step(2, 40.0);  // at z in [1.5, 2.5]: the fluid is at [0, 1]
    FAIL() << "a wire outside the fluid's interface was mapped";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("mapped solver 'wire'"), std::string::npos) << message;
    EXPECT_NE(message.find("at time 40"), std::string::npos) << message;
    EXPECT_NE(message.find("moved by (0, 0, 2)"), std::string::npos) << message;
    EXPECT_NE(message.find("do not overlap"), std::string::npos) << message;
    EXPECT_NE(message.find("left the other's interface"), std::string::npos) << message;
  }
}

TEST(MappedWrapper, MovingFrameWithoutRebuildIsRefused) {
  const Settings settings = Settings::load_string(
      "type: mapped\nsolver_wrapper: {type: test_translating_wire}\n"
      "input_mapper: {type: nearest}\noutput_mapper: {type: nearest}\n"
      "frame_velocity: [0, 0, 1]\n",
      "case.yaml");
  try {
    SolverWrapperRegistry::instance().create(settings, RunSettings{});
    FAIL() << "a moving frame without rebuilt mappings was accepted";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("case.yaml:5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rebuild: time_step"), std::string::npos) << e.what();
  }
}

TEST(MappedWrapper, MismatchedModelPartCountsAreReported) {
  const Settings settings = Settings::load_string(
      "type: mapped\nsolver_wrapper: {type: test_translating_wire}\n"
      "input_mapper: {type: nearest}\noutput_mapper: {type: nearest}\n",
      "case.yaml");
  auto mapped = SolverWrapperRegistry::instance().create(settings, RunSettings{});
  mapped->initialize();
  const Interface empty;
  EXPECT_THROW(mapped->adopt_interfaces(empty, empty), std::runtime_error);
}

}  // namespace
}  // namespace cocopp
