#pragma once
// Waveform: one interface's values over a coupling time window, for solvers that take
// substeps (waveform iteration, docs/coupling.md "Substeps"). The sender's values are samples
// at the ends of its k substeps, at fractions j/k of the window (j = 1..k), beside the value at
// the window's start (fraction 0, the last window's end); a receiver with m substeps needs them
// at i/m, interpolated in time:
//   constant   the next sample's value (as a backward Euler step takes its end's)
//   linear     piecewise linear between neighbouring samples
//   quadratic  through the two samples around the time and the next one (the one before where
//              the time lies in the window's last interval): the sample before the window's
//              start comes from the previous window (its last-but-one sample, or its start)
// A time that is a sample's is given that sample exactly, so that a receiver at the sender's
// times gets the sender's values bit for bit. A receiver with fewer substeps than the sender
// may take instead the mean of the interpolant over each of its substeps (mean(): exact, by
// Simpson's rule on each piece between samples).
#include <Eigen/Core>

namespace cocopp {

class Waveform {
 public:
  enum class Interpolation { kConstant, kLinear, kQuadratic };

  /// Values of `size` numbers sampled at the ends of `samples` substeps.
  Waveform(Eigen::Index size, int samples, Interpolation interpolation);

  /// A constant history: `value` at the window's start and at every sample (the initial
  /// state, held before the run as well).
  void reset(const Eigen::VectorXd& value);
  /// A new window: the last one's end is its start, and the last one's samples its history.
  void begin_window();
  /// This window's samples so far, one column each (size x samples).
  void set_samples(const Eigen::MatrixXd& samples);
  const Eigen::MatrixXd& samples() const { return samples_; }
  /// The values at the ends of `substeps` equal substeps of the window (size x substeps).
  Eigen::MatrixXd at(int substeps) const;
  /// The mean value over each of `substeps` equal substeps of the window (size x substeps).
  Eigen::MatrixXd mean(int substeps) const;

 private:
  /// The interpolant of sample interval j ((j - 1) / k, j / k] at time t (fraction).
  Eigen::VectorXd value_in(int j, double t) const;
  /// The known value whose time is point `p` of: -1 the one before the start, 0 the start,
  /// j = 1..k sample j.
  Eigen::VectorXd point(int p) const;
  double point_time(int p) const;

  int samples_count_;
  Interpolation interpolation_;
  Eigen::VectorXd start_;
  Eigen::VectorXd before_start_;  ///< at point_time(-1)
  double before_start_time_ = -1.0;
  Eigen::MatrixXd samples_;
};

}  // namespace cocopp
