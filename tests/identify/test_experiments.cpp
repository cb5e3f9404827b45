// Several experiments in one study: shared variables, one job per (point,
// experiment), curves and targets qualified by the experiment, errors before the store exists.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "demfit/identify/experiments.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_preflight.hpp"
#include "demfit/identify/study_store.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

// y(x) = c (1 - exp(-3x)), x = 0..1: one scalar c = a b ("product") or a / b ("ratio") shapes the
// curve, so either experiment alone pins one combination of a and b only.
class CombinationModel final : public Model {
 public:
  CombinationModel(bool product, std::atomic<int>* calls, bool accepts_gain = false)
      : product_(product), calls_(calls), accepts_gain_(accepts_gain) {}
  std::vector<ParameterDescriptor> parameters() const override {
    if (accepts_gain_) return unbounded_descriptors({"a", "b", "gain"});
    return unbounded_descriptors({"a", "b"});
  }
  ParameterSet default_parameters() const override {
    if (accepts_gain_) return {{"a", 1.0}, {"b", 1.0}, {"gain", 1.0}};
    return {{"a", 1.0}, {"b", 1.0}};
  }
  CurveSet evaluate(const ParameterSet& p, const EvaluationContext&) const override {
    for (const auto& [name, value] : p)
      if (!default_parameters().count(name)) throw std::runtime_error("unknown parameter '" + name + "'");
    if (calls_) ++*calls_;
    const double c = (product_ ? p.at("a") * p.at("b") : p.at("a") / p.at("b")) * (accepts_gain_ ? p.at("gain") : 1.0);
    Curve curve{"x_1", "y_1", {}, {}};
    for (int i = 0; i <= 20; ++i) {
      curve.x.push_back(i / 20.0);
      curve.y.push_back(c * (1.0 - std::exp(-3.0 * curve.x.back())));
    }
    return {{"signal", curve}};
  }

 private:
  bool product_;
  std::atomic<int>* calls_;
  bool accepts_gain_;
};

constexpr double kTrueA = 2.0, kTrueB = 0.5;  // a b = 1, a / b = 4

nlohmann::json experiment(const std::string& name, bool product) {
  const Curve target = CombinationModel(product, nullptr).evaluate({{"a", kTrueA}, {"b", kTrueB}}, {}).at("signal");
  return {
      {"name", name},
      {"model", {{"case", "analytic"}, {"overrides", {{"mode", name}}}}},
      {"targets", {{{"curve", "signal"}, {"x_column", "x_1"}, {"y_column", "y_1"}, {"x", target.x}, {"y", target.y}}}}};
}

nlohmann::json study(bool with_product, bool with_ratio) {
  nlohmann::json experiments = nlohmann::json::array();
  if (with_product) experiments.push_back(experiment("product", true));
  if (with_ratio) experiments.push_back(experiment("ratio", false));
  return {{"demfit_study_version", 1},
          {"name", "shared_parameters"},
          {"experiments", experiments},
          {"variables",
           {{{"name", "a"}, {"lower", 0.5}, {"upper", 4.0}, {"initial", 1.0}, {"log_scale", true}},
            {{"name", "b"}, {"lower", 0.2}, {"upper", 2.0}, {"initial", 1.0}, {"log_scale", true}}}},
          {"stopping", {{"max_iterations", 12}, {"design_tolerance", 0.0}, {"objective_tolerance", 0.0}}},
          {"seed", 5}};
}

std::unique_ptr<ExperimentSetModel> models_for(const StudySpec& spec, std::atomic<int>* calls) {
  std::vector<std::unique_ptr<Model>> models;
  for (const auto& e : spec.experiments)
    models.push_back(std::make_unique<CombinationModel>(e.name == "product", calls));
  return std::make_unique<ExperimentSetModel>(spec, std::move(models));
}

using test::quiet_options;

bool flagged(const StudyResult& r, const std::string& name) {
  return std::find(r.unidentifiable.begin(), r.unidentifiable.end(), name) != r.unidentifiable.end();
}

}  // namespace

TEST_CASE("Two experiments together recover shared parameters that neither pins alone", "[identify][experiments]") {
  for (const auto& [product, ratio] : {std::pair{true, false}, std::pair{false, true}}) {
    const StudySpec alone = parse_study(study(product, ratio), ".");
    const auto result =
        run_study(alone, *models_for(alone, nullptr), quiet_options(test::fresh_dir("experiments_alone")));
    INFO("alone: " << alone.experiments[0].name << " a " << result.best.at("a") << " b " << result.best.at("b"));
    // The experiment's own combination is matched, but a direction stays free and is flagged.
    const double combination =
        product ? result.best.at("a") * result.best.at("b") : result.best.at("a") / result.best.at("b");
    CHECK(combination == Approx(product ? kTrueA * kTrueB : kTrueA / kTrueB).epsilon(0.01));
    CHECK((flagged(result, "a") || flagged(result, "b")));
  }
  const StudySpec both = parse_study(study(true, true), ".");
  const auto result = run_study(both, *models_for(both, nullptr), quiet_options(test::fresh_dir("experiments_both")));
  INFO("together: a " << result.best.at("a") << " b " << result.best.at("b"));
  CHECK(result.best.at("a") == Approx(kTrueA).epsilon(0.001));  // stated tolerance: 0.1 %
  CHECK(result.best.at("b") == Approx(kTrueB).epsilon(0.001));
  CHECK_FALSE(flagged(result, "a"));
  CHECK_FALSE(flagged(result, "b"));
}

TEST_CASE("Each experiment of a design point is its own job and the answer does not depend on --jobs",
          "[identify][experiments]") {
  const StudySpec spec = parse_study(study(true, true), ".");
  std::atomic<int> calls_one{0}, calls_three{0};
  const auto one =
      run_study(spec, *models_for(spec, &calls_one), quiet_options(test::fresh_dir("experiments_jobs1"), 1));
  const auto three =
      run_study(spec, *models_for(spec, &calls_three), quiet_options(test::fresh_dir("experiments_jobs3"), 3));
  CHECK(calls_one.load() == 2 * one.runs);  // every point ran both experiments, once each
  CHECK(calls_three.load() == calls_one.load());
  CHECK(three.best == one.best);
  CHECK(three.best_objective == one.best_objective);
}

TEST_CASE("An evaluator given points of an experiments model runs every experiment and returns whole points",
          "[identify][experiments][evaluator]") {
  // diagnose and the MPI preflight hand whole points to an evaluator: each must come back with
  // the curves of every experiment, equal to evaluating the set model directly.
  const StudySpec spec = parse_study(study(true, true), ".");
  std::atomic<int> calls{0};
  const auto set = models_for(spec, &calls);
  const std::vector<ParameterSet> points{{{"a", 1.5}, {"b", 0.7}}, {{"a", 3.0}, {"b", 1.2}}, {{"a", 0.9}, {"b", 0.4}}};
  ThreadPoolEvaluator pool(*set, 2, 1, 0);
  std::vector<std::size_t> done;
  const auto outcomes =
      pool.evaluate_points(*set, points, [&](std::size_t point, const EvaluationOutcome&) { done.push_back(point); });
  CHECK(calls.load() == 6);
  std::sort(done.begin(), done.end());
  CHECK(done == std::vector<std::size_t>{0, 1, 2});
  for (std::size_t p = 0; p < points.size(); ++p) {
    REQUIRE(outcomes[p].ok);
    const CurveSet direct = set->evaluate(points[p], {});
    REQUIRE(outcomes[p].curves.size() == 2);
    CHECK(outcomes[p].curves.at("product/signal").y == direct.at("product/signal").y);
    CHECK(outcomes[p].curves.at("ratio/signal").y == direct.at("ratio/signal").y);
  }
}

TEST_CASE("The store keeps each experiment's curves under its name and the report lists every experiment's targets",
          "[identify][experiments]") {
  const StudySpec spec = parse_study(study(true, true), ".");
  const auto dir = test::fresh_dir("experiments_store");
  auto options = quiet_options(dir);
  const auto result = run_study(spec, *models_for(spec, nullptr), options);
  CHECK(result.best_curves.count("product/signal") == 1);
  CHECK(result.best_curves.count("ratio/signal") == 1);
  const StudyStore store = StudyStore::open_existing(dir / "study.db");
  for (const auto& r : store.evaluations()) {
    REQUIRE(r.ok);
    CHECK(r.curves.size() == 2);
    // the objective is the sum of both experiments' terms (mse, s = max|G|)
    double sum = 0.0;
    for (const auto& t : spec.targets) {
      const Curve& f = r.curves.at(t.curve);
      double ymax = 0.0, squares = 0.0;
      for (double y : t.data.y) ymax = std::max(ymax, std::abs(y));
      for (std::size_t i = 0; i < f.y.size(); ++i) squares += std::pow((f.y[i] - t.data.y[i]) / ymax, 2);
      sum += squares / static_cast<double>(f.y.size());
    }
    CHECK(r.objective == Approx(sum).epsilon(1e-12).margin(1e-300));
  }
  std::ifstream report(dir / "report.md");
  const std::string text((std::istreambuf_iterator<char>(report)), {});
  CHECK(text.find("`product.signal`") != std::string::npos);
  CHECK(text.find("`ratio.signal`") != std::string::npos);
  CHECK(text.find("| product |") != std::string::npos);
  std::ifstream resolved(dir / "study_resolved.json");
  const auto json = nlohmann::json::parse(resolved);
  CHECK(json.at("experiments").size() == 2);
  CHECK(std::filesystem::exists(dir / "target_product.signal.csv"));
  CHECK(std::filesystem::exists(dir / "best_ratio.signal.csv"));
}

TEST_CASE(
    "A variable goes to the experiments whose model accepts it; one that no model accepts is refused before "
    "the store exists",
    "[identify][experiments]") {
  auto json = study(true, true);
  json["variables"].push_back({{"name", "gain"}, {"lower", 0.5}, {"upper", 2.0}});
  const StudySpec spec = parse_study(json, ".");
  std::vector<std::unique_ptr<Model>> models;
  models.push_back(std::make_unique<CombinationModel>(true, nullptr, true));  // product accepts gain
  models.push_back(std::make_unique<CombinationModel>(false, nullptr));       // ratio does not
  const ExperimentSetModel set(spec, std::move(models));
  const ParameterSet point{{"a", 3.0}, {"b", 0.25}, {"gain", 1.5}};
  CHECK(set.experiment_parameters(0, point) == ParameterSet{{"a", 3.0}, {"b", 0.25}, {"gain", 1.5}});
  CHECK(set.experiment_parameters(1, point) == ParameterSet{{"a", 3.0}, {"b", 0.25}});
  const CurveSet curves = set.evaluate(point, {});
  CHECK(curves.at("product/signal").y.back() == Approx(3.0 * 0.25 * 1.5 * (1.0 - std::exp(-3.0))));
  CHECK(curves.at("ratio/signal").y.back() == Approx(12.0 * (1.0 - std::exp(-3.0))));

  auto unknown = study(true, true);
  unknown["variables"].push_back({{"name", "nothing"}, {"lower", 0.0}, {"upper", 1.0}});
  const StudySpec bad = parse_study(unknown, ".");
  const auto dir = test::fresh_dir("experiments_unknown_variable");
  CHECK_THROWS_WITH(run_study(bad, *models_for(bad, nullptr), quiet_options(dir)),
                    Catch::Contains("variables[2].name: 'nothing' is not a parameter of any experiment's model"));
  CHECK_FALSE(std::filesystem::exists(dir / "study.db"));

  auto fixed = study(true, true);
  fixed["experiments"][1]["model"]["fixed_parameters"] = {{"gain", 2.0}};
  const StudySpec bad_fixed = parse_study(fixed, ".");
  CHECK_THROWS_WITH(run_study(bad_fixed, *models_for(bad_fixed, nullptr), quiet_options(dir)),
                    Catch::Contains("experiments[1].model.fixed_parameters.gain: not a parameter"));
  CHECK_FALSE(std::filesystem::exists(dir / "study.db"));
}

TEST_CASE("A failed experiment fails its design point and names the experiment", "[identify][experiments]") {
  EvaluationOutcome good;
  good.ok = true;
  good.wall_seconds = 1.0;
  good.curves["torque"] = Curve{"t_s", "M_Nm", {0, 1}, {2, 3}};
  EvaluationOutcome bad;
  bad.error = "unstable: time step too large";
  bad.wall_seconds = 0.5;
  const auto point = combine_experiment_outcomes({"rpm15", "rpm45"}, {good, bad});
  CHECK_FALSE(point.ok);
  CHECK(point.error == "experiment 'rpm45': unstable: time step too large");
  CHECK(point.curves.empty());
  CHECK(point.wall_seconds == 1.5);
  const auto fine = combine_experiment_outcomes({"rpm15", "rpm45"}, {good, good});
  CHECK(fine.ok);
  CHECK(fine.curves.count("rpm15/torque") == 1);
  CHECK(fine.curves.count("rpm45/torque") == 1);
  // the single-model form: one unnamed experiment, curves unchanged
  CHECK(combine_experiment_outcomes({""}, {good}).curves.count("torque") == 1);
}

TEST_CASE("Experiment configuration errors are found when the study is parsed", "[identify][experiments]") {
  auto duplicate = study(true, true);
  duplicate["experiments"][1]["name"] = "product";
  CHECK_THROWS_WITH(parse_study(duplicate, "."),
                    Catch::Contains("experiments[1].name: two experiments are named 'product'"));
  auto both = study(true, true);
  both["model"] = {{"case", "analytic"}};
  CHECK_THROWS_WITH(parse_study(both, "."), Catch::Contains("give either \"experiments\" or a top-level"));
  auto bad_name = study(true, false);
  bad_name["experiments"][0]["name"] = "rpm 15";
  CHECK_THROWS_WITH(parse_study(bad_name, "."), Catch::Contains("experiments[0].name: 'rpm 15'"));
  auto fixed_variable = study(true, false);
  fixed_variable["experiments"][0]["model"]["fixed_parameters"] = {{"a", 1.0}};
  CHECK_THROWS_WITH(parse_study(fixed_variable, "."),
                    Catch::Contains("also in the fixed_parameters of experiment 'product'"));
  auto unknown_key = study(true, false);
  unknown_key["experiments"][0]["rpm"] = 15;
  CHECK_THROWS_WITH(parse_study(unknown_key, "."), Catch::Contains("experiments[0].rpm"));
}

TEST_CASE("A study with experiments resolves to JSON that parses back to the same study", "[identify][experiments]") {
  const StudySpec spec = parse_study(study(true, true), ".");
  REQUIRE(spec.targets.size() == 2);
  CHECK(spec.targets[1].name == "ratio.signal");
  CHECK(spec.targets[1].curve == "ratio/signal");
  CHECK(spec.targets[1].experiment == "ratio");
  const nlohmann::json resolved = to_json(spec);
  CHECK_FALSE(resolved.contains("model"));
  CHECK_FALSE(resolved.contains("targets"));
  CHECK(resolved["experiments"][1]["targets"][0]["name"] == "signal");
  CHECK(resolved["experiments"][1]["model"]["overrides"] == nlohmann::json{{"mode", "ratio"}});
  CHECK(to_json(parse_study(resolved, ".")) == resolved);
  CHECK(study_hash(parse_study(resolved, ".")) == study_hash(spec));
  auto other = study(true, true);
  other["experiments"][1]["model"]["overrides"]["mode"] = "ratio2";
  CHECK(study_hash(parse_study(other, ".")) != study_hash(spec));
}

TEST_CASE("A study with a profile_area target recovers the analytic model's parameters", "[identify][profile_area]") {
  auto json = test::analytic_study();
  json["targets"][0]["metric"] = "profile_area";
  const StudySpec spec = parse_study(json, ".");
  const auto result = run_study(spec, AnalyticCurveModel(), quiet_options(test::fresh_dir("profile_area_study")));
  INFO("amplitude " << result.best.at("amplitude") << " rate " << result.best.at("rate"));
  CHECK(result.best.at("amplitude") == Approx(1.3).epsilon(0.02));  // truth of test::analytic_study, 2 %
  CHECK(result.best.at("rate") == Approx(4.2).epsilon(0.02));
}

TEST_CASE("A study with experiments stopped after some points resumes to the same answer without repeating them",
          "[identify][experiments]") {
  const StudySpec spec = parse_study(study(true, true), ".");
  std::atomic<int> reference_calls{0}, calls{0};
  const auto reference =
      run_study(spec, *models_for(spec, &reference_calls), quiet_options(test::fresh_dir("experiments_ref")));
  const auto dir = test::fresh_dir("experiments_resume");
  struct Stop {};
  auto killed = quiet_options(dir, 2);
  killed.after_evaluation = [](int done) {
    if (done == 7) throw Stop{};
  };
  const auto models = models_for(spec, &calls);
  CHECK_THROWS_AS(run_study(spec, *models, killed), Stop);
  const int before = calls.load();
  auto resumed = quiet_options(dir, 2);
  resumed.resume = true;
  const auto result = run_study(spec, *models, resumed);
  CHECK(result.best == reference.best);
  CHECK(result.best_objective == reference.best_objective);
  // the 7 stored points are not run again: at most the points in flight when stopped are repeated
  CHECK(calls.load() - before <= reference_calls.load() - 2 * 7 + 2);
}

TEST_CASE("The initial-point check's run is stored as run 0 and not evaluated again", "[identify][experiments]") {
  // demfit identify evaluates the initial point before the store exists (preflight_study); the loop
  // takes that run as its run 0/0 when the parameters are exactly the same, and the study's answer
  // is the one it gives when it evaluates run 0/0 itself.
  const StudySpec parsed = parse_study(study(true, true), ".");
  std::atomic<int> calls_plain{0}, calls_reused{0}, calls_other{0};
  const auto plain =
      run_study(parsed, *models_for(parsed, &calls_plain), quiet_options(test::fresh_dir("initial_plain")));
  RunOptions reuse = quiet_options(test::fresh_dir("initial_reused"));
  const auto model = models_for(parsed, &calls_reused);
  const StudySpec spec = preflight_study(parsed, *model, EvaluationContext{}, &reuse.initial_run);
  REQUIRE(reuse.initial_run.has_value());
  CHECK(calls_reused.load() == 2);  // both experiments, once
  const auto reused = run_study(spec, *model, reuse);
  CHECK(calls_reused.load() == calls_plain.load());  // run 0/0 was not evaluated a second time
  CHECK(reused.runs == plain.runs);
  CHECK(reused.best == plain.best);
  CHECK(reused.best_objective == plain.best_objective);
  // A run of other parameters is not taken for run 0/0.
  RunOptions other = quiet_options(test::fresh_dir("initial_other"));
  other.initial_run = reuse.initial_run;
  other.initial_run->parameters["a"] *= 1.5;
  const auto evaluated = run_study(parsed, *models_for(parsed, &calls_other), other);
  CHECK(calls_other.load() == calls_plain.load());
  CHECK(evaluated.best == plain.best);
}

TEST_CASE("The initial-point check through a pool of jobs hands over the run a direct evaluation gives",
          "[identify][experiments]") {
  // demfit identify checks the initial point with the loop's pool (--jobs), so a study's
  // experiments run side by side there too; the run handed to the loop must not depend on that.
  const StudySpec parsed = parse_study(study(true, true), ".");
  std::atomic<int> calls_direct{0}, calls_pool{0};
  std::optional<InitialRun> direct, pooled;
  const auto direct_model = models_for(parsed, &calls_direct);
  const StudySpec spec_direct = preflight_study(parsed, *direct_model, EvaluationContext{}, &direct);
  const auto pool_model = models_for(parsed, &calls_pool);
  ThreadPoolEvaluator pool(*pool_model, 2, 1, static_cast<unsigned long>(parsed.seed));
  const StudySpec spec_pool = preflight_study(parsed, *pool_model, pool, &pooled);
  REQUIRE(direct.has_value());
  REQUIRE(pooled.has_value());
  CHECK(calls_pool.load() == 2);  // both experiments, once
  CHECK(pooled->parameters == direct->parameters);
  CHECK(pooled->outcome.ok);
  REQUIRE(pooled->outcome.curves.size() == direct->outcome.curves.size());
  for (const auto& [name, curve] : direct->outcome.curves) {
    REQUIRE(pooled->outcome.curves.count(name) == 1);
    CHECK(pooled->outcome.curves.at(name).y == curve.y);
  }
  RunOptions from_pool = quiet_options(test::fresh_dir("initial_pooled"));
  from_pool.initial_run = pooled;
  RunOptions from_direct = quiet_options(test::fresh_dir("initial_direct"));
  from_direct.initial_run = direct;
  const auto a = run_study(spec_pool, *pool_model, from_pool);
  const auto b = run_study(spec_direct, *direct_model, from_direct);
  CHECK(a.best == b.best);
  CHECK(a.best_objective == b.best_objective);
}
