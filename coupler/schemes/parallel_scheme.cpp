// parallel: both solvers take the same iterate at once, y~ = F(x) and x~ = S(y) (preCICE's
// parallel-implicit scheme). The unknown is x and y stacked; S runs on a worker thread while F
// runs on the calling one, so that on a core per solver an iteration costs the slower solver's
// time, not the sum. Its fixed point is the serial scheme's: y = F(x), x = S(y). The coupled
// solver has to weigh the two fields against each other (a displacement in m beside a pressure
// in Pa), which `scaling` does (automatic by default here, docs/coupling.md).
#include <chrono>
#include <exception>

#include "coupler/schemes/coupling_scheme.hpp"
#include "solver_wrappers/worker_thread.hpp"

namespace cocopp {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class ParallelScheme : public CouplingScheme {
 public:
  // (Substeps are refused when the case is loaded: CoupledSolver::check_solvers.)
  ParallelScheme(const Settings&, Parts parts) : CouplingScheme(std::move(parts)) {}

  std::vector<const Interface*> unknown_layouts() const override { return {&x_, &y_}; }
  Eigen::VectorXd unknown() const override {
    Eigen::VectorXd u(x_.size() + y_.size());
    u << x_.data(), y_.data();
    return u;
  }
  void set_unknown(const Eigen::VectorXd& u) override {
    x_.set_data(u.head(x_.size()));
    y_.set_data(u.tail(y_.size()));
  }

  Eigen::VectorXd evaluate(const Eigen::VectorXd& u, int iteration) override {
    set_unknown(u);
    const std::array<double, 2> before = step_times();
    const auto start = std::chrono::steady_clock::now();
    const Interface* xt = nullptr;
    worker_.post([&] { xt = &timed_solve(1, y_); });
    const Interface* yt = nullptr;
    std::exception_ptr error;
    try {
      yt = &timed_solve(0, x_);
    } catch (...) {
      error = std::current_exception();
    }
    // S's call ends before anything leaves this function (its result refers to y_).
    try {
      worker_.wait();
    } catch (...) {
      if (!error) error = std::current_exception();
    }
    const double wall = seconds_since(start);
    add_overlap(step_times()[0] - before[0] + step_times()[1] - before[1] - wall);
    if (error) std::rethrow_exception(error);
    check_finite(*yt, *solvers_[0], iteration);
    check_finite(*xt, *solvers_[1], iteration);
    Eigen::VectorXd ut(u.size());
    ut << xt->data(), yt->data();
    return ut;
  }

 private:
  WorkerThread worker_;
};

}  // namespace

COCOPP_REGISTER(CouplingSchemeRegistry, "parallel", ParallelScheme)

}  // namespace cocopp
