// Interpolator base: shared settings, point-set checks, unmatched targets and the default
// sparse-matrix application.
#include "mappers/interpolators/interpolator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/case/suggest.hpp"
#include "mappers/interpolators/parallel.hpp"

namespace cocopp {

namespace {

const std::vector<std::string> kDirectionNames = {"x", "y", "z"};

/// Matrix entries ahead whose source rows apply() prefetches.
constexpr Eigen::Index kPrefetchDistance = 16;

std::vector<int> read_directions(const Settings& settings) {
  const auto names = settings.get<std::vector<std::string>>("directions", kDirectionNames);
  if (names.empty()) settings.fail("directions", "must list at least one of x, y, z");
  std::vector<int> directions;
  for (const auto& name : names) {
    const auto found = std::find(kDirectionNames.begin(), kDirectionNames.end(), name);
    if (found == kDirectionNames.end()) {
      std::string lower = name;
      std::transform(lower.begin(), lower.end(), lower.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      const bool case_typo =
          std::find(kDirectionNames.begin(), kDirectionNames.end(), lower) != kDirectionNames.end();
      settings.fail("directions", "'" + name + "' is not one of: x, y, z" +
                                      (case_typo ? "; did you mean '" + lower + "'?"
                                                 : did_you_mean(name, kDirectionNames)));
    }
    const int direction = static_cast<int>(found - kDirectionNames.begin());
    if (std::find(directions.begin(), directions.end(), direction) != directions.end())
      settings.fail("directions", "'" + name + "' is listed twice");
    directions.push_back(direction);
  }
  return directions;
}

std::string format_point(const Coordinates& points, Eigen::Index i) {
  return fmt::format("({:g}, {:g}, {:g})", points(i, 0), points(i, 1), points(i, 2));
}

std::string format_row(const Eigen::MatrixXd& points, Eigen::Index i) {
  std::string text = "(";
  for (Eigen::Index j = 0; j < points.cols(); ++j)
    text += fmt::format("{}{:g}", j == 0 ? "" : ", ", points(i, j));
  return text + ")";
}

double box_diagonal(const Eigen::MatrixXd& points) {
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

}  // namespace

Interpolator::Interpolator(const Settings& settings)
    : directions_(read_directions(settings)),
      max_distance_(settings.get_in_range("max_distance", std::numeric_limits<double>::infinity(),
                                          Range::positive())) {
  const std::string unmatched =
      settings.get_choice("unmatched", "zero", {"zero", "nearest", "error"});
  unmatched_ = unmatched == "zero"      ? Unmatched::kZero
               : unmatched == "nearest" ? Unmatched::kNearest
                                        : Unmatched::kError;
}

void Interpolator::initialize(const Coordinates& source, const Coordinates& target) {
  source_size_ = target_size_ = 0;  // not usable until everything below succeeded
  unmatched_targets_.clear();
  unmatched_nearest_sources_.clear();
  check_not_empty(source, "source");
  check_not_empty(target, "target");
  const Eigen::MatrixXd source_points = select_directions(source);
  const Eigen::MatrixXd target_points = select_directions(target);
  // The two trees and their duplicate checks are independent: build them side by side.
  auto index = [this](const Eigen::MatrixXd& points, const Coordinates& original,
                      const char* side) {
    auto search = std::make_unique<PointSearch>(points);
    check_no_duplicates(*search, points, original, side);
    return search;
  };
  std::unique_ptr<PointSearch> searches[2];
  parallel_chunks(
      std::size_t{2},
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t side = begin; side < end; ++side)
          searches[side] = side == 0 ? index(source_points, source, "source")
                                     : index(target_points, target, "target");
      },
      static_cast<std::size_t>(source_points.rows() + target_points.rows()));
  source_search_ = std::move(searches[0]);
  target_search_ = std::move(searches[1]);
  check_boxes_overlap(source_points, target_points);

  quality_ = MappingQuality{};
  target_distances_.resize(0);
  matrix_ = Eigen::SparseMatrix<double, Eigen::RowMajor>();
  build(source_points, target_points);
  treat_unmatched(source_points, target_points);
  target_search_.reset();  // only needed while building
  source_size_ = source.rows();
  target_size_ = target.rows();
}

Eigen::MatrixXd Interpolator::select_directions(const Coordinates& points) const {
  Eigen::MatrixXd selected(points.rows(), static_cast<Eigen::Index>(directions_.size()));
  for (std::size_t j = 0; j < directions_.size(); ++j)
    selected.col(static_cast<Eigen::Index>(j)) = points.col(directions_[j]);
  return selected;
}

std::string Interpolator::direction_names() const {
  std::vector<std::string> names;
  for (const int direction : directions_) names.push_back(kDirectionNames[direction]);
  return join(names);
}

void Interpolator::check_not_empty(const Coordinates& points, const std::string& name) const {
  if (points.rows() == 0)
    throw std::invalid_argument("interpolator: the " + name + " point set is empty");
}

void Interpolator::check_no_duplicates(const PointSearch& search, const Eigen::MatrixXd& selected,
                                       const Coordinates& points, const std::string& name) const {
  // Relative to the extent of the set: coordinates written with ~12 digits still count as
  // distinct, while points that only differ by round-off are caught.
  const double tolerance = 1e-12 * box_diagonal(selected);
  const auto pair = search.find_coincident(tolerance);
  if (!pair) return;
  const auto [first, second] = *pair;
  throw std::invalid_argument(fmt::format(
      "interpolator: {} points {} {} and {} {} coincide in the mapped directions ({}): duplicate "
      "points make the mapping ambiguous",
      name, first, format_point(points, first), second, format_point(points, second),
      direction_names()));
}

void Interpolator::check_boxes_overlap(const Eigen::MatrixXd& source,
                                       const Eigen::MatrixXd& target) const {
  const Eigen::RowVectorXd source_min = source.colwise().minCoeff();
  const Eigen::RowVectorXd source_max = source.colwise().maxCoeff();
  const Eigen::RowVectorXd target_min = target.colwise().minCoeff();
  const Eigen::RowVectorXd target_max = target.colwise().maxCoeff();
  double tolerance = 1e-6 * std::max(box_diagonal(source), box_diagonal(target));
  if (std::isfinite(max_distance_)) tolerance += max_distance_;
  for (Eigen::Index j = 0; j < source.cols(); ++j) {
    const double gap = std::max(target_min(j) - source_max(j), source_min(j) - target_max(j));
    if (gap > tolerance)
      throw std::invalid_argument(fmt::format(
          "interpolator: the bounding boxes of the source and target points do not overlap in "
          "direction {}: source {:g} .. {:g}, target {:g} .. {:g} (gap {:g} > tolerance {:g}); "
          "are both model parts in the same units and position?",
          kDirectionNames[directions_[j]], source_min(j), source_max(j), target_min(j),
          target_max(j), gap, tolerance));
  }
}

void Interpolator::treat_unmatched(const Eigen::MatrixXd& /*source*/,
                                   const Eigen::MatrixXd& target) {
  if (!std::isfinite(max_distance_)) return;
  PointSearch::Neighbours nearest;
  Eigen::RowVectorXd query(target.cols());
  std::vector<std::pair<Eigen::Index, Eigen::Index>> unmatched;  // target, nearest source
  for (const Eigen::Index t : target_order()) {
    query = target.row(t);
    source_search().nearest(query.data(), 1, nearest);
    if (std::sqrt(nearest.squared_distances[0]) <= max_distance_) continue;
    unmatched.emplace_back(t, nearest.indices[0]);
  }
  std::sort(unmatched.begin(), unmatched.end());
  for (const auto& [t, s] : unmatched) {
    unmatched_targets_.push_back(t);
    unmatched_nearest_sources_.push_back(s);
  }
  quality_.unmatched = static_cast<int>(unmatched_targets_.size());
  if (target_distances_.size() == target.rows())
    for (const Eigen::Index t : unmatched_targets_)
      target_distances_(t) = std::numeric_limits<double>::infinity();
  if (unmatched_ != Unmatched::kError || unmatched_targets_.empty()) return;
  const Eigen::Index first = unmatched_targets_.front();
  query = target.row(first);
  source_search().nearest(query.data(), 1, nearest);
  throw std::invalid_argument(fmt::format(
      "interpolator: target point {} at {} (directions {}) is {:g} from the nearest source "
      "point, more than max_distance {:g} ({} unmatched target point(s); unmatched: zero or "
      "nearest accepts them)",
      first, format_row(target, first), direction_names(), std::sqrt(nearest.squared_distances[0]),
      max_distance_, unmatched_targets_.size()));
}

void Interpolator::record_distances(const Eigen::VectorXd& distances) {
  target_distances_ = distances;
  if (distances.size() == 0) return;
  quality_.min_distance = distances.minCoeff();
  quality_.mean_distance = distances.mean();
  quality_.max_distance = distances.maxCoeff();
}

void Interpolator::check_initialized() const {
  if (source_size_ == 0)
    throw std::logic_error("interpolator: map() called before a successful initialize()");
}

RowMatrix Interpolator::map(const RowMatrix& source_values) const {
  check_initialized();
  if (source_values.rows() != source_size_)
    throw std::invalid_argument(
        fmt::format("interpolator: map() got values for {} points, but the source has {} points",
                    source_values.rows(), source_size_));
  RowMatrix result = apply(source_values);
  for (std::size_t k = 0; k < unmatched_targets_.size(); ++k) {
    if (unmatched_ == Unmatched::kNearest)
      result.row(unmatched_targets_[k]) = source_values.row(unmatched_nearest_sources_[k]);
    else
      result.row(unmatched_targets_[k]).setZero();
  }
  return result;
}

RowMatrix Interpolator::map_transpose(const RowMatrix& target_values) const {
  check_initialized();
  if (target_values.rows() != target_size_)
    throw std::invalid_argument(fmt::format(
        "interpolator: map_transpose() got values for {} points, but the target has {} points",
        target_values.rows(), target_size_));
  if (unmatched_targets_.empty()) return apply_transpose(target_values);
  // The exact transpose of map(): unmatched rows leave the operator and, with `nearest`,
  // come back as a unit entry at their nearest source point.
  RowMatrix matched = target_values;
  for (const Eigen::Index t : unmatched_targets_) matched.row(t).setZero();
  RowMatrix result = apply_transpose(matched);
  if (unmatched_ == Unmatched::kNearest)
    for (std::size_t k = 0; k < unmatched_targets_.size(); ++k)
      result.row(unmatched_nearest_sources_[k]) += target_values.row(unmatched_targets_[k]);
  return result;
}

RowMatrix Interpolator::apply(const RowMatrix& source_values) const {
  // One pass over the rows with all components at once: Eigen's product goes column by
  // column, which reads the (randomly placed) source rows once per component. Rows are
  // independent: large mappings are applied on all cores.
  const Eigen::Index components = source_values.cols();
  RowMatrix result(matrix_.rows(), components);
  const auto* outer = matrix_.outerIndexPtr();
  const auto* inner = matrix_.innerIndexPtr();
  const double* weights = matrix_.valuePtr();
  const double* in = source_values.data();
  const Eigen::Index nonzeros = matrix_.nonZeros();
  parallel_chunks(
      static_cast<std::size_t>(matrix_.rows()), [&](std::size_t begin, std::size_t end) {
        double* out = result.data() + static_cast<Eigen::Index>(begin) * components;
        for (auto row = static_cast<Eigen::Index>(begin); row < static_cast<Eigen::Index>(end);
             ++row, out += components) {
          for (Eigen::Index c = 0; c < components; ++c) out[c] = 0.0;
          for (auto k = outer[row]; k < outer[row + 1]; ++k) {
            // Source rows are scattered in memory: ask for the ones a few rows ahead now, so that
            // the cache misses overlap instead of following each other.
            if (k + kPrefetchDistance < nonzeros)
              __builtin_prefetch(in + Eigen::Index{inner[k + kPrefetchDistance]} * components);
            const double* from = in + Eigen::Index{inner[k]} * components;
            for (Eigen::Index c = 0; c < components; ++c) out[c] += weights[k] * from[c];
          }
        }
      });
  return result;
}

RowMatrix Interpolator::apply_transpose(const RowMatrix& target_values) const {
  const Eigen::Index components = target_values.cols();
  RowMatrix result = RowMatrix::Zero(matrix_.cols(), components);
  const auto* outer = matrix_.outerIndexPtr();
  const auto* inner = matrix_.innerIndexPtr();
  const double* weights = matrix_.valuePtr();
  const double* in = target_values.data();
  double* out = result.data();
  for (Eigen::Index row = 0; row < matrix_.rows(); ++row, in += components)
    for (auto k = outer[row]; k < outer[row + 1]; ++k) {
      double* to = out + Eigen::Index{inner[k]} * components;
      for (Eigen::Index c = 0; c < components; ++c) to[c] += weights[k] * in[c];
    }
  return result;
}

}  // namespace cocopp
