// `quadratic`: quadratic extrapolation of the last three converged values.
#include "coupler/predictors/extrapolation.hpp"

namespace cocopp {
namespace {

struct Quadratic : Extrapolation {
  explicit Quadratic(const Settings& s) : Extrapolation(s, {3.0, -3.0, 1.0}) {}
};

}  // namespace

COCOPP_REGISTER(PredictorRegistry, "quadratic", Quadratic)

}  // namespace cocopp
