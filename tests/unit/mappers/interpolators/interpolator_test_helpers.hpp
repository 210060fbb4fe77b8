#pragma once
// Point sets and fields shared by the interpolator tests.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "core/case/settings.hpp"
#include "mappers/interpolators/interpolator.hpp"

namespace cocopp::testing {

constexpr double kPi = 3.14159265358979323846;

inline std::unique_ptr<Interpolator> make_interpolator(const std::string& yaml) {
  return InterpolatorRegistry::instance().create(Settings::load_string(yaml, "m.yaml"));
}

/// Uniform random numbers in [lo, hi), reproducible.
class Random {
 public:
  explicit Random(unsigned seed) : engine_(seed) {}
  double operator()(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(engine_);
  }

 private:
  std::mt19937 engine_;
};

/// Random points on the surface of a cylinder around z (radius r, z in [0, length)).
inline Coordinates random_on_cylinder(Eigen::Index n, unsigned seed, double r = 1.0,
                                      double length = 2.0) {
  Random random(seed);
  Coordinates points(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double angle = random(0.0, 2.0 * kPi);
    points.row(i) << r * std::cos(angle), r * std::sin(angle), random(0.0, length);
  }
  return points;
}

/// A grid of n_angle x n_axial points on the same cylinder, the first ring at z = z0.
inline Coordinates grid_on_cylinder(int n_angle, int n_axial, double r = 1.0, double length = 2.0,
                                    double angle0 = 0.0) {
  Coordinates points(n_angle * n_axial, 3);
  for (int j = 0; j < n_axial; ++j)
    for (int i = 0; i < n_angle; ++i) {
      const double angle = angle0 + 2.0 * kPi * i / n_angle;
      points.row(j * n_angle + i) << r * std::cos(angle), r * std::sin(angle),
          length * j / (n_axial - 1);
    }
  return points;
}

/// Three linear fields of the coordinates (one per column).
inline RowMatrix linear_field(const Coordinates& x) {
  RowMatrix values(x.rows(), 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    values.row(i) << 1.0 + 2.0 * x(i, 0) - x(i, 1) + 0.5 * x(i, 2), -3.0 + x(i, 0) + x(i, 2),
        0.25 * x(i, 1) - 4.0 * x(i, 2);
  return values;
}

/// max |a - b| / max |b|
inline double relative_error(const RowMatrix& a, const RowMatrix& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

}  // namespace cocopp::testing
