#pragma once
// SolverError: a solver failed while running (crashed, hung, reported an error, broke the
// protocol). The message is complete (it names the solver and says what to look at); the name
// is carried separately so that callers can tell which solver of a coupled run failed.
#include <stdexcept>
#include <string>

namespace cocopp {

class SolverError : public std::runtime_error {
 public:
  SolverError(std::string solver_name, const std::string& message)
      : std::runtime_error(message), solver_name_(std::move(solver_name)) {}

  const std::string& solver_name() const noexcept { return solver_name_; }

 private:
  std::string solver_name_;
};

/// The solver could not solve the time step for this input (a structure loaded beyond what it
/// can carry, a mesh turned inside out) but kept the state the step started from, so it can
/// solve the step again for another input: the coupled solver may step back and retry.
class SolverRejectedInput : public SolverError {
 public:
  using SolverError::SolverError;
};

}  // namespace cocopp
