#pragma once
// Turns a case reference into an identify::Model. This is the one place where the CLI's
// `identify` command meets the DEM cases.
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "demfit/cases/case_spec.hpp"
#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::cases {

// `reference` is a case JSON path (relative paths resolved against `base_dir`) or a built-in
// name: "pellet_compression", "rotary_drum", or "analytic" (a cheap analytic curve family used
// for tests and demos). `overrides` are fixed case settings from the study file ({} for none);
// unknown keys are errors naming the key. Throws std::runtime_error with a one-line message.
std::unique_ptr<identify::Model> make_model(const std::string& reference, const nlohmann::json& overrides,
                                            const std::filesystem::path& base_dir);

// The model of a whole study: make_model of its "model" in the single-model form, or an
// identify::ExperimentSetModel with one model per experiment (each experiment's case and
// overrides; errors name the experiment). Throws std::runtime_error with a one-line message.
std::unique_ptr<identify::Model> make_study_model(const identify::StudySpec& spec);

// The DEM case a reference names (a built-in name or a case file, as for make_model) with the
// overrides merged in (RFC 7386), parsed. Throws std::runtime_error with a one-line message.
CaseSpec resolve_case(const std::string& reference, const nlohmann::json& overrides,
                      const std::filesystem::path& base_dir);

}  // namespace demfit::cases
