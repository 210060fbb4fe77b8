// A total force per face (`force`, mapped conservatively from the other solver's faces) becomes
// nodal forces that sum to it exactly: spread as a uniform traction's nodal forces are, and on
// a sector of a body of revolution (cylindrical *TRANSFORM) radial at every node, so that a
// sector takes no hoop load the other solver never gave. No ccx.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "solver_wrappers/calculix/interface_loads.hpp"
#include "tests/support/calculix_models.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp::calculix {
namespace {

using cocopp::testing::SectorCylinder;
using cocopp::testing::TemporaryDirectory;
using cocopp::testing::write_text;

class InterfaceLoadsTotals : public ::testing::Test {
 protected:
  InterfaceLoadsTotals() {
    cylinder_.axial = 3;
    write_text(directory_ / "wall.inp", cylinder_.deck());
    deck_ =
        std::make_unique<InputDeck>(InputDeck::read(directory_ / "wall.inp", directory_.path()));
    loads_ = std::make_unique<InterfaceLoads>(*deck_, deck_->surface("INNER"));
  }

  Eigen::Index faces() const { return static_cast<Eigen::Index>(loads_->faces().size()); }
  /// The unit vector away from the axis (z) at `point`.
  static Eigen::Vector3d outwards(const Eigen::Vector3d& point) {
    return Eigen::Vector3d(point.x(), point.y(), 0).normalized();
  }

  SectorCylinder cylinder_;
  TemporaryDirectory directory_;
  std::unique_ptr<InputDeck> deck_;
  std::unique_ptr<InterfaceLoads> loads_;
};

TEST_F(InterfaceLoadsTotals, TheNodesTakeEachFacesForceAlongTheAxisAndRadially) {
  RowMatrix force(faces(), 3);
  double axial = 0.0, radial = 0.0;
  for (Eigen::Index f = 0; f < faces(); ++f) {
    const Eigen::Vector3d centre = loads_->geometry()[static_cast<std::size_t>(f)].centroid;
    const double r = -1.0 - 0.5 * static_cast<double>(f), z = 0.1 * static_cast<double>(f);
    force.row(f) = (r * outwards(centre) + Eigen::Vector3d(0, 0, z)).transpose();
    axial += z;
    radial += r;
  }
  const auto nodal = loads_->nodal_forces_of_totals(force);
  double sum_axial = 0.0, sum_radial = 0.0, largest_hoop = 0.0;
  for (const auto& [node, global] : nodal) {
    const Eigen::Vector3d local = loads_->in_node_system(node, global);
    sum_radial += local.x();
    largest_hoop = std::max(largest_hoop, std::abs(local.y()));
    sum_axial += local.z();
    // Each node's force lies in its own plane through the axis.
    EXPECT_NEAR(global.cross(Eigen::Vector3d::UnitZ()).dot(outwards(deck_->node(node))), 0.0,
                1e-12 * global.norm() + 1e-300);
  }
  EXPECT_NEAR(sum_axial, axial, 1e-13 * std::abs(radial));
  EXPECT_NEAR(sum_radial, radial, 1e-13 * std::abs(radial));
  EXPECT_LT(largest_hoop, 1e-13 * std::abs(radial));
}

TEST_F(InterfaceLoadsTotals, AUniformPressuresTotalsGiveThePressureBack) {
  // The total of a uniform pressure p on each face is -p times the integral of its outward
  // normal: the mean pressure the drive's film stiffness takes is p.
  const double p = 2.5e6;
  RowMatrix force(faces(), 3);
  for (Eigen::Index f = 0; f < faces(); ++f)
    force.row(f) =
        -p * loads_->geometry()[static_cast<std::size_t>(f)].normal_weights.colwise().sum();
  const Eigen::VectorXd pressure = loads_->pressure_of_totals(force);
  for (Eigen::Index f = 0; f < faces(); ++f) EXPECT_NEAR(pressure[f], p, 1e-9 * p);
}

}  // namespace
}  // namespace cocopp::calculix
