// ExactRoundTrip: a wall position given at a film's points, mapped onto a structure's nodes so
// that the output mapper gives it back exactly; alone and through the mapped wrapper's
// `exact_round_trip` key.
#include <gtest/gtest.h>

#include <cmath>

#include "solver_wrappers/mapped/exact_round_trip.hpp"
#include "solver_wrappers/solver_wrapper.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/linear_solvers.hpp"

namespace cocopp {
namespace {

Coordinates on_axis(int points, double z0, double z1) {
  Coordinates coordinates = Coordinates::Zero(points, 3);
  for (int i = 0; i < points; ++i) coordinates(i, 2) = z0 + (z1 - z0) * i / (points - 1);
  return coordinates;
}

Mapper linear_mapper(const std::string& more = "") {
  return Mapper(Settings::load_string("{type: linear, directions: [z]" + more + "}", "test"));
}

/// The film: 61 points on z in [0, 1]; the wire: 12 nodes every 0.1 from -0.05, none at a
/// film point.
struct Sides {
  Coordinates film = on_axis(61, 0.0, 1.0), wire = on_axis(12, -0.05, 1.05);
  Mapper input = linear_mapper(), output = linear_mapper(", components: [y]");
  std::vector<Eigen::Index> rows = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  Sides() {
    input.initialize(film, wire);
    output.initialize(wire, film);
  }
  /// A bent wall at the nodes (radial, y), and where the output mapper puts it at the film.
  RowMatrix nodal_wall() const {
    RowMatrix u = RowMatrix::Zero(wire.rows(), 3);
    for (Eigen::Index k = 0; k < wire.rows(); ++k) u(k, 1) = 1e-3 * std::sin(3.0 * wire(k, 2));
    return u;
  }
};

// The wall a wire's output makes at the film comes back to the same nodes: the plain
// interpolation cuts the bends (h^2 w'' / 8 ~ 1e-5 here), the exact round trip does not.
TEST(ExactRoundTrip, GivesTheNodesWhoseOutputIsTheWall) {
  Sides sides;
  const RowMatrix u = sides.nodal_wall();
  const RowMatrix wall = sides.output.map(u);
  ExactRoundTrip round_trip;
  round_trip.build(sides.input, sides.rows, sides.output, wall.rows(), 3);
  const RowMatrix v = round_trip.map(wall);
  EXPECT_LT((v - u).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((sides.output.map(v) - wall).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_GT((sides.input.map(wall) - u).cwiseAbs().maxCoeff(), 1e-6);  // what it repairs
  EXPECT_GT(round_trip.plain_defect(), 1e-6);
  EXPECT_LT(round_trip.defect(), 1e-15);
}

// A component that the output mapper does not give back (x here) is mapped as the input
// mapper maps it; a wall that no nodes make is met as closely as any nodes can.
TEST(ExactRoundTrip, LeavesWhatItCannotReachAndMeetsTheRestBest) {
  Sides sides;
  RowMatrix wall = sides.output.map(sides.nodal_wall());
  for (Eigen::Index i = 0; i < wall.rows(); ++i) {
    wall(i, 0) = std::cos(5.0 * sides.film(i, 2));
    wall(i, 1) += 1e-4 * std::cos(40.0 * sides.film(i, 2));  // finer than the nodes
  }
  ExactRoundTrip round_trip;
  round_trip.build(sides.input, sides.rows, sides.output, wall.rows(), 3);
  const RowMatrix v = round_trip.map(wall);
  const RowMatrix plain = sides.input.map(wall);
  EXPECT_LT((v.col(0) - plain.col(0)).cwiseAbs().maxCoeff(), 1e-15);
  // Least squares over the film's points: the miss is orthogonal to every node's footprint.
  const Eigen::VectorXd miss = wall.col(1) - sides.output.map(v).col(1);
  for (Eigen::Index k = 0; k < sides.wire.rows(); ++k) {
    RowMatrix unit = RowMatrix::Zero(sides.wire.rows(), 3);
    unit(k, 1) = 1.0;
    EXPECT_NEAR(sides.output.map(unit).col(1).dot(miss), 0.0, 1e-15) << "node " << k;
  }
  EXPECT_LT(miss.norm(), (wall.col(1) - sides.output.map(plain).col(1)).norm());
}

// Nodes the structure does not drive (here the two ends) enter as they are: the driven ones
// are solved for so that, with the held ones' displacement, the output gives the wall.
TEST(ExactRoundTrip, HeldNodesEnterAsTheyAre) {
  Sides sides;
  const RowMatrix u = sides.nodal_wall();
  const RowMatrix wall = sides.output.map(u);
  std::vector<bool> held(12, false);
  held.front() = held.back() = true;
  RowMatrix base = RowMatrix::Zero(12, 3);
  base.row(0) = u.row(0);
  base.row(11) = u.row(11);
  ExactRoundTrip round_trip;
  round_trip.build(sides.input, sides.rows, sides.output, wall.rows(), 3);
  round_trip.hold(held);
  RowMatrix v = round_trip.map(wall, base);
  EXPECT_LT((v.middleRows(1, 10) - u.middleRows(1, 10)).cwiseAbs().maxCoeff(), 1e-15);
  v.row(0) = u.row(0);
  v.row(11) = u.row(11);
  EXPECT_LT((sides.output.map(v) - wall).cwiseAbs().maxCoeff(), 1e-15);
  // Held elsewhere than they stand, the driven nodes next to them make up for it.
  base.row(0) *= 2.0;
  const RowMatrix shifted = round_trip.map(wall, base);
  EXPECT_GT((shifted.row(1) - u.row(1)).cwiseAbs().maxCoeff(), 1e-6);
}

/// Test solvers for the mapped wrapper: a film that gives its wall position (`wall` on its 61
/// points) and takes a displacement, and a wall whose 12 nodes take `wall_displacement` and
/// return it as their displacement. With `holds_ends: true` it does not drive its end nodes:
/// they return the bent wall of Sides::nodal_wall (as loaded nodes would their own
/// displacement), and the nodes report `driven`.
class Film : public testing::InProcessSolver {
 public:
  explicit Film(const RowMatrix& wall) : InProcessSolver("film", Interface(), Interface()) {
    auto part = std::make_shared<ModelPart>();
    part->name = "film";
    part->coordinates = on_axis(61, 0.0, 1.0);
    for (int i = 0; i < 61; ++i) part->ids.push_back(i);
    input_ = Interface({{part, {"displacement"}}});
    output_ = Interface({{part, {"wall_displacement"}}});
    output_.values("film", "wall_displacement") = wall;
  }
  const Interface& solve(const Interface&) override { return output_; }
};

class WallNodes : public testing::InProcessSolver {
 public:
  WallNodes(const Settings& settings, const RunSettings&)
      : InProcessSolver("wall", Interface(), Interface()) {
    auto nodes = std::make_shared<ModelPart>();
    nodes->name = "nodes";
    nodes->coordinates = Sides().wire;
    for (int i = 0; i < 12; ++i) nodes->ids.push_back(100 + i);
    input_ = Interface({{nodes, {"wall_displacement"}}});
    auto returned = nodes;
    if (settings.get<bool>("other_nodes", false)) {  // returns nodes it is not driven at
      returned = std::make_shared<ModelPart>(*nodes);
      returned->name = "returned";
      returned->ids.back() = 999;
    }
    holds_ends_ = settings.get<bool>("holds_ends", false);
    output_ = Interface({{returned, holds_ends_ ? std::vector<std::string>{"displacement", "driven"}
                                                : std::vector<std::string>{"displacement"}}});
  }
  const Interface& solve(const Interface& input) override {
    auto displacement = output_.values(output_.parts()[0].model_part->name, "displacement");
    displacement = input.values("nodes", "wall_displacement");
    if (holds_ends_) {
      const RowMatrix wall = Sides().nodal_wall();
      auto driven = output_.values("nodes", "driven");
      driven.setOnes();
      for (const Eigen::Index end : {Eigen::Index{0}, Eigen::Index{11}}) {
        displacement.row(end) = wall.row(end);
        driven(end, 0) = 0.0;
      }
    }
    return output_;
  }

 private:
  bool holds_ends_ = false;
};

COCOPP_REGISTER(SolverWrapperRegistry, "test_wall_nodes", WallNodes)

std::unique_ptr<SolverWrapper> mapped_wall(const Film& film, const std::string& variables,
                                           const std::string& wall_keys = "") {
  const Settings settings = Settings::load_string(
      "type: mapped\nsolver_wrapper: {type: test_wall_nodes" + wall_keys +
          "}\ninput_mapper: {type: linear, directions: [z]}\noutput_mapper: {type: linear, "
          "directions: [z], components: [y]}\nexact_round_trip: " +
          variables + "\n",
      "case.yaml");
  auto mapped = SolverWrapperRegistry::instance().create(settings, RunSettings{});
  settings.check_unused_keys();
  mapped->initialize();
  mapped->adopt_interfaces(film.output_interface(), film.input_interface());
  return mapped;
}

// Through the mapped wrapper: the wall driven by the film's wall position returns it exactly.
TEST(ExactRoundTrip, MappedWrapperReturnsTheFilmsWall) {
  Sides sides;
  const RowMatrix wall = sides.output.map(sides.nodal_wall());
  Film film(wall);
  auto mapped = mapped_wall(film, "[wall_displacement]");
  mapped->initialize_step(1, 1.0);
  const Interface& returned = mapped->solve(film.output_interface());
  EXPECT_LT((returned.values("film", "displacement") - wall).cwiseAbs().maxCoeff(), 1e-15);

  auto plain = mapped_wall(film, "[]");
  plain->initialize_step(1, 1.0);
  const Interface& missed = plain->solve(film.output_interface());
  EXPECT_GT((missed.values("film", "displacement") - wall).cwiseAbs().maxCoeff(), 1e-6);
}

// A wall that drives all but its end nodes: the film's wall comes back exactly once the wall
// has reported which nodes it holds (from the second solve on).
TEST(ExactRoundTrip, MappedWrapperHoldsTheNodesTheSolverDoesNotDrive) {
  Sides sides;
  const RowMatrix wall = sides.output.map(sides.nodal_wall());
  Film film(wall);
  auto mapped = mapped_wall(film, "[wall_displacement]", ", holds_ends: true");
  mapped->initialize_step(1, 1.0);
  mapped->solve(film.output_interface());
  const Interface& returned = mapped->solve(film.output_interface());
  EXPECT_LT((returned.values("film", "displacement") - wall).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(ExactRoundTrip, MappedWrapperNamesWhatIsWrong) {
  Film film(RowMatrix::Zero(61, 3));
  const std::string typo =
      testing::error_message<std::runtime_error>([&] { mapped_wall(film, "[wall_displacment]"); });
  EXPECT_NE(typo.find("case.yaml:5"), std::string::npos) << typo;
  EXPECT_NE(typo.find("did you mean 'wall_displacement'"), std::string::npos) << typo;
  const std::string nodes = testing::error_message<std::runtime_error>(
      [&] { mapped_wall(film, "[wall_displacement]", ", other_nodes: true"); });
  EXPECT_NE(nodes.find("point 999 of 'returned' (output) is not in 'nodes'"), std::string::npos)
      << nodes;
}

}  // namespace
}  // namespace cocopp
