#pragma once
// Internal: the "cheap_level" block of a study file (study_spec.hpp CheapLevelSpec).
#include "demfit/identify/study_spec.hpp"
#include "json_reader.hpp"

namespace demfit::identify::detail {

// Reads "cheap_level": {"overrides": {...}, "runs": N}. Checks that need the whole study (the
// strategy, the number of variables) are in check_cheap_level.
void parse_cheap_level(JsonReader in, StudySpec& spec);
// After the whole study is read: the cheap level needs expected_improvement and enough runs.
void check_cheap_level(const JsonReader& in, const StudySpec& spec);

}  // namespace demfit::identify::detail
