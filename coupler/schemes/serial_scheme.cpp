// serial: the solvers one after the other, x~ = S(F(x)) (the serial scheme of CoCoNuT and
// preCICE). The unknown is x; S takes F's loads (or what a coupled solver that updates y too
// makes of them: LoadsUpdate).
#include "coupler/schemes/coupling_scheme.hpp"

namespace cocopp {
namespace {

class SerialScheme : public CouplingScheme {
 public:
  SerialScheme(const Settings&, Parts parts) : CouplingScheme(std::move(parts)) {}

  std::vector<const Interface*> unknown_layouts() const override { return {&x_}; }
  Eigen::VectorXd unknown() const override { return x_.data(); }
  void set_unknown(const Eigen::VectorXd& u) override { x_.set_data(u); }

  Eigen::VectorXd evaluate(const Eigen::VectorXd& x, int iteration) override {
    x_.set_data(x);
    const Interface& y = timed_solve(0, x_);
    check_finite(y, *solvers_[0], iteration);
    y_.set_data(loads_update_ ? loads_update_(x, y.data()) : y.data());
    const Interface& xt = timed_solve(1, y_);
    check_finite(xt, *solvers_[1], iteration);
    return xt.data();
  }
};

}  // namespace

COCOPP_REGISTER(CouplingSchemeRegistry, "serial", SerialScheme)

}  // namespace cocopp
