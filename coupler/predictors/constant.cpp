// `constant`: x^(n+1) = x^n: the last converged value.
#include "coupler/predictors/extrapolation.hpp"

namespace cocopp {
namespace {

struct Constant : Extrapolation {
  explicit Constant(const Settings& s) : Extrapolation(s, {1.0}) {}
};

}  // namespace

COCOPP_REGISTER(PredictorRegistry, "constant", Constant)

}  // namespace cocopp
