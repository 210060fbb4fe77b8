// The displacement drive puts the loaded faces where the coupling iteration puts the surface
// in an NLGEOM step (DisplacementDrive::plan): the other solver computed its loads on its wall
// at this iteration's position, so the nodal forces of its traction are the traction times the
// area there, not the deck's area nor that of faces moved on one side of a sector only. Without
// NLGEOM ccx takes loads on the deck's geometry, and so does the drive. No ccx.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "solver_wrappers/calculix/displacement_drive.hpp"
#include "tests/support/calculix_models.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp::calculix {
namespace {

using cocopp::testing::SectorCylinder;
using cocopp::testing::TemporaryDirectory;
using cocopp::testing::write_text;

constexpr double kPi = 3.14159265358979323846;
constexpr double kShear = 2e3;        ///< Pa, along the axis
constexpr double kRadialWall = 1e-4;  ///< m: the wall 1 % of the bore's radius out

class DriveFaces : public ::testing::Test {
 protected:
  DriveFaces() {
    cylinder_.axial = 3;
    cylinder_.nlgeom = true;
    write_text(directory_ / "wall.inp", cylinder_.deck());
    deck_ =
        std::make_unique<InputDeck>(InputDeck::read(directory_ / "wall.inp", directory_.path()));
    loads_ = std::make_unique<InterfaceLoads>(*deck_, deck_->surface("INNER"));
    nodes_ = deck_->node_set("INNERN");
    std::sort(nodes_.begin(), nodes_.end());
    // Returned: one side of the sector (the drive balances every node it drives).
    drive_ = std::make_unique<DisplacementDrive>(*deck_, *loads_, nodes_, nodes_, 1, 1e15);
  }

  /// Every face covered, a uniform axial shear, the wall `kRadialWall` out at every node.
  DisplacementDrive::Inputs inputs() const {
    const auto faces = static_cast<Eigen::Index>(loads_->faces().size());
    const auto nodes = static_cast<Eigen::Index>(nodes_.size());
    DisplacementDrive::Inputs in{
        Eigen::VectorXd::Zero(faces), RowMatrix::Zero(faces, 3),    RowMatrix(),
        Eigen::VectorXd::Ones(faces), Eigen::VectorXd::Ones(faces), RowMatrix::Zero(nodes, 3)};
    in.traction.col(2).setConstant(kShear);
    for (Eigen::Index n = 0; n < nodes; ++n) {
      const Eigen::Vector3d x = deck_->node(nodes_[static_cast<std::size_t>(n)]);
      in.wall_displacement.row(n) = kRadialWall * Eigen::RowVector3d(x.x(), x.y(), 0).normalized();
    }
    return in;
  }

  double axial_force() const {
    double sum = 0.0;
    for (const auto& [node, force] : drive_->film_forces()) sum += force.z();
    return sum;
  }

  /// The shear's force on the bore at radius r over an axial length.
  double expected(double radius, double length) const {
    return kShear * radius * cylinder_.angle_degrees * kPi / 180.0 * length;
  }

  SectorCylinder cylinder_;
  TemporaryDirectory directory_;
  std::unique_ptr<InputDeck> deck_;
  std::unique_ptr<InterfaceLoads> loads_;
  std::vector<std::int64_t> nodes_;
  std::unique_ptr<DisplacementDrive> drive_;
};

TEST_F(DriveFaces, TheTractionActsOnTheAreaWhereTheWallPutsTheSurface) {
  drive_->plan(inputs(), {});
  EXPECT_NEAR(axial_force(), expected(cylinder_.ri + kRadialWall, cylinder_.length),
              1e-9 * expected(cylinder_.ri, cylinder_.length));
}

TEST_F(DriveFaces, TheLastConvergedStepGivesTheOtherDirections) {
  // Converged: every surface node (both sides of the sector) stretched 1 % along the axis and
  // 5e-5 m out; this iteration's wall takes the driven (radial) direction from there.
  NodeDisplacements converged;
  for (const auto node : nodes_) {
    const Eigen::Vector3d x = deck_->node(node);
    converged[node] =
        5e-5 * Eigen::Vector3d(x.x(), x.y(), 0).normalized() + Eigen::Vector3d(0, 0, 0.01 * x.z());
  }
  drive_->plan(inputs(), converged);
  EXPECT_NEAR(axial_force(), expected(cylinder_.ri + kRadialWall, 1.01 * cylinder_.length),
              1e-9 * expected(cylinder_.ri, cylinder_.length));
}

TEST_F(DriveFaces, GivenTotalsTheStructureTakesTheOtherSolversForceExactly) {
  // The other solver's force per face (a film's, mapped conservatively): the structure's nodal
  // forces sum to it along the axis and across it, wherever the faces stand, and the film's
  // stiffness sees the faces' mean pressure.
  auto in = inputs();
  const auto faces = static_cast<Eigen::Index>(loads_->faces().size());
  in.force = RowMatrix::Zero(faces, 3);
  double axial = 0.0, radial = 0.0;
  for (Eigen::Index f = 0; f < faces; ++f) {
    const Eigen::Vector3d centre = loads_->geometry()[static_cast<std::size_t>(f)].centroid;
    const Eigen::Vector3d outwards = Eigen::Vector3d(centre.x(), centre.y(), 0).normalized();
    const double pushed = 0.3 + 0.1 * static_cast<double>(f);  // N, outwards into the wall
    const double dragged = 0.02 * static_cast<double>(f + 1);  // N, along the axis
    in.force.row(f) = (pushed * outwards + Eigen::Vector3d(0, 0, dragged)).transpose();
    axial += dragged;
    radial += pushed;
  }
  drive_->plan(in, {});
  double film_axial = 0.0, film_radial = 0.0, film_hoop = 0.0;
  for (const auto& [node, force] : drive_->film_forces()) {
    const Eigen::Vector3d local = loads_->in_node_system(node, force);  // radial, hoop, axial
    film_radial += local.x();
    film_hoop += local.y();
    film_axial += local.z();
  }
  EXPECT_NEAR(film_axial, axial, 1e-13 * axial);
  EXPECT_NEAR(film_radial, radial, 1e-13 * radial);
  EXPECT_NEAR(film_hoop, 0.0, 1e-13 * radial);
}

TEST_F(DriveFaces, WithoutNonlinearGeometryTheDecksFacesCarryTheLoads) {
  cylinder_.nlgeom = false;
  write_text(directory_ / "linear.inp", cylinder_.deck());
  const InputDeck linear = InputDeck::read(directory_ / "linear.inp", directory_.path());
  InterfaceLoads loads(linear, linear.surface("INNER"));
  DisplacementDrive drive(linear, loads, nodes_, nodes_, 1, 1e15);
  drive.plan(inputs(), {});
  double sum = 0.0;
  for (const auto& [node, force] : drive.film_forces()) sum += force.z();
  EXPECT_NEAR(sum, expected(cylinder_.ri, cylinder_.length),
              1e-9 * expected(cylinder_.ri, cylinder_.length));
}

}  // namespace
}  // namespace cocopp::calculix
