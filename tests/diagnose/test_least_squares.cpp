// The bounded Levenberg-Marquardt fit of the diagnosis: branch-wise residuals of a
// loading-unloading curve, and Broyden-updated / central-difference Jacobians against the plain
// forward-difference fit on a smooth problem with a known optimum.
#include <catch2/catch.hpp>

#include "demfit/diagnose/analytic_effects_model.hpp"
#include "demfit/diagnose/least_squares.hpp"

using namespace demfit;
using namespace demfit::diagnose;

namespace {

// A model whose single curve is a loading-unloading cycle: y = s x for x = 0..1 (loading), then
// y = s x - 0.5 back from x = 1 to 0.5 (unloading, offset by the parameter-free 0.5).
class CycleModel final : public identify::Model {
 public:
  std::vector<identify::ParameterDescriptor> parameters() const override {
    return identify::unbounded_descriptors({"s"});
  }
  identify::ParameterSet default_parameters() const override { return {{"s", 1.0}}; }
  identify::CurveSet evaluate(const identify::ParameterSet& p, const identify::EvaluationContext&) const override {
    identify::Curve c{"x", "y", {}, {}};
    for (int i = 0; i <= 10; ++i) {
      c.x.push_back(0.1 * i);
      c.y.push_back(p.at("s") * 0.1 * i);
    }
    for (int i = 9; i >= 5; --i) {
      c.x.push_back(0.1 * i);
      c.y.push_back(p.at("s") * 0.1 * i - 0.5);
    }
    return {{"cycle", c}};
  }
};

}  // namespace

TEST_CASE("A curve whose x reverses is split into monotone branches at each turning point") {
  const std::vector<std::size_t> starts = monotone_branches({0, 1, 2, 3, 2, 1, 1, 2});
  REQUIRE(starts == std::vector<std::size_t>{0, 3, 6, 8});
  CHECK(monotone_branches({3, 2, 1}) == std::vector<std::size_t>{0, 3});
}

TEST_CASE("Residuals of a loading-unloading target compare each data branch with the same simulated branch") {
  const CycleModel model;
  // Data on both branches at abscissae between the simulated samples: y_load = 2x, y_unload = 2x - 0.5.
  identify::Curve data{"x", "y", {0.05, 0.55, 1.0, 0.75, 0.55}, {}};
  for (std::size_t i = 0; i < data.x.size(); ++i) data.y.push_back(2.0 * data.x[i] - (i >= 3 ? 0.5 : 0.0));
  const std::vector<FitTarget> targets{{"cycle", "cycle", data, 0.1, {}}};
  const auto r = raw_residuals(model.evaluate({{"s", 2.0}}, {}), targets);
  for (double v : r.front()) CHECK(v == Approx(0.0).margin(1e-12));
  // With s = 1 the residual is (1 - 2) x on both branches (the turning point belongs to loading).
  const auto q = raw_residuals(model.evaluate({{"s", 1.0}}, {}), targets);
  for (std::size_t i = 0; i < data.x.size(); ++i) CHECK(q.front()[i] == Approx(-data.x[i]).margin(1e-12));
}

TEST_CASE(
    "Broyden updates, with forward or central differences, reach the forward-difference optimum with fewer "
    "evaluations") {
  // Noise-free data of the analytic family at a known point inside the bounds: the optimum is
  // that point with chi-square 0 (up to the fit's tolerance).
  const AnalyticEffectsModel model(101);
  const identify::ParameterSet truth{{"amplitude", 1.1}, {"rate", 3.0}, {"slope", 0.4}};
  identify::ParameterSet fixed = model.default_parameters();
  for (const auto& [k, v] : truth) fixed[k] = v;
  const identify::Curve data = model.evaluate(fixed, {}).at("response");
  const std::vector<FitVariable> variables{
      {"amplitude", 0.5, 2.0, 1.6}, {"rate", 1.0, 8.0, 5.0}, {"slope", 0.0, 1.5, 0.9}};
  const std::vector<FitTarget> targets{{"response", "response", data, 0.01, {}}};
  FitOptions plain;
  plain.broyden = false;
  plain.absolute_tolerance = 1e-8;
  FitOptions broyden = plain;
  broyden.broyden = true;
  FitOptions central = broyden;
  central.central_differences = true;
  central.fd_step = 1e-4;
  std::vector<int> evaluations;
  for (const FitOptions* o : {&plain, &broyden, &central}) {
    const FitResult f = fit_least_squares(model, fixed, variables, targets, *o);
    evaluations.push_back(f.evaluations);
    INFO("broyden " << o->broyden << ", central " << o->central_differences << ": " << f.evaluations << " evaluations");
    CHECK(f.chi_square < 1e-4);  // RMS below 1e-4 sigma
    CHECK(f.values[0] == Approx(1.1).epsilon(1e-4));
    CHECK(f.values[1] == Approx(3.0).epsilon(1e-4));
    CHECK(f.values[2] == Approx(0.4).epsilon(1e-4));
    CHECK(f.jacobian.rows() == 101);
  }
  INFO("plain " << evaluations[0] << ", broyden " << evaluations[1] << ", broyden + central " << evaluations[2]);
  CHECK(evaluations[1] < evaluations[0]);  // measured 18 vs 29
  CHECK(evaluations[2] < evaluations[0]);  // measured 24 vs 29
}

TEST_CASE("A fit reports every accepted step: numbered from 1, evaluations rising, chi-square falling to the result") {
  const AnalyticEffectsModel model(51);
  identify::ParameterSet fixed = model.default_parameters();
  fixed["amplitude"] = 1.1;
  const identify::Curve data = model.evaluate(fixed, {}).at("response");
  const std::vector<FitVariable> variables{{"amplitude", 0.5, 2.0, 1.6}};
  const std::vector<FitTarget> targets{{"response", "response", data, 0.01, {}}};
  struct Step {
    int iteration, evaluations;
    double chi_square;
  };
  std::vector<Step> steps;
  FitOptions options;
  options.on_step = [&](int iteration, int evaluations, double chi_square) {
    steps.push_back({iteration, evaluations, chi_square});
  };
  const FitResult f = fit_least_squares(model, fixed, variables, targets, options);
  REQUIRE_FALSE(steps.empty());
  CHECK(steps.front().iteration == 1);
  for (std::size_t k = 1; k < steps.size(); ++k) {
    CHECK(steps[k].iteration == steps[k - 1].iteration + 1);
    CHECK(steps[k].evaluations > steps[k - 1].evaluations);
    CHECK(steps[k].chi_square < steps[k - 1].chi_square);
  }
  CHECK(steps.back().chi_square == f.chi_square);
  CHECK(steps.back().evaluations <= f.evaluations);
}
