// The diagnosis workflow on synthetic data with a hidden effect (seeded noise, sigma 0.01 on a
// curve of amplitude ~1.5): the workflow is not told which effect, or whether there is one.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <map>
#include <random>

#include "demfit/diagnose/analytic_effects_model.hpp"
#include "demfit/diagnose/effect.hpp"
#include "demfit/diagnose/workflow.hpp"
#include "demfit/identify/analytic_model.hpp"

using namespace demfit;
using namespace demfit::diagnose;

namespace {

constexpr double kDataNoise = 0.01;

identify::StudySpec synthetic_study(const identify::ParameterSet& truth, unsigned seed, int points = 101) {
  return analytic_effects_study(truth, seed, kDataNoise, points);
}

identify::ParameterSet base_truth() { return {{"amplitude", 1.0}, {"rate", 3.0}, {"slope", 0.5}}; }

Diagnosis diagnose_hidden(const std::string& parameter, double value, unsigned seed,
                          const std::vector<EffectCandidate>& candidates = analytic_effect_candidates()) {
  identify::ParameterSet truth = base_truth();
  if (!parameter.empty()) truth[parameter] = value;
  const AnalyticEffectsModel model(101);
  return run_diagnosis(synthetic_study(truth, seed), model, candidates, DiagnoseOptions{});
}

void check_named(const Diagnosis& d, const std::string& effect) {
  INFO(d.summary);
  CHECK(d.base_analysis.structural);
  REQUIRE(d.verdict == Verdict::effect_identified);
  REQUIRE(d.chosen >= 0);
  CHECK(d.refits[d.chosen].effect == effect);
  CHECK(d.refits[d.chosen].delta_bic > 10.0);
  // Gap after: RMS within 1.5x the true noise (the acceptance criterion).
  CHECK(d.refits[d.chosen].analysis.rms < 1.5 * kDataNoise);
  CHECK(d.base_analysis.rms > 1.5 * kDataNoise);
}

}  // namespace

TEST_CASE("The analytic effects model reproduces the identify analytic model with every effect off") {
  const AnalyticEffectsModel effects(41);
  const identify::AnalyticCurveModel plain(41);
  const identify::ParameterSet p{{"amplitude", 1.3}, {"rate", 2.5}, {"slope", 0.2}};
  const auto a = effects.evaluate(p, {}).at("response");
  const auto b = plain.evaluate(p, {}).at("response");
  REQUIRE(a.y.size() == b.y.size());
  for (std::size_t i = 0; i < a.y.size(); ++i) CHECK(a.y[i] == Approx(b.y[i]).margin(1e-14));
}

TEST_CASE("A hidden stiffening effect is named and the RMS gap shrinks to within 1.5x the noise") {
  const Diagnosis d = diagnose_hidden("stiffening_coefficient", 1.5, 21);
  check_named(d, "stiffening");
  CHECK(d.refits[d.chosen].fit.parameters.at("stiffening_coefficient") == Approx(1.5).margin(0.3));
}

TEST_CASE("A hidden toe shift is named and the RMS gap shrinks to within 1.5x the noise") {
  check_named(diagnose_hidden("toe_shift", 0.05, 22), "toe_shift");
}

TEST_CASE("A hidden yield drop is named, localised in the last third, and the gap shrinks to the noise") {
  const Diagnosis d = diagnose_hidden("yield_drop", 0.25, 23);
  check_named(d, "yield_drop");
  REQUIRE(d.base_analysis.worst_region >= 0);
  CHECK(d.base_analysis.regions[d.base_analysis.worst_region].label.find("last third") != std::string::npos);
}

TEST_CASE("The score test ranks the hidden effect first among the candidates") {
  const Diagnosis d = diagnose_hidden("yield_drop", 0.25, 24);
  REQUIRE(d.screening.size() == 3);
  CHECK(d.screening[2].effect == "yield_drop");
  CHECK(d.screening[2].score > d.screening[0].score);
  CHECK(d.screening[2].score > d.screening[1].score);
  CHECK(d.screening[2].fraction_explained > 0.5);
}

TEST_CASE("Without a hidden effect the workflow reports no missing effect") {
  for (unsigned seed : {31u, 32u, 33u}) {
    const Diagnosis d = diagnose_hidden("", 0.0, seed);
    INFO("seed " << seed << ": " << d.summary);
    CHECK(d.verdict == Verdict::no_missing_effect);
    CHECK(d.chosen < 0);
    // The estimated noise level is the true one within 15 %.
    CHECK(d.targets[0].sigma == Approx(kDataNoise).epsilon(0.15));
  }
}

TEST_CASE("A base fit held at the end of a variable's range says so beside the verdict, and only then") {
  // Truth amplitude 1.0 just beyond the range's end 0.999: the fit stays at 0.999, 0.1 % off, far
  // below the noise, so the verdict is "no missing effect" and the note must qualify it.
  identify::StudySpec study = synthetic_study(base_truth(), 31);
  REQUIRE(study.variables[0].name == "amplitude");
  study.variables[0].upper = 0.999;
  study.variables[0].initial = 0.9;
  const AnalyticEffectsModel model(101);
  const Diagnosis d = run_diagnosis(study, model, analytic_effect_candidates(), DiagnoseOptions{});
  INFO(d.summary);
  CHECK(d.verdict == Verdict::no_missing_effect);
  CHECK(d.summary.find("ran to the end of its range: 'amplitude' at 0.99") != std::string::npos);
  CHECK(d.summary.find("(its upper bound 0.999)") != std::string::npos);
  CHECK(d.summary.find("'rate'") == std::string::npos);
  // The same data with the shipped range (0.5 to 2): no note.
  const Diagnosis free = diagnose_hidden("", 0.0, 31);
  INFO(free.summary);
  CHECK(free.summary.find("ran to the end of its range") == std::string::npos);
}

TEST_CASE("A hidden effect outside the candidate list is reported as an unexplained structural residual") {
  // The ripple is not a candidate: no candidate may be named for it.
  const Diagnosis d = diagnose_hidden("ripple_amplitude", 0.03, 41);
  INFO(d.summary);
  CHECK(d.base_analysis.structural);
  CHECK(d.verdict == Verdict::unexplained_structural);
  CHECK(d.chosen < 0);
  CHECK(d.summary.find("no effect is named") != std::string::npos);
  // A real effect left out of the list is not misnamed either.
  auto without_toe = analytic_effect_candidates();
  without_toe.erase(without_toe.begin());
  const Diagnosis e = diagnose_hidden("toe_shift", 0.05, 42, without_toe);
  INFO(e.summary);
  CHECK(e.verdict == Verdict::unexplained_structural);
}

TEST_CASE("A given noise level replaces the estimate and inconsistent candidates are refused") {
  identify::StudySpec spec = synthetic_study(base_truth(), 51);
  const AnalyticEffectsModel model(101);
  DiagnoseOptions options;
  options.noise_sigma = kDataNoise;
  const Diagnosis d = run_diagnosis(spec, model, analytic_effect_candidates(), options);
  CHECK(d.targets[0].sigma == kDataNoise);
  CHECK(d.verdict == Verdict::no_missing_effect);
  auto bad = analytic_effect_candidates();
  bad[0].parameters[0].off_value = 5.0;
  CHECK_THROWS_WITH(run_diagnosis(spec, model, bad, options), Catch::Contains("off_value"));
  auto unknown = analytic_effect_candidates();
  unknown[0].parameters[0].name = "cohesion_force";
  CHECK_THROWS_WITH(run_diagnosis(spec, model, unknown, options), Catch::Contains("no parameter 'cohesion_force'"));
}

// The analytic effects model declaring that its toe shift must lie in [0, 0.1]; it counts its
// evaluations.
class NarrowToeShiftModel final : public identify::Model {
 public:
  std::vector<identify::ParameterDescriptor> parameters() const override {
    auto out = inner_.parameters();
    for (auto& d : out)
      if (d.name == "toe_shift") d.valid = {0.0, 0.1};
    return out;
  }
  identify::ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  identify::CurveSet evaluate(const identify::ParameterSet& p, const identify::EvaluationContext& c) const override {
    ++evaluations;
    return inner_.evaluate(p, c);
  }
  mutable std::atomic<int> evaluations{0};

 private:
  AnalyticEffectsModel inner_{101};
};

TEST_CASE("An effect candidate whose range leaves the model's valid range is refused before any evaluation") {
  const identify::StudySpec spec = synthetic_study(base_truth(), 52);
  const NarrowToeShiftModel model;
  DiagnoseOptions options;
  options.noise_sigma = kDataNoise;
  // analytic_effect_candidates' toe_shift range is [0, 0.2].
  CHECK_THROWS_WITH(
      run_diagnosis(spec, model, analytic_effect_candidates(), options),
      Catch::Contains("effect 'toe_shift'") && Catch::Contains("[0, 0.2]") && Catch::Contains("[0, 0.1]"));
  CHECK(model.evaluations == 0);
  auto narrowed = analytic_effect_candidates();
  for (auto& c : narrowed)
    if (c.name == "toe_shift") c.parameters[0].upper = 0.1;
  CHECK_NOTHROW(run_diagnosis(spec, model, narrowed, options));
}

TEST_CASE("Over 20 noise seeds hidden effects are named correctly at least 85 percent of the time and never wrongly") {
  // Over 100 seeds (docs/diagnose.md) the rates are 97-98 % named, the rest reported as
  // unexplained (the safe failure: naming needs the residual to pass the tests at 5 %).
  // Wrong names, and names without a hidden effect or for the ripple, must never occur.
  const std::vector<std::pair<std::string, std::string>> hidden{
      {"stiffening_coefficient", "stiffening"}, {"toe_shift", "toe_shift"}, {"yield_drop", "yield_drop"}};
  const std::map<std::string, double> size{{"stiffening_coefficient", 1.5}, {"toe_shift", 0.05}, {"yield_drop", 0.25}};
  std::map<std::string, int> named;
  const int seeds = 20;
  for (unsigned seed = 1000; seed < 1000 + seeds; ++seed) {
    for (const auto& [parameter, effect] : hidden) {
      const Diagnosis d = diagnose_hidden(parameter, size.at(parameter), seed);
      INFO("seed " << seed << ", hidden " << effect << ": " << d.summary);
      CHECK(d.verdict != Verdict::no_missing_effect);
      if (d.chosen < 0) continue;
      CHECK(d.refits[d.chosen].effect == effect);
      CHECK(d.refits[d.chosen].analysis.rms < 1.5 * kDataNoise);
      named[effect] += d.refits[d.chosen].effect == effect;
    }
    const Diagnosis none = diagnose_hidden("", 0.0, seed);
    INFO("seed " << seed << ", no hidden effect: " << none.summary);
    CHECK(none.verdict == Verdict::no_missing_effect);
    const Diagnosis ripple = diagnose_hidden("ripple_amplitude", 0.03, seed);
    INFO("seed " << seed << ", ripple: " << ripple.summary);
    CHECK(ripple.verdict == Verdict::unexplained_structural);
  }
  for (const auto& [parameter, effect] : hidden) {
    INFO(effect);
    CHECK(named[effect] >= 17);
  }
}

TEST_CASE("The diagnosis does not depend on the number of parallel evaluations") {
  identify::ParameterSet truth = base_truth();
  truth["yield_drop"] = 0.25;
  const identify::StudySpec spec = synthetic_study(truth, 61);
  const AnalyticEffectsModel model(101);
  DiagnoseOptions serial, parallel;
  parallel.fit.jobs = 3;
  const Diagnosis a = run_diagnosis(spec, model, analytic_effect_candidates(), serial);
  const Diagnosis b = run_diagnosis(spec, model, analytic_effect_candidates(), parallel);
  CHECK(a.base.chi_square == b.base.chi_square);  // bit-identical
  REQUIRE(a.refits.size() == b.refits.size());
  for (std::size_t i = 0; i < a.refits.size(); ++i) CHECK(a.refits[i].fit.chi_square == b.refits[i].fit.chi_square);
  CHECK(a.summary == b.summary);
}

TEST_CASE("Two targets get their own noise levels and a hidden effect is still named, localised per target") {
  // The same curve measured twice: x in [0, 0.5] with sigma 0.01 and x in [0.5, 1] with sigma 0.03.
  identify::ParameterSet truth = base_truth();
  truth["yield_drop"] = 0.4;
  const AnalyticEffectsModel model(201);
  const identify::Curve full = model.evaluate(truth, {}).at("response");
  std::mt19937 rng(71);
  std::normal_distribution<double> normal(0.0, 1.0);
  identify::StudySpec spec = synthetic_study(base_truth(), 71);
  spec.targets.clear();
  for (int part = 0; part < 2; ++part) {
    identify::TargetSpec t;
    t.name = part == 0 ? "early" : "late";
    t.curve = "response";
    t.data = {"x_1", "y_1", {}, {}};
    for (std::size_t i = 0; i < full.x.size(); ++i)
      if ((part == 0 && full.x[i] <= 0.5) || (part == 1 && full.x[i] > 0.5)) {
        t.data.x.push_back(full.x[i]);
        t.data.y.push_back(full.y[i] + (part == 0 ? 0.01 : 0.03) * normal(rng));
      }
    spec.targets.push_back(t);
  }
  const Diagnosis d = run_diagnosis(spec, model, analytic_effect_candidates(), DiagnoseOptions{});
  INFO(d.summary);
  CHECK(d.targets[0].sigma == Approx(0.01).epsilon(0.25));  // ~100 points each: looser than 15 %
  CHECK(d.targets[1].sigma == Approx(0.03).epsilon(0.25));
  REQUIRE(d.chosen >= 0);
  CHECK(d.refits[d.chosen].effect == "yield_drop");
  REQUIRE(d.base_analysis.worst_region >= 0);
  CHECK(d.base_analysis.regions[d.base_analysis.worst_region].label.rfind("late", 0) == 0);
}

TEST_CASE("A curve-mapping target is refused with a one-line message naming the target") {
  identify::StudySpec spec = synthetic_study(base_truth(), 81);
  spec.targets[0].metric = identify::CurveMetric::curve_mapping;
  const AnalyticEffectsModel model(101);
  CHECK_THROWS_WITH(run_diagnosis(spec, model, analytic_effect_candidates(), DiagnoseOptions{}),
                    Catch::Contains("target 'response'") && Catch::Contains("use \"mse\""));
}

// Independent reference: projecting x^2 and -(x-0.7)+/0.3 on the base sensitivities at the true
// base values (1 - e^{-3x}, x e^{-3x}, x; 101 stations) leaves 0.008 % and 3.7 % of their squared
// norm (Gram-Schmidt, computed outside demfit), i.e. absorbed shares 0.99992 and 0.963.
TEST_CASE("A candidate that cannot pass the criterion even at the end of its range is reported as undetectable") {
  std::vector<EffectCandidate> candidates = analytic_effect_candidates();
  candidates.erase(candidates.begin());     // toe_shift
  candidates[0].parameters[0].lower = 0.0;  // stiffening: at most 1e-4 x^2, far below the noise
  candidates[0].parameters[0].upper = 1e-4;
  const Diagnosis d = diagnose_hidden("", 0.0, 31, candidates);
  INFO(d.summary);
  REQUIRE(d.screening.size() == 2);
  CHECK(d.screening[0].absorbed_by_base == Approx(0.99992).margin(0.001));
  CHECK(d.screening[1].absorbed_by_base == Approx(0.963).margin(0.02));
  CHECK(d.screening[0].full_range_gain < d.bic_threshold);
  CHECK(d.screening[1].full_range_gain > d.bic_threshold);
  CHECK(d.verdict == Verdict::no_missing_effect);
  CHECK(d.summary.find("Undetectable with these data: 'stiffening'") != std::string::npos);
  CHECK(d.summary.find("'yield_drop' (gain") == std::string::npos);
}

namespace {

// The analytic diagnosis with one local re-fit start and a surrogate search of 40 runs after it,
// so the search runs for every candidate whose start fails.
Diagnosis diagnose_with_search(const std::string& parameter, double value, unsigned seed, int jobs = 1) {
  identify::ParameterSet truth = base_truth();
  if (!parameter.empty()) truth[parameter] = value;
  const AnalyticEffectsModel model(101);
  DiagnoseOptions options;
  options.refit_starts = 1;
  options.refit_search_evaluations = 40;
  options.fit.jobs = jobs;
  return run_diagnosis(synthetic_study(truth, seed), model, analytic_effect_candidates(), options);
}

bool searched(const Diagnosis& d) {
  for (const auto& note : d.notes)
    if (note.find("surrogate search") != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("A surrogate search after the failed local re-fits never names an effect that is not hidden",
          "[diagnose][surrogate]") {
  int named = 0;
  for (unsigned seed = 1000; seed < 1005; ++seed) {
    const Diagnosis ripple = diagnose_with_search("ripple_amplitude", 0.03, seed);
    INFO("seed " << seed << ", ripple (no candidate): " << ripple.summary);
    CHECK(searched(ripple));
    CHECK(ripple.verdict == Verdict::unexplained_structural);
    const Diagnosis toe = diagnose_with_search("toe_shift", 0.05, seed);
    INFO("seed " << seed << ", hidden toe shift: " << toe.summary);
    CHECK(toe.verdict != Verdict::no_missing_effect);
    if (toe.chosen >= 0) CHECK(toe.refits[toe.chosen].effect == "toe_shift");
    named += toe.chosen >= 0;
  }
  // Measured: named on 4 of the 5 (seed 1004 "unexplained", its base fit held at two bounds).
  CHECK(named >= 4);
}

TEST_CASE("A diagnosis with a surrogate search does not depend on the number of parallel evaluations",
          "[diagnose][surrogate]") {
  const Diagnosis a = diagnose_with_search("ripple_amplitude", 0.03, 62, 1);
  const Diagnosis b = diagnose_with_search("ripple_amplitude", 0.03, 62, 3);
  REQUIRE(searched(a));
  CHECK(a.notes == b.notes);
  CHECK(a.summary == b.summary);
  CHECK(a.refit_evaluations == b.refit_evaluations);
}
