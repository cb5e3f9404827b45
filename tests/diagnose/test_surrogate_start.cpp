// The surrogate search start of a re-fit (surrogate_start.hpp) on a model whose every run is
// perturbed the way a DEM trajectory is: deterministically, but differently for parameters a
// round-off apart.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "demfit/diagnose/surrogate_start.hpp"
#include "demfit/rbf_surrogate/design.hpp"

using namespace demfit;
using namespace demfit::diagnose;

namespace {

// y(x) = bump sin(pi x) + slope (x - 1/2) on 40 points of [0, 1] (two shapes orthogonal on [0, 1],
// so the chi-square valley is not a long diagonal), plus a perturbation of 0.7 noise levels per
// point drawn from a generator seeded by the parameters' bits (a "trajectory" per run).
class ChaoticBumpModel final : public identify::Model {
 public:
  static constexpr double kPerturbation = 0.035;  // [y units]
  static constexpr double kPi = 3.14159265358979323846;
  std::vector<identify::ParameterDescriptor> parameters() const override {
    return identify::unbounded_descriptors({"bump", "slope"});
  }
  identify::ParameterSet default_parameters() const override { return {{"bump", 1.0}, {"slope", 0.0}}; }
  identify::CurveSet evaluate(const identify::ParameterSet& p, const identify::EvaluationContext&) const override {
    const double bump = p.at("bump"), slope = p.at("slope");
    std::mt19937_64 trajectory(std::bit_cast<std::uint64_t>(bump) ^ (std::bit_cast<std::uint64_t>(slope) << 1));
    identify::Curve c{"x", "y", {}, {}};
    for (int i = 0; i < 40; ++i) {
      const double x = i / 39.0;
      c.x.push_back(x);
      c.y.push_back(bump * std::sin(kPi * x) + slope * (x - 0.5) + kPerturbation * rbf_surrogate::normal01(trajectory));
    }
    return {{"bump_curve", c}};
  }
};

// Data at bump 2.6, slope -1.1 without perturbation, matched with a noise level of 0.05.
std::vector<FitTarget> bump_targets() {
  FitTarget t;
  t.name = "bump_curve";
  t.curve = "bump_curve";
  t.sigma = 0.05;
  t.data.x_label = "x";
  t.data.y_label = "y";
  for (int i = 0; i < 40; ++i) {
    const double x = i / 39.0;
    t.data.x.push_back(x);
    t.data.y.push_back(2.6 * std::sin(ChaoticBumpModel::kPi * x) - 1.1 * (x - 0.5));
  }
  return {t};
}

const std::vector<FitVariable> kBumpVariables{{"bump", 0.0, 4.0, 1.0}, {"slope", -2.0, 2.0, 0.0}};

}  // namespace

TEST_CASE("The surrogate search start lies near the optimum of a model whose runs scatter like trajectories",
          "[diagnose][surrogate]") {
  const ChaoticBumpModel model;
  FitOptions fit;
  fit.jobs = 2;
  const SurrogateStart s =
      surrogate_search_start(model, {}, kBumpVariables, bump_targets(), fit, 30, 5, {{1.0, 0.0}}, {2.0e4});
  CHECK(s.evaluations == 30);
  // 5 % of each range. The valley: a bump error d costs d^2 sum(sin^2)/sigma^2 = 8.0e3 d^2 of
  // chi-square (a slope error 1.4e3 d^2), against a run-to-run spread of sqrt(2 x 40) x 0.49 ~ 4.4
  // at the optimum: 0.1 off costs 80 (14) more than the optimum's ~20.
  CHECK(s.values[0] == Approx(2.6).margin(0.1));
  CHECK(s.values[1] == Approx(-1.1).margin(0.1));
  // The chi-square of the noise-free data against a perturbed run is 40 x 0.49 = 19.6 on average
  // (sd 4.4): the smoothed prediction, not the luckiest run.
  CHECK(s.predicted_chi_square == Approx(19.6).margin(8.0));
}

TEST_CASE("The surrogate search start is the same for the same seed whatever the number of jobs",
          "[diagnose][surrogate]") {
  const ChaoticBumpModel model;
  FitOptions one, two;
  one.jobs = 1;
  two.jobs = 2;
  const auto a = surrogate_search_start(model, {}, kBumpVariables, bump_targets(), one, 16, 9);
  const auto b = surrogate_search_start(model, {}, kBumpVariables, bump_targets(), two, 16, 9);
  CHECK(a.values == b.values);
  CHECK(a.run_chi_square == b.run_chi_square);
}

TEST_CASE("The surrogate search start returns the residual of its chosen run, equal to a fresh run there",
          "[diagnose][surrogate]") {
  const ChaoticBumpModel model;
  const FitOptions fit;
  const SurrogateStart s = surrogate_search_start(model, {}, kBumpVariables, bump_targets(), fit, 16, 9);
  identify::ParameterSet at;
  for (std::size_t j = 0; j < kBumpVariables.size(); ++j) at[kBumpVariables[j].name] = s.values[j];
  const Eigen::VectorXd fresh = residuals_at(model, {at}, bump_targets(), fit).front();
  REQUIRE(s.run_residual.size() == fresh.size());
  CHECK(s.run_residual == fresh);  // the model is deterministic for one parameter set
  CHECK(s.run_residual.squaredNorm() == s.run_chi_square);
}
