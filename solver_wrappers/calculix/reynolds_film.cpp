#include "solver_wrappers/calculix/reynolds_film.hpp"

#include <cmath>
#include <stdexcept>

namespace cocopp::calculix {

ReynoldsFilm::ReynoldsFilm(Eigen::VectorXd position, Eigen::VectorXd length, Eigen::VectorXd gap,
                           const Eigen::VectorXd& pressure)
    : position_(std::move(position)), length_(std::move(length)), gap_(std::move(gap)) {
  const Eigen::Index n = position_.size();
  if (n < 2 || length_.size() != n || gap_.size() != n || pressure.size() != n)
    throw std::invalid_argument("ReynoldsFilm: two faces or more, each with a length and gap");
  for (Eigen::Index k = 0; k < n; ++k) {
    if (!(gap_[k] > 0.0) || !(length_[k] > 0.0))
      throw std::invalid_argument("ReynoldsFilm: a face's gap and length must be > 0");
    if (k > 0 && !(position_[k] > position_[k - 1]))
      throw std::invalid_argument("ReynoldsFilm: the faces' positions must rise");
  }
  const Eigen::VectorXd model = shape(gap_);
  const double model_norm = model.cwiseProduct(model).dot(length_);
  scale_ = model_norm > 0.0 ? model.cwiseProduct(pressure).dot(length_) / model_norm : 0.0;
  const Eigen::VectorXd difference = pressure - scale_ * model;
  const double film_norm = pressure.cwiseProduct(pressure).dot(length_);
  misfit_ = film_norm > 0.0
                ? std::sqrt(difference.cwiseProduct(difference).dot(length_) / film_norm)
                : 1.0;
}

Eigen::VectorXd ReynoldsFilm::shape(const Eigen::VectorXd& gap) const {
  const Eigen::Index n = gap.size();
  // Segments: the inlet's half face (gap as the first face), between centres (linear gap),
  // the outlet's half face. Over a segment of length L from gap a to b:
  //   int dz / h^2 = L / (a b),  int dz / h^3 = L (a + b) / (2 a^2 b^2).
  Eigen::VectorXd i2(n + 1), i3(n + 1);
  const auto segment = [&](Eigen::Index s, double span, double a, double b) {
    i2[s] = span / (a * b);
    i3[s] = span * (a + b) / (2.0 * a * a * b * b);
  };
  segment(0, 0.5 * length_[0], gap[0], gap[0]);
  for (Eigen::Index k = 1; k < n; ++k)
    segment(k, position_[k] - position_[k - 1], gap[k - 1], gap[k]);
  segment(n, 0.5 * length_[n - 1], gap[n - 1], gap[n - 1]);
  // Ambient at both ends fixes the flow rate: sum of (i2 - 2 q i3) over the segments is 0.
  const double twice_q = i2.sum() / i3.sum();
  Eigen::VectorXd p(n);
  double running = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    running += i2[k] - twice_q * i3[k];
    p[k] = running;
  }
  return p;
}

Eigen::MatrixXd ReynoldsFilm::pressure_gradient() const {
  const Eigen::Index n = gap_.size();
  Eigen::MatrixXd gradient(n, n);
  // Central differences: the pressure is smooth in the gaps, and n is a film's few dozen faces.
  for (Eigen::Index g = 0; g < n; ++g) {
    const double step = 1e-6 * gap_[g];
    Eigen::VectorXd up = gap_, down = gap_;
    up[g] += step;
    down[g] -= step;
    gradient.col(g) = scale_ * (shape(up) - shape(down)) / (2.0 * step);
  }
  return gradient;
}

}  // namespace cocopp::calculix
