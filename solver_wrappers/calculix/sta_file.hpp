#pragma once
// Reading ccx's .sta file: one line per attempted increment ("STEP INC ATT ITRS TOT TIME STEP
// TIME INC TIME"), an attempt that failed and was cut back marked with a U ("1U").
#include <filesystem>
#include <optional>
#include <vector>

namespace cocopp::calculix {

struct IncrementAttempt {
  int step = 0;
  int increment = 0;
  bool converged = false;  ///< false: "U", cut back and tried again smaller
  int newton_iterations = 0;
  double increment_time = 0.0;
};

/// Every attempt the .sta file lists, in order; empty if the file is missing.
std::vector<IncrementAttempt> read_sta(const std::filesystem::path& file);

/// The size of the first increment that converged in the file's last step, if any.
std::optional<double> first_converged_increment(const std::vector<IncrementAttempt>& attempts);

/// The initial increment for the next coupling iteration of the same time step: the first one
/// that converged, but never below a quarter of the deck's (`deck_initial`, one cut-back), so
/// that an iteration that needed deeper cut-backs does not make easier ones crawl up from a
/// tiny increment (ccx grows it by 1.5 an increment at most, within *STEP, INC=); nothing if
/// no increment converged.
std::optional<double> carried_initial_increment(const std::vector<IncrementAttempt>& attempts,
                                                double deck_initial);

}  // namespace cocopp::calculix
