// `or`: satisfied when any of its criteria is.
#include "coupler/convergence/combined.hpp"

namespace cocopp {
namespace {

struct Or : Combined {
  explicit Or(const Settings& s) : Combined(s, false) {}
};

}  // namespace

COCOPP_REGISTER(ConvergenceCriterionRegistry, "or", Or)

}  // namespace cocopp
