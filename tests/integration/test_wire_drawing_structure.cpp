// The wire drawing example's wire alone (examples/wire_drawing/make_case.py's CalculiX deck)
// behind the calculix wrapper, with no film load: described in a frame that moves with its exit
// end (the case's frame_velocity), held at that end against the back force on its entry end, it
// must stretch as a bar in uniform tension, sigma = F / (pi R^2): u_z = -(sigma / E)(z_exit - z),
// and narrow by the Poisson contraction, u_r = -nu (sigma / E) R, in every step alike. Needs
// ccx; built only where CMake found it.
#include <gtest/gtest.h>

#include <cmath>

#include "solver_wrappers/calculix/surface_compliance.hpp"
#include "solver_wrappers/solver_wrapper.hpp"
#include "tests/support/run_in.hpp"
#include "tests/support/solver_wrapper_case.hpp"
#include "tests/support/wire_drawing_case.hpp"

namespace cocopp {
namespace {

// examples/wire_drawing/parameters.yaml
constexpr double kRadius = 0.75e-3, kLength = 30e-3, kStart = -20e-3;
constexpr double kBackForce = 100.0, kYoung = 177e9, kPoisson = 0.3;
constexpr double kDeltaT = 1e-4;

/// The wire of make_case.py `arguments` (axial elements `axial`) in uniform tension.
void expect_bar_in_uniform_tension(const std::string& arguments, int axial) {
  testing::TemporaryDirectory directory;
  testing::write_wire_drawing_case(directory.path(), arguments, /*mesh_film=*/false);
  auto wire = testing::initialized_wrapper(
      "type: calculix\nname: wire\nworking_directory: structure\ninput_file: wire.inp\n"
      "interface_surface: SURFACE\ninterface_node_set: SURFACEN\nsave_results: false\n",
      directory.path(), kDeltaT);
  Interface loads = wire->input_interface();
  loads.set_data(Eigen::VectorXd::Zero(loads.size()));

  const double strain = kBackForce / (M_PI * kRadius * kRadius) / kYoung;
  for (int step = 1; step <= 2; ++step) {
    wire->initialize_step(step, step * kDeltaT);
    const Interface& displacement = wire->solve(loads);
    wire->finalize_step();
    const auto& points = displacement.parts()[0].model_part->coordinates;  // x = r, y = z
    const Eigen::MatrixXd u = displacement.values("SURFACEN", "displacement");
    ASSERT_EQ(points.rows(), 2 * axial + 1);
    double axial = 0.0, radial = 0.0;
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      const double expected = -strain * (kStart + kLength - points(i, 1));
      axial = std::max(axial, std::abs(u(i, 1) - expected));
      radial = std::max(radial, std::abs(u(i, 0) + kPoisson * strain * kRadius));
    }
    // Against the stretch of the whole wire, 9.6 um, and the contraction, 0.072 um.
    EXPECT_LT(axial, 1e-3 * strain * kLength) << "step " << step;
    EXPECT_LT(radial, 1e-2 * kPoisson * strain * kRadius) << "step " << step;
    std::printf("step %d: axial difference %.3g m, radial %.3g m\n", step, axial, radial);
  }
  wire->finalize();
}

TEST(WireDrawingStructure, TheWireAloneIsABarInUniformTension) {
  expect_bar_in_uniform_tension(testing::kLoadDrivenWire, 306);
}

// The wire as a 1 degree 3D sector (the case's default, mesh.wire_model: sector, what
// coupling.drive: displacement needs: C3D20R, its outer layer C3D20, C3D15 at the axis,
// cylindrical *TRANSFORM, hoop held), on the coarse grid: the same bar, its x-y side returned.
TEST(WireDrawingStructure, TheSectorWireIsTheSameBar) {
  expect_bar_in_uniform_tension(
      "--set mesh.wire_radial_elements=4 "
      "--set mesh.wire_axial_elements=153",
      153);
}

// examples/wire_drawing/surface_compliance.py (the drive's `surface_compliance`) on the coarse
// sector: every surface line in the file, a symmetric compliance, and its answer to a uniform
// pressure within 5e-3 of the solid cylinder's u = p R (1 - nu) / E (the script refuses 1e-2).
TEST(WireDrawingStructure, TheSurfaceComplianceAnswersAUniformPressure) {
  testing::TemporaryDirectory directory;
  testing::write_wire_drawing_case(
      directory.path(), "--set mesh.wire_radial_elements=4 --set mesh.wire_axial_elements=153",
      /*mesh_film=*/false);
  testing::run_in(directory.path(),
                  "/usr/bin/python3 " +
                      (testing::kWireDrawingExample / "surface_compliance.py").string() + " .");
  const std::string log = testing::read_text(directory / "log.setup");
  const auto at = log.find("the compliance's answer ");
  ASSERT_NE(at, std::string::npos) << log;
  const double difference =
      std::stod(log.substr(at + std::string("the compliance's answer ").size()));
  EXPECT_LT(std::abs(difference), 5e-3) << log;
  const auto compliance =
      calculix::SurfaceCompliance::read(directory / "structure" / "surface_compliance.txt");
  EXPECT_EQ(compliance.lines(), 2 * 153 + 1);
  std::vector<Eigen::Index> all(static_cast<std::size_t>(compliance.lines()));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Eigen::Index>(i);
  const Eigen::MatrixXd matrix = compliance.block(all);
  EXPECT_LT((matrix - matrix.transpose()).cwiseAbs().maxCoeff(), 1e-12 * matrix.maxCoeff());
  EXPECT_GT(matrix.diagonal().minCoeff(), 0.0);
}

}  // namespace
}  // namespace cocopp
