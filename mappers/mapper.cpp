#include "mappers/mapper.hpp"

#include <stdexcept>

#include "core/case/suggest.hpp"
#include "core/protocol/variable_components.hpp"

namespace cocopp {

namespace {

Eigen::RowVector3d read_mask(const Settings& settings) {
  const auto components = settings.get<std::vector<std::string>>("components", {"x", "y", "z"});
  Eigen::RowVector3d mask = Eigen::RowVector3d::Zero();
  for (const auto& component : components) {
    if (component != "x" && component != "y" && component != "z")
      settings.fail("components", "'" + component + "' is not one of: x, y, z");
    mask(component[0] - 'x') = 1.0;
  }
  return mask;
}

std::vector<std::string> variable_names() {
  std::vector<std::string> names;
  for (const auto& definition : protocol::variable_definitions()) names.push_back(definition.name);
  return names;
}

}  // namespace

Mapper::Mapper(const Settings& settings) : mask_(read_mask(settings)) {
  if (settings.has("conservative") && settings.node()["conservative"].IsSequence()) {
    for (const auto& variable : settings.get<std::vector<std::string>>("conservative", {})) {
      if (protocol::variable_components(variable) == 0)
        settings.fail("conservative", "'" + variable + "' is not an interface variable" +
                                          did_you_mean(variable, variable_names()));
      conservative_variables_.insert(variable);
    }
  } else {
    all_conservative_ = settings.get<bool>("conservative", false);
  }
  const bool any_conservative = all_conservative_ || !conservative_variables_.empty();
  conservative_scale_ = settings.get<double>("conservative_scale", 1.0);
  if (settings.has("conservative_scale") && !any_conservative)
    settings.fail("conservative_scale",
                  "scales what is mapped conservatively, and nothing is: give `conservative`");
  if (!(conservative_scale_ > 0.0))
    settings.fail("conservative_scale", "must be positive (the target's share of the source)");
  if (!all_conservative_) consistent_ = InterpolatorRegistry::instance().create(settings);
  if (any_conservative) conservative_ = InterpolatorRegistry::instance().create(settings);
  if (settings.has("transformers")) {
    for (const auto& entry : settings.list("transformers")) {
      auto transformer = TransformerRegistry::instance().create(entry);
      if (any_conservative && !transformer->keeps_totals())
        settings.fail("conservative",
                      "conservative mapping through the transformer '" +
                          entry.get<std::string>("type", "") +
                          "' is not supported: only one that keeps each point one point "
                          "(permutation) keeps totals; map forces as tractions (consistent) or "
                          "drop the transformer");
      auto& side = transformer->side() == Transformer::Side::kSource ? source_side_ : target_side_;
      side.push_back(std::move(transformer));
    }
  }
}

void Mapper::initialize(const Coordinates& source, const Coordinates& target) {
  Coordinates source_points = source;
  for (auto& transformer : source_side_)
    source_points = transformer->transform_points(source_points);
  Coordinates target_points = target;
  // Target-side transformers are undone in reverse order, so they are applied in order here.
  for (auto& transformer : target_side_)
    target_points = transformer->transform_points(target_points);
  if (consistent_) consistent_->initialize(source_points, target_points);
  // Conservative mapping is the transpose of the consistent mapping the other way round.
  if (conservative_) conservative_->initialize(target_points, source_points);
  initialized_ = true;
}

bool Mapper::conservative_for(const std::string& variable) const {
  return all_conservative_ || conservative_variables_.count(variable) != 0;
}

const MappingQuality& Mapper::quality() const {
  return consistent_ ? consistent_->quality() : conservative_->quality();
}

Eigen::VectorXd Mapper::target_distances() const {
  if (!initialized_) throw std::logic_error("Mapper::target_distances called before initialize");
  if (!consistent_)
    throw std::invalid_argument(
        "a mapper that maps everything conservatively measures no distance from each target "
        "point to the source: list the conservative variables (conservative: [force])");
  RowMatrix distances = consistent_->target_distances();
  for (auto it = target_side_.rbegin(); it != target_side_.rend(); ++it)
    distances = (*it)->backward(distances);
  return distances.col(0);
}

RowMatrix Mapper::map(const RowMatrix& source_values) const {
  return map_with(source_values, all_conservative_);
}

RowMatrix Mapper::map(const RowMatrix& source_values, const std::string& variable) const {
  return map_with(source_values, conservative_for(variable));
}

RowMatrix Mapper::map_with(const RowMatrix& source_values, bool conservative) const {
  if (!initialized_) throw std::logic_error("Mapper::map called before initialize");
  RowMatrix values = source_values;
  for (const auto& transformer : source_side_) values = transformer->forward(values);
  values = conservative ? RowMatrix(conservative_scale_ * conservative_->map_transpose(values))
                        : consistent_->map(values);
  for (auto it = target_side_.rbegin(); it != target_side_.rend(); ++it)
    values = (*it)->backward(values);
  if (values.cols() == 3) values.array().rowwise() *= mask_.array();
  return values;
}

}  // namespace cocopp
