#include "demfit/rbf_surrogate/bounds.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

using namespace demfit::rbf_surrogate;

TEST_CASE("Unit normalisation maps bounds to 0 and 1 and round-trips", "[rbf_surrogate][bounds]") {
  const std::vector<Variable> vars{{"a", -2.0, 6.0}, {"b", 1e-3, 1e1, true}};
  VectorXd lo(2), hi(2), mid(2);
  lo << -2.0, 1e-3;
  hi << 6.0, 1e1;
  CHECK((to_unit(vars, lo) - VectorXd::Zero(2)).norm() < 1e-14);
  CHECK((to_unit(vars, hi) - VectorXd::Ones(2)).norm() < 1e-14);
  // Log scale: the unit midpoint is the geometric mean sqrt(1e-3 * 1e1) = 0.1.
  mid << 0.5, 0.5;
  const VectorXd phys = from_unit(vars, mid);
  CHECK(phys[0] == Approx(2.0).epsilon(1e-14));
  CHECK(phys[1] == Approx(0.1).epsilon(1e-12));
  VectorXd x(2);
  x << 1.234, 0.0321;
  CHECK((from_unit(vars, to_unit(vars, x)) - x).norm() < 1e-12);
}

TEST_CASE("Invalid variables are rejected with a message naming the variable", "[rbf_surrogate][bounds]") {
  CHECK_THROWS_WITH(validate(std::vector<Variable>{{"normal_stiffness", 1.0, 1.0}}),
                    Catch::Contains("normal_stiffness"));
  CHECK_THROWS_AS(validate(std::vector<Variable>{{"k", 0.0, 1.0, true}}), std::invalid_argument);
  CHECK_THROWS_AS(validate(std::vector<Variable>{{"k", 0.0, NAN}}), std::invalid_argument);
}

TEST_CASE("Box local coordinates and clamping are consistent", "[rbf_surrogate][bounds]") {
  Box b{VectorXd::Constant(3, 0.2), VectorXd::Constant(3, 0.6)};
  VectorXd u(3);
  u << 0.0, 0.5, 1.0;
  const VectorXd x = b.from_local(u);
  CHECK(x[1] == Approx(0.4));
  CHECK((b.to_local(x) - u).norm() < 1e-14);
  CHECK(b.contains(x));
  CHECK_FALSE(b.contains(VectorXd::Constant(3, 0.7)));
  CHECK((b.clamp(VectorXd::Constant(3, 0.9)) - b.upper).norm() == 0.0);
}
