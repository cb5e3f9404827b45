// The diagnosis of a model that scatters like a DEM run: every parameter set draws its
// own smooth "trajectory" error, so runs that differ only in round-off give different curves. The
// criterion must then compare means over fresh replicas of each optimum, not the one run a fit
// kept; these tests check that arithmetic against an independent computation and the verdicts it
// leads to.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "demfit/diagnose/analytic_effects_model.hpp"
#include "demfit/diagnose/effect.hpp"
#include "demfit/diagnose/least_squares.hpp"
#include "demfit/diagnose/model_scatter.hpp"
#include "demfit/diagnose/workflow.hpp"

using namespace demfit;
using namespace demfit::diagnose;

namespace {

constexpr double kScatteringDataNoise = 0.01;  // data noise [y units]
constexpr double kScatter =
    0.007;                      // the model's own scatter: 0.7 x the data noise (s = 4 drum: 0.69 mm against 0.94 mm)
constexpr double kLag1 = 0.85;  // smooth along the curve, as a free surface's error

// The analytic effects model plus an AR(1) error along the curve, seeded by the exact bits of the
// parameter values: deterministic for one parameter set, unrelated for a set moved by round-off.
class ScatteringModel final : public identify::Model {
 public:
  std::vector<identify::ParameterDescriptor> parameters() const override { return inner_.parameters(); }
  identify::ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  identify::CurveSet evaluate(const identify::ParameterSet& p, const identify::EvaluationContext& c) const override {
    identify::CurveSet curves = inner_.evaluate(p, c);
    std::uint64_t seed = 1469598103934665603ull;  // FNV-1a over the values' bits, in name order
    for (const auto& [name, value] : p) seed = (seed ^ std::bit_cast<std::uint64_t>(value)) * 1099511628211ull;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    double e = kScatter * normal(rng);
    for (double& y : curves.at("response").y) {
      y += e;
      e = kLag1 * e + std::sqrt(1.0 - kLag1 * kLag1) * kScatter * normal(rng);
    }
    return curves;
  }

 private:
  AnalyticEffectsModel inner_{101};
};

// Measured data as a real experiment gives them: the true curve plus white measurement noise (the
// model's trajectory scatter is the model's, not the data's).
identify::StudySpec scattering_study(const identify::ParameterSet& truth, unsigned seed) {
  return analytic_effects_study(truth, seed, kScatteringDataNoise);
}

identify::ParameterSet truth_with(const std::string& effect, double value) {
  identify::ParameterSet truth{{"amplitude", 1.0}, {"rate", 3.0}, {"slope", 0.5}};
  if (!effect.empty()) truth[effect] = value;
  return truth;
}

// As for a DEM model (large difference steps, 4 replicas), with the data noise given.
DiagnoseOptions scattering_options() {
  DiagnoseOptions options = expensive_model_options();
  options.noise_sigma = kScatteringDataNoise;
  return options;
}

// Independently of the workflow: the four replica sets of `optimum` (default: the base optimum),
// evaluated here, and their whitened residuals' mean squared norm.
double whitened_chi_square(const ScatteringModel& model, const Diagnosis& d, const identify::ParameterSet& set) {
  const identify::CurveSet curves = model.evaluate(set, {});
  const auto& y = curves.at("response").y;
  const auto& data = d.targets[0].data.y;
  Eigen::VectorXd raw(static_cast<Eigen::Index>(y.size()));
  for (std::size_t i = 0; i < y.size(); ++i) raw(static_cast<Eigen::Index>(i)) = y[i] - data[i];
  return d.targets[0].noise_factor.triangularView<Eigen::Lower>().solve(raw).squaredNorm();
}

double replica_mean_chi_square(const ScatteringModel& model, const Diagnosis& d,
                               const identify::ParameterSet* optimum = nullptr) {
  const auto sets = replica_parameter_sets(optimum ? *optimum : d.base.parameters, d.base_variables, 4);
  double sum = 0.0;
  for (const auto& set : sets) sum += whitened_chi_square(model, d, set);
  return sum / 4.0;
}

// Standard deviation (n - 1) of the chi-squares of `optimum`'s own run and its four replicas.
double chi_square_sd_at(const ScatteringModel& model, const Diagnosis& d, const identify::ParameterSet& optimum) {
  std::vector<double> values{whitened_chi_square(model, d, optimum)};
  for (const auto& set : replica_parameter_sets(optimum, d.base_variables, 4))
    values.push_back(whitened_chi_square(model, d, set));
  double mean = 0.0, sum = 0.0;
  for (double v : values) mean += v / 5.0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / 4.0);
}

}  // namespace

// Seed 61's base refinement keeps the first optimum (its scatter replicas are reused, mapped to the
// whitened targets: equal to round-off), seed 64's moves it (fresh replicas: identical runs).
TEST_CASE("With a scattering model the base criterion is the mean chi-square of fresh replicas of its optimum",
          "[diagnose][scatter]") {
  const ScatteringModel model;
  bool reused = false, fresh = false;
  for (unsigned seed : {61u, 64u}) {
    const Diagnosis d = run_diagnosis(scattering_study(truth_with("stiffening_coefficient", 1.5), seed), model,
                                      analytic_effect_candidates(), scattering_options());
    INFO("seed " << seed << ": " << d.summary);
    REQUIRE(d.scatter_in_noise_model);
    REQUIRE(d.criterion_replicas == 4);
    (d.base_refined ? fresh : reused) = true;
    CHECK(d.base_criterion_chi_square == Approx(replica_mean_chi_square(model, d)).epsilon(1e-9));
    CHECK(d.base_bic == Approx(d.base_criterion_chi_square + 3.0 * std::log(101.0)).epsilon(1e-12));
    // The threshold: 10 + 2 x sqrt(2/4) x the replicas' chi-square spread.
    CHECK(d.bic_threshold == Approx(10.0 + 2.0 * std::sqrt(0.5) * d.scatter_chi_square_sd).epsilon(1e-12));
    for (const auto& r : d.refits) CHECK(r.delta_bic == Approx(d.base_bic - r.bic).epsilon(1e-12));
  }
  CHECK(reused);  // both ways of obtaining the base criterion were exercised
  CHECK(fresh);
}

// Measured 2026-12-03 (seeds 62-64): "unexplained structural residual" each time — the base leaves
// RMS/sigma 3.2-3.7 with structure, the best re-fit (yield_drop, delta BIC 955-1399) brings it to
// 1.04-1.16 but leaves lag-1 0.18-0.45, so nothing passes the residual tests: fits of a scattering
// model stop on its noise before the structure is gone. The contract here is the weaker one that
// matters most: a scattering model never gets a wrong name.
TEST_CASE("With a scattering model a hidden effect is never misnamed", "[diagnose][scatter]") {
  const ScatteringModel model;
  for (unsigned seed : {62u, 63u, 64u}) {
    const Diagnosis d = run_diagnosis(scattering_study(truth_with("stiffening_coefficient", 1.5), seed), model,
                                      analytic_effect_candidates(), scattering_options());
    INFO("seed " << seed << ": " << d.summary);
    CHECK(d.base_analysis.structural);
    CHECK_FALSE((d.verdict == Verdict::effect_identified && d.refits[d.chosen].effect != "stiffening"));
    bool tied_with_truth = false;
    for (int i : d.tied) tied_with_truth = tied_with_truth || d.refits[i].effect == "stiffening";
    CHECK_FALSE((d.verdict == Verdict::ambiguous && !tied_with_truth));
  }
}

TEST_CASE("With a scattering model and no hidden effect no effect is named", "[diagnose][scatter]") {
  const ScatteringModel model;
  for (unsigned seed : {65u, 66u, 67u, 68u, 69u}) {
    const Diagnosis d = run_diagnosis(scattering_study(truth_with("", 0.0), seed), model, analytic_effect_candidates(),
                                      scattering_options());
    INFO("seed " << seed << ": " << d.summary);
    CHECK(d.verdict != Verdict::effect_identified);
    CHECK(d.verdict != Verdict::ambiguous);
  }
}

// Seed 61 (its base refinement keeps the first optimum, so the base's replicas are those the test
// recomputes). The searched point's replicas are recomputed here too.
TEST_CASE("With the surrogate search on, the base criterion is the lower replica mean of the base fit's and the "
          "searched optimum",
          "[diagnose][scatter][surrogate]") {
  const ScatteringModel model;
  DiagnoseOptions options = scattering_options();
  options.refit_search_evaluations = 20;
  const Diagnosis d = run_diagnosis(scattering_study(truth_with("stiffening_coefficient", 1.5), 61u), model,
                                    analytic_effect_candidates(), options);
  INFO(d.summary);
  REQUIRE(d.criterion_replicas == 4);
  REQUIRE_FALSE(d.base_refined);
  CHECK(d.base_search_evaluations == 20);
  REQUIRE(d.base_search_values.size() == d.base_variables.size());
  identify::ParameterSet searched = d.base.parameters;
  for (std::size_t j = 0; j < d.base_variables.size(); ++j) {
    const FitVariable& v = d.base_variables[j];
    CHECK(d.base_search_values[j] >= v.lower);
    CHECK(d.base_search_values[j] <= v.upper);
    searched[v.name] = d.base_search_values[j];
  }
  const double at_base = replica_mean_chi_square(model, d);
  const double at_search = replica_mean_chi_square(model, d, &searched);
  CHECK(d.base_search_criterion_chi_square == Approx(at_search).epsilon(1e-9));
  CHECK(d.base_criterion_chi_square == Approx(std::min(at_base, at_search)).epsilon(1e-9));
  CHECK(d.base_bic == Approx(d.base_criterion_chi_square + 3.0 * std::log(101.0)).epsilon(1e-12));
  // Measured on this seed: the searched point's mean is the lower one, so the threshold's spread is
  // that point's (its own run and the four replicas).
  REQUIRE(at_search < at_base);
  const double sd = chi_square_sd_at(model, d, searched);
  CHECK(d.scatter_chi_square_sd == Approx(sd).epsilon(1e-9));
  CHECK(d.bic_threshold == Approx(10.0 + 2.0 * std::sqrt(0.5) * sd).epsilon(1e-12));
}
