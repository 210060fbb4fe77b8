// Waveform: the interpolation in time of a solver's samples over a coupling window, exact for
// polynomials of its degree; a sample's own time gives the sample bit for bit; the mean over a
// coarser receiver's substeps is the interpolant's exact mean; the history a new window keeps.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "coupler/schemes/waveform.hpp"

namespace cocopp {
namespace {

using Function = std::function<double(double)>;

/// A waveform of two values, f(t) and 2 f(t), over the window [1, 2] (in window fractions t - 1),
/// with its history from the window [0, 1] before it.
Waveform sampled(const Function& f, int samples, Waveform::Interpolation interpolation) {
  Waveform waveform(2, samples, interpolation);
  auto at = [&](double t) { return Eigen::Vector2d(f(t), 2.0 * f(t)); };
  waveform.reset(at(0.0));
  Eigen::MatrixXd previous(2, samples), current(2, samples);
  for (int j = 1; j <= samples; ++j) {
    previous.col(j - 1) = at(static_cast<double>(j) / samples);
    current.col(j - 1) = at(1.0 + static_cast<double>(j) / samples);
  }
  waveform.set_samples(previous);
  waveform.begin_window();
  waveform.set_samples(current);
  return waveform;
}

void expect_exact(const Function& f, int samples, int substeps,
                  Waveform::Interpolation interpolation) {
  const Eigen::MatrixXd values = sampled(f, samples, interpolation).at(substeps);
  for (int i = 1; i <= substeps; ++i) {
    const double t = 1.0 + static_cast<double>(i) / substeps;
    EXPECT_NEAR(values(0, i - 1), f(t), 1e-12) << "t " << t << ", " << samples << " samples";
    EXPECT_NEAR(values(1, i - 1), 2.0 * f(t), 1e-12);
  }
}

TEST(Waveform, LinearIsExactForStraightLines) {
  const Function line = [](double t) { return 3.0 - 2.0 * t; };
  for (const int samples : {1, 2, 3})
    for (const int substeps : {1, 2, 4, 5, 7})
      expect_exact(line, samples, substeps, Waveform::Interpolation::kLinear);
}

TEST(Waveform, QuadraticIsExactForParabolasAlsoWithOneSampleAWindow) {
  const Function parabola = [](double t) { return 1.0 + t - 3.0 * t * t; };
  for (const int samples : {1, 2, 3, 4})  // one sample: through the last window's start
    for (const int substeps : {1, 3, 4, 8})
      expect_exact(parabola, samples, substeps, Waveform::Interpolation::kQuadratic);
  // ... and not for a cubic: the test can fail.
  const Function cubic = [](double t) { return t * t * t; };
  const Eigen::MatrixXd values = sampled(cubic, 2, Waveform::Interpolation::kQuadratic).at(4);
  EXPECT_GT(std::abs(values(0, 0) - cubic(1.25)), 1e-3);
}

TEST(Waveform, ConstantTakesTheNextSample) {
  const Function line = [](double t) { return t; };
  const Eigen::MatrixXd values = sampled(line, 2, Waveform::Interpolation::kConstant).at(4);
  EXPECT_EQ(values(0, 0), 1.5);
  EXPECT_EQ(values(0, 1), 1.5);
  EXPECT_EQ(values(0, 2), 2.0);
  EXPECT_EQ(values(0, 3), 2.0);
}

TEST(Waveform, ASamplesOwnTimeGivesTheSampleBitForBit) {
  // 0.1 is not a binary fraction: any arithmetic on the samples would show.
  const Function f = [](double t) { return 0.1 * std::exp(t); };
  for (const auto interpolation :
       {Waveform::Interpolation::kLinear, Waveform::Interpolation::kQuadratic}) {
    const Waveform waveform = sampled(f, 4, interpolation);
    const Eigen::MatrixXd two = waveform.at(2), four = waveform.at(4);
    EXPECT_EQ(two(0, 0), waveform.samples()(0, 1));
    EXPECT_EQ(two(0, 1), waveform.samples()(0, 3));
    for (int j = 0; j < 4; ++j) EXPECT_EQ(four(0, j), waveform.samples()(0, j));
  }
}

TEST(Waveform, TheMeanOverACoarserSubstepIsTheInterpolantsExactMean) {
  // Linear between samples of t^2 at quarters of the window [1, 2]: the mean over the whole
  // window is the trapezoidal rule's, over each half the trapezoids of its two quarters.
  const Function square = [](double t) { return t * t; };
  const Waveform linear = sampled(square, 4, Waveform::Interpolation::kLinear);
  auto q = [&](double x) { return square(1.0 + x); };
  const double trapezoids = 0.25 * (0.5 * q(0) + q(0.25) + q(0.5) + q(0.75) + 0.5 * q(1.0));
  EXPECT_NEAR(linear.mean(1)(0, 0), trapezoids, 1e-14);
  EXPECT_NEAR(linear.mean(2)(0, 1), 2.0 * 0.25 * (0.5 * q(0.5) + q(0.75) + 0.5 * q(1.0)), 1e-14);
  // Quadratic interpolation of a parabola is the parabola: its exact mean, 7/3 over [1, 2].
  const Waveform quadratic = sampled(square, 4, Waveform::Interpolation::kQuadratic);
  EXPECT_NEAR(quadratic.mean(1)(0, 0), 7.0 / 3.0, 1e-13);
  EXPECT_NEAR(quadratic.mean(1)(1, 0), 14.0 / 3.0, 1e-13);
}

TEST(Waveform, ANewWindowStartsAtTheLastOnesEnd) {
  Waveform waveform(1, 2, Waveform::Interpolation::kLinear);
  waveform.reset(Eigen::VectorXd::Constant(1, 5.0));
  EXPECT_EQ(waveform.at(4)(0, 0), 5.0);  // the initial state, held
  Eigen::MatrixXd samples(1, 2);
  samples << 6.0, 8.0;
  waveform.set_samples(samples);
  waveform.begin_window();
  samples << 10.0, 12.0;
  waveform.set_samples(samples);
  EXPECT_DOUBLE_EQ(waveform.at(4)(0, 0), 9.0);  // halfway from 8 to 10
  EXPECT_THROW(waveform.set_samples(Eigen::MatrixXd(1, 3)), std::invalid_argument);
}

}  // namespace
}  // namespace cocopp
