// The IQN-ILS least-squares model: preCICE's reference values, filtering, reuse.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <deque>

#include "coupler/coupled_solvers/models/model.hpp"

using namespace cocopp;

namespace {

std::unique_ptr<Model> make(const std::string& yaml) {
  return ModelRegistry::instance().create(Settings::load_string(yaml, "model.yaml"));
}

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(values.size());
  int i = 0;
  for (double x : values) v(i++) = x;
  return v;
}

}  // namespace

// The reference values of preCICE's IQN-ILS unit test: primary
// data d (4 values) in the least-squares problem, secondary data f only in W.
TEST(LeastSquares, ReproducesPreciceReferenceValues) {
  auto model = make("type: ls");
  model->initialize_step();
  const double omega = 0.01;
  const Eigen::VectorXd d1 = vec({1, 1, 1, 1});
  const Eigen::VectorXd dt1 = vec({1, 2, 3, 4});  // solver output, iteration 1
  const Eigen::VectorXd r1 = dt1 - d1;
  // x~ of the model holds d and f: W gets the secondary data too.
  model->add(r1, vec({1, 2, 3, 4, 0.1}));
  ASSERT_FALSE(model->is_ready());
  const Eigen::VectorXd d2 = d1 + omega * r1;
  const double f2 = 0.2 + omega * (0.1 - 0.2);
  EXPECT_NEAR(f2, 0.199, 1e-15);
  EXPECT_TRUE(d2.isApprox(vec({1, 1.01, 1.02, 1.03}), 1e-15));

  // preCICE's test leaves its "old values" at d1 when the solver writes the second output, so
  // its second residual is taken against d1; feed the model the same secant pair.
  const Eigen::VectorXd dt2 = vec({10, 10, 10, 10});
  const Eigen::VectorXd r2 = dt2 - d1;
  model->add(r2, vec({10, 10, 10, 10, 0.199}));
  ASSERT_TRUE(model->is_ready());
  const Eigen::VectorXd update = model->predict(-r2);
  const Eigen::VectorXd d3 = dt2 + update.head(4);
  const double f3 = 0.199 + update(4);
  const Eigen::VectorXd expected =
      vec({-0.565217391304349, 0.608695652173912, 1.78260869565217, 2.95652173913043});
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(d3(i), expected(i), 1e-13) << i;
  EXPECT_NEAR(f3, 0.0827826086956522, 1e-14);
}

TEST(LeastSquares, RepeatedResidualIsFilteredNotNaN) {
  auto model = make("type: ls");
  model->initialize_step();
  const Eigen::VectorXd r = vec({1, 2, 3});
  model->add(r, r);
  model->add(r, r);  // no change: a zero column, dropped at once
  EXPECT_FALSE(model->is_ready());
  EXPECT_EQ(model->columns(), 0);
  EXPECT_TRUE(model->predict(-r).allFinite());
  // The coupled solver turns this into a warning of the step.
  const auto notes = model->take_notes();
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("repeated residual"), std::string::npos) << notes[0];
  EXPECT_TRUE(model->take_notes().empty());
}

TEST(LeastSquares, DependentColumnsAreFilteredKeepingTheNewest) {
  auto model = make("type: ls\nmin_significant_relative: 1e-8");
  model->initialize_step();
  model->add(vec({0, 0, 0}), vec({0, 0, 0}));
  model->add(vec({1, 0, 0}), vec({1, 0, 0}));
  model->add(vec({2, 0, 0}), vec({5, 0, 0}));  // same direction as the first column
  model->predict(vec({1, 0, 0}));
  EXPECT_EQ(model->columns(), 1);
  // The newest column (dr = e1, dx~ = 4 e1) is the one kept.
  EXPECT_NEAR(model->predict(vec({1, 0, 0}))(0), 4.0, 1e-14);
}

// filter_order: with columns (newest first) e1, c1 = (1, 0.05, 0), c2 = (1, 0.5, 0.01) and
// min_significant 0.1, both older columns are insignificant (R_11 = 0.05, R_22 = 0.01).
// `newest` drops c1 first, after which c2's part not explained by e1 (0.5) is significant;
// `smallest` drops c2 first, which leaves c1 as insignificant as before.
TEST(LeastSquares, FilterOrderChoosesWhichInsignificantColumnGoesFirst) {
  auto columns_after = [](const std::string& order) {
    auto model = make("type: ls\nmin_significant: 0.1\nfilter_order: " + order);
    model->initialize_step();
    Eigen::VectorXd r = vec({0, 0, 0});
    model->add(r, r);
    for (const Eigen::VectorXd& column : {vec({1, 0.5, 0.01}), vec({1, 0.05, 0}), vec({1, 0, 0})}) {
      r += column;
      model->add(r, r);
    }
    return model->columns();
  };
  EXPECT_EQ(columns_after("newest"), 2);
  EXPECT_EQ(columns_after("smallest"), 1);
  EXPECT_THROW(make("type: ls\nfilter_order: oldest"), CaseError);
}

TEST(LeastSquares, ReusesQPreviousSteps) {
  auto model = make("type: ls\nq: 1");
  auto add_step = [&](double scale) {
    model->initialize_step();
    model->add(vec({0, 0}), vec({0, 0}));
    model->add(vec({scale, 0}), vec({0, scale}));
    model->finalize_step();
  };
  add_step(1.0);
  model->initialize_step();
  EXPECT_TRUE(model->is_ready());  // one column from the previous step
  EXPECT_EQ(model->columns(), 1);
  model->finalize_step();
  EXPECT_FALSE(model->is_ready());  // older than q = 1 steps: dropped
}

TEST(LeastSquares, InvalidSettings) {
  EXPECT_THROW(make("type: ls\nq: -1"), CaseError);
  EXPECT_THROW(make("type: ls\nmin_significant: -1"), CaseError);
}

// The updated factorization gives the least-squares solution of a fresh one, over many
// iterations and time steps with reuse (filters off).
TEST(LeastSquares, MatchesADirectLeastSquaresSolveWithReuse) {
  std::srand(3);
  const int n = 30;
  auto model = make("type: ls\nq: 2\nmin_significant: 0");
  std::deque<std::pair<Eigen::VectorXd, Eigen::VectorXd>> kept;  // (v, w), newest first
  std::deque<int> ages;
  for (int step = 0; step < 4; ++step) {
    model->initialize_step();
    Eigen::VectorXd r_ref, xt_ref;
    for (int iteration = 0; iteration < 5; ++iteration) {
      const Eigen::VectorXd r = Eigen::VectorXd::Random(n), xt = Eigen::VectorXd::Random(n);
      model->add(r, xt);
      if (iteration > 0) {
        kept.push_front({r - r_ref, xt - xt_ref});
        ages.push_front(0);
      }
      r_ref = r;
      xt_ref = xt;
      if (kept.empty()) continue;
      Eigen::MatrixXd v(n, kept.size()), w(n, kept.size());
      for (std::size_t i = 0; i < kept.size(); ++i) {
        v.col(i) = kept[i].first;
        w.col(i) = kept[i].second;
      }
      const Eigen::VectorXd dr = Eigen::VectorXd::Random(n);
      const Eigen::VectorXd expected = w * v.colPivHouseholderQr().solve(dr);
      EXPECT_TRUE(model->predict(dr).isApprox(expected, 1e-9)) << step << " " << iteration;
    }
    model->finalize_step();
    for (auto& age : ages) ++age;
    while (!ages.empty() && ages.back() > 2) {
      ages.pop_back();
      kept.pop_back();
    }
    EXPECT_EQ(model->columns(), int(kept.size()));
  }
}
