#include "coupler/results/run_outcome.hpp"

#include <iterator>
#include <stdexcept>

namespace cocopp {
namespace {

constexpr const char* kStatusNames[] = {"completed",   "stalled", "diverged",    "solver_failed",
                                        "interrupted", "failed",  "invalid_case"};

}  // namespace

const char* to_string(RunStatus status) {
  return kStatusNames[static_cast<int>(status)];
}

const char* to_string(DivergenceKind kind) {
  switch (kind) {
    case DivergenceKind::kNonFinite:
      return "non-finite values";
    case DivergenceKind::kGrowth:
      return "residual growth";
    case DivergenceKind::kNone:
      break;
  }
  return "";
}

RunStatus run_status_from_string(const std::string& name) {
  for (std::size_t i = 0; i < std::size(kStatusNames); ++i)
    if (name == kStatusNames[i]) return static_cast<RunStatus>(i);
  throw std::invalid_argument("unknown run status '" + name + "'");
}

int RunOutcome::exit_code() const {
  if (status == RunStatus::kStalled) return 3;
  if (ran_all_steps(status)) return 0;
  return status == RunStatus::kInvalidCase ? 2 : 1;
}

}  // namespace cocopp
