#include "solver_wrappers/calculix/sta_file.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

namespace cocopp::calculix {

std::vector<IncrementAttempt> read_sta(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<IncrementAttempt> attempts;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    IncrementAttempt attempt;
    std::string mark;
    double total_time = 0.0, step_time = 0.0;
    // The header lines ("SUMMARY ...", "STEP INC ...") do not start with a number.
    if (!(fields >> attempt.step >> attempt.increment >> mark >> attempt.newton_iterations >>
          total_time >> step_time >> attempt.increment_time))
      continue;
    attempt.converged = mark.back() != 'U';
    attempts.push_back(attempt);
  }
  return attempts;
}

std::optional<double> first_converged_increment(const std::vector<IncrementAttempt>& attempts) {
  if (attempts.empty()) return std::nullopt;
  const int last_step = attempts.back().step;
  for (const auto& attempt : attempts)
    if (attempt.step == last_step && attempt.converged) return attempt.increment_time;
  return std::nullopt;
}

std::optional<double> carried_initial_increment(const std::vector<IncrementAttempt>& attempts,
                                                double deck_initial) {
  const auto first = first_converged_increment(attempts);
  if (!first) return std::nullopt;
  return std::max(*first, 0.25 * deck_initial);
}

}  // namespace cocopp::calculix
