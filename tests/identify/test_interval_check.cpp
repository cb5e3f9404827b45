// Interval-end checks (interval_check.hpp): runs at the posterior intervals' ends
// widen an interval drawn too narrow, and never narrow one.
#include <catch2/catch.hpp>

#include <cmath>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/interval_check.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

const std::vector<VariableSpec> kTwo{{"a", 0.0, 1.0, 0.5}, {"b", 0.0, 1.0, 0.5}};

// The best point 0.5, 0.5 with the posterior's runs in a small cloud around it (every end given
// in these tests lies beyond it, so every variable is checked).
IntervalCheckInput input(double best_objective, std::vector<double> nearby, std::vector<double> lower,
                         std::vector<double> upper) {
  IntervalCheckInput in;
  in.best_unit = Eigen::VectorXd::Constant(2, 0.5);
  in.best_objective = best_objective;
  in.nearby_objectives = std::move(nearby);
  in.lower = std::move(lower);
  in.upper = std::move(upper);
  in.fitted_runs.resize(3, 2);
  in.fitted_runs << 0.498, 0.5, 0.5, 0.498, 0.502, 0.502;
  return in;
}

IntervalCheckSpec settings(int max_steps) {
  IntervalCheckSpec s;
  s.max_steps = max_steps;
  s.replicates = 2;
  s.first_step = 0.02;
  return s;
}

// A profile that puts the other coordinate at 0.5.
ProfilePoint flat_profile() {
  return [](int variable, double unit) {
    Eigen::VectorXd p = Eigen::VectorXd::Constant(2, 0.5);
    p(variable) = unit;
    return p;
  };
}

// Evaluates `objective` on every row; replicates (rows at the best point) get `replicate_value`.
struct Recorder {
  std::function<double(const Eigen::VectorXd&)> objective;
  double replicate_value = 1.0;
  std::vector<Eigen::VectorXd> checked;
  EvaluateBatch evaluate() {
    return [this](int, const Eigen::MatrixXd& points, const std::vector<std::string>& kinds) {
      Eigen::VectorXd out(points.rows());
      for (int i = 0; i < points.rows(); ++i) {
        if (kinds[i] == "replicate") {
          out(i) = replicate_value;
          continue;
        }
        checked.push_back(points.row(i).transpose());
        out(i) = objective(points.row(i).transpose());
      }
      return out;
    };
  }
};

}  // namespace

TEST_CASE("An interval end that fits within the run-to-run spread is widened to the first run that fits worse",
          "[identify][interval_check]") {
  // Flat within 0.2 of 0.5 along a (anything there fits as well as the best run), steep beyond;
  // the posterior claims [0.49, 0.51]. Replicates at the best point spread up to 1.05.
  Recorder r;
  r.objective = [](const Eigen::VectorXd& u) { return 1.0 + 10.0 * std::max(0.0, std::abs(u(0) - 0.5) - 0.2); };
  r.replicate_value = 1.05;
  const auto out =
      check_interval_ends(kTwo, input(1.0, {}, {0.49, 0.45}, {0.51, 0.55}), settings(6), flat_profile(), r.evaluate());
  // Distances 0.02, 0.04, 0.08, 0.16 fit, 0.32 does not: the ends move to 0.5 -/+ 0.32.
  CHECK(out.lower[0].end == Approx(0.18).margin(1e-12));
  CHECK(out.upper[0].end == Approx(0.82).margin(1e-12));
  CHECK(out.lower[0].widened);
  CHECK(out.threshold == 1.05);
  CHECK(out.replicate_objectives.size() == 2);
  // b does not change the objective: its ends walk to the bounds.
  CHECK(out.lower[1].end == 0.0);
  CHECK(out.upper[1].end == 1.0);
}

TEST_CASE("An interval end whose first check fits worse than the spread is kept", "[identify][interval_check]") {
  // A noise-free bowl: no spread, so every run away from the best fits worse.
  Recorder r;
  r.objective = [](const Eigen::VectorXd& u) { return 1.0 + (u - Eigen::VectorXd::Constant(2, 0.5)).squaredNorm(); };
  const auto out =
      check_interval_ends(kTwo, input(1.0, {}, {0.45, 0.4}, {0.55, 0.6}), settings(6), flat_profile(), r.evaluate());
  CHECK(out.lower[0].end == 0.45);
  CHECK(out.upper[0].end == 0.55);
  CHECK(out.lower[1].end == 0.4);
  CHECK(out.upper[1].end == 0.6);
  CHECK_FALSE(out.lower[0].widened);
  CHECK_FALSE(out.upper[1].widened);
  // Each end: one check at the posterior's end; its retry re-draws the same profile and is not run.
  CHECK(r.checked.size() == 4);
}

TEST_CASE("An end closer to the best point than the first step is run itself when the first step fits worse",
          "[identify][interval_check]") {
  // Flat within 0.015 of 0.5 along a, steep beyond; the posterior claims a in [0.495, 0.505], inside
  // the first step (0.02). The first checks, at 0.48 and 0.52, fit worse; the ends themselves fit,
  // so the data cannot exclude them and the interval reaches to the runs that fitted worse.
  Recorder r;
  r.objective = [](const Eigen::VectorXd& u) { return 1.0 + 10.0 * std::max(0.0, std::abs(u(0) - 0.5) - 0.015); };
  r.replicate_value = 1.01;
  const auto out =
      check_interval_ends(kTwo, input(1.0, {}, {0.495, 0.0}, {0.505, 1.0}), settings(6), flat_profile(), r.evaluate());
  CHECK(out.lower[0].end == Approx(0.48).margin(1e-12));
  CHECK(out.upper[0].end == Approx(0.52).margin(1e-12));
  CHECK(out.lower[0].widened);
  REQUIRE(out.lower[0].values.size() == 2);  // the first step (its retry repeats it, not run), then the end
  CHECK(out.lower[0].values[1] == Approx(0.495).margin(1e-12));
  CHECK(out.lower[0].fits[1]);
  // Where the end itself fits worse too, it stands: a steeper bowl.
  Recorder steep;
  steep.objective = [](const Eigen::VectorXd& u) { return 1.0 + 100.0 * std::abs(u(0) - 0.5); };
  steep.replicate_value = 1.01;
  const auto kept = check_interval_ends(kTwo, input(1.0, {}, {0.495, 0.0}, {0.505, 1.0}), settings(6), flat_profile(),
                                        steep.evaluate());
  CHECK(kept.lower[0].end == 0.495);
  CHECK(kept.upper[0].end == 0.505);
  CHECK_FALSE(kept.upper[0].widened);
}

TEST_CASE("A rejected check is retried once with a re-drawn profile that can find the valley",
          "[identify][interval_check]") {
  // A valley b = a: only the profile along it fits. Each distance's first attempt (the other where
  // the last run fitted) misses it, the retry (the profile) follows it.
  Recorder r;
  r.objective = [](const Eigen::VectorXd& u) { return 1.0 + 100.0 * std::pow(u(1) - u(0), 2); };
  r.replicate_value = 1.01;
  const ProfilePoint profile = [&](int variable, double unit) {
    Eigen::VectorXd p(2);
    p(variable) = unit;
    p(1 - variable) = unit;
    return p;
  };
  const auto out =
      check_interval_ends(kTwo, input(1.0, {}, {0.45, 0.45}, {0.55, 0.55}), settings(3), profile, r.evaluate());
  // Along the valley every distance fits: after the retry the walks run to their last step
  // (distances 0.05, 0.1, 0.2) and, never fitting worse, report the bounds.
  CHECK(out.lower[0].end == 0.0);
  CHECK(out.upper[1].end == 1.0);
  CHECK(out.lower[0].objectives.size() == 6);  // a miss and a fitting retry at each of three distances
  for (int k : {0, 2, 4}) CHECK_FALSE(out.lower[0].fits[k]);
  for (int k : {1, 3, 5}) CHECK(out.lower[0].fits[k]);
}

TEST_CASE("Each distance first tries the other variables where the end's last run fitted",
          "[identify][interval_check]") {
  // A flat-bottomed valley b in [0.6, 0.7] for a < 0.5 that the surrogate's profile (b = 0.5) finds
  // only once: after that run fitted, the walk keeps b where it fitted.
  Recorder r;
  r.objective = [](const Eigen::VectorXd& u) {
    const bool in_valley = u(1) >= 0.6 && u(1) <= 0.7;
    return u(0) >= 0.5 || in_valley ? 1.0 : 2.0;
  };
  r.replicate_value = 1.0;
  int calls = 0;
  const ProfilePoint profile = [&](int variable, double unit) {
    Eigen::VectorXd p = Eigen::VectorXd::Constant(2, 0.5);
    p(variable) = unit;
    if (variable == 0 && ++calls == 1) p(1) = 0.65;  // only the first profile finds the valley
    return p;
  };
  const auto out =
      check_interval_ends(kTwo, input(1.0, {}, {0.45, 0.49}, {0.55, 0.51}), settings(3), profile, r.evaluate());
  // Distance 0.05: held b 0.5 misses, profile b 0.65 fits; 0.1 and 0.2: b 0.65 kept, both fit.
  CHECK(out.lower[0].objectives.size() == 4);
  CHECK(out.lower[0].end == 0.0);
  CHECK(calls == 1);
}

TEST_CASE("With all_variables false an interval within the runs the posterior was fitted to is not checked",
          "[identify][interval_check]") {
  Recorder r;
  r.objective = [](const Eigen::VectorXd&) { return 1.0; };  // flat: any check would widen
  IntervalCheckInput in = input(1.0, {}, {0.45, 0.3}, {0.55, 0.7});
  in.fitted_runs.resize(4, 2);
  in.fitted_runs << 0.4, 0.45, 0.6, 0.55, 0.45, 0.4, 0.55, 0.6;  // a spans [0.4, 0.6], b [0.4, 0.6]
  IntervalCheckSpec beyond_runs = settings(6);
  beyond_runs.all_variables = false;
  const auto out = check_interval_ends(kTwo, in, beyond_runs, flat_profile(), r.evaluate());
  CHECK_FALSE(out.lower[0].checked);  // [0.45, 0.55] inside the runs: kept, no run
  CHECK(out.lower[0].end == 0.45);
  CHECK(out.upper[0].end == 0.55);
  CHECK(out.lower[1].checked);  // [0.3, 0.7] reaches beyond them: checked, walks to the bounds
  CHECK(out.lower[1].end == 0.0);
  CHECK(out.upper[1].end == 1.0);
  for (const auto& point : r.checked) CHECK(point(0) == 0.5);
  IntervalCheckInput inside = input(1.0, {}, {0.45, 0.45}, {0.55, 0.55});
  inside.fitted_runs = in.fitted_runs;
  Recorder none;
  none.objective = r.objective;
  const auto unchecked = check_interval_ends(kTwo, inside, beyond_runs, flat_profile(), none.evaluate());
  CHECK(unchecked.runs == 0);  // nothing to check: not even the replicates run
  const auto all = check_interval_ends(kTwo, inside, settings(6), flat_profile(), none.evaluate());
  CHECK(all.lower[0].checked);  // the default checks every variable
  CHECK(all.lower[0].end == 0.0);
}

TEST_CASE("The study's runs next to the best one set the spread threshold", "[identify][interval_check]") {
  Recorder r;
  r.objective = [](const Eigen::VectorXd& u) { return 1.0 + 10.0 * std::abs(u(0) - 0.5); };
  // 1.3 from a nearby run: a check 0.02 away (1.2) fits, 0.04 away (1.4) does not.
  const auto out = check_interval_ends(kTwo, input(1.0, {1.3, std::nan("")}, {0.49, 0.4}, {0.51, 0.6}), settings(6),
                                       flat_profile(), r.evaluate());
  CHECK(out.threshold == 1.3);
  CHECK(out.lower[0].end == Approx(0.46).margin(1e-12));
  CHECK(out.upper[0].end == Approx(0.54).margin(1e-12));
}

namespace {

// The reported interval of variable `j` as the study stores it after the check (lower_95/upper_95
// the checked ends) and every output reads it.
ReportedInterval reported_after_check(const IntervalCheckOutcome& out, int j, double answer) {
  nlohmann::json uncertainty;
  uncertainty["posterior"]["variables"]["a"] = {
      {"lower_95", out.lower[j].end},
      {"upper_95", out.upper[j].end},
      {"widened_by_interval_check", out.lower[j].widened || out.upper[j].widened}};
  return reported_interval(uncertainty, "a", answer);
}

// An objective with its minimum at a = 0.492 (the generating value) and slope 10 either side; b
// does not matter. The answer 0.5 (a final selection's choice) fits it to 1.08.
double v_at_0492(const Eigen::VectorXd& u) { return 1.0 + 10.0 * std::abs(u(0) - 0.492); }

}  // namespace

TEST_CASE("An answer below the posterior's interval is checked outward from the answer, with room on both sides",
          "[identify][interval_check]") {
  // The posterior claims a in [0.51, 0.55], above the answer 0.5 (the posterior's centre is its
  // regression's, the answer a selection's); the generating 0.492 lies below the answer. The
  // first step down from the answer, 0.48, fits worse (1.12 against the spread 1.09): the data
  // exclude 0.48 but not the answer, so the lower end is 0.48, not the answer (no room) nor the
  // posterior's 0.51 (excluding the answer).
  Recorder r;
  r.objective = v_at_0492;
  r.replicate_value = 1.09;
  const auto out =
      check_interval_ends(kTwo, input(1.08, {}, {0.51, 0.45}, {0.55, 0.55}), settings(6), flat_profile(), r.evaluate());
  CHECK(out.lower[0].end == Approx(0.48).margin(1e-12));
  CHECK(out.lower[0].widened);
  REQUIRE(out.lower[0].values.size() == 1);  // the retry would repeat the run: one run decides it
  CHECK_FALSE(out.lower[0].fits[0]);
  CHECK(out.upper[0].end == 0.55);  // its check at 0.55 fits worse: kept
  const ReportedInterval reported = reported_after_check(out, 0, 0.5);
  CHECK(reported.lower < 0.5 - 0.01);  // room below the answer
  CHECK(reported.upper > 0.5 + 0.01);  // and above it
  CHECK(reported.lower < 0.492);       // the generating value inside
  CHECK(reported.upper > 0.492);
  CHECK(reported.method.find("widened to the answer") == std::string::npos);
}

TEST_CASE("An interval end at the answer is checked even when all_variables is off", "[identify][interval_check]") {
  // The posterior's [0.5, 0.54] lies within the runs it was fitted to (so all_variables false would
  // not check a) but its lower end is the answer itself, which says nothing below it. Only that
  // side is run: with a spread up to 1.15 the first step down (0.48, 1.12) fits, the second (0.46,
  // 1.32) fits worse.
  Recorder r;
  r.objective = v_at_0492;
  r.replicate_value = 1.15;
  IntervalCheckInput in = input(1.08, {}, {0.5, 0.45}, {0.54, 0.55});
  in.fitted_runs.resize(4, 2);
  in.fitted_runs << 0.44, 0.44, 0.56, 0.56, 0.44, 0.56, 0.56, 0.44;
  IntervalCheckSpec within_runs = settings(6);
  within_runs.all_variables = false;
  const auto out = check_interval_ends(kTwo, in, within_runs, flat_profile(), r.evaluate());
  CHECK(out.lower[0].checked);
  CHECK_FALSE(out.upper[0].checked);
  CHECK_FALSE(out.lower[1].checked);
  CHECK(out.lower[0].end == Approx(0.46).margin(1e-12));
  CHECK(out.upper[0].end == 0.54);
  for (const auto& point : r.checked) CHECK(point(0) < 0.5);
  const ReportedInterval reported = reported_after_check(out, 0, 0.5);
  CHECK(reported.lower < 0.492);
  CHECK(reported.upper > 0.5);
}

TEST_CASE("A study with interval checks stores them after the verification run and a resume repeats none",
          "[identify][interval_check]") {
  auto json = test::analytic_study(0.2, 6);
  json["interval_check"] = {{"max_steps", 3}, {"replicates", 2}};
  const auto spec = parse_study(json, ".");
  CHECK(spec.interval_check.max_steps == 3);
  const AnalyticCurveModel model;
  const auto dir = test::fresh_dir("interval_check_study");
  RunOptions options;
  options.output_dir = dir;
  options.plots = false;
  options.progress = false;
  const auto result = run_study(spec, model, options);
  const auto store = StudyStore::open_existing(dir / "study.db");
  int replicates = 0, checks = 0;
  for (const auto& e : store.evaluations()) {
    if (e.kind == "replicate") ++replicates;
    if (e.kind == "interval_check") ++checks;
    if (e.kind == "replicate" || e.kind == "interval_check") CHECK(e.iteration > result.iterations);
  }
  CHECK(replicates == 2);
  CHECK(checks >= 2 * static_cast<int>(spec.variables.size()));
  CHECK(result.runs == static_cast<int>(store.evaluations().size()));
  const auto stored = store.result();
  REQUIRE(stored);
  REQUIRE((*stored)["uncertainty"]["posterior"].contains("interval_check"));
  // Every reported interval contains the answer with room on both sides (none lies at a bound here).
  for (const auto& [name, interval] : result.intervals) {
    INFO(name << " " << result.best.at(name) << " in [" << interval.lower << ", " << interval.upper << "] ("
              << interval.method << ")");
    CHECK(interval.lower < result.best.at(name));
    CHECK(interval.upper > result.best.at(name));
  }
  RunOptions resume = options;
  resume.resume = true;
  int evaluated = 0;
  resume.after_evaluation = [&](int done) { evaluated = done; };
  const auto again = run_study(spec, model, resume);
  CHECK(evaluated == 0);
  CHECK(again.intervals.at("rate").lower == result.intervals.at("rate").lower);
  CHECK(again.intervals.at("rate").upper == result.intervals.at("rate").upper);
}
