// The cheap level of a study (study_spec.hpp CheapLevelSpec): reading it and the study it runs.
#include "cheap_level.hpp"

#include <string>

namespace demfit::identify {
namespace detail {

namespace {
// Each cheap run is a simulation; more than this is a typo, not a plan.
constexpr int kMaxCheapRuns = 10000;
}  // namespace

void parse_cheap_level(JsonReader in, StudySpec& spec) {
  CheapLevelSpec level;
  const nlohmann::json& overrides = in.raw("overrides");
  if (!overrides.is_object() || overrides.empty())
    in.fail("overrides",
            "expected a non-empty object of case settings the cheap level changes, e.g. "
            "{\"drum\": {\"scale_factor\": 6}}");
  level.overrides = overrides;
  if (!in.has("runs")) in.fail("runs", "missing; give the number of cheap runs (at least the variables + 2)");
  level.runs = in.integer_or("runs", 0);
  in.finish();
  if (level.runs < 1 || level.runs > kMaxCheapRuns)
    in.fail("runs", "must be 1 to " + std::to_string(kMaxCheapRuns) + " runs");
  spec.cheap_level = std::move(level);
}

void check_cheap_level(const JsonReader& in, const StudySpec& spec) {
  if (!spec.cheap_level) return;
  if (spec.strategy != SamplingStrategy::expected_improvement)
    in.fail("cheap_level",
            "only the expected_improvement strategy uses a cheap level; set sampling.strategy to "
            "\"expected_improvement\" or remove cheap_level");
  const int minimum = static_cast<int>(spec.variables.size()) + 2;
  if (spec.cheap_level->runs < minimum)
    in.fail("cheap_level.runs", "must be at least the variables + 2 = " + std::to_string(minimum) +
                                    " (a kriging model of the cheap runs needs them)");
}

}  // namespace detail

StudySpec cheap_level_study(const StudySpec& spec) {
  StudySpec cheap = spec;
  const nlohmann::json& patch = spec.cheap_level.value().overrides;
  if (cheap.experiments.empty()) cheap.model_overrides.merge_patch(patch);
  for (auto& experiment : cheap.experiments) experiment.model_overrides.merge_patch(patch);
  cheap.cheap_level.reset();
  cheap.name = spec.name + "_cheap_level";
  return cheap;
}

}  // namespace demfit::identify
