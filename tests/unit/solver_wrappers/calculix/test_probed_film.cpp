// ProbedFilm (probed_film.hpp): a film's finite-difference sensitivity as the displacement
// drive's film stiffness between its lines, on a made-up film whose answer is known: ten faces
// of 1 mm, eleven wall lines, each line's move changing the traction of its two faces only.
#include <gtest/gtest.h>

#include <fstream>

#include "solver_wrappers/calculix/probed_film.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp::calculix {
namespace {

constexpr double kPitch = 1e-3, kGap = 1e-6, kStiffness = 1e15;  // m, m, Pa/m

/// The film's pressure on face f: rising along the axis, so that its 2 p / gap places the film.
double pressure(int face) {
  return 1e6 * (1.0 + face);
}

std::filesystem::path write_probe(const std::filesystem::path& directory) {
  const auto file = directory / "probe.txt";
  std::ofstream out(file);
  out << "# cocoppPimpleFoam sensitivity probe: step 7, each hoop line of wall points moved "
         "radially by 1e-08 m\n# faces 10: axial and radial position of the centre (m), area "
         "(m^2), gap (m), radial and axial force (N)\n";
  for (int f = 0; f < 10; ++f)
    out << (f + 0.5) * kPitch << " 1e-3 2e-6 " << kGap << ' ' << -pressure(f) * 2e-6 << " 0\n";
  out << "# lines 11: axial position (m), then per face the change of its radial force, then of "
         "its axial force (N per m of move)\n";
  for (int j = 0; j <= 10; ++j) {
    out << j * kPitch;
    for (int f = 0; f < 10; ++f) out << ' ' << (f == j - 1 || f == j ? -kStiffness * 2e-6 : 0.0);
    for (int f = 0; f < 10; ++f) out << " 0";
    out << '\n';
  }
  return file;
}

TEST(ProbedFilm, GivesTheFilmsStiffnessAtTheStructuresLines) {
  const testing::TemporaryDirectory directory;
  const ProbedFilm film = ProbedFilm::read(write_probe(directory.path()));
  EXPECT_EQ(film.step(), 7);
  // The structure's lines sit on the film's lines 2..8, their reference 3 mm behind the film's.
  constexpr double kOffset = 3e-3;
  Eigen::VectorXd axial(7), weight = Eigen::VectorXd::Constant(7, 2.0), local(7);
  for (int l = 0; l < 7; ++l) {
    axial[l] = (l + 2) * kPitch - kOffset;
    local[l] = (pressure(l + 1) + pressure(l + 2)) / kGap;  // 2 p / gap between its faces
  }
  const Eigen::MatrixXd k = film.stiffness(axial, weight, local);
  EXPECT_NEAR(film.offset(), kOffset, 1e-7);
  for (int l = 0; l < 7; ++l) {
    // A line's own move: both its faces' traction change by -kStiffness, so at the line -k.
    EXPECT_NEAR(k(l, l), 2.0 * kStiffness, 1e-3 * kStiffness) << l;
    // A neighbour's move changes one of the two faces: half of that at the line.
    if (l + 1 < 7) {
      EXPECT_NEAR(k(l, l + 1), kStiffness, 1e-3 * kStiffness) << l;
    }
    if (l + 2 < 7) {
      EXPECT_NEAR(k(l, l + 2), 0.0, 1e-3 * kStiffness) << l;
    }
  }
}

TEST(ProbedFilm, AFileItCannotReadIsNamed) {
  const testing::TemporaryDirectory directory;
  try {
    ProbedFilm::read(directory / "none.txt");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("none.txt: cannot be read"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace cocopp::calculix
