#include "mappers/mapper.hpp"

#include <stdexcept>

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

}  // namespace

Mapper::Mapper(const Settings& settings)
    : interpolator_(InterpolatorRegistry::instance().create(settings)),
      conservative_(settings.get<bool>("conservative", false)),
      mask_(read_mask(settings)) {
  if (settings.has("transformers")) {
    for (const auto& entry : settings.list("transformers")) {
      auto transformer = TransformerRegistry::instance().create(entry);
      auto& side = transformer->side() == Transformer::Side::kSource ? source_side_ : target_side_;
      side.push_back(std::move(transformer));
    }
  }
  if (conservative_ && !(source_side_.empty() && target_side_.empty()))
    settings.fail("conservative",
                  "conservative mapping through transformers is not supported yet: map forces "
                  "as tractions (consistent) or drop the transformers");
}

void Mapper::initialize(const Coordinates& source, const Coordinates& target) {
  Coordinates source_points = source;
  for (auto& transformer : source_side_)
    source_points = transformer->transform_points(source_points);
  Coordinates target_points = target;
  // Target-side transformers are undone in reverse order, so they are applied in order here.
  for (auto& transformer : target_side_)
    target_points = transformer->transform_points(target_points);
  // Conservative mapping is the transpose of the consistent mapping the other way round.
  if (conservative_)
    interpolator_->initialize(target_points, source_points);
  else
    interpolator_->initialize(source_points, target_points);
  initialized_ = true;
}

RowMatrix Mapper::map(const RowMatrix& source_values) const {
  if (!initialized_) throw std::logic_error("Mapper::map called before initialize");
  RowMatrix values = source_values;
  for (const auto& transformer : source_side_) values = transformer->forward(values);
  values = conservative_ ? interpolator_->map_transpose(values) : interpolator_->map(values);
  for (auto it = target_side_.rbegin(); it != target_side_.rend(); ++it)
    values = (*it)->backward(values);
  if (values.cols() == 3) values.array().rowwise() *= mask_.array();
  return values;
}

}  // namespace cocopp
