// `and`: satisfied when all of its criteria are.
#include "coupler/convergence/combined.hpp"

namespace cocopp {
namespace {

struct And : Combined {
  explicit And(const Settings& s) : Combined(s, true) {}
};

}  // namespace

COCOPP_REGISTER(ConvergenceCriterionRegistry, "and", And)

}  // namespace cocopp
