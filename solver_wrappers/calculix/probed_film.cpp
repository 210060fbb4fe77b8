#include "solver_wrappers/calculix/probed_film.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace cocopp::calculix {

namespace {

/// Linear interpolation of (x, y), x ascending; beyond the ends `outside`, or the end's value
/// without it. Within a thousandth of a pitch of an end is at the end: the film's frame is
/// found to that, and an end line keeps its own move.
double interpolate(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double at,
                   std::optional<double> outside = std::nullopt) {
  if (x.size() == 0) return outside.value_or(0.0);
  const double slack = x.size() > 1 ? 1e-3 * (x[x.size() - 1] - x[0]) / double(x.size() - 1) : 0.0;
  if (at < x[0]) return at < x[0] - slack ? outside.value_or(y[0]) : y[0];
  if (at > x[x.size() - 1])
    return at > x[x.size() - 1] + slack ? outside.value_or(y[x.size() - 1]) : y[x.size() - 1];
  const auto upper = std::upper_bound(x.data(), x.data() + x.size(), at) - x.data();
  if (upper >= x.size()) return y[x.size() - 1];
  const auto lower = upper - 1;
  const double t = (at - x[lower]) / (x[upper] - x[lower]);
  return (1.0 - t) * y[lower] + t * y[upper];
}

/// The count after "# <word> " on a header line (-1: none).
long header_count(const std::string& line, const std::string& word) {
  const std::string prefix = "# " + word + " ";
  if (line.rfind(prefix, 0) != 0) return -1;
  try {
    return std::stol(line.substr(prefix.size()));
  } catch (const std::exception&) {
    return -1;
  }
}

}  // namespace

ProbedFilm ProbedFilm::read(const std::filesystem::path& file) {
  std::ifstream in(file);
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error(fmt::format("film probe {}: {}", file.string(), what));
  };
  if (!in) fail("cannot be read (run the film with COCOPP_SENSITIVITY_PROBE='every MOVE FILE')");
  ProbedFilm film;
  std::string line;
  std::getline(in, line);
  const auto at = line.find("step ");
  try {
    film.step_ = std::stoi(line.substr(at == std::string::npos ? line.size() : at + 5));
  } catch (const std::exception&) {
    fail("no step in its first line");
  }
  std::getline(in, line);
  const long faces = header_count(line, "faces");
  if (faces <= 0) fail("no '# faces N' line");
  film.face_axial_.resize(faces);
  film.face_local_.resize(faces);
  Eigen::VectorXd areas(faces);
  for (long f = 0; f < faces; ++f) {
    double axial, radius, area, gap, radial_force, axial_force;
    if (!(in >> axial >> radius >> area >> gap >> radial_force >> axial_force))
      fail(fmt::format("face {} of {} cannot be read", f + 1, faces));
    film.face_axial_[f] = axial;
    areas[f] = area;
    film.face_local_[f] = gap > 0.0 ? std::max(0.0, 2.0 * (-radial_force / area) / gap) : 0.0;
    std::getline(in, line);
  }
  std::getline(in, line);
  const long lines = header_count(line, "lines");
  if (lines <= 0) fail("no '# lines N' line");
  film.line_axial_.resize(lines);
  film.traction_.resize(lines, faces);
  for (long l = 0; l < lines; ++l) {
    if (!(in >> film.line_axial_[l])) fail(fmt::format("line {} cannot be read", l + 1));
    for (long f = 0; f < faces; ++f)
      if (!(in >> film.traction_(l, f))) fail(fmt::format("line {} is short", l + 1));
    std::getline(in, line);  // the axial force changes: not used
  }
  // The radial force changes become tractions.
  film.traction_ = film.traction_ * areas.cwiseInverse().asDiagonal();
  return film;
}

double ProbedFilm::find_offset(const Eigen::VectorXd& axial, const Eigen::VectorXd& local) const {
  const auto misfit = [&](double offset) {
    double sum = 0.0;
    for (Eigen::Index l = 0; l < axial.size(); ++l) {
      const double d = interpolate(face_axial_, face_local_, axial[l] + offset, 0.0) - local[l];
      sum += d * d;
    }
    return sum;
  };
  const double span = face_axial_.maxCoeff() - face_axial_.minCoeff();
  const double centre = face_axial_.minCoeff() - axial.minCoeff();
  const auto best_in = [&](double from, double to, int count) {
    double best = from, lowest = std::numeric_limits<double>::max();
    for (int k = 0; k <= count; ++k) {
      const double offset = from + (to - from) * k / count;
      const double value = misfit(offset);
      if (value < lowest) lowest = value, best = offset;
    }
    return best;
  };
  const double coarse = best_in(centre - 2 * span, centre + 2 * span, 4000);
  const double step = span / 1000;
  return best_in(coarse - step, coarse + step, 200);
}

Eigen::MatrixXd ProbedFilm::stiffness(const Eigen::VectorXd& axial, const Eigen::VectorXd& weight,
                                      const Eigen::VectorXd& local) const {
  offset_ = find_offset(axial, local);
  const Eigen::Index count = axial.size(), probed = line_axial_.size();
  // The film's traction change at each line per move of each film line.
  Eigen::MatrixXd at_lines(probed, count);
  for (Eigen::Index j = 0; j < probed; ++j)
    for (Eigen::Index l = 0; l < count; ++l)
      at_lines(j, l) = interpolate(face_axial_, traction_.row(j).transpose(), axial[l] + offset_);
  // A film line's move per move of a line: the lines' hat functions along the axis.
  std::vector<Eigen::Index> order(static_cast<std::size_t>(count));
  for (Eigen::Index l = 0; l < count; ++l) order[static_cast<std::size_t>(l)] = l;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return axial[a] < axial[b]; });
  Eigen::VectorXd sorted(count);
  for (Eigen::Index k = 0; k < count; ++k) sorted[k] = axial[order[static_cast<std::size_t>(k)]];
  Eigen::MatrixXd carried = Eigen::MatrixXd::Zero(probed, count);
  for (Eigen::Index k = 0; k < count; ++k) {
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(count);
    unit[k] = 1.0;
    for (Eigen::Index j = 0; j < probed; ++j)
      carried(j, order[static_cast<std::size_t>(k)]) =
          interpolate(sorted, unit, line_axial_[j] - offset_, 0.0);
  }
  return -(weight.asDiagonal() * (at_lines.transpose() * carried));
}

}  // namespace cocopp::calculix
