// Surrogate-based minimisation of expensive functions with few evaluations (issue #3 targets).
#include "demfit/rbf_surrogate/expensive.hpp"
#include "test_functions.hpp"

#include <catch2/catch.hpp>

using namespace demfit::rbf_surrogate;

namespace {

const std::vector<Variable> kBraninVars{{"x1", -5.0, 10.0}, {"x2", 0.0, 15.0}};

std::vector<Variable> hartmann_vars() {
    std::vector<Variable> v;
    for (int i = 0; i < 6; ++i) {
        std::string name = "x";
        name += std::to_string(i);
        v.push_back({name, 0.0, 1.0});
    }
    return v;
}

}  // namespace

TEST_CASE("SRSM loop reaches Branin's global minimum within 1e-3 in at most 60 evaluations",
          "[rbf_surrogate][expensive]") {
    ExpensiveOptions o;
    o.strategy = InfillStrategy::srsm;
    o.max_evaluations = 60;
    const ExpensiveResult r = minimise_expensive(testfn::branin, kBraninVars, o);
    INFO("best " << r.value << " after " << r.evaluations);
    CHECK(r.evaluations <= 60);
    CHECK(r.value - testfn::kBraninMinimum < 1e-3);
    CHECK(r.value == Approx(testfn::branin(r.x)).epsilon(1e-15));
}

TEST_CASE("Adaptive infill loop reaches Branin's global minimum within 1e-3 in at most 60 evaluations",
          "[rbf_surrogate][expensive]") {
    ExpensiveOptions o;
    o.strategy = InfillStrategy::adaptive;
    o.max_evaluations = 60;
    const ExpensiveResult r = minimise_expensive(testfn::branin, kBraninVars, o);
    INFO("best " << r.value << " after " << r.evaluations);
    CHECK(r.value - testfn::kBraninMinimum < 1e-3);
}

TEST_CASE("SRSM loop reaches Hartmann-6 within 1 % in at most 200 evaluations", "[rbf_surrogate][expensive]") {
    ExpensiveOptions o;
    o.strategy = InfillStrategy::srsm;
    o.max_evaluations = 200;
    const ExpensiveResult r = minimise_expensive(testfn::hartmann6, hartmann_vars(), o);
    INFO("best " << r.value << " after " << r.evaluations);
    CHECK(r.value < 0.99 * testfn::kHartmann6Minimum);
}

TEST_CASE("Adaptive infill loop reaches Hartmann-6 within 1 % in at most 200 evaluations",
          "[rbf_surrogate][expensive]") {
    ExpensiveOptions o;
    o.strategy = InfillStrategy::adaptive;
    o.max_evaluations = 200;
    o.target = 0.99 * testfn::kHartmann6Minimum;  // stop once reached: keeps the test short
    const ExpensiveResult r = minimise_expensive(testfn::hartmann6, hartmann_vars(), o);
    INFO("best " << r.value << " after " << r.evaluations);
    CHECK(r.value < 0.99 * testfn::kHartmann6Minimum);
}

TEST_CASE("Expensive minimisation is deterministic for a seed", "[rbf_surrogate][expensive]") {
    ExpensiveOptions o;
    o.max_evaluations = 25;
    const ExpensiveResult a = minimise_expensive(testfn::branin, kBraninVars, o);
    const ExpensiveResult b = minimise_expensive(testfn::branin, kBraninVars, o);
    CHECK(a.points == b.points);
    CHECK(a.values == b.values);
    REQUIRE(a.best_so_far.size() == 25);
    for (std::size_t i = 1; i < a.best_so_far.size(); ++i) CHECK(a.best_so_far[i] <= a.best_so_far[i - 1]);
}
