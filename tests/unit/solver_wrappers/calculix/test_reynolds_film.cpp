// ReynoldsFilm (reynolds_film.hpp): the film model the displacement drive takes its film's
// stiffness from, against the slider bearing's closed form (a gap falling linearly from h_in
// to h_out under a wall sliding towards the outlet), and the gradient's exact properties.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "solver_wrappers/calculix/reynolds_film.hpp"

namespace cocopp::calculix {
namespace {

constexpr double kLength = 1e-3, kInlet = 10e-6, kOutlet = 4e-6;

/// The slider bearing's pressure for 6 eta U = 1: dp/dz = 1/h^2 - h*/h^3, p = 0 at both ends,
/// h* = 2 h_in h_out / (h_in + h_out).
double slider_pressure(double z) {
  const double slope = (kOutlet - kInlet) / kLength, h = kInlet + slope * z;
  const double h_star = 2.0 * kInlet * kOutlet / (kInlet + kOutlet);
  return ((1.0 / kInlet - 1.0 / h) + 0.5 * h_star * (1.0 / (h * h) - 1.0 / (kInlet * kInlet))) /
         slope;
}

struct Chain {
  Eigen::VectorXd position, length, gap, pressure;
};

Chain slider(Eigen::Index faces, double pressure_scale) {
  Chain chain{Eigen::VectorXd(faces), Eigen::VectorXd::Constant(faces, kLength / faces),
              Eigen::VectorXd(faces), Eigen::VectorXd(faces)};
  for (Eigen::Index k = 0; k < faces; ++k) {
    const double z = (static_cast<double>(k) + 0.5) * kLength / static_cast<double>(faces);
    chain.position[k] = z;
    chain.gap[k] = kInlet + (kOutlet - kInlet) * z / kLength;
    chain.pressure[k] = pressure_scale * slider_pressure(z);
  }
  return chain;
}

TEST(ReynoldsFilm, FitsTheSliderBearingsPressureAndItsScale) {
  // Given the closed form times 3e9 (6 eta U), the model finds that factor and the profile,
  // to what its constant-gap half faces at both ends leave (O(1/faces)).
  const Chain chain = slider(400, 3e9);
  const ReynoldsFilm film(chain.position, chain.length, chain.gap, chain.pressure);
  EXPECT_LT(film.misfit(), 3e-3);
  const Eigen::VectorXd p = film.pressure();
  EXPECT_LT((p - chain.pressure).cwiseAbs().maxCoeff(), 5e-3 * chain.pressure.maxCoeff());
}

TEST(ReynoldsFilm, SlidingTheOtherWayFitsANegativeScale) {
  const Chain chain = slider(100, -1.0);
  const ReynoldsFilm film(chain.position, chain.length, chain.gap, chain.pressure);
  EXPECT_LT(film.misfit(), 2e-2);
  EXPECT_LT((film.pressure() - chain.pressure).cwiseAbs().maxCoeff(),
            2e-2 * chain.pressure.cwiseAbs().maxCoeff());
}

TEST(ReynoldsFilm, PressureGoesAsOneOverTheGapSquared) {
  // Every gap scaled by s scales the pressure by 1/s^2, so sum_g dp_f/dh_g h_g = -2 p_f
  // (Euler): the local 2 p / gap is the gradient's row sum, spread over the film.
  const Chain chain = slider(40, 2e9);
  const ReynoldsFilm film(chain.position, chain.length, chain.gap, chain.pressure);
  const Eigen::VectorXd euler = film.pressure_gradient() * chain.gap;
  EXPECT_LT((euler + 2.0 * film.pressure()).cwiseAbs().maxCoeff(),
            1e-6 * film.pressure().maxCoeff());
}

TEST(ReynoldsFilm, AThinnerOutletRaisesThePressureAlongTheWholeFilm) {
  // Not local: the outlet face's gap sets the flow rate, and with it the pressure upstream.
  const Chain chain = slider(40, 2e9);
  const ReynoldsFilm film(chain.position, chain.length, chain.gap, chain.pressure);
  const Eigen::VectorXd outlet = film.pressure_gradient().col(39);
  for (Eigen::Index f = 0; f < 39; ++f) EXPECT_LT(outlet[f], 0.0) << "face " << f;
  EXPECT_GT(std::abs(outlet[5]), 0.05 * std::abs(outlet[39]));
}

TEST(ReynoldsFilm, RefusesAChainItCannotModel) {
  const Chain chain = slider(4, 1.0);
  Eigen::VectorXd gap = chain.gap;
  gap[2] = 0.0;
  EXPECT_THROW(ReynoldsFilm(chain.position, chain.length, gap, chain.pressure),
               std::invalid_argument);
  Eigen::VectorXd position = chain.position;
  position[2] = position[1];
  EXPECT_THROW(ReynoldsFilm(position, chain.length, chain.gap, chain.pressure),
               std::invalid_argument);
  EXPECT_THROW(ReynoldsFilm(chain.position.head(1), chain.length.head(1), chain.gap.head(1),
                            chain.pressure.head(1)),
               std::invalid_argument);
}

}  // namespace
}  // namespace cocopp::calculix
