#pragma once
// VariableScaling: per-variable weights for the least-squares problems of the quasi-Newton
// methods. An interface that carries pressure (1e5 Pa) next to shear traction (1 Pa), or
// displacement next to a load, makes an unweighted least-squares fit see only the largest
// variable: the small one's secant information looks like round-off and is filtered away.
// Weighting each variable's values gives every variable a say.
//
// Case file (`coupled_solver.scaling`):
//   absent                      all weights 1 (no scaling); `residual_sum` where the coupled
//                               solver asks for it (the parallel scheme: displacement and
//                               loads side by side in one unknown)
//   none                        all weights 1
//   residual_sum                one weight per field (x; y: all its variables together),
//                               1 / s_f, with s_f the sum over every coupling iteration so far
//                               of ||r_f|| / ||r|| (r_f the field's part of the residual):
//                               preCICE's residual-sum preconditioner, summed over the run
//                               instead of a step (a step's first displacement residual can be
//                               near zero side by side). Per field, not per variable: a small,
//                               noisy variable (a wall's viscous traction beside its pressure)
//                               weighed up to the others' size makes the fit chase its noise. The
//                               weights change at the start of a step (every iteration in the run's
//                               first step), so that a step's secant columns share them; the models
//                               re-express the columns they keep in new weights (Model::rescale;
//                               `ls` can).
//   {pressure: 1e-5, ...}       fixed weight per variable (others 1)
//   automatic                   weight 1 / RMS of the first non-zero values of the variable the
//                               models see (iqni: the residual; ibqn: x and y), then frozen,
//                               so that the models' stored columns stay consistent (values
//                               seen before were zero, which no weight changes)
// The weights apply to what the models fit (IQN-ILS then solves argmin ||D (V c + r)||); the
// absolute filter `min_significant` is in the weighted units.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "core/case/settings.hpp"
#include "core/data/interface.hpp"
#include "coupler/results/state.hpp"

namespace cocopp {

class VariableScaling {
 public:
  /// Reads `scaling` from the coupled solver's settings; `residual_sum_by_default`: what an
  /// absent key means.
  explicit VariableScaling(const Settings& coupled_solver_settings,
                           bool residual_sum_by_default = false);

  /// Lay the weights out on the interfaces whose values get weighted (x for iqni; x and y
  /// for ibqn). A named variable on none of them is a case error that lists those present.
  void bind(const std::vector<const Interface*>& layouts);

  /// Weighted copy of values laid out as interface `index` of bind(). With `automatic`, the
  /// first call with a non-zero variable fixes that variable's weight.
  Eigen::VectorXd apply(std::size_t index, const Eigen::VectorXd& values);

  /// The unweighted values of weighted ones (after apply() has fixed the weights they used).
  Eigen::VectorXd remove(std::size_t index, const Eigen::VectorXd& weighted) const;

  /// apply() and remove() on values laid out as every bound interface one after the other
  /// (a stacked unknown: x, then y).
  Eigen::VectorXd apply_all(const Eigen::VectorXd& values);
  Eigen::VectorXd remove_all(const Eigen::VectorXd& weighted) const;

  /// The weight of every value of interface `index` as fixed so far: apply() is
  /// values.cwiseProduct(weights(index)). Empty when scaling is off.
  const Eigen::VectorXd& weights(std::size_t index) const {
    return enabled() ? layouts_.at(index).weights : no_weights_;
  }

  bool enabled() const { return automatic_ || residual_sum_ || !fixed_.empty(); }
  /// Whether the weights change with every residual (residual_sum).
  bool changing() const { return residual_sum_; }
  /// residual_sum: take the residual r (laid out as apply_all's values) into the fields' sums.
  void accumulate(const Eigen::VectorXd& r);
  /// residual_sum: the weights from the sums so far, if one of them moved by more than 10 %;
  /// returns, per value, the new weight over the old one (for Model::rescale), or nothing
  /// when the weights in use stay.
  Eigen::VectorXd refresh();
  /// "automatic" or "pressure 1e-05, traction 1"; "" when off.
  std::string describe() const;
  /// The weight of each variable, as fixed so far (for the saved state).
  const std::map<std::string, double>& weights() const { return weights_; }
  /// The weights as scalars named after the variables, and back.
  void save_state(State& state) const;
  void load_state(const State& state);

 private:
  struct Layout {
    std::vector<Interface::Block> blocks;
    Eigen::VectorXd weights;  ///< one per value; rebuilt when weights_ change
    Eigen::Index offset = 0;  ///< where its values start in a stacked vector (apply_all)
  };
  /// The part of a stacked vector (laid out as every bound interface in turn) for `layout`.
  template <class Vector>
  static auto segment_of(Vector& stacked, const Layout& layout) {
    return stacked.segment(layout.offset, layout.weights.size());
  }
  void fix_automatic_weights(const Layout& layout, const Eigen::VectorXd& values);
  void refresh_weights();
  /// Every bound interface's weights one after the other.
  Eigen::VectorXd stacked_weights() const;

  bool automatic_ = false;
  bool residual_sum_ = false;
  std::vector<double> field_sums_;         ///< residual_sum: the sums s_f, one per bound interface
  std::vector<double> field_weights_;      ///< residual_sum: the weights in use, one per interface
  std::map<std::string, double> fixed_;    ///< from the case file
  std::map<std::string, double> weights_;  ///< in use: fixed_, plus automatic ones found so far
  std::vector<Layout> layouts_;
  Eigen::VectorXd no_weights_;  ///< what weights() gives when scaling is off: empty
  Settings settings_;           ///< the coupled solver's, for errors found in bind()
};

}  // namespace cocopp
