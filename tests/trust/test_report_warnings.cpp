// The report says what a confident-looking answer may hide: an optimum on a bound, a
// study stopped at the iteration limit, a verification run far from its prediction, and a misfit
// far above the noise of the data, with the misfit in the curve's own units, and runs far from
// quasi-static.
#include <catch2/catch.hpp>

#include <cmath>

#include "demfit/identify/study_warnings.hpp"

namespace {
namespace id = demfit::identify;

id::StudySpec spec_with_target(std::vector<double> y) {
  id::StudySpec spec;
  spec.variables.push_back({"k", 1.0, 2.0, 1.5, false, 1.0});
  spec.max_iterations = 4;
  id::TargetSpec t;
  t.name = "pv";
  t.curve = "pressure_volume";
  std::vector<double> x;
  for (std::size_t i = 0; i < y.size(); ++i) x.push_back(static_cast<double>(i));
  t.data = {"volume_cm3", "pressure_MPa", x, y};
  spec.targets.push_back(t);
  return spec;
}

id::EvaluationRecord run(double k, const std::vector<double>& y, const std::string& kind = "design") {
  id::EvaluationRecord r;
  r.kind = kind;
  r.ok = true;
  r.objective = 1.0;
  r.parameters = {{"k", k}};
  std::vector<double> x;
  for (std::size_t i = 0; i < y.size(); ++i) x.push_back(static_cast<double>(i));
  r.curves["pressure_volume"] = {"volume_cm3", "pressure_MPa", x, y};
  return r;
}

bool mentions(const std::vector<std::string>& warnings, const std::string& text) {
  for (const auto& w : warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("the RMS misfit is reported in the curve's units and against the second-difference noise") {
  // Target = line + alternating +-0.1: second differences are +-0.4, so sigma = 0.4/sqrt(6).
  std::vector<double> target, model;
  for (int i = 0; i < 21; ++i) {
    target.push_back(0.5 * i + (i % 2 ? 0.1 : -0.1));
    model.push_back(0.5 * i + 1.0);  // 1 MPa above the line: RMS misfit = sqrt(1 + 0.01 + 2 * 0.1 * (+-)) ...
  }
  const auto spec = spec_with_target(target);
  const auto best = run(1.5, model);
  const auto d = id::study_diagnostics(spec, {best}, {}, &best, nlohmann::json{{"converged", true}});
  REQUIRE(d.misfits.size() == 1);
  double sum = 0.0;
  for (int i = 0; i < 21; ++i) sum += (model[i] - target[i]) * (model[i] - target[i]);
  CHECK(d.misfits[0].rms == Approx(std::sqrt(sum / 21)).epsilon(1e-12));
  CHECK(d.misfits[0].noise == Approx(0.4 / std::sqrt(6.0)).epsilon(1e-12));
  CHECK(d.misfits[0].y_label == "pressure_MPa");
  CHECK(mentions(d.warnings, "x the noise of the data"));
  CHECK(!mentions(d.warnings, "bound"));
  CHECK(!mentions(d.warnings, "iteration limit"));
}

TEST_CASE("an optimum on a bound, the iteration limit and a verification far from its prediction are warned") {
  std::vector<double> y{0, 1, 2, 3, 4};
  const auto spec = spec_with_target(y);
  const auto best = run(2.0, y);
  auto verification = run(2.0, y, "verification");
  verification.objective = 10.0;
  id::IterationRecord last;
  last.predicted_objective = 1.0;
  const auto d = id::study_diagnostics(spec, {best, verification}, {last}, &best, nlohmann::json{{"converged", false}});
  CHECK(mentions(d.warnings, "'k' = 2 lies on its upper bound"));
  CHECK(mentions(d.warnings, "iteration limit (4)"));
  CHECK(mentions(d.warnings, "far from the surrogate's prediction"));
  CHECK(!mentions(d.warnings, "noise"));  // an exact fit
  // Near-zero objectives of an exact fit differ relatively but not absolutely: no warning.
  auto design = run(1.5, y);
  design.objective = 1.0;
  verification.objective = 1e-18;
  last.predicted_objective = 3e-19;
  const auto exact =
      id::study_diagnostics(spec, {design, verification}, {last}, &best, nlohmann::json{{"converged", true}});
  CHECK(!mentions(exact.warnings, "far from the surrogate's prediction"));
}

TEST_CASE("a best run far from quasi-static is warned, and so are other runs that were") {
  std::vector<double> y{0, 1, 2, 3, 4};
  const auto spec = spec_with_target(y);
  auto with_check = [&](double k, double largest) {
    auto r = run(k, y);
    r.curves[id::kQuasiStaticCurve] = {
        "volume_cm3", "kinetic_over_elastic_energy_per_limit", {3, 2, 1}, {0.1, largest, 0.2}};
    return r;
  };
  const auto inertial = with_check(1.5, 4.0);
  const auto calm = with_check(1.4, 0.5);
  const auto d = id::study_diagnostics(spec, {inertial, calm}, {}, &inertial, nlohmann::json{{"converged", true}});
  CHECK(mentions(d.warnings, "the best run is far from quasi-static: its kinetic energy reached 4 x the case's limit"));
  const auto other = id::study_diagnostics(spec, {inertial, calm}, {}, &calm, nlohmann::json{{"converged", true}});
  CHECK(mentions(other.warnings, "1 of 2 runs were far from quasi-static"));
  const auto fine = id::study_diagnostics(spec, {calm}, {}, &calm, nlohmann::json{{"converged", true}});
  CHECK(!mentions(fine.warnings, "quasi-static"));
  // A model without the check curve (the drum, the analytic model) gets no such warning.
  const auto plain = run(1.5, y);
  CHECK(!mentions(id::study_diagnostics(spec, {plain}, {}, &plain, nlohmann::json{{"converged", true}}).warnings,
                  "quasi-static"));
}
