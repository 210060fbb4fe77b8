#pragma once
// SurrogateMapping: carries interface vectors between a case's interface and its surrogate's
// (iqnism), block by block: the i-th (model part, variable) block of one to the i-th of the
// other, which must be the same variable, each by a Mapper on the model parts' coordinates:
// `mapper` both ways, or `mapper_to_surrogate` and `mapper_from_surrogate` where the two
// directions differ (transformers between a 3D wedge and a 2D model). Without mapper settings
// both interfaces must have the same layout and vectors pass unchanged.
#include <memory>
#include <optional>
#include <vector>

#include "core/data/interface.hpp"
#include "mappers/mapper.hpp"

namespace cocopp {

class SurrogateMapping {
 public:
  /// Reads the mapper keys of `surrogate` (the iqnism's `surrogate` settings).
  explicit SurrogateMapping(const Settings& surrogate);

  /// Check that the interfaces fit and build the mappers; throws std::runtime_error naming
  /// both layouts if they do not fit.
  void initialize(const Interface& real, const Interface& surrogate);
  Eigen::VectorXd to_surrogate(const Eigen::VectorXd& real) const;
  Eigen::VectorXd from_surrogate(const Eigen::VectorXd& surrogate) const;

 private:
  /// `from`'s data in `to`'s layout, block i by mappers[i].
  static Eigen::VectorXd carry(const Interface& from, const Eigen::VectorXd& values,
                               const Interface& to,
                               const std::vector<std::unique_ptr<Mapper>>& mappers);

  std::optional<Settings> to_settings_, from_settings_;
  Interface real_, surrogate_;
  std::vector<std::unique_ptr<Mapper>> to_surrogate_, from_surrogate_;
};

}  // namespace cocopp
