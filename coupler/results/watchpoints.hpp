#pragma once
// Watchpoints: the interface variables at chosen points, step by step (as preCICE's
// watchpoints), for a history at a point without reading whole interfaces back.
//
//   settings:
//     watchpoints:
//       - name: middle                 # a plain name: results/<case>_watchpoint_middle.csv
//         coordinates: [0, 0.005, 0]   # m, in the interface's initial coordinates
//         model_part: wall             # optional: default the model part nearest the point
//         interpolator: {type: linear, directions: [z]}   # optional: default nearest
//
// Each watchpoint takes every variable its model part carries on x and on y (displacement,
// pressure, traction, ...), interpolated at the point with any interpolator of the mappers (the
// same keys). As an Interface (one model part of one point per watchpoint), the results file
// keeps them like x and y (group /watchpoints), and WatchpointCsv writes them as CSV.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "core/case/settings.hpp"
#include "core/data/interface.hpp"
#include "mappers/interpolators/interpolator.hpp"

namespace cocopp {

class Watchpoints {
 public:
  Watchpoints() = default;
  /// Reads `settings.watchpoints` (none if absent): names, points, interpolators (created now,
  /// so that their keys are checked with the case). Throws CaseError at the key.
  explicit Watchpoints(const Settings& settings);

  bool empty() const { return definitions_.empty(); }

  /// Finds each watchpoint's model part on x and y and builds its interpolators. Throws
  /// std::runtime_error naming the watchpoint, its place in the case file and what to change.
  void attach(const Interface& x, const Interface& y);

  /// The watchpoints' layout: one model part of one point per watchpoint (after attach).
  const Interface& layout() const { return values_; }
  /// The watchpoints' values for these x and y (same layout as at attach).
  const Interface& sample(const Interface& x, const Interface& y);
  /// The model part each watchpoint reads, in layout order (after attach).
  std::vector<std::string> source_parts() const;

 private:
  struct Definition {
    std::string name;
    Eigen::RowVector3d point;
    std::string model_part;  ///< empty: the nearest
    std::string where;       ///< "case.yaml:7:9: watchpoint 'middle'"
    /// One per interface (x, y): the interpolators are built on different points.
    std::unique_ptr<Interpolator> on_x, on_y;
  };
  std::string nearest_model_part(const Definition& d, const Interface& x, const Interface& y) const;
  void build(Definition& d, Interpolator& interpolator, const ModelPart& part) const;

  /// Where each variable of a watchpoint comes from, decided once at attach().
  struct Source {
    std::size_t definition;  ///< index in definitions_
    std::string variable;
    bool from_x;  ///< x's values where x carries the variable, else y's
  };

  std::vector<Definition> definitions_;
  std::vector<Source> sources_;
  Interface values_;
};

}  // namespace cocopp
