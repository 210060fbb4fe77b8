#include "coupler/coupled_solvers/surrogate_mapping.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace cocopp {

namespace {

const ModelPart& part_of(const Interface& interface, const std::string& name) {
  for (const auto& part : interface.parts())
    if (part.model_part->name == name) return *part.model_part;
  throw std::logic_error("no model part '" + name + "' in the interface");
}

}  // namespace

SurrogateMapping::SurrogateMapping(const Settings& surrogate) {
  const bool both = surrogate.has("mapper");
  const bool to = surrogate.has("mapper_to_surrogate"),
             from = surrogate.has("mapper_from_surrogate");
  if (both && (to || from))
    surrogate.fail(to ? "mapper_to_surrogate" : "mapper_from_surrogate",
                   "give either 'mapper' (both ways) or 'mapper_to_surrogate' and "
                   "'mapper_from_surrogate', not both");
  if (to != from)
    surrogate.fail(to ? "mapper_to_surrogate" : "mapper_from_surrogate",
                   std::string("needs its counterpart '") +
                       (to ? "mapper_from_surrogate" : "mapper_to_surrogate") +
                       "' (or one 'mapper' for both ways)");
  if (both) to_settings_ = from_settings_ = surrogate.child("mapper");
  if (to) {
    to_settings_ = surrogate.child("mapper_to_surrogate");
    from_settings_ = surrogate.child("mapper_from_surrogate");
  }
  // Read the settings now, while the case is read, so that mistakes show before the solvers
  // start.
  if (to_settings_) {
    Mapper check_to(*to_settings_), check_from(*from_settings_);
  }
}

void SurrogateMapping::initialize(const Interface& real, const Interface& surrogate) {
  real_ = real;
  surrogate_ = surrogate;
  auto mismatch = [&](const std::string& why) {
    return std::runtime_error(
        fmt::format("the surrogate's interface [{}] does not fit the case's [{}]: {}",
                    surrogate.describe(), real.describe(), why));
  };
  if (!to_settings_) {
    if (!real.same_layout(surrogate))
      throw mismatch(
          "give the surrogate's solvers the same model parts, points and variables, or give "
          "'surrogate.mapper' (e.g. {type: linear, directions: [z]}) to map between them");
    return;
  }
  const auto& real_blocks = real.blocks();
  const auto& surrogate_blocks = surrogate.blocks();
  if (real_blocks.size() != surrogate_blocks.size())
    throw mismatch("the mapper maps block by block, and the numbers of blocks differ");
  for (std::size_t i = 0; i < real_blocks.size(); ++i) {
    if (real_blocks[i].variable != surrogate_blocks[i].variable)
      throw mismatch(fmt::format("block {} is '{}' in the case and '{}' in the surrogate", i + 1,
                                 real_blocks[i].variable, surrogate_blocks[i].variable));
    const Coordinates& real_points = part_of(real, real_blocks[i].model_part).coordinates;
    const Coordinates& surrogate_points =
        part_of(surrogate, surrogate_blocks[i].model_part).coordinates;
    to_surrogate_.push_back(std::make_unique<Mapper>(*to_settings_));
    to_surrogate_.back()->initialize(real_points, surrogate_points);
    from_surrogate_.push_back(std::make_unique<Mapper>(*from_settings_));
    from_surrogate_.back()->initialize(surrogate_points, real_points);
  }
}

Eigen::VectorXd SurrogateMapping::carry(const Interface& from, const Eigen::VectorXd& values,
                                        const Interface& to,
                                        const std::vector<std::unique_ptr<Mapper>>& mappers) {
  Interface source = from, target = to;
  source.set_data(values);
  for (std::size_t i = 0; i < mappers.size(); ++i) {
    const auto& in = source.blocks()[i];
    const auto& out = target.blocks()[i];
    target.values(out.model_part, out.variable) =
        mappers[i]->map(RowMatrix(source.values(in.model_part, in.variable)));
  }
  return target.data();
}

Eigen::VectorXd SurrogateMapping::to_surrogate(const Eigen::VectorXd& real) const {
  return to_settings_ ? carry(real_, real, surrogate_, to_surrogate_) : real;
}

Eigen::VectorXd SurrogateMapping::from_surrogate(const Eigen::VectorXd& surrogate) const {
  return to_settings_ ? carry(surrogate_, surrogate, real_, from_surrogate_) : surrogate;
}

}  // namespace cocopp
