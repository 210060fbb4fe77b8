// `cubic`: cubic extrapolation of the last four converged values.
#include "coupler/predictors/extrapolation.hpp"

namespace cocopp {
namespace {

struct Cubic : Extrapolation {
  explicit Cubic(const Settings& s) : Extrapolation(s, {4.0, -6.0, 4.0, -1.0}) {}
};

}  // namespace

COCOPP_REGISTER(PredictorRegistry, "cubic", Cubic)

}  // namespace cocopp
