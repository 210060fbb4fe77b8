#include "coupler/schemes/waveform.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cocopp {

Waveform::Waveform(Eigen::Index size, int samples, Interpolation interpolation)
    : samples_count_(samples),
      interpolation_(interpolation),
      start_(Eigen::VectorXd::Zero(size)),
      before_start_(Eigen::VectorXd::Zero(size)),
      samples_(Eigen::MatrixXd::Zero(size, samples)) {
  if (samples < 1) throw std::invalid_argument("Waveform: at least one sample a window");
}

void Waveform::reset(const Eigen::VectorXd& value) {
  start_ = value;
  before_start_ = value;
  before_start_time_ = samples_count_ > 1 ? -1.0 / samples_count_ : -1.0;
  samples_.colwise() = value;
}

void Waveform::begin_window() {
  const int k = samples_count_;
  // The previous window's last-but-one point, shifted back by one window.
  before_start_ = k > 1 ? Eigen::VectorXd(samples_.col(k - 2)) : start_;
  before_start_time_ = k > 1 ? -1.0 / k : -1.0;
  start_ = samples_.col(k - 1);
}

void Waveform::set_samples(const Eigen::MatrixXd& samples) {
  if (samples.rows() != samples_.rows() || samples.cols() != samples_count_)
    throw std::invalid_argument("Waveform: " + std::to_string(samples.rows()) + " x " +
                                std::to_string(samples.cols()) + " samples, expected " +
                                std::to_string(samples_.rows()) + " x " +
                                std::to_string(samples_count_));
  samples_ = samples;
}

Eigen::VectorXd Waveform::point(int p) const {
  if (p < 0) return before_start_;
  if (p == 0) return start_;
  return samples_.col(p - 1);
}

double Waveform::point_time(int p) const {
  return p < 0 ? before_start_time_ : static_cast<double>(p) / samples_count_;
}

Eigen::VectorXd Waveform::value_in(int j, double t) const {
  const int k = samples_count_;
  if (interpolation_ == Interpolation::kConstant) return point(j);
  if (interpolation_ == Interpolation::kLinear) {
    const double t0 = point_time(j - 1), t1 = point_time(j);
    const double w = (t - t0) / (t1 - t0);
    return (1.0 - w) * point(j - 1) + w * point(j);
  }
  // Quadratic (Lagrange) through j - 1, j and j + 1, or j - 2 where j is the last sample.
  const int a = j < k ? j - 1 : j - 2;
  Eigen::VectorXd value = Eigen::VectorXd::Zero(samples_.rows());
  for (int m = a; m <= a + 2; ++m) {
    double weight = 1.0;
    for (int n = a; n <= a + 2; ++n)
      if (n != m) weight *= (t - point_time(n)) / (point_time(m) - point_time(n));
    value += weight * point(m);
  }
  return value;
}

Eigen::MatrixXd Waveform::at(int substeps) const {
  const int k = samples_count_;
  Eigen::MatrixXd values(samples_.rows(), substeps);
  for (int i = 1; i <= substeps; ++i) {
    // Time i/substeps lies in (j - 1, j] / k: at sample j exactly when i k = j substeps.
    const int j = (i * k + substeps - 1) / substeps;
    values.col(i - 1) = i * k == j * substeps ? Eigen::VectorXd(samples_.col(j - 1))
                                              : value_in(j, static_cast<double>(i) / substeps);
  }
  return values;
}

Eigen::MatrixXd Waveform::mean(int substeps) const {
  const int k = samples_count_;
  Eigen::MatrixXd values(samples_.rows(), substeps);
  for (int i = 1; i <= substeps; ++i) {
    const double from = static_cast<double>(i - 1) / substeps,
                 to = static_cast<double>(i) / substeps;
    Eigen::VectorXd integral = Eigen::VectorXd::Zero(samples_.rows());
    // The pieces of (from, to] between the sample times j / k: one interpolant each.
    const int first = (i - 1) * k / substeps + 1, last = (i * k + substeps - 1) / substeps;
    for (int j = first; j <= last; ++j) {
      const double c = std::max(from, point_time(j - 1)), d = std::min(to, point_time(j));
      if (d <= c) continue;
      integral +=
          (d - c) / 6.0 * (value_in(j, c) + 4.0 * value_in(j, 0.5 * (c + d)) + value_in(j, d));
    }
    values.col(i - 1) = integral / (to - from);
  }
  return values;
}

}  // namespace cocopp
