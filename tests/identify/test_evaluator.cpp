#include <catch2/catch.hpp>

#include <stdexcept>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/evaluator.hpp"

using namespace demfit::identify;

TEST_CASE("The thread pool returns outcomes in submission order and records model failures", "[identify][evaluator]") {
  const AnalyticCurveModel model;
  std::vector<ParameterSet> batch;
  for (int i = 0; i < 9; ++i) batch.push_back({{"amplitude", 1.0 + i}});
  batch[4] = {{"stiffness", 1.0}};  // unknown parameter: the model throws
  ThreadPoolEvaluator pool(model, 3, 1, 0);
  int callbacks = 0;
  const auto outcomes = pool.evaluate_points(model, batch, [&](std::size_t, const EvaluationOutcome&) { ++callbacks; });
  CHECK(callbacks == 9);
  for (int i = 0; i < 9; ++i) {
    if (i == 4) {
      CHECK_FALSE(outcomes[i].ok);
      CHECK_THAT(outcomes[i].error, Catch::Contains("stiffness"));
      continue;
    }
    REQUIRE(outcomes[i].ok);
    // y(x) = a (1 - exp(-3 x)) + 0.5 x at x = 1 with a = 1 + i
    CHECK(outcomes[i].curves.at("response").y.back() == Approx((1.0 + i) * (1 - std::exp(-3.0)) + 0.5));
  }
}

TEST_CASE("An exception thrown by the completion callback stops the batch and propagates", "[identify][evaluator]") {
  const AnalyticCurveModel model;
  std::vector<ParameterSet> batch(20, ParameterSet{});
  ThreadPoolEvaluator pool(model, 2, 1, 0);
  int done = 0;
  CHECK_THROWS_WITH(pool.evaluate_points(model, batch,
                                         [&](std::size_t, const EvaluationOutcome&) {
                                           if (++done == 3) throw std::runtime_error("killed");
                                         }),
                    "killed");
  CHECK(done == 3);
}
