// `legacy`: x^(n+1) = 5/2 x^n - 2 x^(n-1) + 1/2 x^(n-2).
#include "coupler/predictors/extrapolation.hpp"

namespace cocopp {
namespace {

struct Legacy : Extrapolation {
  explicit Legacy(const Settings& s) : Extrapolation(s, {2.5, -2.0, 0.5}) {}
};

}  // namespace

COCOPP_REGISTER(PredictorRegistry, "legacy", Legacy)

}  // namespace cocopp
