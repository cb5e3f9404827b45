#include "demfit/rbf_surrogate/optimize.hpp"
#include "test_functions.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace demfit::rbf_surrogate;

namespace {

// Branin on the unit square (x1 = -5 + 15u, x2 = 15v) with its analytic gradient.
double branin_unit_with_gradient(const VectorXd& u, VectorXd* g) {
  VectorXd x(2);
  x << -5 + 15 * u[0], 15 * u[1];
  const double pi = 3.141592653589793;
  const double b = 5.1 / (4 * pi * pi), c = 5 / pi, t = 1 / (8 * pi);
  const double w = x[1] - b * x[0] * x[0] + c * x[0] - 6;
  if (g) {
    g->resize(2);
    (*g)[0] = 15 * (2 * w * (-2 * b * x[0] + c) - 10 * (1 - t) * std::sin(x[0]));
    (*g)[1] = 15 * (2 * w);
  }
  return testfn::branin(x);
}

}  // namespace

TEST_CASE("Minimize finds Branin's global minimum with and without gradients", "[rbf_surrogate][optimize]") {
  for (bool use_gradient : {true, false}) {
    MinimizeOptions o;
    o.use_gradient = use_gradient;
    o.global_evaluations = 500;
    const MinimizeResult r = minimize(branin_unit_with_gradient, Box::unit(2), o);
    INFO("gradient " << use_gradient << " value " << r.value);
    CHECK(r.value == Approx(testfn::kBraninMinimum).epsilon(1e-8));
    CHECK(r.value == Approx(branin_unit_with_gradient(r.x, nullptr)).epsilon(1e-14));
  }
}

TEST_CASE("Minimize polishes a narrow valley to the analytic optimum", "[rbf_surrogate][optimize]") {
  // Rosenbrock-2 on [-2,2]^2 mapped to the unit square; minimum 0 at (1,1) -> (0.75, 0.75).
  const Objective f = [](const VectorXd& u, VectorXd* g) {
    const double x = -2 + 4 * u[0], y = -2 + 4 * u[1];
    if (g) {
      g->resize(2);
      (*g)[0] = 4 * (-400 * x * (y - x * x) - 2 * (1 - x));
      (*g)[1] = 4 * (200 * (y - x * x));
    }
    return 100 * (y - x * x) * (y - x * x) + (1 - x) * (1 - x);
  };
  MinimizeOptions o;
  o.local_evaluations = 500;
  const MinimizeResult r = minimize(f, Box::unit(2), o);
  CHECK(r.value < 1e-10);
  CHECK(r.x[0] == Approx(0.75).margin(1e-5));
  CHECK(r.x[1] == Approx(0.75).margin(1e-5));
}

TEST_CASE("Minimize respects the box and handles zero-width dimensions", "[rbf_surrogate][optimize]") {
  // Linear objective: the minimum is the lower-left corner of the box; dimension 1 is fixed.
  const Objective f = [](const VectorXd& x, VectorXd* g) {
    if (g) *g = VectorXd::Ones(3);
    return x.sum();
  };
  Box box{VectorXd::Zero(3), VectorXd::Zero(3)};
  box.lower << 0.2, 0.5, 0.3;
  box.upper << 0.6, 0.5, 0.9;
  const MinimizeResult r = minimize(f, box, {});
  CHECK((r.x - box.lower).norm() < 1e-9);
  CHECK(box.contains(r.x));
}

TEST_CASE("Minimize is deterministic and propagates objective errors", "[rbf_surrogate][optimize]") {
  MinimizeOptions o;
  o.global_evaluations = 300;
  const MinimizeResult a = minimize(branin_unit_with_gradient, Box::unit(2), o),
                       b = minimize(branin_unit_with_gradient, Box::unit(2), o);
  CHECK(a.x == b.x);
  CHECK(a.value == b.value);
  const Objective bad = [](const VectorXd&, VectorXd*) -> double { throw std::invalid_argument("boom"); };
  CHECK_THROWS_WITH(minimize(bad, Box::unit(2), o), "boom");
}
