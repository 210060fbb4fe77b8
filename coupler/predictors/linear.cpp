// `linear`: linear extrapolation of the last two converged values.
#include "coupler/predictors/extrapolation.hpp"

namespace cocopp {
namespace {

struct Linear : Extrapolation {
  explicit Linear(const Settings& s) : Extrapolation(s, {2.0, -1.0}) {}
};

}  // namespace

COCOPP_REGISTER(PredictorRegistry, "linear", Linear)

}  // namespace cocopp
