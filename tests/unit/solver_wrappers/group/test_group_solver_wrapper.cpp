// The `group` solver wrapper with in-process bodies: a fluid with two flags, one body a flag
// (each member maps only its own model part, `model_parts`); one model part shared by two
// members along it; a rejected input and an error passed on from a member's thread as thrown.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "core/case/settings.hpp"
#include "solver_wrappers/solver_wrapper.hpp"
#include "tests/support/linear_solvers.hpp"
#include "tests/support/solver_wrapper_case.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp {
namespace {

/// `points` points along x from 0 to `length`, at y = z = 0.
std::shared_ptr<ModelPart> line(const std::string& name, int points, double start, double end) {
  auto part = std::make_shared<ModelPart>();
  part->name = name;
  part->coordinates = Coordinates::Zero(points, 3);
  for (int i = 0; i < points; ++i) {
    part->ids.push_back(i);
    part->coordinates(i, 0) = start + (end - start) * i / (points - 1);
  }
  return part;
}

/// A body along x: its nodes take a pressure and move in y by `compliance` times it. With
/// `reject_above` it rejects a larger pressure (as a structure loaded beyond what it carries);
/// with `fail_above` it fails.
class Body : public testing::InProcessSolver {
 public:
  Body(const Settings& settings, const RunSettings&)
      : InProcessSolver(settings.get_name("name", "body"), Interface(), Interface()),
        compliance_(settings.get<double>("compliance", 1.0)),
        reject_above_(settings.get<double>("reject_above", 1e300)),
        fail_above_(settings.get<double>("fail_above", 1e300)) {
    const auto nodes =
        line("nodes", settings.get<int>("points", 11), 0.0, settings.get<double>("length", 1.0));
    input_ = Interface({{nodes, {"pressure"}}});
    output_ = Interface({{nodes, {"displacement"}}});
  }
  void set_default_name(const std::string& name) override { name_ = name; }
  const Interface& solve(const Interface& input) override {
    const auto pressure = input.values("nodes", "pressure");
    if (pressure.maxCoeff() > reject_above_)
      throw SolverRejectedInput(name_, name_ + " rejects the load");
    if (pressure.maxCoeff() > fail_above_) throw SolverError(name_, name_ + " failed");
    auto displacement = output_.values("nodes", "displacement");
    displacement.setZero();
    displacement.col(1) = compliance_ * pressure.col(0);
    return output_;
  }

 private:
  double compliance_, reject_above_, fail_above_;
};

COCOPP_REGISTER(SolverWrapperRegistry, "test_body", Body)

/// The fluid side: model parts `parts` with pressures given, displacements taken.
struct Fluid {
  Interface loads, displacement;
  explicit Fluid(const std::vector<std::shared_ptr<ModelPart>>& parts) {
    std::vector<Interface::Part> given, taken;
    for (const auto& part : parts) {
      given.push_back({part, {"pressure"}});
      taken.push_back({part, {"displacement"}});
    }
    loads = Interface(given);
    displacement = Interface(taken);
  }
};

std::string member(const std::string& name, const std::string& body_keys,
                   const std::string& extra) {
  return "{type: mapped, name: " + name + ", solver_wrapper: {type: test_body, " + body_keys +
         "}, input_mapper: {type: linear, directions: [x]}, output_mapper: {type: linear, "
         "directions: [x]}" +
         (extra.empty() ? "" : ", " + extra) + "}";
}

std::unique_ptr<SolverWrapper> group(const std::string& members) {
  static testing::TemporaryDirectory directory;
  return testing::initialized_wrapper(
      "{type: group, name: bodies, solver_wrappers: [" + members + "]}", directory.path(), 1.0);
}

TEST(GroupSolverWrapper, TwoFlagsInOneFluidEachMappedByItsOwnBody) {
  Fluid fluid({line("flag_a", 21, 0.0, 1.0), line("flag_b", 7, 2.0, 3.0)});
  auto bodies = group(member("a", "compliance: 1.0, points: 6", "model_parts: [flag_a]") + ", " +
                      member("b", "compliance: 2.0, points: 4",
                             "model_parts: [flag_b], frame_origin: [2.0, 0.0, 0.0]"));
  bodies->adopt_interfaces(fluid.loads, fluid.displacement);
  ASSERT_TRUE(bodies->output_interface().same_layout(fluid.displacement));
  Interface loads = fluid.loads;
  auto a = loads.values("flag_a", "pressure");
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    a(i, 0) = 1.0 + loads.parts()[0].model_part->coordinates(i, 0);
  loads.values("flag_b", "pressure").setConstant(5.0);
  bodies->initialize_step(1, 1.0);
  const Interface& moved = bodies->solve(loads);
  // Linear in x, so the two linear mappings carry it exactly: y = 1 (1 + x) on flag a, 2 * 5 on b.
  const auto on_a = moved.values("flag_a", "displacement");
  for (Eigen::Index i = 0; i < on_a.rows(); ++i)
    EXPECT_NEAR(on_a(i, 1), 1.0 + loads.parts()[0].model_part->coordinates(i, 0), 1e-12) << i;
  const auto on_b = moved.values("flag_b", "displacement");
  for (Eigen::Index i = 0; i < on_b.rows(); ++i) EXPECT_NEAR(on_b(i, 1), 10.0, 1e-12) << i;
  EXPECT_EQ(bodies->output_distances("flag_b").maxCoeff(), 0.0);
  bodies->finalize();
}

TEST(GroupSolverWrapper, OneModelPartSharedAlongItsLength) {
  // Points 0 .. 2 in steps of 0.1; a covers 0 .. 1 (11 nodes), b 1.1 .. 2 (10 nodes): the
  // points between 1 and 1.1 do not exist, so every point lies inside one member.
  Fluid fluid({line("wall", 21, 0.0, 2.0)});
  auto wall = group(
      member("a", "compliance: 1.0, points: 11, length: 1.0", "") + ", " +
      member("b", "compliance: 3.0, points: 10, length: 0.9", "frame_origin: [1.1, 0.0, 0.0]"));
  wall->adopt_interfaces(fluid.loads, fluid.displacement);
  Interface loads = fluid.loads;
  loads.values("wall", "pressure").setOnes();
  wall->initialize_step(1, 1.0);
  const auto moved = wall->solve(loads).values("wall", "displacement");
  for (Eigen::Index i = 0; i < 21; ++i) EXPECT_NEAR(moved(i, 1), i <= 10 ? 1.0 : 3.0, 1e-12) << i;
}

TEST(GroupSolverWrapper, TwoMembersInOnePlaceOrAMisspeltPartAreCaseErrors) {
  Fluid fluid({line("flag_a", 5, 0.0, 1.0), line("flag_b", 5, 2.0, 3.0)});
  auto bodies = group(member("a", "points: 3", "model_parts: [flag_a]") + ", " +
                      member("b", "points: 3", "model_parts: [flag_a]"));
  try {
    bodies->adopt_interfaces(fluid.loads, fluid.displacement);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    // Both cover flag_a from inside; flag_b is nobody's.
    EXPECT_NE(std::string(e.what()).find("covered equally by members 'a' and 'b'"),
              std::string::npos)
        << e.what();
  }
  auto misspelt = group(member("a", "points: 3", "model_parts: [flag_c]") + ", " +
                        member("b", "points: 3", "model_parts: [flag_b]"));
  try {
    misspelt->adopt_interfaces(fluid.loads, fluid.displacement);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("model_parts: 'flag_c' is not a model part of the other "
                                         "side's interface (it has: flag_a, flag_b); did you "
                                         "mean 'flag_a'?"),
              std::string::npos)
        << e.what();
  }
}

TEST(GroupSolverWrapper, AMembersRejectionReachesTheCoupledSolverAsARejection) {
  Fluid fluid({line("flag_a", 5, 0.0, 1.0), line("flag_b", 5, 2.0, 3.0)});
  auto bodies = group(member("a", "points: 3", "model_parts: [flag_a]") + ", " +
                      member("b", "points: 3, reject_above: 4.0, fail_above: 2.0",
                             "model_parts: [flag_b], frame_origin: [2.0, 0.0, 0.0]"));
  bodies->adopt_interfaces(fluid.loads, fluid.displacement);
  bodies->initialize_step(1, 1.0);
  Interface loads = fluid.loads;
  loads.values("flag_b", "pressure").setConstant(5.0);
  EXPECT_THROW(bodies->solve(loads), SolverRejectedInput);  // b, on its own thread
  loads.values("flag_b", "pressure").setConstant(3.0);
  try {
    bodies->solve(loads);
    FAIL() << "no error";
  } catch (const SolverRejectedInput&) {
    FAIL() << "a failure passed on as a rejection";
  } catch (const SolverError& e) {
    EXPECT_EQ(e.solver_name(), "b");
  }
  loads.values("flag_b", "pressure").setConstant(1.0);
  EXPECT_NEAR(bodies->solve(loads).values("flag_b", "displacement")(0, 1), 1.0, 1e-12);
}

}  // namespace
}  // namespace cocopp
